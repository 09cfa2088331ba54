#!/usr/bin/env bash
# Remakes the generated records kept in records/ (records/README.md) with the built tool:
#   records/paper/            `repose paper`: the paper's cases, figures (PNG) and comparison table
#   records/example-reports/  the three example HTML reports of docs/reports.md, by exactly its commands
# The mutation-testing samples (records/mutation-testing/) take hours; each is remade by the scripts/mutate.sh
# command its README row states.
# Usage: scripts/records.sh [REPOSE_BINARY]   (default build/release/apps/repose/repose; needs matplotlib)
set -euo pipefail
cd "$(dirname "$0")/.."
repose=${1:-build/release/apps/repose/repose}
[ -x "$repose" ] || { echo "records.sh: no repose binary at $repose (build it: cmake --build --preset release)" >&2; exit 2; }
"$repose" paper --out records/paper
reports=records/example-reports
"$repose" settle irregular:seed=7 --orientation axis-angle:1,0.5,0.2,1.2 --damping 0.02 \
  --html "$reports/settle-irregular-grain.html" >/dev/null
"$repose" poses irregular:seed=7 -n 20000 --html "$reports/poses-irregular-grain.html" >/dev/null
cp records/paper/report.html "$reports/paper-report.html"
echo "records.sh: remade records/paper and $reports (git status shows what changed)"
