#!/usr/bin/env bash
# Quick start: install the dependencies, build repose (release) and run the main job: the paper's regular
# tetrahedron (edge 1 cm, 1.2 g/cm^3) settling from a vertex, results in results/tetrahedron/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)"
mkdir -p results
build/release/apps/repose/repose settle "tetrahedron:edge=1" --density 1.2 --units cgs \
  --orientation "axis-angle:1,0.3,0,2.5" --out results/tetrahedron
echo "Time series and summary: results/tetrahedron/timeseries.csv, results/tetrahedron/summary.json"
