"""What every experiment set shares: running `repose poses`, the toss model, the statistics of a table."""
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


def chi2_statistic(counts, probs):
    """Pearson's chi-square of `counts` under `probs`; predictions of 0 are floored at 1e-6 so that a single
    count there gives a p-value of ~0 rather than a division by zero."""
    n = sum(counts)
    expected = [max(p, 1e-6) * n for p in probs]
    scale = n / sum(expected)
    expected = [e * scale for e in expected]
    return sum((c - e) ** 2 / e for c, e in zip(counts, expected))


def p_value(counts, probs):
    """Pearson's chi-square goodness of fit (k − 1 degrees of freedom)."""
    return stats.chi2.sf(chi2_statistic(counts, probs), len(counts) - 1)


def unrested_note(runs):
    """A line naming drops that hit a limit (none expected), or ''."""
    unrested = [r["n"] - r["status_counts"]["rest"] for r in runs if r is not None]
    return f"(drops not at rest within the limits, from rest and tossed: {unrested})\n" if any(unrested) else ""
