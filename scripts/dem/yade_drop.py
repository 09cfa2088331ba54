"""Polyhedral grains dropped onto a floor in Yade (a real DEM code), alone or handed over to repose at first touch.

Run inside Yade:  yade -n -j1 -x scripts/dem/yade_drop.py MODE N SEED OUT.json [LIBREPOSE_C]
  MODE alone     Yade settles every grain with its own polyhedra contact law (the material of its own example
                 examples/polyhedra/free-fall.py: gravel, density 2600 kg/m³, young 1e7 N/m³ (a volumetric
                 stiffness), poisson 2e-3, friction angle 0.5 rad; Cundall's local damping 0.3 on the contact
                 forces, not on gravity: free fall is exact), until it rests (yade_scene.RestTest, sampled every
                 1 ms) or T_MAX.
  MODE handover  Yade runs each grain until its first contact with the floor, then hands the grain's state to
                 repose through its C API (librepose_c.so, through ctypes), which settles it to rest with the
                 friction of Yade's material (μ = tan 0.5) and the restitution of Yade's contact, measured on a
                 flat drop in Yade first (yade_restitution).
Each grain falls from a random orientation, its centre of mass 2 L above the floor, at rest, in a Yade scene of
its own (grains that would fall in separate lanes and never meet; one scene each is what Yade's polyhedra law
needs: yade_scene.py). The grains are the convex hulls of 16 points on a jittered ellipsoid (semi-axes 20, 15,
11 mm), the same points in both codes, in the same axes: repose's particle is the convex model of the points.
Writes per grain: the final orientation (the points' axes), the time to rest, the deepest overlap with the
floor, the wall time; for repose also its rest face's pose.
"""
import json
import math
import os
import random
import statistics
import sys
import time

from yade import polyhedra_utils

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
from yade_scene import Grain, RestTest, lowest  # noqa: E402

MODE, N, SEED, OUT = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
if MODE not in ("alone", "handover"):
    sys.exit("MODE must be alone or handover, not " + MODE)
G = 9.81
A = (0.02, 0.015, 0.011)  # m: the ellipsoid's semi-axes (L about 2.2 cm, the size of Yade's example's gravel)
DENSITY = 2600.0
YOUNG = float(os.environ.get("YADE_YOUNG", "1e7"))  # N/m³: the contact's volumetric stiffness (Yade's example)
DT = float(os.environ.get("YADE_DT", "5e-5"))  # s
T_MAX = 5.0  # s of simulated time at most
SAMPLE = 0.001  # s between the rest and overlap checks
WINDOW = 0.1  # s: the rest window


def grain_points(rng):
    pts = []
    for _ in range(16):
        u, phi = rng.uniform(-1, 1), rng.uniform(0, 2 * math.pi)
        s, r = math.sqrt(1 - u * u), rng.uniform(0.85, 1.0)
        pts.append((A[0] * r * s * math.cos(phi), A[1] * r * s * math.sin(phi), A[2] * r * u))
    return pts


def random_quaternion(rng):  # uniform on SO(3) (Shoemake)
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return (b * math.cos(2 * math.pi * u3), a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2),
            b * math.sin(2 * math.pi * u3))  # w, x, y, z


def gravel():
    return PolyhedraMat(density=DENSITY, young=YOUNG, poisson=20000 / 1e7, frictionAngle=0.5)


def drop(points, orientation, length):
    return Grain(gravel(), points, orientation, position=(0, 0, 2 * length), gravity=G, damping=0.3,
                 damp_gravity=False)


