#!/usr/bin/env bash
# Measures `repose poses` on 1 and 2 MPI ranks and on 1 and 2 threads (the table in docs/cluster.md).
#   scripts/scaling.sh [path/to/repose]   (default build/release/apps/repose/repose)
set -euo pipefail
cd "$(dirname "$0")/.."
repose="${1:-build/release/apps/repose/repose}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
timed() {
  local start end
  start=$(date +%s.%N)
  "$@" >"$scratch/log" 2>&1
  end=$(date +%s.%N)
  awk -v s="$start" -v e="$end" -v c="$*" 'BEGIN { printf "%6.1f s  %s\n", e - s, c }'
}
one="poses irregular:seed=3 -n 4000 --no-progress"
timed "$repose" $one --threads 1
timed mpirun -np 1 "$repose" $one --threads 1
timed mpirun -np 2 --oversubscribe "$repose" $one --threads 1
timed "$repose" $one --threads 2
many="poses box:x=1,y=1,z=1 ellipsoid:a=0.625,b=0.5,c=0.285,n=10 irregular:seed=3 -n 1000 --no-progress"
timed "$repose" $many --threads 1 --out "$scratch/a"
timed mpirun -np 2 --oversubscribe "$repose" $many --threads 1 --out "$scratch/b"
timed "$repose" $many --threads 2 --out "$scratch/c"
