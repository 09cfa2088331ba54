#!/usr/bin/env bash
# Installs the Debian 12 packages of the named groups that are missing (all groups when none is named).
# Idempotent: does nothing when they are all present. Needs root (or sudo) and Debian's package archive.
#   scripts/install-deps.sh core python plots      what scripts/quickstart.sh installs
#   scripts/install-deps.sh --list                 the groups and their packages
# What each group is for, and why these packages: docs/building.md#dependencies.
set -euo pipefail

declare -A group=(
  # Build and run the library and the `repose` tool (CGAL: --repair, header-only with GMP and MPFR).
  [core]="g++ cmake ninja-build pkg-config libeigen3-dev libboost-dev libcli11-dev nlohmann-json3-dev
          libqhull-dev libtbb-dev librandom123-dev libcgal-dev libadolc-dev"
  # The Python package `repose` (pybind11 extension, NumPy arrays) in Debian's python3.
  [python]="python3 python3-dev pybind11-dev python3-numpy"
  # The figures and comparison table of `repose paper`, and the plotting scripts. python3-munkres meets
  # python3-fonttools' dependency "python3-scipy | python3-munkres" (matplotlib needs fonttools) without
  # SciPy's 62 MB, which the figures never use: 12 s less on a fresh machine.
  [plots]="python3-matplotlib python3-munkres"
  # The test suites: GoogleTest, pytest, SciPy as the independent ODE reference.
  [tests]="libgtest-dev libgmock-dev python3-pytest python3-scipy"
  # The MPI runner (mpirun -np K repose poses) and its tests.
  [mpi]="libopenmpi-dev openmpi-bin"
  # The Fortran module over the C API and its example.
  [fortran]="gfortran"
  # Google Benchmark, and Bullet as the peer of the peer benchmark (bench/peers/).
  [bench]="libbenchmark-dev libbullet-dev"
  # The HTML reports opened in headless Chromium (tests/output/report_browser_test.py).
  [browser]="chromium chromium-driver python3-selenium fonts-liberation"
  # The libFuzzer harnesses (scripts/fuzz.sh): clang and its sanitizer and libFuzzer runtimes.
  [fuzz]="clang libclang-rt-14-dev"
)
order=(core python plots tests mpi fortran bench browser fuzz)

if [ "${1:-}" = "--list" ]; then
  for g in "${order[@]}"; do
    echo "$g:" ${group[$g]}
  done
  exit 0
fi
names=("$@")
[ ${#names[@]} -gt 0 ] || names=("${order[@]}")
packages=()
for g in "${names[@]}"; do
  if [ -z "${group[$g]+set}" ]; then
    echo "install-deps.sh: unknown group '$g' (groups: ${order[*]})" >&2
    exit 2
  fi
  read -r -d '' -a list <<<"${group[$g]}" || true  # every line of the group, not only its first
  packages+=("${list[@]}")
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "Installing (${names[*]}): ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
