#!/usr/bin/env bash
# identical_runs.sh: the before/after proof for the restructuring of the simulation engine (issue 32).
#
# Runs a fixed list of repose runs (settle and poses, see the `run` lines below) with the given binary and
# writes everything they output into OUTDIR, then OUTDIR/SHA256SUMS. Run it once with the binary built from
# the commit before the restructuring and once with the binary after it, then
#
#   diff OUTDIR_BEFORE/SHA256SUMS OUTDIR_AFTER/SHA256SUMS      # no output: every run is byte-identical
#   diff -r OUTDIR_BEFORE OUTDIR_AFTER                          # the differing bytes, when there are any
#
# Usage: scripts/identical_runs.sh REPOSE_BINARY OUTDIR      (OUTDIR must not exist or be empty)
#
# Per run NAME:
#   OUTDIR/NAME.json     its stdout (the --json output), timing values masked (below)
#   OUTDIR/NAME.rc       its exit code (0, or 3 for the runs stopped by --max-time/--max-steps)
#   OUTDIR/NAME.stderr   its stderr (normally empty)
#   OUTDIR/NAME/         the files its --out (and --vtk) directory got: timeseries.csv, summary.json, ...
# Not hashed: OUTDIR/raw/NAME.json (the unmasked stdout of the runs whose output has timing) and
# OUTDIR/logs/ (wall-clock time per run).
#
# The one filter: `repose poses` writes a "timing" object whose "seconds" and "settles_per_second" are wall
# clock and differ from run to run. mask_timing() replaces those two values (only inside "timing") with
# "<masked>" in NAME.json and in any poses.json/summary.json under NAME/; "threads" (and "ranks") stay. Every
# other byte is compared as written. `repose settle` output has no wall-clock field.
#
# Each pair NAME-t1 / NAME-t2 (the same poses run with --threads 1 and --threads 2) is also checked to give
# the same result (the whole "timing" object aside); a difference fails the script.
#
# The script fails (exit 1) if any run's exit code is not the one expected, or a thread pair differs; it
# still writes SHA256SUMS then, in which the .rc files show the difference. 76 runs, about 11 s with the
# baseline release build on 2 cores.
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 REPOSE_BINARY OUTDIR" >&2
  exit 2
fi
if [[ ! -x $1 ]]; then
  echo "$0: $1 is not an executable" >&2
  exit 2
fi
BIN=$(realpath "$1")
mkdir -p "$2"
OUT=$(realpath "$2")
if [[ -n $(ls -A "$OUT") ]]; then
  echo "$0: $OUT is not empty; give a new directory" >&2
  exit 2
fi
mkdir -p "$OUT/raw" "$OUT/logs"

# The runs use paths relative to the repository root (scenarios/, data/, tests/data/), which appear as
# such in the outputs, so the before and after trees may live anywhere.
cd "$(dirname "${BASH_SOURCE[0]}")/.."

export LC_ALL=C

# Mask the wall-clock values of a "timing" object (pretty-printed JSON, one key per line).
mask_timing() {
  awk '
    /"timing": \{/ { in_timing = 1; print; next }
    in_timing && /^ *\}/ { in_timing = 0 }
    in_timing && /"(seconds|settles_per_second)": / { sub(/: .*[^,]/, ": \"<masked>\"") }
    { print }
  '
}
# The whole "timing" object removed (for comparing a --threads 1 run with its --threads 2 twin).
strip_timing() {
  awk '
    /"timing": \{/ { in_timing = 1; next }
    in_timing { if (/^ *\}/) in_timing = 0; next }
    { print }
  '
}

failures=()
count=0
# run NAME EXPECTED_EXIT_CODE ARGS...: runs `repose ARGS...`; @OUT@ in an argument stands for OUTDIR/NAME.
run() {
  local name=$1 expected=$2
  shift 2
  local args=() a
  for a in "$@"; do args+=("${a//@OUT@/$OUT/$name}"); done
  count=$((count + 1))
  local rc=0 t0 t1
  t0=$(date +%s.%N)
  "$BIN" "${args[@]}" >"$OUT/raw/$name.json" 2>"$OUT/$name.stderr" || rc=$?
  t1=$(date +%s.%N)
  echo "$rc" >"$OUT/$name.rc"
  printf '%-40s rc=%s %6.2fs\n' "$name" "$rc" "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" | tee -a "$OUT/logs/times.txt"
  mask_timing <"$OUT/raw/$name.json" >"$OUT/$name.json"
  if cmp -s "$OUT/raw/$name.json" "$OUT/$name.json"; then rm "$OUT/raw/$name.json"; fi
  if [[ -d $OUT/$name ]]; then
    local f
    while IFS= read -r -d '' f; do
      if grep -q '"timing": {' "$f"; then
        mask_timing <"$f" >"$f.masked" && mv "$f.masked" "$f"
      fi
    done < <(find "$OUT/$name" -type f -name '*.json' -print0)
  fi
  if [[ $rc -ne $expected ]]; then
    echo "!!! $name: exit code $rc, expected $expected: repose ${args[*]}" >&2
    [[ -s $OUT/$name.stderr ]] && sed 's/^/!!!   /' "$OUT/$name.stderr" >&2
    failures+=("$name (exit $rc, expected $expected)")
  fi
}

