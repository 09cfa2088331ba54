"""The printed dice of Baktash et al. 2025 (data/experiments/baktash2025): one table per object and series."""
import csv
import itertools
import json
import math
import os

from . import common

DATA = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                    "data", "experiments", "baktash2025")

# The 2d6 hendecahedra: outcomes are the sums 2..12 of two dice; the repository does not say which of two
# mirror-image faces is which sum (e.g. 6 or 8, both 5/36), so sums of equal designed probability are
# compared together: 7; 6 or 8; 5 or 9; 4 or 10; 3 or 11; 2 or 12.
SUMS = list(range(2, 13))
SUM_CLASSES = ["7", "6 or 8", "5 or 9", "4 or 10", "3 or 11", "2 or 12"]


def sum_class(designed_probability):
    k = round(designed_probability * 36)  # 6 − |s − 7|
    return "7" if k == 6 else f"{7 - (6 - k)} or {7 + (6 - k)}"


# The d3 dice and the d6 bunny (non-convex, their centre of mass moved by the authors' design): only their
# convex hulls and centres of mass are in the repository as text (data/experiments/baktash2025/README.md),
# which is all that settling on a table needs but the inertia (taken as the uniform hull's about that centre,
# --com). Which die face is which outcome label is not stated: for the d3 dice the label of each outcome
# normal is inferred by matching repose's exact quasi-static probabilities to the authors' own quasi-static
# column ("Ours", the same method) over all permutations (LABELS_FROM_OURS). The bunny has no outcome normals
# and its six quasi-static probabilities are all within 0.013 of 1/6, so no labelling can be inferred; it is
# compared without labels (bunny_table).
MESH_OPTIONS = {
    "D3_kitten__opt_test.obj": ["--com", "0.0197607689,0.0421846323,0.0115263518"],
    "good_armadilo0_G_deform__hull_final_armadilo_d3.obj": ["--com", "0,0,0"],
    "good_rgb_dragon_d3_out__hull_rgb_dragon_d3.obj": ["--com", "0,0,0"],
    "nonconvex_deformation__bunny_d6.obj": ["--com", "0.0482910499,-0.0509713218,0.02014821717"],
}
LABELS_FROM_OURS = {"kitten_d3", "armadillo_d3", "xyz_rgb_dragon_d3"}

OBJECTS = [
    # name in counts.csv, series, mesh, outcome normals, label
    ("binom2_3prism", "single", "Binom2__opt_test.obj", "Binom2__final_normal_probs.json", "3-sided prism (binom2)"),
    ("binom3_4prism", "wooden_surface(freq2)", "Binom3__opt_test.obj", "Binom3__final_normal_probs.json",
     "4-sided prism (binom3), wooden table"),
    ("binom3_4prism", "stone_surface(freq1)", "Binom3__opt_test.obj", "Binom3__final_normal_probs.json",
     "4-sided prism (binom3), stone surface"),
    ("binom4_5prism", "single", "Binom4__opt_test.obj", "Binom4__final_normal_probs.json", "5-sided prism (binom4)"),
    ("hendecahedron_2d6_design_v2", "series_V1(=SLA list in experiment_results.txt)",
     "2D6_hendecahedron_V1__opt_test.obj", "2D6_hendecahedron_V1__final_normal_probs.json",
     "2d6 hendecahedron, design v2, first series (SLA print)"),
    ("hendecahedron_2d6_design_v2", "series_V2", "2D6_hendecahedron_V1__opt_test.obj",
     "2D6_hendecahedron_V1__final_normal_probs.json", "2d6 hendecahedron, design v2, second series"),
    ("hendecahedron_2d6_design_v2", "FDM", "2D6_hendecahedron_V1__opt_test.obj",
     "2D6_hendecahedron_V1__final_normal_probs.json", "2d6 hendecahedron, design v2, FDM print"),
    ("hendecahedron_2d6_design_v2", "F170", "2D6_hendecahedron_V1__opt_test.obj",
     "2D6_hendecahedron_V1__final_normal_probs.json", "2d6 hendecahedron, design v2, F170 print"),
    ("hendecahedron_2d6_design_v2", "SLS", "2D6_hendecahedron_V1__opt_test.obj",
     "2D6_hendecahedron_V1__final_normal_probs.json", "2d6 hendecahedron, design v2, SLS print"),
    ("hendecahedron_2d6_design_v5", "single", "2D6_hendecahedron_V2__opt_test.obj",
     "2D6_hendecahedron_V2__final_normal_probs.json", "2d6 hendecahedron, design v5"),
    ("kitten_d3", "single", "D3_kitten__opt_test.obj", "D3_kitten__final_normal_probs.json",
     "kitten d3 (convex hull and centre of mass only)"),
    ("armadillo_d3", "single", "good_armadilo0_G_deform__hull_final_armadilo_d3.obj",
     "D3_armadillo__final_normal_probs.json", "armadillo d3 (convex hull and centre of mass only)"),
    ("xyz_rgb_dragon_d3", "single", "good_rgb_dragon_d3_out__hull_rgb_dragon_d3.obj",
     "D3_dragon__final_normal_probs.json", "dragon d3 (convex hull and centre of mass only)"),
]
BUNNY = ("bunny_d6", "single", "nonconvex_deformation__bunny_d6.obj", "bunny d6 (convex hull and centre of mass only)")


