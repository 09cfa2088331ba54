#!/usr/bin/python3
"""Landing frequencies of real dice against repose (docs/experiments.md, issue 14).

For each object with a mesh and measured counts in data/experiments/, runs `repose poses` three ways —
quasi-static, dynamic from rest (the paper's model, no rebound) and tossed with rebound — maps each rest pose
to the experiment's outcome by its body-frame down normal (the nearest of the authors' outcome normals, as
their own clustering does), and prints a Markdown table per object: measured frequency with its 95 % Wilson
interval, each prediction, and Pearson's chi-square p-value of the measured counts under each prediction.

Usage: scripts/experiments.py [--repose build/release/apps/repose/repose] [-n DROPS] [--threads T]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

from scipy import stats

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "data", "experiments", "baktash2025")

# One toss model for every object (not fitted to any): the experiments state no drop height, throw or
# material (docs/experiments.md). Lengths in L, speeds in sqrt(g*L), spins in sqrt(g/L).
TOSS = {"drop_height": 4.0, "velocity_max": 1.5, "spin_max": 1.5, "restitution": 0.5, "friction": 0.3}

# The 2d6 hendecahedra: outcomes are the sums 2..12 of two dice; the repository does not say which of two
# mirror-image faces is which sum (e.g. 6 or 8, both 5/36), so sums of equal designed probability are
# compared together: 7; 6 or 8; 5 or 9; 4 or 10; 3 or 11; 2 or 12.
SUMS = list(range(2, 13))


def sum_class(designed_probability):
    k = round(designed_probability * 36)  # 6 − |s − 7|
    return "7" if k == 6 else f"{7 - (6 - k)} or {7 + (6 - k)}"


OBJECTS = [
    # name in counts.csv, series, mesh, outcome normals, label; outcomes grouped by designed probability?
    ("binom2_3prism", "single", "Binom2__opt_test.obj", "Binom2__final_normal_probs.json", "3-sided prism (binom2)"),
    ("binom3_4prism", "wooden_surface(freq2)", "Binom3__opt_test.obj", "Binom3__final_normal_probs.json",
     "4-sided prism (binom3), wooden table"),
    ("binom4_5prism", "single", "Binom4__opt_test.obj", "Binom4__final_normal_probs.json", "5-sided prism (binom4)"),
    ("hendecahedron_2d6_design_v2", "series_V1(=SLA list in experiment_results.txt)",
     "2D6_hendecahedron_V1__opt_test.obj", "2D6_hendecahedron_V1__final_normal_probs.json",
     "2d6 hendecahedron, design v2, first series (SLA print)"),
    ("hendecahedron_2d6_design_v2", "series_V2", "2D6_hendecahedron_V1__opt_test.obj",
     "2D6_hendecahedron_V1__final_normal_probs.json", "2d6 hendecahedron, design v2, second series"),
    ("hendecahedron_2d6_design_v5", "single", "2D6_hendecahedron_V2__opt_test.obj",
     "2D6_hendecahedron_V2__final_normal_probs.json", "2d6 hendecahedron, design v5"),
]


def wilson(k, n, z=1.959963984540054):
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return max(0.0, c - h), min(1.0, c + h)


def run_poses(repose, mesh, args, drops, threads):
    cmd = [repose, "poses", mesh, "-n", str(drops), "--threads", str(threads), "--json"] + args
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def outcome_probabilities(result, normals):
    """Sums the poses' probabilities over the outcome whose normal is nearest each pose's down normal."""
    probs = [0.0] * len(normals)
    for pose in result["poses"]:
        d = pose["down_normal_body"]
        best = min(range(len(normals)), key=lambda i: sum((a - b) ** 2 for a, b in zip(d, normals[i])))
        probs[best] += pose["probability"]
    return probs


def p_value(counts, probs):
    """Pearson's chi-square goodness of fit (k − 1 degrees of freedom); predictions of 0 are floored at
    1e-6 so that a single count there gives a p-value of ~0 rather than a division by zero."""
    n = sum(counts)
    expected = [max(p, 1e-6) * n for p in probs]
    scale = n / sum(expected)
    expected = [e * scale for e in expected]
    chi2 = sum((c - e) ** 2 / e for c, e in zip(counts, expected))
    return stats.chi2.sf(chi2, len(counts) - 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repose", default=os.path.join(ROOT, "build", "release", "apps", "repose", "repose"))
    ap.add_argument("-n", "--drops", type=int, default=100000)
    ap.add_argument("--threads", type=int, default=0)
    a = ap.parse_args()
    counts = {}
    with open(os.path.join(DATA, "counts.csv")) as f:
        for row in csv.DictReader(f):
            counts.setdefault((row["object"], row["series"]), []).append(int(row["exp_sample_count"]))
    print(f"repose poses, {a.drops} drops per prediction; toss: {TOSS}\n")
    for name, series, mesh_file, normals_file, label in OBJECTS:
        mesh = os.path.join(DATA, "meshes", mesh_file)
        with open(os.path.join(DATA, "outcomes", normals_file)) as f:
            pairs = json.load(f)["pairs"]
        normals = [p["normal"] for p in pairs]
        measured = counts[(name, series)]
        labels = [str(i) for i in range(len(measured))]
        group = None  # outcome index → row, when outcomes are compared in groups
        if name.startswith("hendecahedron_2d6"):
            labels = ["7", "6 or 8", "5 or 9", "4 or 10", "3 or 11", "2 or 12"]
            grouped = [0] * len(labels)
            for s_, c in zip(SUMS, measured):
                grouped[labels.index(sum_class((6 - abs(s_ - 7)) / 36))] += c
            measured = grouped
            group = [labels.index(sum_class(p["probability"])) for p in pairs]
        n = sum(measured)
        quasi = run_poses(a.repose, mesh, ["--method", "quasi-static"], a.drops, a.threads)
        length, g = quasi["particle"]["characteristic_length"], 9.81
        rest = run_poses(a.repose, mesh, [], a.drops, a.threads)
        toss = run_poses(a.repose, mesh, [
            "--drop-height", repr(TOSS["drop_height"] * length),
            "--velocity-max", repr(TOSS["velocity_max"] * math.sqrt(g * length)),
            "--spin-max", repr(TOSS["spin_max"] * math.sqrt(g / length)),
            "--restitution", repr(TOSS["restitution"]), "--friction", repr(TOSS["friction"])], a.drops, a.threads)
        def regroup(probs):
            if group is None:
                return probs
            out = [0.0] * len(labels)
            for i, p in enumerate(probs):
                out[group[i]] += p
            return out

        predictions = [("quasi-static", regroup(outcome_probabilities(quasi, normals))),
                       ("dynamic, from rest (no rebound)", regroup(outcome_probabilities(rest, normals))),
                       ("tossed, with rebound", regroup(outcome_probabilities(toss, normals)))]
        print(f"### {label}: {n} throws\n")
        print("| outcome | measured | 95 % interval | " + " | ".join(p for p, _ in predictions) + " |")
        print("|---|---:|---|" + "---:|" * len(predictions))
        for i, c in enumerate(measured):
            lo, hi = wilson(c, n)
            print(f"| {labels[i]} | {c / n:.3f} ({c}) | [{lo:.3f}, {hi:.3f}] | " +
                  " | ".join(f"{probs[i]:.3f}" for _, probs in predictions) + " |")
        print("| χ² p-value | | | " + " | ".join(f"{p_value(measured, probs):.3g}" for _, probs in predictions)
              + " |\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