BOX=box:x=1,y=2,z=3
CYL=cylinder:r=0.5,h=1,n=64
ELL=ellipsoid:a=1,b=0.7,c=0.5
TET=tetrahedron:edge=1
IRR3=irregular:seed=3,n=4
IRR7=irregular:seed=7
COIN=cylinder:r=1,h=0.2,n=64
MESH=data/experiments/baktash2025/meshes/D3_kitten__opt_test.obj   # a printed 3-sided die (OBJ, ~1 unit)
CUBE=tests/data/cube_binary.stl

# --- settle: the paper's cases, both integrators (cgs, as in the scenario files) ---------------------------
for c in cylinder-1106 cylinder-1108 ellipsoid-c075 ellipsoid-c150 irregular tetrahedron; do
  run "paper-$c-adaptive" 0 settle --scenario "scenarios/paper/$c.json" --integrator adaptive --json
  run "paper-$c-paper"    0 settle --scenario "scenarios/paper/$c.json" --integrator paper --json
done
# ... with the time series (and ParaView frames) of the --out directory
run paper-tetrahedron-adaptive-out 0 settle --scenario scenarios/paper/tetrahedron.json --json --out @OUT@
run paper-tetrahedron-paper-out    0 settle --scenario scenarios/paper/tetrahedron.json --integrator paper --json --out @OUT@
run paper-irregular-adaptive-out   0 settle --scenario scenarios/paper/irregular.json --json --out @OUT@ --sample-dt 0.0005 --vtk @OUT@/vtk --frames 5
run paper-ellipsoid-c075-paper-out 0 settle --scenario scenarios/paper/ellipsoid-c075.json --integrator paper --json --out @OUT@ --sample-dt 0.001

# --- settle: tosses with rebound (SI, density 1) -----------------------------------------------------------
run toss-box-e03-muinf            0 settle $BOX --orientation axis-angle:1,2,0.5,0.8 --drop-height 1 --velocity 1.5,0.5,-1 --spin 2,-3,1 --restitution 0.3 --friction inf --json
run toss-box-e06-mu06             0 settle $BOX --orientation axis-angle:1,2,0.5,0.8 --drop-height 1 --velocity 1.5,0.5,-1 --spin 2,-3,1 --restitution 0.6 --friction 0.6 --json
run toss-box-e06-mu06-paper       0 settle $BOX --orientation axis-angle:1,2,0.5,0.8 --drop-height 1 --velocity 1.5,0.5,-1 --spin 2,-3,1 --restitution 0.6 --friction 0.6 --integrator paper --json
run toss-box-e09-mu02-out         0 settle $BOX --orientation quat:0.9,0.3,-0.2,0.25 --drop-height 0.5 --velocity 0,1,2 --spin 0,0,6 --restitution 0.9 --friction 0.2 --json --out @OUT@
run toss-cyl-e06-mu02             0 settle $CYL --orientation axis-angle:1,0,0,0.6 --drop-height 0.5 --velocity 1,0,0 --spin 0,4,0 --restitution 0.6 --friction 0.2 --json
run toss-cyl-e06-mu02-paper       0 settle $CYL --orientation axis-angle:1,0,0,0.6 --drop-height 0.5 --velocity 1,0,0 --spin 0,4,0 --restitution 0.6 --friction 0.2 --integrator paper --json
run toss-cyl-e09-muinf            0 settle $CYL --orientation axis-angle:0,1,1,2.0 --drop-height 1 --velocity 0,0,-2 --spin 3,1,0 --restitution 0.9 --friction inf --json
run toss-ell-e09-mu06             0 settle $ELL --orientation axis-angle:1,1,1,1.0 --drop-height 0.8 --velocity 0.5,-0.5,0 --spin 2,2,-1 --restitution 0.9 --friction 0.6 --json
run toss-ell-e09-mu06-paper       0 settle $ELL --orientation axis-angle:1,1,1,1.0 --drop-height 0.8 --velocity 0.5,-0.5,0 --spin 2,2,-1 --restitution 0.9 --friction 0.6 --integrator paper --json
run toss-ell-e03-mu02             0 settle $ELL --orientation quat:0.5,0.5,0.5,0.5 --drop-height 0.3 --spin 0,5,0 --restitution 0.3 --friction 0.2 --json
run toss-tet-e03-mu02             0 settle $TET --orientation axis-angle:1,0,0,2.5 --drop-height 0.5 --velocity 1,1,0 --spin 0,0,8 --restitution 0.3 --friction 0.2 --json
run toss-tet-e09-muinf            0 settle $TET --orientation quat:0.3,0.6,-0.5,0.55 --drop-height 1 --velocity -1,0,1 --spin 5,-2,3 --restitution 0.9 --friction inf --json
run toss-irr3-e06-mu06            0 settle $IRR3 --orientation axis-angle:3,-1,2,1.3 --drop-height 0.5 --velocity 0.8,0,0 --spin 1,6,-2 --restitution 0.6 --friction 0.6 --json
run toss-irr3-e06-mu06-paper      0 settle $IRR3 --orientation axis-angle:3,-1,2,1.3 --drop-height 0.5 --velocity 0.8,0,0 --spin 1,6,-2 --restitution 0.6 --friction 0.6 --integrator paper --json
run toss-irr7-e03-muinf           0 settle $IRR7 --orientation axis-angle:0,1,0,2.2 --drop-height 1 --velocity 0,-1,0.5 --spin -4,0,2 --restitution 0.3 --friction inf --json
run toss-irr7-e09-mu02            0 settle $IRR7 --orientation quat:0.1,0.7,0.7,0.1 --drop-height 0.7 --velocity 1,1,-1 --spin 3,3,3 --restitution 0.9 --friction 0.2 --json
run toss-coin-e06-mu02            0 settle $COIN --orientation axis-angle:1,0,0,0.3 --drop-height 1 --velocity 0.5,0,0 --spin 15,0,0 --restitution 0.6 --friction 0.2 --json
run toss-coin-e09-muinf-paper     0 settle $COIN --orientation axis-angle:1,1,0,1.2 --drop-height 1.5 --spin 10,-10,0 --restitution 0.9 --friction inf --integrator paper --json
run toss-coin-e03-mu06            0 settle $COIN --orientation identity --drop-height 0.5 --velocity 0,0.5,0 --spin 0,20,2 --restitution 0.3 --friction 0.6 --json

