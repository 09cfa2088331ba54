"""Why the Yade scripts run one grain per scene (yade_scene.py): Yade 2023.02's polyhedra contact law keeps the
friction force in the law object, not per contact, so two grains on one floor disturb each other.

Run:  yade -n -j1 -x scripts/dem/yade_shared_shear.py
The same cube (edge 0.4 m, Yade's default PolyhedraMat) is dropped from the same tilted start: alone, and with
a second cube 5 m away on the same floor (the two never touch). Prints both first cubes' speed and spin after
4 s: alone it is at rest to rounding; beside the other it creeps and turns on.
"""
import sys

from yade import polyhedra_utils

a = 0.2
CUBE = [(x, y, z) for x in (-a, a) for y in (-a, a) for z in (-a, a)]
TILT = Quaternion(Vector3(1, 1, 0).normalized(), 0.5)


def run(cubes):
    O.reset()
    material = PolyhedraMat()
    O.materials.append(material)
    O.bodies.append(utils.wall(0, axis=2, sense=1, material=material))
    ids = []
    for k in range(cubes):
        b = polyhedra_utils.polyhedra(material, v=CUBE)
        b.state.ori = TILT
        pos = Vector3(5.0 * k, 0, 0)
        pos[2] -= min((pos + b.state.ori * v)[2] for v in b.shape.v)
        b.state.pos = pos
        ids.append(O.bodies.append(b))
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop([Ig2_Wall_Polyhedra_PolyhedraGeom()], [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
        NewtonIntegrator(gravity=(0, 0, -9.81)),
    ]
    O.dt = 1e-3
    for _ in range(4000):
        O.step()
    b = O.bodies[ids[0]]
    return b.state.vel.norm(), b.state.angVel.norm()


for cubes in (1, 2):
    speed, spin = run(cubes)
    print("%d cube(s) on the floor: the first cube after 4 s moves at %.2g m/s and turns at %.2g rad/s"
          % (cubes, speed, spin))
sys.exit(0)