def load_counts():
    """(object, series) → measured counts and the authors' quasi-static column, in outcome order."""
    counts, theirs = {}, {}
    with open(os.path.join(DATA, "counts.csv")) as f:
        for row in csv.DictReader(f):
            counts.setdefault((row["object"], row["series"]), []).append(int(row["exp_sample_count"]))
            theirs.setdefault((row["object"], row["series"]), []).append(float(row["Ours"] or "nan"))
    return counts, theirs


def mesh_and_normals(mesh_file, normals_file):
    with open(os.path.join(DATA, "outcomes", normals_file)) as f:
        pairs = json.load(f)["pairs"]
    return os.path.join(DATA, "meshes", mesh_file), MESH_OPTIONS.get(mesh_file, []), pairs


def fit_key(name):
    """(object, series) of the counts a fit on `name` uses: its first series in OBJECTS (None: no such object)."""
    return next(((o[0], o[1]) for o in OBJECTS if o[0] == name), None)


# The grid of the fit: restitution E (Stronge's energetic coefficient) and friction mu (inf: no slip).
FIT_E = [0.1, 0.3, 0.5, 0.7, 0.9, 0.95]
FIT_MU = [0.1, 0.3, 0.6, 1.0, math.inf]


def fit(a, counts):
    """Fits E and mu on one object by the multinomial likelihood of its counts over the grid, and sets
    common.TOSS["restitution"], common.TOSS["friction"] to the best point."""
    name, series, mesh_file, normals_file, label = next(o for o in OBJECTS if o[0] == a.fit)
    mesh, extra, pairs = mesh_and_normals(mesh_file, normals_file)
    normals = [p["normal"] for p in pairs]
    measured = counts[(name, series)]
    length = common.run_poses(a.repose, mesh, extra + ["--method", "quasi-static"], 1, a.threads)["particle"][
        "characteristic_length"]
    print(f"Fit of E and mu on {label} ({sum(measured)} throws), {a.fit_drops} drops per point: "
          "log-likelihood of the counts (higher is better), chi-square p-value (of that one point: k − 1 degrees "
          "of freedom, expected counts below 5 pooled, the point's Monte-Carlo error counted)\n")
    print("| E \\ mu | " + " | ".join("inf" if math.isinf(m) else f"{m:g}" for m in FIT_MU) + " |")
    print("|---|" + "---:|" * len(FIT_MU))
    best = None
    for e in FIT_E:
        row = []
        for mu in FIT_MU:
            r = common.run_poses(a.repose, mesh, extra + common.toss_args(length, e, mu), a.fit_drops, a.threads)
            probs = common.outcome_probabilities(r, normals)
            loglik = sum(c * math.log(max(p, 1e-6)) for c, p in zip(measured, probs))
            row.append(f"{loglik:.1f}, {common.format_p(common.goodness_of_fit(measured, probs, r['n']), 2)}")
            if best is None or loglik > best[0]:
                best = (loglik, e, mu)
        print(f"| {e:g} | " + " | ".join(row) + " |")
    common.TOSS["restitution"], common.TOSS["friction"] = best[1], best[2]
    print(f"\nBest: E = {best[1]:g}, mu = {best[2]:g}; used unchanged for every object below.\n")


