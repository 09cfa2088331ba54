#!/usr/bin/env python3
"""Writes the mesh files used by tests/io/mesh_io_test.cpp into this directory.

Run from anywhere: python3 tests/data/make_data.py. The output is committed, so the tests need no Python;
re-run this only to change the data. Binary files are written little-endian unless the name says otherwise.
"""

import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# Unit cube [0,1]^3: vertex i has x = bit 0, y = bit 1, z = bit 2.
CUBE_VERTICES = [(i & 1, (i >> 1) & 1, (i >> 2) & 1) for i in range(8)]
# Quads, counter-clockwise seen from outside.
CUBE_QUADS = [
    (0, 2, 3, 1),  # z = 0
    (4, 5, 7, 6),  # z = 1
    (0, 1, 5, 4),  # y = 0
    (2, 6, 7, 3),  # y = 1
    (0, 4, 6, 2),  # x = 0
    (1, 3, 7, 5),  # x = 1
]
CUBE_TRIANGLES = [t for a, b, c, d in CUBE_QUADS for t in ((a, b, c), (a, c, d))]


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normal(p, q, r):
    n = cross(sub(q, p), sub(r, p))
    length = sum(x * x for x in n) ** 0.5
    return tuple(x / length for x in n) if length > 0 else (0.0, 0.0, 0.0)


def write(name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(HERE, name), mode) as f:
        f.write(data)


def stl_ascii(vertices, triangles):
    lines = ["solid cube"]
    for t in triangles:
        p = [vertices[i] for i in t]
        # Non-numeric coordinates ("nan") get a zero normal.
        n = normal(*p) if all(isinstance(x, (int, float)) for v in p for x in v) else (0, 0, 0)
        lines.append("  facet normal %g %g %g" % n)
        lines.append("    outer loop")
        lines += ["      vertex %s %s %s" % tuple(v) for v in p]
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append("endsolid cube")
    return "\n".join(lines) + "\n"


def stl_binary(vertices, triangles, header=b"repose test cube", count=None):
    out = bytearray(header.ljust(80, b" ")[:80])
    out += struct.pack("<I", len(triangles) if count is None else count)
    for t in triangles:
        p = [vertices[i] for i in t]
        out += struct.pack("<3f", *normal(*p))
        for v in p:
            out += struct.pack("<3f", *v)
        out += struct.pack("<H", 0)
    return bytes(out)


def off(vertices, faces, counts=None):
    nv, nf = counts if counts else (len(vertices), len(faces))
    lines = ["OFF", "# test mesh", "%d %d 0" % (nv, nf)]
    lines += ["%s %s %s" % tuple(v) for v in vertices]
    lines += ["%d %s" % (len(f), " ".join(map(str, f))) for f in faces]
    return "\n".join(lines) + "\n"


def obj(vertices, faces):
    lines = ["# test mesh"] + ["v %s %s %s" % tuple(v) for v in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def ply_header(fmt, nv, nf):
    return (
        "ply\nformat %s 1.0\ncomment repose test cube\n"
        "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
        "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (fmt, nv, nf)
    )


def ply_ascii(vertices, faces):
    body = ["%s %s %s" % tuple(v) for v in vertices]
    body += ["%d %s" % (len(f), " ".join(map(str, f))) for f in faces]
    return ply_header("ascii", len(vertices), len(faces)) + "\n".join(body) + "\n"


def ply_binary(vertices, faces, endian="<", counts=None):
    nv, nf = counts if counts else (len(vertices), len(faces))
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    out = bytearray(ply_header(fmt, nv, nf).encode())
    for v in vertices:
        out += struct.pack(endian + "3f", *v)
    for f in faces:
        out += struct.pack(endian + "B%di" % len(f), len(f), *f)
    return bytes(out)


def main():
    v, quads, tris = CUBE_VERTICES, CUBE_QUADS, CUBE_TRIANGLES

    # One unit cube per supported format.
    write("cube_ascii.stl", stl_ascii(v, tris))
    write("cube_binary.stl", stl_binary(v, tris))
    # Many exporters start binary headers with "solid"; the content decides, not the first word.
    write("cube_binary_solid_header.stl", stl_binary(v, tris, header=b"solid cube exported as binary"))
    write("cube_binary_trailing.stl", stl_binary(v, tris) + b"\0" * 7)
    write("cube.obj", obj(v, quads))
    # Two groups ("o" statements): one surface, the statements ignored.
    write(
        "cube_groups.obj",
        "\n".join(["v %s %s %s" % p for p in v] + ["o top"]
                  + ["f " + " ".join(str(i + 1) for i in q) for q in quads[:3]] + ["o bottom"]
                  + ["f " + " ".join(str(i + 1) for i in q) for q in quads[3:]]) + "\n",
    )
    write("cube.off", off(v, quads))
    write("cube_ascii.ply", ply_ascii(v, quads))
    write("cube_binary.ply", ply_binary(v, tris))
    write("cube_binary_be.ply", ply_binary(v, quads, endian=">"))

    # Files a reader must reject before (or instead of) allocating what the header claims.
    write("empty.stl", b"")
    write("unknown.abc", "0 0 0\n1 0 0\n0 1 0\n")
    write("truncated.stl", stl_binary(v, tris)[:-20])
    # 2^31 * 50 overflows 32 bits to 0, so a naive size check sees an 84-byte file as consistent.
    write("huge_count.stl", stl_binary(v, [], count=2**31))
    write("huge_vertices.ply", ply_header("ascii", 1000000000, 12) + "0 0 0\n")
    write("huge_faces_binary.ply", ply_binary(v, tris[:1], counts=(8, 1000000000)))
    write("huge.off", off(v[:3], [(0, 1, 2)], counts=(1000000000, 1000000000)))
    write("bad_index.off", off(v, tris[:5] + [(0, 1, 8)] + tris[6:]))
    write("bad_index.obj", obj(v, tris[:5] + [(0, 1, 8)] + tris[6:]))
    write("bad_index.ply", ply_ascii(v, tris[:5] + [(0, 1, 8)] + tris[6:]))
    # Fewer faces than the header claims (assimp 5.2, used before issue 13, aborted the process on this one).
    write("truncated.off", off(v, quads[:5], counts=(8, 6)))
    write("truncated_ascii.ply", ply_ascii(v, quads).replace("element face 6", "element face 7"))
    write("truncated_binary.ply", ply_binary(v, tris)[:-7])
    write("nan.stl", stl_ascii([(0, 0, 0), (1, 0, 0), ("nan", 1, 0)], [(0, 1, 2)]))
    write("nan.off", off([(0, 0, 0), (1, 0, 0), (0, "nan", 0), (0, 0, 1)],
                         [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]))
    write("inf.obj", obj([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, "inf")],
                         [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]))
    write("lines_only.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\np 1\n")

    # Parse fine but are not closed solids with consistent winding.
    write("open_cube.off", off(v, quads[:5]))
    write("flipped_face.off", off(v, [t[::-1] if i == 3 else t for i, t in enumerate(tris)]))
    write("inverted_cube.off", off(v, [q[::-1] for q in quads]))
    write("flat.off", off([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2), (0, 2, 1)]))
    write("nonmanifold.off", off([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)],
                                 [(0, 1, 2), (1, 0, 3), (0, 1, 4)]))


if __name__ == "__main__":
    main()
