#!/usr/bin/env python3
"""Runs the rest-pose studies quoted in docs/rest-poses.md and prints their tables (Markdown).

Usage: scripts/pose_tables.py [--repose build/release/apps/repose/repose] [-n 20000] [--threads 0]

1. A 64-segment cylinder (diameter 1) with h/d from 0.2 to 1.5: probability of resting on its side, by the
   dynamic and the exact quasi-static estimator, beside the non-bouncing coin value h/sqrt(h^2 + d^2)
   (Yong & Mahadevan, Am. J. Phys. 79:1195, 2011: fair three-way coin at h/d = 1/sqrt(8) = 0.354).
2. Box 1 x 2 x 3 and two irregular particles: every pose by both estimators, side by side, with its depth
   (barrier minus rest height: how much energy it takes to roll out of it), in units of L.
"""
import argparse
import json
import math
import subprocess
import sys


def poses(repose, particle, n, threads, extra=()):
    cmd = [repose, "poses", particle, "-n", str(n), "--threads", str(threads), "--json", "--no-progress", *extra]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def side_probability(result, key):
    return sum(p[key] for p in result["poses"] if abs(p["down_normal_body"][2]) < 0.5)


def side_interval(result):
    # Side poses are disjoint events, so their counts add; Wilson interval of the total.
    n = result["n"]
    k = sum(p["count"] for p in result["poses"] if abs(p["down_normal_body"][2]) < 0.5)
    z = 1.959963984540054
    phat = k / n
    centre = (phat + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(phat * (1 - phat) / n + z * z / (4 * n * n))
    return phat, max(0.0, centre - half), min(1.0, centre + half)


def cylinder_table(repose, n, threads):
    print("| h/d | side, dynamic (95 % interval) | side, quasi-static (exact) | h/sqrt(h^2+d^2) |")
    print("|---:|---:|---:|---:|")
    for ratio in (0.2, 0.3, 0.354, 0.4, 0.5, 0.6, 0.8, 1.0, 1.25, 1.5):
        r = poses(repose, f"cylinder:r=0.5,h={ratio},n=64", n, threads)
        p, lo, hi = side_interval(r)
        qs = side_probability(r, "quasi_static_probability")
        coin = ratio / math.sqrt(ratio * ratio + 1)
        print(f"| {ratio} | {p:.4f} ({lo:.4f}-{hi:.4f}) | {qs:.4f} | {coin:.4f} |")
        sys.stdout.flush()


def comparison_table(repose, particle, n, threads):
    r = poses(repose, particle, n, threads)
    print(f"\n`{particle}`: {r['n']} drops, {len(r['poses'])} stable faces, "
          f"{r['timing']['settles_per_second']:.0f} drops/s on {r['timing']['threads']} threads\n")
    length = r["particle"]["characteristic_length"]
    print("| pose | down normal (body) | COM height / L | depth / L | dynamic (95 % interval) | quasi-static (exact) |")
    print("|---:|---|---:|---:|---:|---:|")
    for p in r["poses"]:
        if p["count"] == 0 and p["quasi_static_probability"] < 1e-3:
            continue
        d = ", ".join(f"{x:.3f}" for x in p["down_normal_body"])
        depth = "-" if p["barrier"] is None else f"{(p['barrier'] - p['com_height']) / length:.4f}"
        print(f"| {p['pose']} | ({d}) | {p['com_height'] / length:.4f} | {depth} | {p['probability']:.4f} "
              f"({p['ci95'][0]:.4f}-{p['ci95'][1]:.4f}) | {p['quasi_static_probability']:.4f} |")
    sys.stdout.flush()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repose", default="build/release/apps/repose/repose")
    parser.add_argument("-n", type=int, default=20000)
    parser.add_argument("--threads", type=int, default=0)
    a = parser.parse_args()
    print(f"Cylinder, 64 segments, diameter 1, N = {a.n} per row\n")
    cylinder_table(a.repose, a.n, a.threads)
    for particle in ("box:x=1,y=2,z=3", "irregular:seed=3", "irregular:seed=7"):
        comparison_table(a.repose, particle, a.n, a.threads)


if __name__ == "__main__":
    main()
