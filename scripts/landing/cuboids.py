"""Square cuboidal steel dice (Budden 1980, data/experiments/budden1980): how often a square face lands."""
import csv
import os

from scipy import stats

from . import common

DATA = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                    "data", "experiments", "budden1980")
SQUARE = [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]  # body-frame normals of the square faces of box:x=1,y=1,z=R


def load():
    """The dice: (x/y, throws, square-face count). The count is the one integer k with round(k/N, 3) equal to
    the published p (the table prints p, not k)."""
    dice = []
    with open(os.path.join(DATA, "counts.csv")) as f:
        for row in csv.DictReader(f):
            n, p = int(row["throws"]), float(row["p_published"])
            ks = [k for k in range(n + 1) if round(k / n, 3) == p]
            if len(ks) != 1:
                raise SystemExit(f"{DATA}/counts.csv: die {row['die']}: {len(ks)} counts give p = {p} of {n}")
            dice.append((float(row["x_over_y"]), n, ks[0]))
    return dice


def square_probability(result):
    """Probability that the die rests on a square face (its down normal is ±z)."""
    return sum(pose["probability"] for pose in result["poses"]
               if max(sum(a * b for a, b in zip(pose["down_normal_body"], s)) for s in SQUARE) > 0.99)


def table(a):
    """The dice's table; returns the tossed model's common.Tested of each die (none with --no-toss)."""
    dice = load()
    names = ["quasi-static", "dynamic, from rest (no rebound)"] + ([] if a.no_toss else ["tossed, with rebound"])
    print(f"### Square cuboidal steel dice (Budden 1980): {len(dice)} dice, {sum(n for _, n, _ in dice)} rolls\n")
    print("p: the fraction of rolls ending on one of the two square faces. Each prediction's χ² p-value "
          "(1 degree of freedom, the prediction's Monte-Carlo error counted) in brackets.\n")
    print("| x/y | rolls | measured p (count) | 95 % interval | " + " | ".join(names) + " |")
    print("|---:|---:|---:|---|" + "---:|" * len(names))
    total, dofs, drops, small, notes, tested = [0.0] * len(names), [0] * len(names), [0] * len(names), [], [], []
    for ratio, n, k in dice:
        runs = [r for r in common.three_predictions(a, f"box:x=1,y=1,z={ratio:g}", [], a.drops) if r is not None]
        lo, hi = common.wilson(k, n)
        cells = []
        for j, r in enumerate(runs):
            p = square_probability(r)
            fit = common.goodness_of_fit([k, n - k], [p, 1 - p], r["n"])
            total[j] += fit.chi2
            dofs[j] += fit.dof
            drops[j] = r["n"]
            if fit.min_expected < 5:
                small.append(f"{names[j]} at x/y {ratio:.2f} ({fit.min_expected:.1f})")
            cells.append(f"{p:.3f} ({common.format_p(fit, 2)})")
        print(f"| {ratio:.2f} | {n} | {k / n:.3f} ({k}) | [{lo:.3f}, {hi:.3f}] | " + " | ".join(cells) + " |")
        notes.append(common.unrested_note(runs[1:]))
        if not a.no_toss:
            tested.append(common.Tested(f"steel die x/y = {ratio:.2f} (Budden 1980)", [fit], False, ""))
    dof = " / ".join(str(d) for d in dofs) if len(set(dofs)) > 1 else str(dofs[0])
    print(f"| all {len(dice)} | | χ² ({dof} degrees of freedom), p-value | | " +
          " | ".join(f"{t:.1f}, {stats.chi2.sf(t, d):.2g}" for t, d in zip(total, dofs)) + " |\n")
    print(f"χ² with each prediction's Monte-Carlo error (N = {' / '.join(str(d) for d in drops)} drops): 1 degree "
          "of freedom per die (2 outcomes, nothing fitted on these dice); two outcomes cannot be pooled"
          + (f", expected counts below 5: {', '.join(small)}" if small else ", no expected count below 5") + ".\n")
    print("".join(notes), end="")
    return tested