def print_table(label, labels, measured, predictions, fitted_reason=""):
    """One object's table; `predictions` are (name, probabilities by label, drops, parameters fitted on these
    counts). Returns each prediction's Fit."""
    n = sum(measured)
    fits = [common.goodness_of_fit(measured, probs, drops, fitted) for _, probs, drops, fitted in predictions]
    print(f"### {label}: {n} throws\n")
    print("| outcome | measured | 95 % interval | " + " | ".join(p[0] for p in predictions) + " |")
    print("|---|---:|---|" + "---:|" * len(predictions))
    for i, c in enumerate(measured):
        lo, hi = common.wilson(c, n)
        print(f"| {labels[i]} | {c / n:.3f} ({c}) | [{lo:.3f}, {hi:.3f}] | " +
              " | ".join(f"{p[1][i]:.3f}" for p in predictions) + " |")
    print("| χ² p-value | | | " + " | ".join(common.format_p(f) for f in fits) + " |\n")
    print(common.fits_note([p[0] for p in predictions], fits, [p[2] for p in predictions], labels, fitted_reason))
    return fits


def labelled_tables(a, counts, theirs):
    """The tables of the labelled objects; returns the tossed model's common.Tested of each (none with
    --no-toss). `a.fitted_on`: the (object, series) whose counts E and μ were fitted on, or None."""
    tested = []
    for name, series, mesh_file, normals_file, label in OBJECTS:
        if a.only and name not in a.only.split(","):
            continue
        mesh, extra, pairs = mesh_and_normals(mesh_file, normals_file)
        normals = [p["normal"] for p in pairs]
        measured = counts[(name, series)]
        labels = [str(i) for i in range(len(measured))]
        orders = [list(range(len(normals)))]  # under labelling o, row i of the table is outcome normal o[i]
        if name.startswith("hendecahedron_2d6"):
            labels = SUM_CLASSES
            grouped = [0] * len(labels)
            for s_, c in zip(SUMS, measured):
                grouped[labels.index(sum_class((6 - abs(s_ - 7)) / 36))] += c
            measured = grouped
        quasi, rest, toss = common.three_predictions(a, mesh, extra, a.drops)

        def rows(probs, order, name=name, pairs=pairs):
            if name.startswith("hendecahedron_2d6"):  # the normals' sums, grouped by designed probability
                out = [0.0] * len(SUM_CLASSES)
                for p, pair in zip(probs, pairs):
                    out[SUM_CLASSES.index(sum_class(pair["probability"]))] += p
                return out
            return [probs[k] for k in order]

        def label_list(order, normals=normals):
            return [order.index(i) + 1 for i in range(len(normals))]

        if name in LABELS_FROM_OURS:
            labels = [str(i + 1) for i in range(len(measured))]
            exact = common.outcome_probabilities(quasi, normals, "quasi_static_probability")
            ours = theirs[(name, series)]
            orders = [list(o) for o in common.tied_labellings(exact, ours)]
            tie = (f"; {len(orders)} labellings tie within the authors' rounding: "
                   + " / ".join(str(label_list(o)) for o in orders)) if len(orders) > 1 else ""
            print(f"{label}: outcome normals → labels {label_list(orders[0])} "
                  f"(repose quasi-static {[round(exact[k], 4) for k in orders[0]]}, the authors' {ours}){tie}\n")
        fitted = 2 if toss is not None and a.fitted_on == (name, series) else 0
        runs = [("quasi-static", quasi, 0), ("dynamic, from rest (no rebound)", rest, 0)]
        if toss is not None:
            runs.append(("tossed, with rebound", toss, fitted))

        def predictions(order, normals=normals):
            return [(p, rows(common.outcome_probabilities(r, normals), order), r["n"], f) for p, r, f in runs]

        reason = " (tossed: k − 1 − 2, E and μ were fitted on these counts)" if fitted else ""
        fits = print_table(label, labels, measured, predictions(orders[0]), reason)
        every = [fits] + [[common.goodness_of_fit(measured, probs, drops, f) for _, probs, drops, f in predictions(o)]
                          for o in orders[1:]]
        if len(orders) > 1:
            print(f"p-values under the {len(orders)} labellings the authors' values cannot tell apart (labels "
                  + " / ".join(str(label_list(o)) for o in orders) + "): "
                  + "; ".join(f"{p} " + " / ".join(common.format_p(fs[j]) for fs in every)
                              for j, (p, _, _) in enumerate(runs)) + ".\n")
        print(common.unrested_note((rest, toss)), end="")
        if toss is not None:
            tested.append(common.Tested(label, [fs[-1] for fs in every], bool(fitted), "*" if len(orders) > 1 else ""))
    return tested


