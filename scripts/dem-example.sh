#!/usr/bin/env bash
# The worked coupling with a real DEM code (docs/dem.md): N polyhedral grains dropped onto a floor in Yade
# 2023.02 (Debian's), (a) settled by Yade alone with its own polyhedra contact law, (b) run in Yade until each
# grain first touches the floor, then handed to repose through its C API (librepose_c.so). Prints the
# comparison table and writes it, with both runs' per-grain JSON, to results/dem/.
#   scripts/dem-example.sh [N]     N grains (default 100); Yade alone takes about 10 s per grain on 2 cores
# Installs Yade from Debian itself (so the quick start does not grow); needs root or sudo.
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-100}"
scripts/install-deps.sh
if ! command -v yade >/dev/null; then
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  echo "Installing Yade (Debian's yade package)"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends yade >/dev/null
fi
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target repose_c
lib="$PWD/build/release/src/librepose_c.so"
out=results/dem
mkdir -p "$out"
# Yade prints its banner and warnings (no spheres for its P-wave time step, which the script sets itself).
yade -n -j"$(nproc)" -x scripts/dem/yade_drop.py handover "$n" 1 "$out/handover.json" "$lib" >"$out/handover.log" 2>&1
yade -n -j"$(nproc)" -x scripts/dem/yade_drop.py alone "$n" 1 "$out/alone.json" >"$out/alone.log" 2>&1
/usr/bin/python3 scripts/dem/compare.py "$out/alone.json" "$out/handover.json" "$lib" --grains | tee "$out/table.txt"
