#!/usr/bin/env bash
# Quick start: install the dependencies, build repose (release) and run the main job: `repose paper`, the
# paper's four cases (six runs) with figures, ParaView series and a comparison table, in results/paper/.
# Also installs the Python package (import repose).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)"
# The Python package, where Debian's /usr/bin/python3 finds it (python3 -c "import repose").
cmake --install build/release --component python >/dev/null
build/release/apps/repose/repose paper --out results/paper
echo "Look at: results/paper/report.html (open it in a browser: the runs in 3-D, the comparison, the figures),"
echo "         results/paper/report.md (comparison with the paper), results/paper/<case>/*.png (figures),"
echo "         results/paper/<case>/vtk/settling.pvd (open in ParaView), results/paper/<case>/timeseries.csv"
