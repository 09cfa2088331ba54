#!/usr/bin/python3
"""Landing frequencies of real dice against repose (docs/experiments.md, issue 14).

For each object with measured counts in data/experiments/, runs `repose poses` three ways — quasi-static,
dynamic from rest (the paper's model, no rebound) and tossed with rebound — maps each rest pose to the
experiment's outcome by its body-frame down normal, and prints Markdown tables: measured frequency with its 95 %
Wilson interval, each prediction, and Pearson's chi-square p-value of the measured counts under each prediction.
The toss's E and mu are fitted on ONE object (--fit) and used unchanged for every other.

Sets: baktash2025 (the printed dice of Baktash et al. 2025; scripts/landing/baktash2025.py) and budden1980
(square cuboidal steel dice; scripts/landing/cuboids.py).

Usage: scripts/experiments.py [--repose build/release/apps/repose/repose] [-n DROPS] [--threads T] [--set S]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from landing import baktash2025, common, cuboids  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SETS = ["baktash2025", "budden1980"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repose", default=os.path.join(ROOT, "build", "release", "apps", "repose", "repose"))
    ap.add_argument("-n", "--drops", type=int, default=100000)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--set", default=",".join(SETS), help=f"comma-separated experiment sets (default: all of "
                                                           f"{', '.join(SETS)})")
    ap.add_argument("--only", default="", help="baktash2025: comma-separated object names of counts.csv "
                                               "(default: all)")
    ap.add_argument("--fit", default="binom4_5prism",
                    help="fit E and mu of the toss on this one object (a baktash2025 counts.csv name; 'none': "
                         "the assumed E = 0.5, mu = 0.3), then use them unchanged for every object")
    ap.add_argument("--fit-drops", type=int, default=10000, help="drops per grid point of the fit")
    ap.add_argument("--toss", default="", help="E,MU: skip the fit and use these (a fit's result)")
    ap.add_argument("--no-toss", action="store_true", help="only the quasi-static and from-rest predictions")
    ap.add_argument("--toss-drops", type=int, default=0,
                    help="drops of the tossed predictions (default: -n); rebounds at high E are slow")
    a = ap.parse_args()
    sets = a.set.split(",")
    if any(s not in SETS for s in sets):
        ap.error(f"--set {a.set}: the sets are {', '.join(SETS)}")
    counts, theirs = baktash2025.load_counts()
    if a.toss:
        common.TOSS["restitution"], common.TOSS["friction"] = (float(x) for x in a.toss.split(","))
    elif a.fit != "none" and not a.no_toss:
        baktash2025.fit(a, counts)
    print(f"repose poses, {a.drops} drops per prediction ({a.toss_drops or a.drops} tossed); "
          f"toss: {common.TOSS}\n")
    if "baktash2025" in sets:
        baktash2025.labelled_tables(a, counts, theirs)
        if not a.only or baktash2025.BUNNY[0] in a.only.split(","):
            baktash2025.bunny_table(a, counts)
    if "budden1980" in sets:
        cuboids.table(a)
    return 0


if __name__ == "__main__":
    sys.exit(main())
