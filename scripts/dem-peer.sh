#!/usr/bin/env bash
# Yade as a peer in the peer benchmark (issue 36 item 4; docs/performance.md, "Yade as a peer"): the benchmark's
# own drops (the same shapes, sizes and start orientations as repose's and Bullet's) settled by Yade 2023.02
# (Debian's), each at Yade's candidate steps, with its step chosen as Bullet's is. Writes results/peer-yade/:
# drops.json (repose_peer_bullet --export), bullet.txt (that run's own tables), yade.json, table.txt (printed).
#   scripts/dem-peer.sh [DROPS] [SHAPES]   default 100 drops of cube,box123,tetrahedron,grain100,cylinder64
#                                          (about 3.5 h on one 2 GHz core, most of it Yade's finest steps on
#                                          the 128- and 105-vertex hulls); SHAPES: comma-separated names
#   YADE_STEPS=2e-3 scripts/dem-peer.sh 10 ellipsoid2000,grain1000   Yade at one step only (its cost per step
#                                          grows with the hull: ~3 ms at 1,000 vertices)
# Installs Yade from Debian itself (so the quick start does not grow); needs root or sudo.
set -euo pipefail
cd "$(dirname "$0")/.."
drops="${1:-100}"
shapes="${2:-cube,box123,tetrahedron,grain100,cylinder64}"
scripts/install-deps.sh core python bench
scripts/dem/install-yade.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target repose_peer_bullet
out=results/peer-yade
mkdir -p "$out"
rm -f "$out/yade.json"  # yade_peer.py would extend it; these are new drops
build/release/bench/peers/repose_peer_bullet --drops "$drops" --only "$shapes" --export "$out/drops.json" \
  >"$out/bullet.txt"
# One thread, as repose and Bullet run; Yade prints a collider warning per scene (no spheres: verletDist 0).
yade -n -j1 -x scripts/dem/yade_peer.py "$out/drops.json" "$out/yade.json" >"$out/yade.log" 2>&1
/usr/bin/python3 scripts/dem/peer_table.py "$out/drops.json" "$out/yade.json" | tee "$out/table.txt"
