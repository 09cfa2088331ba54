"""The DEM coupling example's table: Yade alone against Yade handing over to repose at first touch.

  python3 scripts/dem/compare.py ALONE.json HANDOVER.json LIBREPOSE_C [--grains]
  python3 scripts/dem/compare.py --yade-pair ALONE.json OTHER_ALONE.json LIBREPOSE_C

Per grain (with --grains) and in total: the rest pose in each (same or not), the pose histogram, time to rest,
the deepest overlap with the floor, the wall time. A grain's rest pose is a pose of repose's exact catalogue of
its convex hull (stable hull faces, numbered by centre-of-mass height, 0 the lowest); a final orientation is in
the pose whose down normal is nearest the grain's body-frame down direction (both runs mapped the same way;
repose's own rest face is checked to give the same pose).
"""
import json
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import repose_capi  # noqa: E402


def rotate_inverse(q, v):  # R(q)^T v for q = (w, x, y, z)
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, -x / n, -y / n, -z / n
    # v' = q v q*, expanded
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + (y * tz - z * ty), v[1] + w * ty + (z * tx - x * tz), v[2] + w * tz + (x * ty - y * tx))


def nearest_pose(poses, orientation):
    down = rotate_inverse(orientation, (0.0, 0.0, -1.0))
    dots = [sum(p.down_normal_body[k] * down[k] for k in range(3)) for p in poses]
    best = max(range(len(poses)), key=lambda i: dots[i])
    return best, math.degrees(math.acos(max(-1.0, min(1.0, dots[best]))))


def yade_against_itself(first, second, lib):
    """The per-grain agreement of two Yade-alone runs of the same grains at other settings: how reproducible a
    single drop's pose is under a change of the contact model alone (a baseline for the hand-over's)."""
    a, b = (json.load(open(p)) for p in (first, second))
    same = 0
    for x, y in zip(a["grains"], b["grains"]):
        particle = lib.convex_particle(x["vertices"], 2600.0, "grain")
        poses, handle = lib.poses(particle)
        same += nearest_pose(poses, x["orientation"])[0] == nearest_pose(poses, y["orientation"])[0]
        lib.lib.repose_poses_free(handle)
        lib.lib.repose_particle_free(particle)
    print("Yade alone against Yade alone at the other stiffness (young %.0e against %.0e): the same pose for %d of "
          "%d grains" % (a["young"], b["young"], same, len(a["grains"])))


