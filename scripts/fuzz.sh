#!/usr/bin/env bash
# Builds the libFuzzer harnesses (preset fuzz: clang, ASan + UBSan) and runs each for a bounded time.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]   default 30 s, every target
# Each harness runs on a scratch copy of its seed corpus (fuzz/corpus/TARGET) under build/fuzz/runs/, so new
# inputs never land in the repository. Limits: -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024.
# Exits non-zero if any harness finds a crash, leak, timeout or out-of-memory, naming the reproducer.
# The mutation sequence is seeded (REPOSE_FUZZ_SEED, default 1), so a CI run explores the same inputs each time
# (as many as fit in the time); set another seed to explore elsewhere.
# See docs/fuzzing.md for longer and parallel runs.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] ||
  targets=(mesh_stl mesh_obj mesh_ply mesh_off mesh_xyz mesh_options shape_spec orientation_spec scenario poses_result)

scripts/install-deps.sh core fuzz
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j"$(nproc)"

runs="build/fuzz/runs/$(date +%Y%m%d-%H%M%S)-$$"
failed=()
for target in "${targets[@]}"; do
  work="$runs/$target"
  mkdir -p "$work/corpus" "$work/artifacts"
  cp fuzz/corpus/"$target"/* "$work/corpus/"
  echo "== fuzz_$target for ${seconds} s ($work)"
  if build/fuzz/fuzz/fuzz_"$target" "$work/corpus" -max_total_time="$seconds" -seed="${REPOSE_FUZZ_SEED:-1}" -timeout=10 \
      -rss_limit_mb=2048 -malloc_limit_mb=1024 -artifact_prefix="$work/artifacts/" -print_final_stats=1 \
      >"$work/log" 2>&1; then
    grep -E '^stat::number_of_executed_units|^Done' "$work/log" | tr '\n' ' '
    echo
  else
    failed+=("$target")
    tail -n 40 "$work/log"
    for artifact in "$work"/artifacts/*; do
      [ -e "$artifact" ] && echo "reproducer: $artifact (rerun: build/fuzz/fuzz/fuzz_$target $artifact)"
    done
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzzing found problems in: ${failed[*]}" >&2
  exit 1
fi
echo "fuzzing: no crash, leak, timeout or out-of-memory in ${#targets[@]} targets (${seconds} s each)"