# --- settle: drops from rest, damping, --smooth, --drop-height, orientations --------------------------------
run drop-box-damped               0 settle $BOX --orientation axis-angle:1,1,0,0.7 --drop-height 0.5 --damping 2 --json
run drop-box-damped-paper         0 settle $BOX --orientation axis-angle:1,1,0,0.7 --drop-height 0.5 --damping 2 --integrator paper --json
run drop-ell-smooth-auto          0 settle $ELL --orientation axis-angle:1,0.2,0,1.1 --drop-height 0.2 --damping 0.5 --smooth auto --json
run drop-ell-smooth-on            0 settle $ELL --orientation axis-angle:1,0.2,0,1.1 --drop-height 0.2 --damping 0.5 --smooth on --json
run drop-ell-smooth-off           0 settle $ELL --orientation axis-angle:1,0.2,0,1.1 --drop-height 0.2 --damping 0.5 --smooth off --json
run drop-cyl-smooth-on            0 settle $CYL --orientation quat:0.95,0.2,0.1,-0.2 --drop-height 0.3 --damping 0.3 --smooth on --json
run drop-cyl-smooth-off-paper     0 settle $CYL --orientation quat:0.95,0.2,0.1,-0.2 --drop-height 0.3 --damping 0.3 --smooth off --integrator paper --json
run drop-tet-quat                 0 settle $TET --orientation quat:0.2,-0.4,0.8,0.4 --drop-height 0.25 --damping 0.01 --json
run drop-irr7-quat-smooth-off     0 settle $IRR7 --orientation quat:0.6,-0.2,0.7,0.3 --drop-height 2 --damping 0.1 --smooth off --json
run drop-irr3-units-cgs           0 settle $IRR3 --orientation axis-angle:-1,2,1,2.8 --units cgs --density 2.65 --drop-height 0.4 --json

# --- settle: stopped by the limits (exit code 3) ------------------------------------------------------------
run limit-max-time                3 settle $BOX --orientation axis-angle:1,1,0,0.7 --drop-height 0.5 --max-time 1.0 --json
run limit-max-time-toss           3 settle $COIN --orientation axis-angle:1,0,0,0.3 --drop-height 1 --velocity 0.5,0,0 --spin 15,0,0 --restitution 0.6 --friction 0.2 --max-time 2 --json
run limit-max-time-paper          3 settle $ELL --orientation axis-angle:1,1,1,1.0 --integrator paper --max-time 3 --json
run limit-max-steps               3 settle $IRR7 --orientation axis-angle:0,1,0,2.2 --drop-height 1 --velocity 0,-1,0.5 --spin -4,0,2 --restitution 0.3 --max-steps 20 --json
run limit-max-steps-paper         3 settle $ELL --orientation axis-angle:1,1,1,1.0 --integrator paper --max-steps 500 --json