def main():
    if sys.argv[1] == "--yade-pair":
        yade_against_itself(sys.argv[2], sys.argv[3], repose_capi.Library(sys.argv[4]))
        return
    alone, handover = (json.load(open(p)) for p in sys.argv[1:3])
    lib = repose_capi.Library(sys.argv[3])
    show_grains = "--grains" in sys.argv
    rows = []
    for a, h in zip(alone["grains"], handover["grains"]):
        particle = lib.convex_particle(a["vertices"], 2600.0, "grain")
        poses, handle = lib.poses(particle)
        yade_pose, yade_tilt = nearest_pose(poses, a["orientation"])
        repose_pose, repose_tilt = nearest_pose(poses, h["orientation"])
        if repose_pose != h["repose_pose"]:
            sys.exit("grain %d: repose's rest face is pose %d, its orientation nearest pose %d"
                     % (a["id"], h["repose_pose"], repose_pose))
        rows.append({"grain": a["id"], "poses": len(poses), "yade": yade_pose, "yade_tilt": yade_tilt,
                     "yade_rest": a["at_rest"], "repose": repose_pose, "repose_tilt": repose_tilt,
                     "yade_time": a["rest_time"], "repose_time": h["rest_time"],
                     "yade_overlap": a["max_overlap"] / a["length"], "handover_overlap": h["handover"]["overlap"],
                     "repose_overlap": h["repose_penetration"], "length": a["length"], "twist": a["twist"]})
        lib.lib.repose_poses_free(handle)
        lib.lib.repose_particle_free(particle)

    n = len(rows)
    if show_grains:
        print("grain  poses  Yade pose (tilt, rest)  repose pose (tilt)  same  time to rest Yade / repose (s)"
              "  Yade max overlap (L)")
        for r in rows:
            print("%5d  %5d  %4d (%5.2f°, %-5s)    %4d (%5.2f°)      %-4s  %6.3f / %6.3f  %22.3f" % (
                r["grain"], r["poses"], r["yade"], r["yade_tilt"], "yes" if r["yade_rest"] else "no", r["repose"],
                r["repose_tilt"], "yes" if r["yade"] == r["repose"] else "no", r["yade_time"], r["repose_time"],
                r["yade_overlap"]))
        print()
    same = sum(r["yade"] == r["repose"] for r in rows)
    top = max(max(r["yade"], r["repose"]) for r in rows)
    print("%d grains; Yade: volumetric stiffness (young) %.0e N/m^3, step %.2g s, one scene per grain" % (
        n, alone["young"], alone["dt"]))
    print("repose after the hand-over: friction tan 0.5 = 0.546, restitution %.3f (Yade's contact's, measured on a "
          "flat drop)" % handover["summary"]["restitution"])
    print("rest pose the same in both: %d of %d" % (same, n))
    print("pose histogram (pose 0 = the lowest centre of mass of each grain):")
    print("  pose  " + "".join("%6d" % k for k in range(top + 1)))
    print("  Yade  " + "".join("%6d" % sum(r["yade"] == k for r in rows) for k in range(top + 1)))
    print("  repose" + "".join("%6d" % sum(r["repose"] == k for r in rows) for k in range(top + 1)))
    settled = [r for r in rows if r["yade_rest"]]
    print("  the same among the grains Yade settled: %d of %d" % (sum(r["yade"] == r["repose"] for r in settled),
                                                                  len(settled)))
    # Pearson's chi-square test of homogeneity on the two histograms, poses 3 and up pooled (every expected count
    # >= 5): a 2 x 4 table, 3 degrees of freedom, whose survival function is erfc(sqrt(x/2)) + sqrt(2x/pi) e^(-x/2).
    table = [[sum(r[side] == k for r in rows) for k in range(3)] + [sum(r[side] >= 3 for r in rows)]
             for side in ("yade", "repose")]
    columns = [table[0][k] + table[1][k] for k in range(4)]
    chi2 = sum((table[i][k] - sum(table[i]) * columns[k] / (2 * n)) ** 2 / (sum(table[i]) * columns[k] / (2 * n))
               for i in range(2) for k in range(4) if columns[k] > 0)
    p = math.erfc(math.sqrt(chi2 / 2)) + math.sqrt(2 * chi2 / math.pi) * math.exp(-chi2 / 2)
    print("  histograms (poses 0, 1, 2, 3+): chi-square %.2f, 3 degrees of freedom, p = %.2f" % (chi2, p))
    rested = sum(r["yade_rest"] for r in rows)
    print("Yade alone at rest by %.0f s: %d of %d (the peer benchmark's rest test on v_z and the tilting rate: "
          "yade_scene.RestTest); its final tilt off the nearest pose's face: median %.2f deg, max %.2f deg; its spin "
          "about the vertical at rest: median %.2g rad/s" % (
              alone["t_max"], rested, n, statistics.median(r["yade_tilt"] for r in rows),
              max(r["yade_tilt"] for r in rows), statistics.median(r["twist"] for r in rows)))
    print("time to rest, median (s): Yade alone %.3f, handed over %.3f" % (
        statistics.median(r["yade_time"] for r in rows if r["yade_rest"]),
        statistics.median(r["repose_time"] for r in rows)))
    print("deepest overlap with the floor (fraction of L): Yade alone median %.3f, max %.3f; handed over: "
          "Yade's at hand-over max %.2e L, repose's max %.1e m" % (
              statistics.median(r["yade_overlap"] for r in rows), max(r["yade_overlap"] for r in rows),
              max(r["handover_overlap"] / r["length"] for r in rows), max(r["repose_overlap"] for r in rows)))
    ya, yh, rh = (alone["summary"]["yade_wall_time"], handover["summary"]["yade_wall_time"],
                  handover["summary"]["repose_wall_time"])
    print("wall time (s): Yade alone %.1f; handed over %.1f (Yade to first touch %.1f + repose %.2f): %.0fx less" % (
        ya, yh + rh, yh, rh, ya / (yh + rh)))


if __name__ == "__main__":
    main()
