"""Polyhedral grains dropped onto a floor in Yade (a real DEM code), alone or handed over to repose at first touch.

Run inside Yade:  yade -n -j1 -x scripts/dem/yade_drop.py MODE N SEED OUT.json [LIBREPOSE_C]
  MODE alone     Yade settles every grain with its own polyhedra contact law (the settings of its own example
                 examples/polyhedra/free-fall.py: gravel, E = 1e7 Pa, friction angle 0.5 rad, Cundall damping
                 0.3), until each grain's kinetic energy stays below 1e-6 m g L.
  MODE handover  Yade runs each grain until its first contact with the floor, then hands the grain's state to
                 repose through its C API (librepose_c.so, through ctypes), which settles it to rest.
Each grain falls in its own lane (5 L apart: they never meet) from a random orientation, its centre of mass
2 L above the floor, at rest. The grains are the convex hulls of 16 points on a jittered ellipsoid (semi-axes
20, 15, 11 mm), the same vertex lists in both codes (Yade's body frame: centroid origin, principal axes).
Writes per grain: the final orientation, the rest pose (the pose of repose's catalogue whose down normal is
nearest the grain's body-frame down direction; for repose also its own rest face's pose), the time to rest,
the deepest overlap with the floor, and the wall time of the run.
"""
import json
import math
import os
import random
import sys
import time

from yade import polyhedra_utils

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))

MODE, N, SEED, OUT = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
if MODE not in ("alone", "handover"):
    sys.exit("MODE must be alone or handover, not " + MODE)
G = 9.81
A = (0.02, 0.015, 0.011)  # m: the ellipsoid's semi-axes (L about 2.2 cm, the size of Yade's example's gravel)
DT = float(os.environ.get("YADE_DT", "5e-5"))  # s: the same rest poses and overlaps as 2e-5 on 4 grains
T_MAX = 2.0  # s of simulated time at most (settled grains rest by 0.8 s)
SAMPLE = 0.001  # s between the rest and overlap checks (every 100 steps)


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


def wxyz(q):  # Yade's Quaternion as w, x, y, z
    axis, angle = q.toAxisAngle()
    s = math.sin(angle / 2)
    return [math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s]


def lowest(b):
    return min((b.state.pos + b.state.ori * v)[2] for v in b.shape.v)


gravel = PolyhedraMat(density=2600, young=1e7, poisson=20000 / 1e7, frictionAngle=0.5)
O.bodies.append(utils.wall(0, axis=2, sense=1, material=gravel))
rng = random.Random(SEED)
grains = []
for k in range(N):
    b = polyhedra_utils.polyhedra(gravel, v=grain_points(rng))
    length = (6 * b.shape.GetVolume() / math.pi) ** (1 / 3)
    w, x, y, z = random_quaternion(rng)
    b.state.ori = Quaternion(w, x, y, z)
    b.state.pos = (5 * length * (k % 10), 5 * length * (k // 10), 2 * length)
    O.bodies.append(b)
    grains.append({"id": b.id, "length": length, "mass": b.state.mass, "vertices": [list(v) for v in b.shape.v],
                   "start": {"position": list(b.state.pos), "orientation": wxyz(b.state.ori)},
                   "max_overlap": 0.0, "rest_time": None, "last_moving": 0.0})

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()], verletDist=0.0005),
    InteractionLoop([Ig2_Wall_Polyhedra_PolyhedraGeom()], [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                    [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -G)),
]
O.dt = DT
by_id = {g["id"]: g for g in grains}
wall_start = time.time()

if MODE == "alone":
    # Rest: the grain's kinetic energy below 1e-6 m g L from some time to the end (checked every SAMPLE).
    quiet_needed = 0.05
    while O.time < T_MAX:
        O.run(int(round(SAMPLE / DT)), True)
        for g in grains:
            b = O.bodies[g["id"]]
            g["max_overlap"] = max(g["max_overlap"], -lowest(b))
            energy = 0.5 * b.state.mass * b.state.vel.squaredNorm() + 0.5 * sum(
                b.state.inertia[i] * (b.state.ori.conjugate() * b.state.angVel)[i] ** 2 for i in range(3))
            if energy > 1e-6 * g["mass"] * G * g["length"]:
                g["last_moving"] = O.time
        if all(O.time - g["last_moving"] >= quiet_needed for g in grains):
            break
    wall = time.time() - wall_start
    for g in grains:
        b = O.bodies[g["id"]]
        g["orientation"] = wxyz(b.state.ori)
        g["position"] = list(b.state.pos)
        g["at_rest"] = O.time - g["last_moving"] >= quiet_needed
        g["rest_time"] = g["last_moving"]
    summary = {"yade_wall_time": wall, "simulated_time": O.time, "steps": O.iter}
else:
    import repose_capi

    # Each grain's first contact with the floor: its state is handed over and the grain leaves Yade.
    handed = {}
    while len(handed) < N and O.time < T_MAX:
        O.step()
        for i in O.interactions:
            if not i.isReal or not i.geom.penetrationVolume > 0:  # a true overlap (NaN before one)
                continue
            gid = i.id2 if i.id1 == 0 else i.id1
            if gid in handed or gid not in by_id:
                continue
            b = O.bodies[gid]
            handed[gid] = {"time": O.time, "position": list(b.state.pos), "orientation": wxyz(b.state.ori),
                           "velocity": list(b.state.vel), "angular_velocity": list(b.state.angVel),
                           "overlap": -lowest(b)}
        for gid in handed:
            if O.bodies[gid] is not None and O.bodies[gid].state.blockedDOFs != "xyzXYZ":
                O.bodies[gid].state.blockedDOFs = "xyzXYZ"  # out of Yade's dynamics from now on
                O.bodies[gid].state.vel = Vector3(0, 0, 0)
                O.bodies[gid].state.angVel = Vector3(0, 0, 0)
    yade_wall = time.time() - wall_start
    lib = repose_capi.Library(sys.argv[5])
    params = lib.params(friction=math.tan(0.5))
    repose_start = time.time()
    for g in grains:
        h = handed[g["id"]]
        particle = lib.convex_particle(g["vertices"], 2600.0, "grain")
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
    summary = {"yade_wall_time": yade_wall, "repose_wall_time": time.time() - repose_start,
               "simulated_time": O.time, "steps": O.iter}

with open(OUT, "w") as f:
    json.dump({"mode": MODE, "n": N, "seed": SEED, "dt": DT, "summary": summary, "grains": grains}, f)
print("wrote", OUT, summary)
sys.exit(0)