# --- settle: starting on the wall with a downward speed ----------------------------------------------------
run wall-box-drop-speed           0 settle $BOX --orientation axis-angle:0,1,0,0.4 --drop-height 0 --drop-speed 1.5 --json
run wall-ell-drop-speed-e06       0 settle $ELL --orientation axis-angle:1,0,1,0.9 --drop-height 0 --drop-speed 2 --restitution 0.6 --friction 0.6 --json
run wall-coin-drop-speed-paper    0 settle $COIN --orientation axis-angle:1,0,0,0.5 --drop-height 0 --drop-speed 1 --integrator paper --json

# --- settle: mesh files -------------------------------------------------------------------------------------
run mesh-kitten-settle-mm         0 settle $MESH --mesh-units mm --density 1250 --orientation axis-angle:1,2,3,1.0 --drop-height 0.002 --damping 1e-9 --json
run mesh-kitten-toss              0 settle $MESH --units cgs --density 1.25 --orientation quat:0.4,0.1,-0.8,0.3 --drop-height 2 --velocity 30,0,-20 --spin 20,5,-10 --restitution 0.6 --friction 0.3 --json --out @OUT@
run mesh-cube-stl-paper           0 settle $CUBE --orientation axis-angle:1,0.5,0,0.6 --drop-height 0.1 --integrator paper --json

# --- poses: dynamic and quasi-static, each with --threads 1 and --threads 2 ----------------------------------
for t in 1 2; do
  run "poses-box-dyn-t$t"         0 poses $BOX -n 200 --json --seed 1 --threads $t
  run "poses-tet-dyn-paper-t$t"   0 poses $TET -n 200 --json --seed 2 --threads $t --integrator paper
  run "poses-ell-dyn-t$t"         0 poses $ELL -n 200 --json --seed 3 --threads $t
  run "poses-irr7-dyn-t$t"        0 poses $IRR7 -n 200 --json --seed 4 --threads $t --drop-height 0.5
  run "poses-coin-toss-t$t"       0 poses $COIN -n 200 --json --seed 5 --threads $t --drop-height 1 --velocity-max 2 --spin-max 10 --restitution 0.6 --friction 0.4
  run "poses-cyl-full-t$t"        0 poses $CYL -n 200 --json --seed 6 --threads $t --full-settle --damping-ratio 0.1
  run "poses-box-qs-t$t"          0 poses $BOX -n 200 --json --seed 7 --threads $t --method quasi-static
  run "poses-irr3-qs-t$t"         0 poses $IRR3 -n 200 --json --seed 8 --threads $t --method quasi-static
  run "poses-kitten-dyn-t$t"      0 poses $MESH --units cgs --density 1.25 -n 200 --json --seed 9 --threads $t --out @OUT@
  run "poses-kitten-qs-t$t"       0 poses $MESH --units cgs --density 1.25 -n 200 --json --seed 9 --threads $t --method quasi-static
done

# --- the --threads 1 and --threads 2 twins must agree ------------------------------------------------------
for f in "$OUT"/*-t1.json; do
  twin=${f%-t1.json}-t2.json
  if ! cmp -s <(strip_timing <"$f") <(strip_timing <"$twin"); then
    echo "!!! $(basename "$f") and $(basename "$twin") differ (beyond \"timing\")" >&2
    failures+=("$(basename "${f%-t1.json}"): --threads 1 and --threads 2 differ")
  fi
done

# --- SHA256SUMS: every output file (not raw/ nor logs/), sorted by name ----------------------------------
(
  cd "$OUT"
  find . -type f ! -name SHA256SUMS ! -path './raw/*' ! -path './logs/*' -print0 | sed -z 's|^\./||' | sort -z |
    xargs -0 sha256sum >logs/SHA256SUMS.tmp
  mv logs/SHA256SUMS.tmp SHA256SUMS
)

echo "$count runs, $(wc -l <"$OUT/SHA256SUMS") files hashed into $OUT/SHA256SUMS"
echo "compare with: diff OTHER_OUTDIR/SHA256SUMS $OUT/SHA256SUMS   (details: diff -r OTHER_OUTDIR $OUT)"
if [[ ${#failures[@]} -gt 0 ]]; then
  echo "FAILED (${#failures[@]}):" >&2
  printf '  %s\n' "${failures[@]}" >&2
  exit 1
fi
