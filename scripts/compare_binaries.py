#!/usr/bin/python3
"""Two repose binaries, the same tosses: do they give the same rest-pose statistics?

usage: scripts/compare_binaries.py OLD NEW N SHAPE [SHAPE ...]

Each binary runs `repose poses SHAPE -n N` with the peer benchmark's toss (from 4·L, speeds up to
1.5·sqrt(g·L) and 1.5·sqrt(g/L), E 0.1, μ 0.3: the fit of docs/experiments.md). Prints both count vectors
and Pearson's χ² test of homogeneity (poses with fewer than 10 drops in both pooled). For a change that
moves trajectories at round-off (docs/performance.md, session 24): the counts should agree within sampling
error, or be identical where the decisions do not depend on the round-off.
"""
import json
import math
import subprocess
import sys

from scipy.stats import chi2_contingency


def counts(binary, args):
    out = subprocess.run([binary] + args, capture_output=True, text=True, check=True).stdout
    return {p["pose"]: p["count"] for p in json.loads(out)["poses"]}


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    old, new, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    for shape in sys.argv[4:]:
        info = subprocess.run([new, "poses", shape, "-n", "1", "--json"], capture_output=True, text=True, check=True)
        L = json.loads(info.stdout)["particle"]["characteristic_length"]
        args = ["poses", shape, "-n", str(n), "--drop-height", f"{4 * L:.6g}",
                "--velocity-max", f"{1.5 * math.sqrt(9.81 * L):.6g}", "--spin-max", f"{1.5 * math.sqrt(9.81 / L):.6g}",
                "--restitution", "0.1", "--friction", "0.3", "--no-progress", "--json"]
        a, b = counts(old, args), counts(new, args)
        keys = sorted(set(a) | set(b))
        rows = [[c.get(k, 0) for k in keys] for c in (a, b)]
        total = [x + y for x, y in zip(*rows)]
        big = [i for i, t in enumerate(total) if t >= 10]
        small = [i for i, t in enumerate(total) if 0 < t < 10]
        table = [[r[i] for i in big] + ([sum(r[i] for i in small)] if small else []) for r in rows]
        chi, p, dof, _ = chi2_contingency(table)
        same = "identical" if rows[0] == rows[1] else "differ"
        print(f"{shape}: L {L:.4g}, {n} tosses each, counts {same}; old {rows[0]} new {rows[1]}; "
              f"chi2 {chi:.2f} on {dof} dof, p {p:.3f}", flush=True)


if __name__ == "__main__":
    main()