def yade_restitution(length):
    """The restitution of Yade's contact at the drops' impact speed: a cube of the grains' size (edge
    L·(π/6)^(1/3), the same volume) of the same material, dropped flat from the same height (centre of mass 2 L
    up), rebound speed over impact speed. repose's hand-over uses it, so that the hand-over keeps the DEM
    material's bounce (Cundall's damping 0.3 gives 0.7 here, where repose's default is a plastic landing)."""
    a = 0.5 * length * (math.pi / 6) ** (1 / 3)
    cube = [(x, y, z) for x in (-a, a) for y in (-a, a) for z in (-a, a)]
    grain = drop(cube, (1, 0, 0, 0), length)
    O.dt = DT
    impact = None
    while O.time < T_MAX:
        O.step()
        b = grain.body
        if impact is None and lowest(b) < 0:
            impact = b.state.vel[2]
        elif impact is not None and lowest(b) > 0:
            return -b.state.vel[2] / impact
    sys.exit("the calibration cube did not rebound within %g s" % T_MAX)


rng = random.Random(SEED)
grains = []
for k in range(N):
    points = grain_points(rng)
    orientation = random_quaternion(rng)
    body = polyhedra_utils.polyhedra(gravel(), v=points)  # not in a scene: its hull's volume and mass
    length = (6 * body.shape.GetVolume() / math.pi) ** (1 / 3)
    grains.append({"id": k, "length": length, "mass": body.state.mass, "vertices": points,
                   "start": {"orientation": orientation, "height": 2 * length}})

per_sample = max(1, int(round(SAMPLE / DT)))
wall_start = time.perf_counter()
if MODE == "alone":
    for g in grains:
        grain = drop(g["vertices"], g["start"]["orientation"], g["length"])
        O.dt = DT
        rest = RestTest(g["length"], G, int(round(WINDOW / (per_sample * DT))))
        rested, depth = grain.run_to_rest(rest, per_sample, T_MAX)
        g["orientation"] = grain.orientation()
        g["position"] = list(grain.body.state.pos)
        g["at_rest"] = rested
        g["rest_time"] = O.time - WINDOW if rested else O.time  # the quiet window's start
        g["max_overlap"] = depth
        g["twist"] = abs(grain.body.state.angVel[2])
    summary = {"yade_wall_time": time.perf_counter() - wall_start}
else:
    import repose_capi

    lib = repose_capi.Library(sys.argv[5])
    restitution = yade_restitution(statistics.median(g["length"] for g in grains))
    params = lib.params(friction=math.tan(0.5), restitution=restitution)
    yade_wall = repose_wall = 0.0
    for g in grains:
        started = time.perf_counter()
        grain = drop(g["vertices"], g["start"]["orientation"], g["length"])
        O.dt = DT
        while O.time < T_MAX - 1e-12 and not grain.touching():
            O.step()
        b = grain.body
        h = {"time": O.time, "position": list(b.state.pos), "orientation": grain.orientation(),
             "velocity": list(b.state.vel), "angular_velocity": list(b.state.angVel), "overlap": -lowest(b)}
        handed = time.perf_counter()
        yade_wall += handed - started
        particle = lib.convex_particle(g["vertices"], DENSITY, "grain")
        r = lib.settle(particle, params, h["position"], h["orientation"], h["velocity"], h["angular_velocity"], 0.0)
        poses, handle = lib.poses(particle)
        g["handover"] = h
        g["orientation"] = list(r.orientation)
        g["position"] = list(r.position)
        g["at_rest"] = r.status == repose_capi.REPOSE_REST
        g["rest_time"] = h["time"] + r.time
        g["max_overlap"] = max(h["overlap"], r.max_penetration)  # Yade's at the hand-over, then repose's
        g["repose_penetration"] = r.max_penetration
        g["lift"] = r.lift
        g["repose_steps"] = r.steps
        g["repose_pose"] = lib.pose_of_face(handle, r.rest_face) if r.rest_face >= 0 else -1
        lib.lib.repose_poses_free(handle)
        lib.lib.repose_particle_free(particle)
        repose_wall += time.perf_counter() - handed
    summary = {"yade_wall_time": yade_wall, "repose_wall_time": repose_wall, "restitution": restitution}

with open(OUT, "w") as f:
    json.dump({"mode": MODE, "n": N, "seed": SEED, "dt": DT, "young": YOUNG, "t_max": T_MAX, "summary": summary,
               "grains": grains}, f)
print("wrote", OUT, summary)
sys.exit(0)
