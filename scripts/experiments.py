#!/usr/bin/python3
"""Landing frequencies of real dice against repose (docs/experiments.md, issue 14).

For each object with measured counts in data/experiments/, runs `repose poses` three ways — quasi-static,
dynamic from rest (the paper's model, no rebound) and tossed with rebound — maps each rest pose to the
experiment's outcome by its body-frame down normal, and prints Markdown tables: measured frequency with its 95 %
Wilson interval, each prediction, and Pearson's chi-square p-value of the measured counts under each prediction.
The toss's E and mu are fitted on ONE object (--fit) and used unchanged for every other.

The chi-square (scripts/landing/common.py): expected counts below 5 pooled, each prediction's own Monte-Carlo error
counted, k - 1 degrees of freedom (k - 1 - 2 for the tossed model on the fit object). A last table corrects the
tossed model's p-values of the objects it was not fitted on for multiple comparisons (Holm-Bonferroni) and sums
their chi-squares.

Sets: baktash2025 (the printed dice of Baktash et al. 2025; scripts/landing/baktash2025.py) and budden1980
(square cuboidal steel dice; scripts/landing/cuboids.py).

Usage: scripts/experiments.py [--repose build/release/apps/repose/repose] [-n DROPS] [--threads T] [--set S]
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from landing import baktash2025, common, cuboids  # noqa: E402
from scipy import stats  # noqa: E402

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
    ap.add_argument("--toss", default="", help="E,MU: skip the fit and use these (a fit's result on the --fit "
                                               "object, whose tossed chi-square then loses 2 degrees of freedom)")
    ap.add_argument("--no-toss", action="store_true", help="only the quasi-static and from-rest predictions")
    ap.add_argument("--toss-drops", type=int, default=0,
                    help="drops of the tossed predictions (default: -n); rebounds at high E are slow")
    a = ap.parse_args()
    sets = a.set.split(",")
    if any(s not in SETS for s in sets):
        ap.error(f"--set {a.set}: the sets are {', '.join(SETS)}")
    if a.fit != "none" and baktash2025.fit_key(a.fit) is None:
        ap.error(f"--fit {a.fit}: not an object of {baktash2025.DATA}/counts.csv")
    # The counts E and mu were fitted on: none with the assumed values (--fit none) or without a toss.
    a.fitted_on = None if a.fit == "none" or a.no_toss else baktash2025.fit_key(a.fit)
    counts, theirs = baktash2025.load_counts()
    if a.toss:
        common.TOSS["restitution"], common.TOSS["friction"] = (float(x) for x in a.toss.split(","))
    elif a.fit != "none" and not a.no_toss:
        baktash2025.fit(a, counts)
    print(f"repose poses, {a.drops} drops per prediction ({a.toss_drops or a.drops} tossed); "
          f"toss: {common.TOSS}\n")
    tested = []
    if "baktash2025" in sets:
        tested += baktash2025.labelled_tables(a, counts, theirs)
        if not a.only or baktash2025.BUNNY[0] in a.only.split(","):
            tested += baktash2025.bunny_table(a, counts)
    if "budden1980" in sets:
        tested += cuboids.table(a)
    if tested:
        holm_table(tested)
    return 0


def cell(lo, hi, fmt):
    """One value, or 'least / most favourable' when the labellings the authors' values cannot tell apart differ."""
    return fmt(lo) if fmt(lo) == fmt(hi) else f"{fmt(lo)} / {fmt(hi)}"


def holm_table(tested):
    """The tossed model's p-values of the objects it was not fitted on, Holm–Bonferroni adjusted, and their
    summed χ². With labellings the authors' values cannot tell apart, Holm runs twice: every such object at its
    least, then at its most favourable p; Holm's adjusted p-values rise with every p, so the two runs bound
    every combination of labellings."""
    fitted = [t for t in tested if t.fitted]
    rows = [t for t in tested if not t.fitted and not all(math.isnan(f.p) for f in t.fits)]
    worst = [min(t.fits, key=lambda f: f.p) for t in rows]
    best = [max(t.fits, key=lambda f: f.p) for t in rows]
    adj_worst, adj_best = common.holm([f.p for f in worst]), common.holm([f.p for f in best])
    print(f"### Holm–Bonferroni over the tossed model's p-values: {len(rows)} objects tested in this run\n")
    for t in fitted:
        print(f"Not in it: {t.label}, the object E and μ were fitted on (tossed p = {common.format_p(t.fits[0])} "
              f"on {t.fits[0].dof} degrees of freedom).\n")
    if not rows:
        return
    print("| object | p | Holm-adjusted p | rejected at 0.05 |")
    print("|---|---:|---:|---|")
    for t, w, b, aw, ab in zip(rows, worst, best, adj_worst, adj_best):
        print(f"| {t.label}{' ' + t.mark if t.mark else ''} | {cell(w.p, b.p, lambda p: f'{p:.3g}')} | "
              f"{cell(aw, ab, lambda p: f'{p:.3g}')} | {cell(aw, ab, lambda p: 'yes' if p <= 0.05 else 'no')} |")
    print()
    if any(t.mark == "*" for t in rows):
        print("\\* labellings the authors' values cannot tell apart: p under the least / most favourable one; "
              "the adjusted p-values, here and in every other row where two are given, are those with every such "
              "object at its least / most favourable labelling.\n")
    if any(t.mark == "†" for t in rows):
        print("† compared without labels: the most favourable of all labellings, an upper bound of p.\n")
    results = []
    for fits in (worst, best):
        chi2, dof = sum(f.chi2 for f in fits), sum(f.dof for f in fits)
        results.append(f"χ² = {chi2:.1f} on {dof} degrees of freedom, p = {stats.chi2.sf(chi2, dof):.2g}")
    print(f"Combined, the {len(rows)} test objects (the fit object excluded), χ² and degrees of freedom summed: "
          + (results[0] if results[0] == results[1] else f"{results[0]} with every undecided labelling at its least "
             f"favourable, {results[1]} at its most favourable") + ".\n")


if __name__ == "__main__":
    sys.exit(main())
