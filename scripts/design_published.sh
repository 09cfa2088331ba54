#!/usr/bin/env bash
# The published designs of Baktash et al. 2025 (convex_dice; data/experiments/baktash2025) against repose's
# quasi-static design from the same initial shapes and targets (docs/inverse-design.md, "Checked against
# the published designs"). Their rule for outcomes: every hull face to the nearest target normal
# (--outcome-angle 180), the normals following their most probable faces after every step (the column "their
# rule": --outcome-normals follow, with our --min-margin 0.02 where they have a barycentre regulariser);
# their centre of mass: the uniform solid's, following the shape (frozen_G false).
#   scripts/design_published.sh [REPOSE]      (default build/ci/apps/repose/repose)
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
repose="${1:-$repo/build/ci/apps/repose/repose}"
# Their optimiser bounds no move; ours by --max-move (x L).
move="${MOVE:-1}"
# Extra options for every design (e.g. EXTRA=--fold-faces).
read -r -a extra <<<"${EXTRA:-}"
data="$repo/data/experiments/baktash2025"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
printf '%-22s %-12s %-14s %-28s %-28s %-28s\n' example "their design" "ours: refined" "ours from their start" \
  "the same, their rule" "ours, centre of mass free"
row() {  # name, their design, its target, initial shape, its target
  local name=$1 design=$2 target=$3 start=$4 start_target=$5
  local theirs refined ours rule free
  theirs=$("$repose" design "$design" "${extra[@]}" --inertia convex --target "$target" --vary vertices --outcome-angle 180 \
           --iterations 0 --json | python3 -c 'import json,sys; print("%.4f" % json.load(sys.stdin)["max_error"])')
  refined=$("$repose" design "$design" "${extra[@]}" --inertia convex --target "$target" --vary vertices --outcome-angle 180 \
            --json | python3 -c 'import json,sys; j=json.load(sys.stdin); print("%.1e (%d it)" % (j["max_error"], len(j["history"])))')
  ours=$( { /usr/bin/time -f "%e" "$repose" design "$start" "${extra[@]}" --inertia convex --target "$start_target" \
            --vary vertices --outcome-angle 180 --max-move "$move" --json > "$out/o.json"; } 2>&1 )
  ours=$(python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print("%.1e (%d it, %s s)" % (j["max_error"], len(j["history"]), sys.argv[2]))' "$out/o.json" "$ours")
  rule=$( { /usr/bin/time -f "%e" "$repose" design "$start" "${extra[@]}" --inertia convex --target "$start_target" \
            --vary vertices --outcome-angle 180 --outcome-normals follow --min-margin 0.02 --max-move "$move" \
            --json > "$out/r.json"; } 2>&1 )
  rule=$(python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print("%.1e (%d it, %s s)" % (j["max_error"], len(j["history"]), sys.argv[2]))' "$out/r.json" "$rule")
  free=$("$repose" design "$start" "${extra[@]}" --inertia convex --target "$start_target" --vary vertices+center-of-mass --max-move "$move" \
         --outcome-angle 180 --json | python3 -c 'import json,sys; j=json.load(sys.stdin); import math; o=j["center_of_mass_offset"]; print("%.1e (offset %.2f L)" % (j["max_error"], math.sqrt(sum(x*x for x in o))/j["characteristic_length"]))')
  printf '%-22s %-12s %-14s %-28s %-28s %-28s\n' "$name" "$theirs" "$refined" "$ours" "$rule" "$free"
}
i="$data/initial"
row Binom2 "$data/meshes/Binom2__opt_test.obj" "$data/outcomes/Binom2__final_normal_probs.json" \
    "$i/Binom2__3_prism.obj" "$i/Binom2__normal_probs_B2.json"
row Binom3 "$data/meshes/Binom3__opt_test.obj" "$data/outcomes/Binom3__final_normal_probs.json" \
    "$i/Binom3__4_prism.obj" "$i/Binom3__initial_normal_probs.json"
row Binom4 "$data/meshes/Binom4__opt_test.obj" "$data/outcomes/Binom4__final_normal_probs.json" \
    "$i/Binom4__5_prism.obj" "$i/Binom4__normal_probs_B4.json"
row 2D6_hendecahedron_V2 "$data/meshes/2D6_hendecahedron_V2__opt_test.obj" \
    "$data/outcomes/2D6_hendecahedron_V2__final_normal_probs.json" \
    "$i/2D6_hendecahedron_V2__hendecahedron.obj" "$i/2D6_hendecahedron_V2__initial_normal_probs.json"
row 2D6_hendecahedron_V1 "$data/meshes/2D6_hendecahedron_V1__opt_test.obj" \
    "$data/outcomes/2D6_hendecahedron_V1__final_normal_probs.json" \
    "$i/2D6_hendecahedron_V2__hendecahedron.obj" "$i/2D6_hendecahedron_V1__normal_probs_hendeca_v1.json"
# The D3 dice (their centre of mass frozen, G in *_G_opt_out.txt; their initial hulls are not in their
# repository): their design by our exact landscape, ours refined from it (vertices, G fixed), and ours moving
# the centre of mass alone on their design's hull.
printf '\n%-22s %-12s %-24s %-24s %-24s\n' example "their design" "ours: refined (G fixed)" "the same, no min edge/face" \
  "ours: centre of mass"
for d in armadillo dragon; do
  mesh="$data/meshes/D3_${d}__opt_out.obj" target="$i/D3_${d}__initial_normal_probs.json"
  G=$(tr -s ' \n' ',' < "$data/meshes/D3_${d}__G_opt_out.txt" | sed 's/,$//')
  run() { "$repose" design "$mesh" "${extra[@]}" --inertia convex --com "$G" --target "$target" --outcome-angle 180 \
            --max-move "$move" --json "$@" | python3 -c 'import json,sys; j=json.load(sys.stdin); print("%.1e (%d it)" % (j["max_error"], len(j["history"])))'; }
  printf '%-22s %-12s %-24s %-24s %-24s\n' "D3_$d" "$(run --vary vertices --mass fixed --iterations 0 | cut -d' ' -f1)" \
    "$(run --vary vertices --mass fixed)" "$(run --vary vertices --mass fixed --min-edge 0 --min-face 0)" \
    "$(run --vary center-of-mass)"
done
