#!/usr/bin/env python3
"""The damped fall of a box about its edge, through the command line, against SciPy.

`repose settle box:x=1,y=2,z=3 --units cgs --density 1 --damping C` tilted about x by θc + 0.05 pivots on its
edge at body (·, −1, −1.5) until its 1 × 3 face lands. About that fixed line the motion is the damped inverted
pendulum I·φ'' + C·φ' = m·g·d·sin φ, φ the tilt of the centre of mass from the vertical through the edge,
m = 6 g, I = m·(2² + 3²)/3 = 26 g·cm², d = sqrt(1 + 1.5²) cm. SciPy's solve_ivp (DOP853, rtol 1e-12) integrates
it; the engine's time series (timeseries.csv) and time to rest (summary.json) must match: φ(t) at every sample
to 1e-6 rad, the landing time to 5e-7 relative (measured: 2.5e-7 rad and 6.9e-8 at worst; the engine's
trapezoidal rule is O(dt²) at dt = 1e-3·sqrt(L/g)). A damping moment off by a factor of two moves the landing by ~5 %.
Usage: damped_fall_scipy.py REPOSE_EXECUTABLE
"""

import csv
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

G, M, INERTIA = 981.0, 6.0, 26.0
D = math.hypot(1.0, 1.5)
THETA_C = math.atan(1.0 / 1.5)
PHI0 = 0.05
PHI_LAND = math.pi / 2 - THETA_C


def engine_run(repose, damping, out):
    theta0 = THETA_C + PHI0
    subprocess.run([repose, "settle", "box:x=1,y=2,z=3", "--units", "cgs", "--density", "1", "--damping",
                    repr(damping), "--orientation", f"axis-angle:1,0,0,{theta0!r}", "--out", str(out)],
                   check=True, stdout=subprocess.DEVNULL)
    with open(out / "timeseries.csv") as f:
        rows = list(csv.DictReader(f))
    summary = json.loads((out / "summary.json").read_text())
    return rows, summary


def reference(damping):
    def rhs(_, y):
        return [y[1], (M * G * D * math.sin(y[0]) - damping * y[1]) / INERTIA]

    def landed(_, y):
        return y[0] - PHI_LAND
    landed.terminal, landed.direction = True, 1
    return solve_ivp(rhs, (0, 5), [PHI0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True,
                     events=landed)


def main():
    repose = sys.argv[1]
    lam0 = math.sqrt(M * G * D / INERTIA)
    failures = []
    for damping in (0.0, 0.5 * INERTIA * lam0, 2 * INERTIA * lam0):
        with tempfile.TemporaryDirectory() as tmp:
            rows, summary = engine_run(repose, damping, Path(tmp))
        sol = reference(damping)
        t_land = sol.t_events[0][0]
        # The edge stays where it touched: its world y from the first sample's pose.
        first = rows[0]
        q = [float(first[k]) for k in ("qw", "qx", "qy", "qz")]
        w, x, y, z = q
        # Body point (0, −1, −1.5) rotated by q (body → world), y component.
        r_y = 2 * (x * y - w * z) * 0 + (1 - 2 * (x * x + z * z)) * -1.0 + 2 * (y * z - w * x) * -1.5
        edge_y = float(first["com_y"]) + r_y
        worst = 0.0
        for row in rows[:-1]:  # the last row is the rest, after the landing impact
            t = float(row["t"])
            phi = math.atan2(abs(float(row["com_y"]) - edge_y), float(row["com_z"]))
            worst = max(worst, abs(phi - sol.sol(min(t, t_land))[0]))
        t_rest = summary["time"]
        rel = abs(t_rest - t_land) / t_land
        print(f"C = {damping:.6g}: landing {t_rest:.12g} s, SciPy {t_land:.12g} s, relative {rel:.2e}; "
              f"largest |Δφ| {worst:.2e} rad over {len(rows) - 1} samples")
        if worst > 1e-6:
            failures.append(f"C = {damping}: φ(t) off by {worst:.3e} rad")
        if rel > 5e-7:
            failures.append(f"C = {damping}: landing at {t_rest} s, SciPy {t_land} s")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
