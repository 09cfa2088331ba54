"""Yade's column beside repose's and Bullet's in the peer benchmark (docs/performance.md, "Yade as a peer").

  python3 scripts/dem/peer_table.py EXPORT.json YADE.json

EXPORT.json: `repose_peer_bullet --export` (repose's and Bullet's answers, Bullet at its chosen step);
YADE.json: scripts/dem/yade_peer.py (Yade at each of its candidate steps). Yade's step is chosen per shape as
Bullet's is (bench/peers/bullet_steps.hpp, ported here): the largest step whose rest-pose histogram (the poses
and "no rest") agrees with its finest step's, and whose count of drops at rest does too, by a permutation test
of homogeneity (Pearson's chi-square, 10,000 seeded permutations) at p >= 0.05. Prints Yade's steps, then the
three engines side by side, then each shape's rest-pose histograms.
"""
import json
import random
import sys

AGREEMENT_LEVEL = 0.05
PERMUTATIONS = 10000


def chi2(a, b):
    return sum((x - y) ** 2 / (x + y) for x, y in zip(a, b) if x + y > 0)


def homogeneity(a, b):
    """Pearson's chi-square of two histograms of one total N and its permutation p-value."""
    statistic = chi2(a, b)
    outcomes = [i for i in range(len(a)) for _ in range(a[i] + b[i])]
    if sum(1 for x, y in zip(a, b) if x + y > 0) < 2:
        return statistic, 1.0
    n = len(outcomes) // 2
    rng = random.Random(20261128)
    as_large = 0
    for _ in range(PERMUTATIONS):
        rng.shuffle(outcomes)
        x, y = [0] * len(a), [0] * len(a)
        for i, o in enumerate(outcomes):
            (x if i < n else y)[o] += 1
        as_large += chi2(x, y) >= statistic - 1e-9
    return statistic, (1.0 + as_large) / (1.0 + PERMUTATIONS)


def rest_or_not(h):
    return [sum(h[:-1]), h[-1]]


def histogram(run, poses):
    h = [0] * (poses + 1)  # last bin: no rest
    for d in run["drops"]:
        h[d["pose"] if d["pose"] >= 0 else poses] += 1
    return h


def main():
    exported = json.load(open(sys.argv[1]))
    yade = json.load(open(sys.argv[2]))
    rows = []
    print("Yade's step per shape: its rest-pose histogram against its finest step's (chi-square homogeneity by "
          "permutation; the chosen step is the largest with p >= %.2f, for the poses and for at rest or not)\n"
          % AGREEMENT_LEVEL)
    print("| shape | step (s) | Yade ms/settle | simulated s/settle | max depth of a hull vertex (L) | no rest | "
          "off a stable face | chi-square | p | p, at rest or not | chosen |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for shape in exported["shapes"]:
        runs = yade["shapes"].get(shape["name"])
        if not runs:
            continue
        poses = len(shape["pose_down_normals"])
        drops = len(shape["drops"])
        hists = [histogram(run, poses) for run in runs]
        tests = [(homogeneity(h, hists[-1]), homogeneity(rest_or_not(h), rest_or_not(hists[-1]))) for h in hists]
        chosen = next((i for i, (t, r) in enumerate(tests) if t[1] >= AGREEMENT_LEVEL and r[1] >= AGREEMENT_LEVEL),
                      len(runs) - 1)
        for i, run in enumerate(runs):
            d = run["drops"]
            print("| %s | %g | %.1f | %.2f | %.1e | %d | %d | %.1f | %.3g | %.3g | %s |" % (
                shape["name"], run["step"], 1e3 * run["wall_seconds"] / drops, sum(x["time"] for x in d) / drops,
                max(x["depth"] for x in d) / shape["length"], sum(not x["rested"] for x in d),
                sum(x["off_face"] for x in d), tests[i][0][0], tests[i][0][1], tests[i][1][1],
                "yes" if i == chosen else ""))
        rows.append((shape, runs[chosen], hists[chosen], poses, drops))

    print("\nThe three engines, the same drops (one thread each; Yade at its chosen step, each drop in a scene of "
          "its own)\n")
    print("| shape | hull vertices | L (m) | drops | repose ms/settle | Bullet step | Bullet ms/settle | Bullet max "
          "depth (L) | Yade step | Yade ms/settle | Yade / repose | Yade / Bullet | Yade set-up ms/drop | Yade max depth (L) | "
          "Yade no rest / off a stable face | same pose as repose: Bullet, Yade | Yade mass / repose's |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for shape, run, hist, poses, drops in rows:
        r, b = shape["repose"], shape["bullet"]
        yade_ms = 1e3 * run["wall_seconds"] / drops
        same = sum(d["pose"] == s["repose_pose"] for d, s in zip(run["drops"], shape["drops"]))
        print("| %s | %d | %.3f | %d | %.3f | 1/%.0f s | %.3f | %.1e | %g s | %.1f | %.0f | %.0f | %.2f | %.1e | %d / %d | "
              "%d %%, %d %% | %.6f |" % (
                  shape["name"], len(shape["hull_vertices"]), shape["length"], drops, r["ms_per_settle"],
                  1 / b["step"], b["ms_per_settle"], b["max_depth_L"], run["step"], yade_ms,
                  yade_ms / r["ms_per_settle"], yade_ms / b["ms_per_settle"], 1e3 * run["setup_seconds"] / drops,
                  max(d["depth"] for d in run["drops"]) / shape["length"], sum(not d["rested"] for d in run["drops"]),
                  sum(d["off_face"] for d in run["drops"]), 100 * b["same_pose_as_repose"] // drops,
                  100 * same // drops, run["yade_mass"] / shape["mass"]))

    for shape, run, hist, poses, drops in rows:
        print("\n%s: rest poses (repose catalogue; the final down direction -> nearest hull face -> its pose)\n"
              % shape["name"])
        print("| pose | down normal (body) | repose | Bullet %g s | Yade %g s |" % (shape["bullet"]["step"], run["step"]))
        print("|---:|---|---:|---:|---:|")
        r, b = shape["repose"]["histogram"], shape["bullet"]["histogram"]
        for p in sorted(range(poses + 1), key=lambda p: -(r[p] + b[p] + hist[p])):
            if r[p] + b[p] + hist[p] == 0:
                continue
            label = "no rest | " if p == poses else "%d | (%+.3f, %+.3f, %+.3f)" % ((p,) + tuple(
                shape["pose_down_normals"][p]))
            print("| %s | %d | %d | %d |" % (label, r[p], b[p], hist[p]))
        statistic, p = homogeneity(hist, r)
        print("\nYade against repose: chi-square %.1f, permutation p = %.3g" % (statistic, p))


if __name__ == "__main__":
    main()
