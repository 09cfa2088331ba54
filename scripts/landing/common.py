"""What every experiment set shares: running `repose poses`, the toss model, the statistics of a table."""
import collections
import itertools
import json
import math
import subprocess

from scipy import stats

# One toss model for every object: the experiments state no drop height or throw (docs/experiments.md).
# Lengths in L, speeds in sqrt(g*L), spins in sqrt(g/L). restitution and friction are set by the fit on one
# object (scripts/experiments.py --fit) or by --toss, and then used unchanged for every object.
TOSS = {"drop_height": 4.0, "velocity_max": 1.5, "spin_max": 1.5, "restitution": 0.5, "friction": 0.3}
G = 9.81  # m/s^2: repose's default units (si)


def toss_args(length, restitution, friction, g=G):
    """`repose poses` options of the toss model for a particle of characteristic length `length`."""
    return ["--drop-height", repr(TOSS["drop_height"] * length),
            "--velocity-max", repr(TOSS["velocity_max"] * math.sqrt(g * length)),
            "--spin-max", repr(TOSS["spin_max"] * math.sqrt(g / length)),
            "--restitution", repr(restitution), "--friction", "inf" if math.isinf(friction) else repr(friction)]


_RUNS = {}


def run_poses(repose, particle, args, drops, threads):
    """`repose poses` on `particle` (a mesh path or shape spec); each distinct run once: series share a die."""
    cmd = [repose, "poses", particle, "-n", str(drops), "--threads", str(threads), "--json"] + args
    key = tuple(cmd)
    if key not in _RUNS:
        _RUNS[key] = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    return _RUNS[key]


def three_predictions(a, particle, extra, drops):
    """The quasi-static, from-rest and tossed runs of one particle (tossed None with --no-toss)."""
    quasi = run_poses(a.repose, particle, extra + ["--method", "quasi-static"], drops, a.threads)
    length = quasi["particle"]["characteristic_length"]
    rest = run_poses(a.repose, particle, extra, drops, a.threads)
    toss = None if a.no_toss else run_poses(
        a.repose, particle, extra + toss_args(length, TOSS["restitution"], TOSS["friction"]),
        a.toss_drops or drops, a.threads)
    return quasi, rest, toss


def nearest(direction, normals):
    """Index of the outcome normal nearest `direction` (the authors' clustering rule, Baktash et al.)."""
    return min(range(len(normals)), key=lambda i: sum((a - b) ** 2 for a, b in zip(direction, normals[i])))


def outcome_probabilities(result, normals, key="probability"):
    """Sums the poses' probabilities over the outcome whose normal is nearest each pose's down normal."""
    probs = [0.0] * len(normals)
    for pose in result["poses"]:
        probs[nearest(pose["down_normal_body"], normals)] += pose[key]
    return probs


def wilson(k, n, z=1.959963984540054):
    """95 % Wilson score interval of a binomial proportion k / n."""
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return max(0.0, c - h), min(1.0, c + h)


def chi2_statistic(counts, probs, drops=math.inf):
    """Pearson's chi-square of `counts` under `probs`, each term divided by (1 + n/N) for a prediction estimated
    from N = `drops` simulated drops (math.inf: an exact prediction, plain Pearson).

    Why: p̂ from N drops has variance p(1 − p)/N, so with c the count of n throws (independent of p̂)
    Var(c − n·p̂) = n·p(1 − p) + n²·p(1 − p)/N, whose diagonal approximation — the one Pearson's denominator
    n·p makes for an exact p — is n·p + n²·p/N = n·p·(1 + n/N): the statistic is Σ (c − n·p̂)² / (n·p̂·(1 + n/N)).
    (The whole covariance of c − n·p̂ is (1 + n/N) times the multinomial one, so it stays χ² with k − 1 degrees
    of freedom for large n.) Predictions of 0 are floored at 1e-6 so that a count there gives a p-value of ~0
    rather than a division by zero."""
    n = sum(counts)
    expected = [max(p, 1e-6) * n for p in probs]
    scale = n / sum(expected)
    expected = [e * scale for e in expected]
    inflation = 1 + n / drops
    return sum((c - e) ** 2 / (e * inflation) for c, e in zip(counts, expected))


def pool_small_expected(counts, probs, minimum=5.0):
    """Merges categories whose expected count is below `minimum` — the smallest expected into the next-smallest,
    again and again — until every pooled expected count is ≥ `minimum` or only 2 categories are left: χ² is
    not near its distribution with small expected counts. Returns the pooled counts, the pooled probabilities
    and the groups (lists of the original indices), in the order of each group's first index."""
    n, total = sum(counts), sum(probs)
    groups = [[i] for i in range(len(counts))]

    def expected(g):
        return n * sum(probs[i] for i in g) / total if total > 0 else 0.0

    while len(groups) > 2:
        ranked = sorted(groups, key=lambda g: (expected(g), g[0]))
        if expected(ranked[0]) >= minimum:
            break
        groups.remove(ranked[0])
        groups.remove(ranked[1])
        groups.append(sorted(ranked[0] + ranked[1]))
    groups.sort()
    return ([sum(counts[i] for i in g) for g in groups], [sum(probs[i] for i in g) for g in groups], groups)