def bunny_table(a, counts):
    """The d6 bunny, compared without labels: the repository gives no outcome normals for it, and its six
    outcomes' quasi-static probabilities are all within 0.013 of 1/6, so which measured column is which face
    cannot be inferred. Its outcomes are the hull's six stable faces of non-negligible basin (a seventh has
    0.0005 and joins the nearest, the authors' clustering rule). Each column is sorted from most to least
    likely, and the p-value is that of the most favourable of the 720 labellings: an upper bound, so a
    rejection holds under every labelling, and an acceptance says only that some labelling fits."""
    name, series, mesh_file, label = BUNNY
    mesh, extra = os.path.join(DATA, "meshes", mesh_file), MESH_OPTIONS[mesh_file]
    measured = counts[(name, series)]
    quasi, rest, toss = common.three_predictions(a, mesh, extra, a.drops)
    poses = sorted(quasi["poses"], key=lambda p: -p["quasi_static_probability"])
    normals = [p["down_normal_body"] for p in poses[:len(measured)]]
    columns = [("quasi-static", common.outcome_probabilities(quasi, normals)),
               ("dynamic, from rest (no rebound)", common.outcome_probabilities(rest, normals))]
    if toss is not None:
        columns.append(("tossed, with rebound", common.outcome_probabilities(toss, normals)))
    n = sum(measured)
    print(f"### {label}: {n} throws, compared without labels\n")
    print("| rank | measured | 95 % interval | " + " | ".join(c for c, _ in columns) + " |")
    print("|---|---:|---|" + "---:|" * len(columns))
    sorted_measured = sorted(measured, reverse=True)
    sorted_columns = [sorted(probs, reverse=True) for _, probs in columns]
    for i, c in enumerate(sorted_measured):
        lo, hi = common.wilson(c, n)
        print(f"| {i + 1} | {c / n:.3f} ({c}) | [{lo:.3f}, {hi:.3f}] | " +
              " | ".join(f"{probs[i]:.3f}" for probs in sorted_columns) + " |")
    drops = [r["n"] for r in (quasi, rest, toss) if r is not None]
    best = [max((common.goodness_of_fit(measured, [probs[k] for k in perm], d)
                 for perm in itertools.permutations(range(len(measured)))), key=lambda f: f.p)
            for (_, probs), d in zip(columns, drops)]
    print("| χ² p-value, most favourable labelling | | | " + " | ".join(common.format_p(f) for f in best) + " |\n")
    print("Under the most favourable labelling: "
          + common.fits_note([c for c, _ in columns], best, drops, [str(i + 1) for i in range(len(measured))]))
    print(common.unrested_note((rest, toss)), end="")
    return [common.Tested(label, [best[-1]], False, "†")] if toss is not None else []
