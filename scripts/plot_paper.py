#!/usr/bin/env python3
"""Figures and comparison table for `repose paper` (the four cases of section 3 of Daghooghi & Borazjani 2021).

Usage: plot_paper.py OUT_DIR
Reads OUT_DIR/<case>/{timeseries.csv, summary.json, vtk/*.vtp} written by `repose paper` and writes PNG and SVG
figures into each case directory, the combined cylinder figure into OUT_DIR, and OUT_DIR/report.md with the
table quantity | paper | exact or analytic | repose. Needs python3 with numpy and matplotlib (Debian:
python3-matplotlib). `repose paper` runs it; it can also be rerun by hand on an existing output directory.
"""
import csv
import json
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

G_CGS = 981.0
CONTACT_COLOURS = {"free-fall": "#bbbbbb", "point": "#d62728", "line": "#ff7f0e", "surface": "#2ca02c"}


def load_case(out, name):
    d = os.path.join(out, name)
    with open(os.path.join(d, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(d, "timeseries.csv")) as f:
        rows = list(csv.DictReader(f))
    ts = {k: np.array([float(r[k]) for r in rows]) for k in rows[0] if k != "contact"}
    ts["contact"] = [r["contact"] for r in rows]
    return d, summary, ts


FIGURES = []  # (PNG path, title) of every figure, in the order made: report.json lists them for report.html


def save(fig, d, stem):
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(d, f"{stem}.{ext}"), dpi=120)
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    case = os.path.basename(os.path.normpath(d))
    FIGURES.append((os.path.join(d, f"{stem}.png"), f"{case}: {titles[0] if titles else stem}"))
    plt.close(fig)


def swept_angle(ts, axis="omega_x"):
    """Angle swept about a world axis: the integral of that component of omega (trapezoidal rule)."""
    w, t = ts[axis], ts["t"]
    return np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])


