#!/usr/bin/env bash
# Quick start: install the Debian packages the main job needs (groups core, python and plots of
# scripts/install-deps.sh, the last while the build runs; not the test tools, which scripts/test.sh installs),
# build what the main job needs (release: the `repose` tool and the Python module, not the tests or
# benchmarks, which scripts/test.sh builds), install both, and run the main
# job: `repose paper`, the paper's four cases (six runs) with figures, ParaView series and a comparison table,
# in results/paper/.
#   the tool `repose`           -> /usr/local/bin/repose, on the PATH (cmake --install ... --component cli)
#   the Python package `repose` -> where Debian's /usr/bin/python3 finds it (--component python)
set -euo pipefail
cd "$(dirname "$0")/.."
elapsed() { printf '[%d:%02d] %s\n' $((SECONDS / 60)) $((SECONDS % 60)) "$1"; }
scripts/install-deps.sh core python
elapsed "packages installed"
# matplotlib is needed only by the paper's figures, at the end: it installs while the build runs.
mkdir -p build
scripts/install-deps.sh plots >build/install-plots.log 2>&1 &
plots=$!
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target quickstart  # repose_cli and _repose (CMakeLists.txt)
cmake --install build/release --component cli >/dev/null
cmake --install build/release --component python >/dev/null
elapsed "repose and the Python package built and installed"
if ! wait "$plots"; then
  cat build/install-plots.log >&2
  echo "quickstart.sh: installing matplotlib (scripts/install-deps.sh plots) failed; log above" >&2
  exit 1
fi
elapsed "matplotlib installed"
build/release/apps/repose/repose paper --out results/paper
elapsed "the paper's cases reproduced"
echo "Look at: results/paper/report.html (open it in a browser: the runs in 3-D, the comparison, the figures),"
echo "         results/paper/report.md (comparison with the paper), results/paper/<case>/*.png (figures),"
echo "         results/paper/<case>/vtk/settling.pvd (open in ParaView), results/paper/<case>/timeseries.csv"
echo "Installed: /usr/local/bin/repose (try repose --help) and the Python package (python3 -c 'import repose')."
echo "The tests: scripts/test.sh"