def dof(k, fitted=0):
    """Degrees of freedom of a χ² over k (pooled) categories: one is taken by the fixed number of throws, one
    more by every parameter fitted on these same counts (E and μ: 2 on the fit object, 0 elsewhere)."""
    return k - 1 - fitted


# A goodness of fit: the statistic, its degrees of freedom, the p-value (nan with no degree of freedom left),
# the pooled groups of the original categories and the smallest pooled expected count.
Fit = collections.namedtuple("Fit", "chi2 dof p groups min_expected")


def goodness_of_fit(counts, probs, drops=math.inf, fitted=0):
    """χ² of `counts` under a prediction `probs` of `drops` drops: small expected counts pooled, the prediction's
    Monte-Carlo error counted, `fitted` parameters taken off the degrees of freedom."""
    pooled_counts, pooled_probs, groups = pool_small_expected(counts, probs)
    chi2 = chi2_statistic(pooled_counts, pooled_probs, drops)
    d = dof(len(groups), fitted)
    n, total = sum(counts), sum(probs)
    min_expected = min(n * p / total for p in pooled_probs) if total > 0 else 0.0
    return Fit(chi2, d, stats.chi2.sf(chi2, d) if d > 0 else math.nan, groups, min_expected)


def p_value(counts, probs, drops=math.inf, fitted=0):
    """The p-value of goodness_of_fit (k − 1 − fitted degrees of freedom over the pooled k)."""
    return goodness_of_fit(counts, probs, drops, fitted).p


def format_p(fit, digits=3):
    """A table cell: the p-value, or a dash when fitting left no degree of freedom."""
    return f"— ({fit.dof} dof)" if math.isnan(fit.p) else f"{fit.p:.{digits}g}"


def holm(pvalues):
    """Holm–Bonferroni adjusted p-values, in the order given: the i-th smallest p times (m − i + 1), made
    non-decreasing in p and capped at 1. A hypothesis is rejected at level α iff its adjusted p ≤ α, which
    keeps the chance of any false rejection among the m tests ≤ α."""
    m = len(pvalues)
    adjusted, running = [0.0] * m, 0.0
    for rank, i in enumerate(sorted(range(m), key=lambda i: pvalues[i])):
        running = max(running, min(1.0, (m - rank) * pvalues[i]))
        adjusted[i] = running
    return adjusted


def tied_labellings(exact, theirs, tolerance=1e-6):
    """The labellings (perm: label j is outcome normal perm[j]) that match repose's quasi-static probabilities
    `exact` to the authors' `theirs` as well as the best one does, as far as the authors' rounding can tell:
    a squared distance within `tolerance` of the best's, or a reassignment only among labels whose authors'
    values are equal. The best first."""
    k = len(theirs)
    perms = list(itertools.permutations(range(len(exact))))
    distance = {perm: sum((exact[perm[j]] - theirs[j]) ** 2 for j in range(k)) for perm in perms}
    best = min(perms, key=distance.get)

    def among_equal(perm):
        return all(theirs[best.index(perm[j])] == theirs[j] for j in range(k))

    return sorted((perm for perm in perms if distance[perm] <= distance[best] + tolerance or among_equal(perm)),
                  key=lambda perm: (perm != best, distance[perm]))


def fits_note(names, fits, drops, labels, fitted_reason=""):
    """The line under a table: each prediction's Monte-Carlo drops, degrees of freedom and pooled outcomes."""
    pooled = [f"{name} " + ", ".join("{" + ", ".join(labels[i] for i in g) + "}" for g in f.groups if len(g) > 1)
              for name, f in zip(names, fits) if any(len(g) > 1 for g in f.groups)]
    small = [f"{name} ({f.min_expected:.1f})" for name, f in zip(names, fits) if f.min_expected < 5]
    return (f"χ² with each prediction's Monte-Carlo error (N = {' / '.join(str(d) for d in drops)} drops): "
            f"{' / '.join(str(f.dof) for f in fits)} degrees of freedom{fitted_reason}; "
            + (f"expected counts below 5 pooled: {'; '.join(pooled)}" if pooled else "no expected count below 5")
            + (f"; still below 5 with only 2 categories left: {', '.join(small)}" if small else "") + ".\n")


# An object tested by the tossed model, for the Holm table: its row label, its Fits (one per labelling the
# authors' values cannot tell apart), whether E and μ were fitted on it, and a mark for the table's notes.
Tested = collections.namedtuple("Tested", "label fits fitted mark")


def unrested_note(runs):
    """A line naming drops that hit a limit (none expected), or ''."""
    unrested = [r["n"] - r["status_counts"]["rest"] for r in runs if r is not None]
    return f"(drops not at rest within the limits, from rest and tossed: {unrested})\n" if any(unrested) else ""