def read_vtp_points(path):
    root = ET.parse(path).getroot()
    piece = root.find(".//Piece")
    pts = np.array(piece.find("./Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
    polys = piece.find("./Polys")
    tris = None
    if polys is not None:
        conn = np.array(polys.find("./DataArray[@Name='connectivity']").text.split(), dtype=int)
        tris = conn.reshape(-1, 3)
    return pts, tris


def frames(d, prefix):
    v = os.path.join(d, "vtk")
    return sorted(os.path.join(v, f) for f in os.listdir(v) if f.startswith(prefix) and f.endswith(".vtp"))


def plot_pose(d, name):
    """Initial and final pose, rendered from the first and last VTK frames."""
    fr = frames(d, "particle_")
    fig = plt.figure(figsize=(9, 4.2))
    for i, (path, title) in enumerate(((fr[0], "initial pose"), (fr[-1], "final pose (at rest)"))):
        pts, tris = read_vtp_points(path)
        ax = fig.add_subplot(1, 2, i + 1, projection="3d")
        poly = Poly3DCollection(pts[tris], facecolor="#8fb4d9", edgecolor="#35556f", linewidth=0.2, alpha=0.95)
        ax.add_collection3d(poly)
        c = pts.mean(axis=0)
        r = np.abs(pts - c).max() * 1.1
        ax.set_xlim(c[0] - r, c[0] + r)
        ax.set_ylim(c[1] - r, c[1] + r)
        ax.set_zlim(0, 2 * r)
        xx, yy = np.meshgrid([c[0] - r, c[0] + r], [c[1] - r, c[1] + r])
        ax.plot_surface(xx, yy, np.zeros_like(xx), color="#999999", alpha=0.3)
        ax.set_title(title)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        ax.view_init(elev=12, azim=-60)
    fig.suptitle(name)
    save(fig, d, "pose")


def plot_com_height(d, name, ts):
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(ts["t"], ts["com_z"], color="k")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("centre-of-mass height (cm)")
    ax.set_title(f"{name}: centre-of-mass height")
    ax.grid(alpha=0.3)
    save(fig, d, "com_height")


def mark_transitions(ax, ts):
    prev = ts["contact"][0]
    for i, c in enumerate(ts["contact"]):
        if c != prev:
            ax.axvline(ts["t"][i], color=CONTACT_COLOURS.get(c, "k"), ls="--", lw=1)
            ax.text(ts["t"][i], ax.get_ylim()[1], f" {c}", color=CONTACT_COLOURS.get(c, "k"), va="top", fontsize=8)
        prev = c


def plot_omega(d, name, ts, components=("x", "y", "z"), transitions=False, swept=False, stem="omega"):
    fig, axes = plt.subplots(2 if swept else 1, 1, figsize=(6.5, 6 if swept else 3.8), sharex=True, squeeze=False)
    ax = axes[0][0]
    for comp, col in zip(components, ("#1f77b4", "#d62728", "#2ca02c")):
        ax.plot(ts["t"], ts[f"omega_{comp}"], label=f"$\\omega_{comp}$", color=col)
    ax.set_ylabel("angular velocity (rad/s)")
    ax.grid(alpha=0.3)
    ax.legend(loc="best")
    if transitions:
        mark_transitions(ax, ts)
    ax.set_title(f"{name}: angular velocity")
    if swept:
        ax2 = axes[1][0]
        ax2.plot(ts["t"], swept_angle(ts), color="k")
        ax2.set_ylabel("swept angle about x (rad)")
        ax2.grid(alpha=0.3)
    axes[-1][0].set_xlabel("t (s)")
    save(fig, d, stem)


def plot_contacts(d, name):
    """Contact points during the settling (Fig 9): their footprints on the wall, coloured by time."""
    fig, ax = plt.subplots(figsize=(5.5, 5))
    fr = frames(d, "markers_")
    for k, path in enumerate(fr):
        root = ET.parse(path).getroot()
        piece = root.find(".//Piece")
        pts = np.array(piece.find("./Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
        kind = np.array(piece.find("./PointData/DataArray[@Name='kind']").text.split(), dtype=int)
        colour = plt.cm.viridis(k / max(1, len(fr) - 1))
        contact = pts[kind == 1]
        ax.scatter(contact[:, 0], contact[:, 1], s=12, color=colour)
        com = pts[kind == 0]
        ax.scatter(com[:, 0], com[:, 1], s=6, marker="x", color=colour)
    sm = plt.cm.ScalarMappable(cmap="viridis")
    fig.colorbar(sm, ax=ax, label="time (fraction of the run)")
    ax.set_aspect("equal")
    ax.set_xlabel("x (cm)")
    ax.set_ylabel("y (cm)")
    ax.set_title(f"{name}: contact points (dots) and COM (x) on the wall")
    ax.grid(alpha=0.3)
    save(fig, d, "contacts")


def cylinder_pivot_time(summary, theta0, theta_end):
    """Exact rigid-pivot time about the rim tangent (quadrature of the energy equation, u = sqrt|θ−θ0|)."""
    spec = summary["particle"]["source"]
    r = float(re.search(r"r=([0-9.eE+-]+)", spec).group(1))
    h = float(re.search(r"h=([0-9.eE+-]+)", spec).group(1))
    m = summary["particle"]["mass"]
    inertia = summary["particle"]["inertia"][0][0] + m * (r * r + h * h / 4)
    height = lambda th: r * np.sin(th) + h / 2 * np.cos(th)  # noqa: E731
    sign = 1.0 if theta_end > theta0 else -1.0
    u = np.linspace(0, math.sqrt(abs(theta_end - theta0)), 200001)
    th = theta0 + sign * u * u
    with np.errstate(divide="ignore", invalid="ignore"):
        f = 2 * u / np.sqrt(2 * m * G_CGS * (height(theta0) - height(th)) / inertia)
    dz = abs(r * math.cos(theta0) - h / 2 * math.sin(theta0))
    f[0] = 2 / math.sqrt(2 * m * G_CGS * dz / inertia)
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(u)))


def edge_tip_time(summary, sides=64, offset=1e-8):
    """Time for the cylinder balanced on the generator between two side faces to fall onto one: repose tips an
    edge balance off by offset·L (docs/method.md), then it is an inverted pendulum about the generator
    (d = r, I = I_axis + m·r²) turning π/n. Quadrature of dφ/sqrt(2·m·g·r·(cos φ0 − cos φ)/I) with
    φ = φ0·cosh(u), which removes the singularity at φ0."""
    spec = summary["particle"]["source"]
    r = float(re.search(r"r=([0-9.eE+-]+)", spec).group(1))
    m = summary["particle"]["mass"]
    inertia = summary["particle"]["inertia"][2][2] + m * r * r
    phi0 = math.asin(offset * summary["particle"]["characteristic_length"] / r)
    u = np.linspace(0, math.acosh((math.pi / sides) / phi0), 200001)
    phi = phi0 * np.cosh(u)
    drop = 2 * np.sin((phi + phi0) / 2) * np.sin((phi - phi0) / 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = phi0 * np.sinh(u) / np.sqrt(2 * m * G_CGS * r * drop / inertia)
    f[0] = 1 / math.sqrt(m * G_CGS * r / inertia)
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(u)))


def first_time(t, values, threshold):
    idx = np.nonzero(np.abs(values) >= threshold)[0]
    return float(t[idx[0]]) if len(idx) else float("nan")


def fmt(x, digits=4):
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    return f"{x:.{digits}g}"


def main(out):
    rows = []  # (case, quantity, paper, exact, repose)
    cases = {}
    for name in ("ellipsoid-c075", "ellipsoid-c150", "cylinder-1106", "cylinder-1108", "tetrahedron", "irregular"):
        if os.path.isdir(os.path.join(out, name)):
            cases[name] = load_case(out, name)

    for name, (d, s, ts) in cases.items():
        plot_pose(d, name)
        plot_com_height(d, name, ts)
        rows.append((name, "final COM height (cm)", "—", s["rest"]["face_com_height"], s["rest"]["com"][2]))
        rows.append((name, "time to rest (s)", "—", "—", s["time_to_rest"]))

    # Ellipsoid (Fig 6): omega components and swept angle; swept angle 0.65 rad and the first maximum.
    paper_ell = {"ellipsoid-c075": (0.035, 1.79, 0.064), "ellipsoid-c150": (0.039, 1.55, 0.070)}
    for name in ("ellipsoid-c075", "ellipsoid-c150"):
        if name not in cases:
            continue
        d, s, ts = cases[name]
        plot_omega(d, name, ts, components=("x", "y"), swept=True)
        sw = swept_angle(ts)
        k = int(np.argmax(np.abs(sw[: len(sw) // 2 + 1])))
        t065, thmax, tmax = paper_ell[name]
        rows.append((name, "time to sweep 0.65 rad about x (s)", t065, "—", first_time(ts["t"], sw, 0.65)))
        rows.append((name, "first maximum swept angle (rad)", thmax, "—", abs(sw[k])))
        rows.append((name, "time of the first maximum (s)", tmax, "—", ts["t"][k]))
        rows.append((name, "COM height at rest vs c = 0.285 cm", 0.285, 0.285, s["rest"]["com"][2]))

    # Cylinders (Fig 7): |omega| of both, swept angles and times against the exact rigid-pivot times.
    if "cylinder-1106" in cases and "cylinder-1108" in cases:
        fig, ax = plt.subplots(figsize=(6.5, 3.8))
        for name, col in (("cylinder-1106", "#1f77b4"), ("cylinder-1108", "#d62728")):
            d, s, ts = cases[name]
            wabs = np.sqrt(ts["omega_x"] ** 2 + ts["omega_y"] ** 2 + ts["omega_z"] ** 2)
            ax.plot(ts["t"], wabs, label=f"θ0 = {name[-4]}.{name[-3:]} rad", color=col)
            plot_omega(d, name, ts, components=("x",), transitions=True, swept=True)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("|ω| (rad/s)")
        ax.set_title("cylinders: |ω| against time (Fig 7e)")
        ax.legend()
        ax.grid(alpha=0.3)
        save(fig, out, "cylinders_omega")
        theta_c = math.pi / 2 - math.atan(0.67 / (2 * 0.67))
        rows.append(("cylinder", "critical angle θc (rad)", 1.107, theta_c, "—"))
        for name, theta0, end, paper_sweep, paper_time, face in (
            ("cylinder-1106", 1.106, 0.0, 1.106, 1.105, "base"),
            ("cylinder-1108", 1.108, math.pi / 2, 0.463, 0.976, "side"),
        ):
            d, s, ts = cases[name]
            sweep = abs(swept_angle(ts)[-1])
            exact_t = cylinder_pivot_time(s, theta0, end)
            if face == "side":  # it lands balanced on a generator, then tips onto a side face
                exact_t += edge_tip_time(s)
            down = s["rest"]["down_normal_body"]
            rest = "base" if abs(abs(down[2]) - 1) < 1e-9 else "side"
            rows.append((name, "rest face", face, face, rest))
            rows.append((name, "swept angle (rad)", paper_sweep, abs(end - theta0), sweep))
            rows.append((name, "time to rest (s)", paper_time, exact_t, s["time_to_rest"]))

    # Tetrahedron (Fig 8): omega with the contact-type transitions, phase durations.
    if "tetrahedron" in cases:
        d, s, ts = cases["tetrahedron"]
        plot_omega(d, "tetrahedron", ts, transitions=True)
        ph = s["phases"]
        names = [p["contact"] for p in ph]
        if names[:2] == ["point", "line"]:
            rows.append(("tetrahedron", "point phase (s)", 0.0053, "—", ph[0]["t1"] - ph[0]["t0"]))
            rows.append(("tetrahedron", "line phase (s)", 0.0032, "—", ph[1]["t1"] - ph[1]["t0"]))
        rows.append(("tetrahedron", "COM height at rest (cm)", "—", math.sqrt(2 / 3) / 4, s["rest"]["com"][2]))

    # Irregular particle (Fig 9): contact points during the settling.
    if "irregular" in cases:
        d, s, ts = cases["irregular"]
        plot_contacts(d, "irregular")
        plot_omega(d, "irregular", ts, transitions=True)
        rows.append(("irregular", "support points at rest", "several", "—", len(s["rest"]["contact_points"])))

    table = [[case, q, fmt(paper), fmt(exact, 7), fmt(ours, 7)] for case, q, paper, exact, ours in rows]
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write("| case | quantity | paper | exact or analytic | repose |\n|---|---|---|---|---|\n")
        for row in table:
            f.write("| " + " | ".join(row) + " |\n")
    # The same table and the figures' files for report.html (written by repose paper), paths relative to OUT_DIR.
    figures = [{"file": os.path.relpath(path, out), "title": title} for path, title in FIGURES]
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump({"table": table, "figures": figures}, f, indent=1)
    print(f"figures and report.md written to {out}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: plot_paper.py OUT_DIR")
    main(sys.argv[1])
