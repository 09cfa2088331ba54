#!/usr/bin/env bash
# The published binomial prisms and 2d6 hendecahedra of Baktash et al. 2025 (data/experiments/baktash2025)
# under the toss fitted on the 5-sided prism in docs/experiments.md (released 4 L above the table, speed up to
# 1.5 sqrt(gL), spin up to 1.5 sqrt(g/L), E = 0.1, mu = 0.3, L their design's), redesigned for that toss from
# their printed design as a uniform part (vertices only, their outcome rule: every face to the nearest
# normal), and compared with their measured counts (docs/inverse-design.md, "The published designs under the
# toss"). NAMES="Binom2 ..." runs some of them.
#   scripts/design_toss_published.sh [DROPS] [CHECK] [REPOSE]     (defaults 20000, 10000, build/ci)
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
drops="${1:-20000}" check="${2:-10000}"
repose="${3:-$repo/build/ci/apps/repose/repose}"
data="$repo/data/experiments/baktash2025"
out="${OUT:-$(mktemp -d)}"
mkdir -p "$out"
# NAMES: which designs (default all five: the three prisms and the two hendecahedra).
for name in ${NAMES:-Binom2 Binom3 Binom4 2D6_hendecahedron_V1 2D6_hendecahedron_V2}; do
  design="$data/meshes/${name}__opt_test.obj" target="$data/outcomes/${name}__final_normal_probs.json"
  L=$("$repose" design "$design" --inertia convex --target "$target" --outcome-angle 180 --vary vertices \
      --iterations 0 --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["characteristic_length"])')
  read -r height speed spin <<< "$(python3 -c "import math; L=$L; g=9.81; print(4*L, 1.5*math.sqrt(g*L), 1.5*math.sqrt(g/L))")"
  echo "== $name (L = $L)"
  "$repose" design "$design" --inertia convex --target "$target" --outcome-angle 180 --vary vertices \
    --max-move 1 --model tossed --drop-height "$height" --velocity-max "$speed" --spin-max "$spin" \
    --restitution 0.1 --friction 0.3 --drops "$drops" --check-drops "$check" --out "$out/$name" \
    --html "$out/$name.html"
done
echo "files in $out"
