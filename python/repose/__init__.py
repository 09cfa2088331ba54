"""repose: how a rigid particle settles on a flat wall, where it comes to rest, and how likely each rest is.

    import repose
    p = repose.Particle.shape("tetrahedron:edge=1")
    r = repose.settle(p, [1, 0, 0, 0])
    print(r.status, r.time_to_rest, r.rest.down_normal_body)
    study = repose.poses(p, n=10000, seed=1)

Units: lengths in the mesh's own units (after `units`/`scale`), time in seconds, mass in the density's unit
times volume; gravity 9.81 along −z unless `gravity` is given (981 for centimetres). Orientations map body
coordinates to world coordinates; the wall is the plane z = 0. Results carry the same fields and numbers as
the command line's --json (docs/python.md).
"""
from ._repose import Particle, Settler as _Settler
from . import _repose
from ._results import DesignResult, PosesResult, Pose, Record, SettleResult, Series

__all__ = ["Particle", "Settler", "settle", "poses", "quasi_static", "design", "SettleResult", "PosesResult", "Pose",
           "Series", "DesignResult"]
__version__ = "0.1.0"


def _shape(spec, density=1.0):
    """A built-in shape from its spec, e.g. "box:x=1,y=2,z=3", "cylinder:r=0.5,h=1,n=64",
    "tetrahedron:edge=1", "ellipsoid:a=1,b=0.8,c=0.6,n=10", "irregular:seed=3"."""
    return Particle.load(spec, density=density)


Particle.shape = staticmethod(_shape)


def settle(particle, orientation="identity", *, sample_dt=None, **params):
    """Settles `particle` from `orientation` (a spec string or [w, x, y, z]) and returns a SettleResult.

    Keyword parameters are those of `repose settle`: damping (torque per angular velocity), integrator
    ("adaptive" or "paper"), dt, tolerance, contact_threshold and line_threshold (fractions of L and L²),
    smooth ("auto", "on", "off"), drop_height, drop_speed, velocity and spin ([x, y, z], world frame),
    restitution, friction (None: no slip), restitution_threshold, max_time, max_steps, gravity. The time
    series is sampled every `sample_dt` (default: 1e-3·sqrt(L/g) with the adaptive integrator, every step with the paper's).
    Raises ValueError for bad input; Ctrl-C stops the run (KeyboardInterrupt)."""
    summary, series = _repose.settle(particle, orientation, float(sample_dt or 0), dict(params))
    return SettleResult(summary, series)


class Settler:
    """The step-wise engine (a DEM code's view): step() advances one step, advance_to(t) to time t;
    sample() is the current state (t, quaternion, omega, com, velocity, energies, contact); result() the summary."""

    def __init__(self, particle, orientation="identity", **params):
        self._engine = _Settler(particle, orientation, dict(params))

    def step(self):
        """One step (shorter if an event falls inside it); False once the run has ended."""
        return self._engine.step()

    def advance_to(self, time):
        """Advances to `time` (seconds), taking as many steps and events as needed; False once ended."""
        return self._engine.advance_to(float(time))

    def sample(self):
        return self._engine.sample()

    @property
    def status(self):
        """"running", "rest", "max_time" or "max_steps"."""
        return self._engine.status

    def result(self):
        """The summary so far (final once status != "running"), as settle() returns it, without series."""
        return SettleResult(self._engine.result_json())


def poses(particle, n, *, seed=1, threads=0, method="dynamic", damping_ratio=0.05, full_settle=False,
          velocity_max=0.0, spin_max=0.0, persistence=None, **params):
    """The rest poses of `n` drops (drop i from repose.drop_orientation(seed, i), from rest unless tossed),
    with probabilities, 95 % intervals and the exact quasi-static probabilities: `repose poses` as a
    PosesResult. Results are identical for any thread count. Keyword parameters as for settle(); damping
    defaults to damping_ratio·m·sqrt(g·L³). Raises ValueError for bad input; Ctrl-C stops the run."""
    return PosesResult(_repose.poses(particle, int(n), int(seed), int(threads), method, float(damping_ratio),
                                     not full_settle, float(velocity_max), float(spin_max), persistence,
                                     dict(params)))


def quasi_static(particle, *, persistence=None):
    """The rest poses and their exact quasi-static probabilities (steepest descent of the centre of mass's
    height from a uniform random orientation: basin areas on the Gauss map / 4π), as a list of Pose."""
    return PosesResult(_repose.quasi_static(particle, persistence)).poses


def design(particle, target, **options):
    """Designs the centre of mass and/or the convex hull of `particle` for a target probability per outcome
    under quasi-static rolling, or under the toss with model="tossed" (`repose design`,
    docs/inverse-design.md), and returns a DesignResult.

    `target`: a path to a JSON file, or the JSON itself as a list of [normal, probability] pairs (convex_dice's
    form), {"outcomes": [{"normal": [...], "probability": p}, ...]} or {"fair": [normals]}; normals in the
    mesh's frame. Keyword options are the command line's: vary ("vertices+center-of-mass" by default,
    "center-of-mass", "vertices", "faces", "faces+center-of-mass"), mass ("follows" or "fixed"),
    outcome_angle (degrees), outcome_normals ("fixed" or "follow": after every step each outcome's normal
    moves to its most probable face's, convex_dice's rule), com_margin, max_move, max_step, min_edge,
    min_face, min_margin, smoothing (x L, L^2), tolerance, iterations, keep_faces_flat (True), html (a path:
    the HTML report, as --html). model="tossed" takes toss=dict(...) with drops, check_drops, seed, threads,
    iterations (tossed estimates), velocity_max, spin_max, damping_ratio and settle()'s parameters
    (drop_height, restitution, friction, ...); the result then has a "tossed" entry (the checks of both
    designs on unseen drops, the history). Raises ValueError for bad input; Ctrl-C stops a tossed design."""
    import json as _json
    import os as _os
    if isinstance(target, (str, _os.PathLike)) and not str(target).lstrip().startswith(("[", "{")):
        name = _os.fspath(target)
        with open(name, encoding="utf-8") as f:
            text = f.read()
    else:
        name = "target"
        text = target if isinstance(target, str) else _json.dumps(target)
    summary, vertices, triangles = _repose.design(particle, text, name, dict(options))
    return DesignResult(summary, vertices, triangles)
