#!/usr/bin/env bash
# Mutation testing: plants one realistic bug at a time in src/ (operators: scripts/mutation/operators.py),
# rebuilds a copy of the tree incrementally, runs the test suite without the pinned hash, and writes a table
# of mutants, killed by which test or survived. Documented in docs/testing.md.
#   scripts/mutate.sh                          every mutant of src/sim src/geometry src/model src/poses
#   scripts/mutate.sh src/sim/body/dynamics.cpp     one file
#   scripts/mutate.sh --sample 0.1 --seed 1    a deterministic 10 % sample
#   scripts/mutate.sh --list src/sim           list the mutants only
# Interrupt at will: a rerun of the same command resumes (results in build/mutate/results.jsonl).
set -euo pipefail
cd "$(dirname "$0")/.."
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
exec "$py" scripts/mutation/mutate.py "$@"
