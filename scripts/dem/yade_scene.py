"""What the Yade scripts (yade_drop.py, yade_peer.py) share: one grain on a floor in a Yade scene of its own, its
state in repose's conventions, and the rest test.

One grain per scene: Yade 2023.02's polyhedra contact law keeps the shear force in the law object
(Law2_PolyhedraGeom_PolyhedraPhys_Volumetric::shearForce, a member of the functor), not in each contact, so
in a scene with more than one contact the contacts exchange their friction forces: two cubes settling side by
side, never touching, creep at ~5 mm/s and turn at ~0.2 rad/s for ever, where each alone comes to rest to
1e-14 m/s (yade_shared_shear.py). Grains that never meet (ours fall in lanes) are therefore run one scene
each, which is exact.
"""
import math

from yade import O, utils, polyhedra_utils  # noqa: F401 (O: the running simulation)
from yade.minieigenHP import Quaternion, Vector3
from yade.wrapper import (Bo1_Polyhedra_Aabb, Bo1_Wall_Aabb, ForceResetter, Ig2_Wall_Polyhedra_PolyhedraGeom,
                          InsertionSortCollider, InteractionLoop, Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys,
                          Law2_PolyhedraGeom_PolyhedraPhys_Volumetric, NewtonIntegrator)


def wxyz(q):
    """Yade's Quaternion as (w, x, y, z)."""
    axis, angle = q.toAxisAngle()
    s = math.sin(angle / 2)
    return [math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s]


def lowest(b):
    """The height of the grain's lowest vertex (negative: below the floor, an overlap)."""
    return min((b.state.pos + b.state.ori * v)[2] for v in b.shape.v)


class Grain:
    """A new scene with a floor (a wall at z = 0) and one polyhedron, the convex hull of `vertices` (in the
    caller's body axes), oriented by `orientation` (w, x, y, z: the caller's body axes -> world) with its centre
    of mass at `position`, or (position None) with its lowest point on the floor.

    Yade re-centres a polyhedron on its centroid and turns it to its principal axes (a vertex v of the caller's
    is centroid + principal · v_yade); the caller's axes are kept by composing with that turn both ways."""

    def __init__(self, material, vertices, orientation, position=None, gravity=9.81, damping=0.2,
                 damp_gravity=True):
        O.reset()
        O.materials.append(material)
        O.bodies.append(utils.wall(0, axis=2, sense=1, material=material))
        b = polyhedra_utils.polyhedra(material, v=vertices)
        self.principal = Quaternion(b.state.ori)
        b.state.ori = Quaternion(*orientation) * self.principal
        if position is None:
            pos = Vector3(0, 0, 0)
            pos[2] -= min((pos + b.state.ori * v)[2] for v in b.shape.v)
        else:
            pos = Vector3(*position)
        b.state.pos = pos
        O.bodies.append(b)
        self.id = b.id
        O.engines = [
            ForceResetter(),
            InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()]),
            InteractionLoop([Ig2_Wall_Polyhedra_PolyhedraGeom()], [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                            [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()]),
            NewtonIntegrator(gravity=(0, 0, -gravity), damping=damping, dampGravity=damp_gravity),
        ]

    @property
    def body(self):
        return O.bodies[self.id]

    def orientation(self):
        """Body -> world in the caller's body frame, (w, x, y, z)."""
        return wxyz(self.body.state.ori * self.principal.conjugate())

    def down_body(self):
        """The world's down direction in the caller's body frame."""
        return list(self.principal * (self.body.state.ori.conjugate() * Vector3(0, 0, -1)))

    def touching(self):
        """Whether the grain overlaps the floor (Yade's penetration volume > 0; NaN before a first overlap)."""
        return any(i.isReal and i.geom.penetrationVolume > 0 for i in O.interactions)

    @staticmethod
    def steps(n):
        for _ in range(n):
            O.step()  # synchronous; O.run(n, True) costs ~40 ms a call in waiting alone

    def run_to_rest(self, rest, per_sample, t_max):
        """Steps until `rest` (a RestTest, fed every `per_sample` steps) says the grain rests, or to `t_max`.
        Returns (rested, the deepest overlap with the floor at the samples)."""
        depth, rested = 0.0, False
        while O.time < t_max - 1e-12 and not rested:
            Grain.steps(per_sample)
            depth = max(depth, -lowest(self.body))
            rested = rest.sample(self.body)
        return rested, depth


class RestTest:
    """The peer benchmark's rest test for Bullet (bench/peers/bullet_side.hpp) on the motions that change the
    pose, fed one sample per call: at rest at the first window of `window` seconds in which the mean vertical
    speed |v_z| and tilting rate |(ω_x, ω_y)| are below 1e-3·sqrt(g·L) and 1e-3·sqrt(g/L) and not growing
    (the window's second half no faster than its first). The spin about the vertical is left out: the polyhedra
    contact acts at one point (the overlap's centroid) with no twisting friction, and Cundall's damping scales
    with the torque, so a grain spinning about the vertical on its face spins on."""

    def __init__(self, length, gravity, samples_per_window):
        self.v_tol = 1e-3 * math.sqrt(gravity * length)
        self.w_tol = 1e-3 * math.sqrt(gravity / length)
        self.window = 2 * max(1, samples_per_window // 2)
        self.speeds, self.spins = [], []

    def sample(self, b):
        w = b.state.angVel
        self.speeds.append(abs(b.state.vel[2]))
        self.spins.append(math.hypot(w[0], w[1]))
        n, half = self.window, self.window // 2
        s, w = self.speeds[-n:], self.spins[-n:]
        return len(s) == n and sum(s) / n < self.v_tol and sum(w) / n < self.w_tol and \
            sum(s[half:]) <= sum(s[:half]) + 1e-3 * self.v_tol * n and \
            sum(w[half:]) <= sum(w[:half]) + 1e-3 * self.w_tol * n
