#!/usr/bin/env python3
"""Writes the large test inputs of docs/performance.md ("Large scans") into a directory (default /tmp):

  bumpy_sphere_2m.ply   a closed bumpy sphere, 1,001,002 vertices and 2,002,000 triangles (binary PLY), most
                        vertices inside the convex hull, as on a real scan
  ellipsoid_2m.ply      the same grid on an ellipsoid 1 x 0.8 x 0.6: every vertex on the convex hull (the
                        worst case for the hull)
  bumpy_sphere_2m_holes.ply  the bumpy sphere with 100 holes punched (a 6 x 6 patch of grid cells, 72
                        triangles, removed at each of 100 random places): a scan for --repair
  grain_200k.xyz        a 200,000-point cloud of a rough grain (ASCII x y z)

Usage: scripts/make_large_meshes.py [DIR]   (needs NumPy: Debian python3-numpy, installed with matplotlib)
"""
import os
import sys

import numpy as np


def write_ply(path, verts, faces):
    with open(path, "wb") as out:
        out.write(
            f"ply\nformat binary_little_endian 1.0\nelement vertex {len(verts)}\nproperty double x\n"
            f"property double y\nproperty double z\nelement face {len(faces)}\n"
            "property list uchar int vertex_indices\nend_header\n".encode())
        out.write(verts.astype("<f8").tobytes())
        rec = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<i4", 3)])
        rec["n"] = 3
        rec["i"] = faces
        out.write(rec.tobytes())


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "/tmp"
    os.makedirs(out, exist_ok=True)
    rng = np.random.default_rng(1)
    nu, nv = 1000, 1001  # longitudes, latitude rings between the poles
    th = np.linspace(0, np.pi, nv + 2)[1:-1]
    ph = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    t, p = np.meshgrid(th, ph, indexing="ij")
    unit = np.column_stack([(np.sin(t) * np.cos(p)).ravel(), (np.sin(t) * np.sin(p)).ravel(), np.cos(t).ravel()])
    unit = np.vstack([unit, [0, 0, 1.0], [0, 0, -1.0]])
    north, south = len(unit) - 2, len(unit) - 1
    idx = np.arange(nv * nu).reshape(nv, nu)
    nxt = np.r_[1:nu, 0]
    a, b, c, d = idx[:-1, :], idx[:-1, nxt], idx[1:, :], idx[1:, nxt]
    faces = np.vstack([
        np.stack([a, c, b], -1).reshape(-1, 3),  # outward: latitude increases downwards
        np.stack([b, c, d], -1).reshape(-1, 3),
        np.stack([np.full(nu, north), idx[0, :], idx[0, nxt]], -1),
        np.stack([np.full(nu, south), idx[-1, nxt], idx[-1, :]], -1),
    ]).astype(np.int32)
    r = 1 + 0.05 * np.sin(5 * t) * np.cos(3 * p) + 0.002 * rng.standard_normal(t.shape)
    bumpy = unit * np.concatenate([r.ravel(), [1.0, 1.0]])[:, None]
    write_ply(os.path.join(out, "bumpy_sphere_2m.ply"), bumpy, faces)
    write_ply(os.path.join(out, "ellipsoid_2m.ply"), unit * np.array([1.0, 0.8, 0.6]), faces)
    # Holes: grid cells (row, column) away from the poles; cell (i, j) owns triangles i*nu + j in both halves.
    keep = np.ones(len(faces), dtype=bool)
    cells = (nv - 1) * nu
    for i0, j0 in zip(rng.integers(10, nv - 20, 100), rng.integers(0, nu - 10, 100)):
        for i in range(i0, i0 + 6):
            for j in range(j0, j0 + 6):
                keep[i * nu + j] = keep[cells + i * nu + j] = False
    write_ply(os.path.join(out, "bumpy_sphere_2m_holes.ply"), bumpy, faces[keep])
    pts = rng.standard_normal((200000, 3))
    pts /= np.linalg.norm(pts, axis=1)[:, None]
    pts *= (1 + 0.1 * rng.random(200000))[:, None] * np.array([1.0, 0.8, 0.6])
    np.savetxt(os.path.join(out, "grain_200k.xyz"), pts, fmt="%.9f")
    print(f"wrote {out}/bumpy_sphere_2m.ply, ellipsoid_2m.ply ({len(faces)} triangles), grain_200k.xyz")


if __name__ == "__main__":
    main()
