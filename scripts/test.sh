#!/usr/bin/env bash
# Builds repose with warnings as errors and runs every test.
#   scripts/test.sh            optimised build (preset ci)
#   scripts/test.sh --sanitize also the AddressSanitizer + UBSan build (preset asan)
set -euo pipefail
cd "$(dirname "$0")/.."
# Everything the suites build and run but the fuzzers (scripts/fuzz.sh installs clang for those).
scripts/install-deps.sh core python plots tests mpi fortran bench browser
presets=(ci)
[ "${1:-}" = "--sanitize" ] && presets+=(asan)
for preset in "${presets[@]}"; do
  echo "== preset $preset"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j"$(nproc)"
  ctest --preset "$preset" -j"$(nproc)"
done
