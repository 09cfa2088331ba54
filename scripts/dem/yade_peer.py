"""Yade (a real DEM code) as a third peer in the peer benchmark: the benchmark's own drops, settled by Yade.

Run inside Yade:  yade -n -j1 -x scripts/dem/yade_peer.py EXPORT.json OUT.json [SHAPE[,SHAPE...]]
EXPORT.json is written by `repose_peer_bullet --export` (bench/peers/peer_export.hpp): per shape its convex hull
(SI, the centre of mass at the origin), the hull faces' normals and rest poses, and every drop's start
orientation. Each drop starts as the benchmark's do: from rest, its lowest point on the floor (Yade: touching
the wall plane, no overlap), under g = 9.81 m/s².

Yade's set-up is its own defaults, as the benchmark gives Bullet its own: PolyhedraMat() (density 1000 kg/m³, the
benchmark's; young 1e8 N/m³, its volumetric stiffness; poisson 0.25, the shear-to-normal stiffness ratio;
friction angle 0.5 rad), the polyhedra contact law Law2_PolyhedraGeom_PolyhedraPhys_Volumetric against a wall,
NewtonIntegrator() (Cundall's local damping 0.2), one thread. A polyhedron in Yade is the convex hull of its
vertices, so the particle is the benchmark's hull with the hull's own mass properties (printed against
repose's: equal for a convex particle).

Each drop runs in a Yade scene of its own, as each of Bullet's does (and as Yade's polyhedra law needs:
yade_scene.py). A drop ends at rest by the benchmark's rest test for Bullet on the motions that change the pose
(yade_scene.RestTest), sampled every 1 ms of simulated time, or at 20 s ("no rest"); the spin about the vertical
that the polyhedra contact cannot stop is recorded ("twist"). The deepest overlap is the deepest hull vertex
below the wall, sampled at the same times. The rest pose: the final down direction in the body frame -> the
nearest hull face -> its pose (as Bullet's).

Yade's step: like Bullet's, chosen per shape as the largest of the candidates (STEPS) whose rest-pose histogram
agrees with the finest's (the benchmark's permutation test, scripts/dem/peer_table.py); every candidate is run
and recorded (an existing OUT.json of the same drops is extended with the steps it lacks). 4 ms is not a
candidate: at 4 ms none of the cube's 100 drops rests within 20 s. Time per settle is the wall time of a
drop's whole scene (building it, Yade's steps and the rest checks); the set-up (the scene built, before the
first step) is also recorded alone.
"""
import hashlib
import json
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
from yade_scene import Grain, RestTest  # noqa: E402

# Yade's candidate steps (s), coarsest first; the finest is the reference (YADE_STEPS overrides).
STEPS = [float(s) for s in os.environ.get("YADE_STEPS", "2e-3,1e-3,5e-4,2.5e-4,1e-4").split(",")]
SAMPLE = 1e-3  # s between rest and overlap checks
WINDOW = 0.1  # s: the rest window (two halves)
MAX_TIME = 20.0  # s


def nearest_face(faces, down):
    dots = [f["normal"][0] * down[0] + f["normal"][1] * down[1] + f["normal"][2] * down[2] for f in faces]
    best = max(range(len(faces)), key=lambda i: dots[i])
    return best, math.acos(max(-1.0, min(1.0, dots[best])))


def drop_once(shape, drop, gravity, step):
    """One drop in a scene of its own: its pose, time, overlap, wall time and set-up time."""
    started = time.perf_counter()
    grain = Grain(PolyhedraMat(), shape["hull_vertices"], drop["orientation"], gravity=gravity)
    O.dt = step
    setup = time.perf_counter() - started
    per_sample = max(1, int(round(SAMPLE / step)))
    rest = RestTest(shape["length"], gravity, int(round(WINDOW / (per_sample * step))))
    rested, depth = grain.run_to_rest(rest, per_sample, MAX_TIME)
    wall = time.perf_counter() - started
    face, angle = nearest_face(shape["faces"], grain.down_body())
    b = grain.body
    return {"pose": shape["faces"][face]["pose"] if rested else -1, "face": face, "tilt": angle,
            "off_face": shape["faces"][face]["stability_margin"] <= 0 or angle > 1e-2, "rested": rested,
            "time": O.time, "depth": depth, "twist": abs(b.state.angVel[2]), "orientation": grain.orientation(),
            "wall_seconds": wall, "setup_seconds": setup, "steps": O.iter, "yade_mass": b.state.mass}


def run_shape(shape, gravity, step):
    """The shape's drops at one step, one scene each."""
    drops = [drop_once(shape, drop, gravity, step) for drop in shape["drops"]]
    return {"step": step, "wall_seconds": sum(d["wall_seconds"] for d in drops),
            "setup_seconds": sum(d["setup_seconds"] for d in drops), "steps": sum(d["steps"] for d in drops),
            "yade_mass": drops[0]["yade_mass"], "drops": drops}


def main():
    export_file, out_file = sys.argv[1], sys.argv[2]
    exported = json.load(open(export_file))
    only = sys.argv[3].split(",") if len(sys.argv) > 3 else None
    # An existing OUT.json of the same drops is extended: the steps it holds are kept, the missing ones run.
    drops_id = hashlib.sha256(json.dumps([[s["name"], s["hull_vertices"], [d["orientation"] for d in s["drops"]]]
                                          for s in exported["shapes"]]).encode()).hexdigest()[:16]
    results = {"shapes": {}}
    if os.path.exists(out_file):
        results = json.load(open(out_file))
        if results.get("drops_id") != drops_id:
            sys.exit("%s holds the results of other drops than %s's: remove it first" % (out_file, export_file))
    results["drops_id"] = drops_id
    for shape in exported["shapes"]:
        if only and shape["name"] not in only:
            continue
        runs = {run["step"]: run for run in results["shapes"].get(shape["name"], [])}
        for step in STEPS:
            if step in runs:
                continue
            run = runs[step] = run_shape(shape, exported["gravity"], step)
            print("%s at %g s: %.1f s wall for %d drops (%d steps)" % (shape["name"], step, run["wall_seconds"],
                                                                      len(run["drops"]), run["steps"]), flush=True)
            results["shapes"][shape["name"]] = [runs[k] for k in sorted(runs, reverse=True)]  # coarsest first
            with open(out_file + ".partial", "w") as f:
                json.dump(results, f)
            os.replace(out_file + ".partial", out_file)  # whole after each run: a long run can be cut and resumed
    print("wrote", out_file)


main()
sys.exit(0)
