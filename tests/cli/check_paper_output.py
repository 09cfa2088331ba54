#!/usr/bin/env python3
"""Checks a `repose paper --out DIR` directory: every file exists and is non-trivial.

PNGs must decode and not be blank, CSVs must have the expected columns and rows, every VTK file must parse and
each .pvd must list exactly the frames on disk. Prints one line per problem; exit status 1 if any.
"""
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib.image as mpimg
import numpy as np

CASES = ["ellipsoid-c075", "ellipsoid-c150", "cylinder-1106", "cylinder-1108", "tetrahedron", "irregular"]
COLUMNS = ("t,qw,qx,qy,qz,omega_x,omega_y,omega_z,com_x,com_y,com_z,contact,contact_count,kinetic_energy,"
           "potential_energy,sticking,sliding").split(",")
FIGURES = {case: ["pose", "com_height", "omega"] for case in CASES}
FIGURES["irregular"].append("contacts")
problems = []


def check_png(path):
    if not os.path.isfile(path):
        problems.append(f"missing {path}")
        return
    img = mpimg.imread(path)
    if img.ndim < 2 or img.shape[0] < 100 or img.shape[1] < 100 or float(np.std(img)) < 0.02:
        problems.append(f"{path}: blank or tiny image {img.shape}")


def check_pvd(vtk_dir, pvd, prefix):
    root = ET.parse(os.path.join(vtk_dir, pvd)).getroot()
    listed = [d.get("file") for d in root.iter("DataSet")]
    on_disk = sorted(f for f in os.listdir(vtk_dir) if f.startswith(prefix) and f.endswith(".vtp"))
    if sorted(listed) != on_disk:
        problems.append(f"{vtk_dir}/{pvd}: lists {len(listed)} frames, {len(on_disk)} on disk")
    times = [float(d.get("timestep")) for d in root.iter("DataSet")]
    if times != sorted(times):
        problems.append(f"{vtk_dir}/{pvd}: timesteps not increasing")
    for f in on_disk:
        piece = ET.parse(os.path.join(vtk_dir, f)).getroot().find(".//Piece")
        n = int(piece.get("NumberOfPoints"))
        pts = piece.find("./Points/DataArray").text.split()
        if len(pts) != 3 * n:
            problems.append(f"{vtk_dir}/{f}: {len(pts)} coordinates for {n} points")
    return len(on_disk)


out = sys.argv[1]
frames_expected = int(sys.argv[2])
for case in CASES:
    d = os.path.join(out, case)
    with open(os.path.join(d, "timeseries.csv")) as f:
        rows = list(csv.reader(f))
    if rows[0] != COLUMNS:
        problems.append(f"{d}/timeseries.csv: columns {rows[0]}")
    if len(rows) < 50:
        problems.append(f"{d}/timeseries.csv: only {len(rows) - 1} rows")
    summary = json.load(open(os.path.join(d, "summary.json")))
    if summary["status"] != "rest":
        problems.append(f"{d}: status {summary['status']}")
    for stem in FIGURES[case]:
        check_png(os.path.join(d, stem + ".png"))
    n = check_pvd(os.path.join(d, "vtk"), "settling.pvd", "particle_")
    check_pvd(os.path.join(d, "vtk"), "markers.pvd", "markers_")
    if not 2 <= n <= frames_expected:
        problems.append(f"{d}: {n} frames, expected at most {frames_expected}")
check_png(os.path.join(out, "cylinders_omega.png"))
if not os.path.isfile(os.path.join(out, "report.md")):
    problems.append("missing report.md")
# report.html: one page carrying the six runs, the table of report.md (same rows) and every figure listed.
html_path = os.path.join(out, "report.html")
if not os.path.isfile(html_path):
    problems.append("missing report.html")
else:
    page = open(html_path, encoding="utf-8").read()
    start = page.find('<script id="repose-data" type="application/json">')
    data = json.loads(page[page.index(">", start) + 1:page.index("</script>", start)])
    md_rows = [line for line in open(os.path.join(out, "report.md")) if line.startswith("| ")][1:]
    listed = json.load(open(os.path.join(out, "report.json")))
    if len(data["cases"]) != 6:
        problems.append(f"report.html: {len(data['cases'])} runs, expected 6")
    if len(data["table"]) != len(md_rows) or ["| " + " | ".join(r) + " |\n" for r in data["table"]] != md_rows:
        problems.append("report.html: its table is not report.md's")
    if len(data["figures"]) != len(listed["figures"]) or len(data["figures"]) < 10:
        problems.append(f"report.html: {len(data['figures'])} figures, report.json lists {len(listed['figures'])}")
    for f in data["figures"]:
        if not f["src"].startswith("data:image/png;base64,iVBORw0KGgo"):
            problems.append(f"report.html: figure {f['title']} is not an embedded PNG")
for p in problems:
    print(p)
sys.exit(1 if problems else 0)
