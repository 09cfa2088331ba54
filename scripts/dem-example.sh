#!/usr/bin/env bash
# The worked coupling with a real DEM code (docs/dem.md): N polyhedral grains dropped onto a floor in Yade
# 2023.02 (Debian's), (a) settled by Yade alone with its own polyhedra contact law, (b) run in Yade until each
# grain first touches the floor, then handed to repose through its C API (librepose_c.so) with the friction of
# Yade's material and the restitution of Yade's contact (measured in Yade first). Both at two contact
# stiffnesses: Yade's polyhedra example's gravel (young 1e7 N/m³, step 5e-5 s) and Yade's default material
# (young 1e8 N/m³, step 1.6e-5 s: the step scaled by 1/sqrt(stiffness)). Prints the comparison tables and
# writes them, with every run's per-grain JSON, to results/dem/.
#   scripts/dem-example.sh [N]     N grains (default 100); about 25 min on one 2 GHz core for 100
# Installs Yade from Debian itself (so the quick start does not grow); needs root or sudo.
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-100}"
scripts/install-deps.sh core python
scripts/dem/install-yade.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target repose_c
lib="$PWD/build/release/src/librepose_c.so"
out=results/dem
mkdir -p "$out"
: >"$out/table.txt"
for setting in "1e7 5e-5" "1e8 1.6e-5"; do
  read -r young dt <<<"$setting"
  export YADE_YOUNG="$young" YADE_DT="$dt"
  # One thread: each grain is a scene of its own, too small for Yade's threads to pay.
  yade -n -j1 -x scripts/dem/yade_drop.py handover "$n" 1 "$out/handover-$young.json" "$lib" \
    >"$out/handover-$young.log" 2>&1
  yade -n -j1 -x scripts/dem/yade_drop.py alone "$n" 1 "$out/alone-$young.json" >"$out/alone-$young.log" 2>&1
  /usr/bin/python3 scripts/dem/compare.py "$out/alone-$young.json" "$out/handover-$young.json" "$lib" --grains \
    | tee -a "$out/table.txt"
  echo | tee -a "$out/table.txt"
done
/usr/bin/python3 scripts/dem/compare.py --yade-pair "$out/alone-1e7.json" "$out/alone-1e8.json" "$lib" \
  | tee -a "$out/table.txt"
