#!/usr/bin/env bash
# Where a build's time went, from Ninja's log of it (BUILD_DIR/.ninja_log, written by every preset's build):
# the seconds of each target's compile and link steps summed, then the slowest steps.
#   scripts/build-times.sh BUILD_DIR [N]     N slowest steps (default 15)
# Targets under 1 s are left out. Times are each step's wall time as Ninja saw it; with -jK, K steps share the cores, so the sum is the CPU
# time the build needs rather than its wall time. Only the newest build of each output counts.
set -euo pipefail
log="${1:?usage: scripts/build-times.sh BUILD_DIR [N]}/.ninja_log"
slowest="${2:-15}"
[ -f "$log" ] || { echo "build-times.sh: no $log (not a Ninja build directory?)" >&2; exit 2; }
# .ninja_log v5: start ms, end ms, mtime, output, command hash; a rebuilt output appears again later.
awk -F'\t' 'NR > 1 { t[$4] = ($2 - $1) / 1000 }
  END {
    for (out in t) {
      target = out
      if (match(out, /CMakeFiles\/[^\/]+\.dir/)) target = substr(out, RSTART + 11, RLENGTH - 15)
      sum[target] += t[out]; steps[target]++; total += t[out]
    }
    for (g in sum) if (sum[g] >= 1) printf "%8.1f s  %4d steps  %s\n", sum[g], steps[g], g
    printf "%8.1f s  in all\n", total
  }' "$log" | sort -rn
echo "slowest steps:"
awk -F'\t' 'NR > 1 { t[$4] = ($2 - $1) / 1000 } END { for (o in t) printf "%8.1f s  %s\n", t[o], o }' "$log" |
  sort -rn | head -n "$slowest"
