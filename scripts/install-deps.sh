#!/usr/bin/env bash
# Installs the Debian 12 packages repose needs to build, test and plot. Idempotent: does nothing when all
# are present. Needs root (or sudo) and Debian's package archive.
set -euo pipefail
packages=(
  g++ cmake make pkg-config git
  gfortran  # the Fortran module over the C API (bindings/fortran/) and its example
  libeigen3-dev libboost-dev libcli11-dev nlohmann-json3-dev libqhull-dev libtbb-dev librandom123-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcgal-dev  # --repair: CGAL Polygon Mesh Processing (header-only; GPL-3+)
  libbullet-dev  # bench/peers: the peer benchmark against Bullet 3.24 (double precision); builds without it too
  libopenmpi-dev openmpi-bin  # the MPI runner (mpirun -np K repose poses); builds without it too
  clang libclang-rt-14-dev  # scripts/fuzz.sh: the clang driver and libFuzzer + sanitizer runtimes
  python3 python3-matplotlib python3-scipy  # scipy: independent ODE reference in the physics tests
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest  # the Python package (python/)
  chromium chromium-driver python3-selenium fonts-liberation  # the HTML reports opened in headless Chromium (tests/output)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "Installing: ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
