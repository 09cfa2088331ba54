"""The Python package against the command line and against closed forms (issue 15).

The CLI's --json and the Python results come from the same library serialiser, so they must be equal to the
bit: every comparison with the CLI is exact (==), never approximate. Physical checks use independent
references: the unit cube's inertia (m/6 on the diagonal), the tetrahedron's and the cube's quasi-static
probabilities by symmetry (1/4 and 1/6), a unit quaternion, an energy that damping never raises.
Run with: PYTHONPATH=<build>/python REPOSE_CLI=<build>/apps/repose/repose python3 -m pytest python/tests
"""
import json
import os
import pathlib
import signal
import subprocess
import threading
import time
import _thread

import numpy as np
import pytest

import repose

CLI = os.environ.get("REPOSE_CLI", "repose")
DATA = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data"


def cli_json(*args):
    out = subprocess.run([CLI, *args, "--json"], capture_output=True, text=True)
    assert out.returncode in (0, 3), out.stderr
    return json.loads(out.stdout)


def without_timing(d):
    d = dict(d)
    d.pop("timing", None)
    return d


def test_the_readme_example_rests():
    r = repose.settle(repose.Particle.shape("tetrahedron:edge=1"), [1, 0, 0, 0])
    assert r.status == "rest"


@pytest.mark.parametrize("shape,orientation,options", [
    ("tetrahedron:edge=1", "axis-angle:1,2,3,0.7", {}),
    ("box:x=1,y=2,z=3", "quat:0.9,0.3,-0.2,0.1", {"damping": 0.5}),
    ("cylinder:r=0.5,h=1,n=32", "axis-angle:1,0,0,1.0", {"damping": 0.2, "drop_height": 0.3}),
    ("irregular:seed=3", "axis-angle:0,1,1,2.0", {"damping": 0.01, "integrator": "paper"}),
    ("box:x=1,y=1,z=1", "axis-angle:1,1,0,0.4", {"velocity": [1.0, 0.5, 0.0], "spin": [0, 2.0, 1.0],
                                                  "restitution": 0.5, "friction": 0.3}),
])
def test_settle_equals_the_cli_json(shape, orientation, options):
    args = ["settle", shape, "--orientation", orientation]
    for k, v in options.items():
        args += ["--" + k.replace("_", "-"), ",".join(map(repr, v)) if isinstance(v, list) else str(v)]
    expected = cli_json(*args)
    got = repose.settle(repose.Particle.shape(shape), orientation, **options).to_dict()
    assert got == expected


def test_orientation_as_numbers_equals_the_spec():
    p = repose.Particle.shape("box:x=1,y=2,z=3")
    a = repose.settle(p, [0.9, 0.3, -0.2, 0.1], damping=0.5).to_dict()
    b = repose.settle(p, "quat:0.9,0.3,-0.2,0.1", damping=0.5).to_dict()
    assert a == b


def test_poses_equal_the_cli_json():
    expected = cli_json("poses", "box:x=1,y=2,z=3", "-n", "600", "--seed", "7", "--threads", "2")
    got = repose.poses(repose.Particle.shape("box:x=1,y=2,z=3"), n=600, seed=7, threads=2)
    assert without_timing(got.to_dict()) == without_timing(expected)
    assert sum(p.count for p in got.poses) == 600
    assert abs(got.probabilities.sum() - 1) < 1e-12


def test_tossed_poses_equal_the_cli_json():
    args = ["poses", "tetrahedron:edge=1", "-n", "200", "--restitution", "0.4", "--friction", "0.5",
            "--velocity-max", "1", "--spin-max", "3", "--drop-height", "0.5"]
    expected = cli_json(*args)
    got = repose.poses(repose.Particle.shape("tetrahedron:edge=1"), n=200, restitution=0.4, friction=0.5,
                       velocity_max=1.0, spin_max=3.0, drop_height=0.5)
    assert without_timing(got.to_dict()) == without_timing(expected)


def test_poses_do_not_depend_on_the_thread_count():
    p = repose.Particle.shape("irregular:seed=3")
    one = repose.poses(p, n=300, threads=1).to_dict()
    two = repose.poses(p, n=300, threads=2).to_dict()
    assert without_timing(one) == without_timing(two)


def test_quasi_static_probabilities_by_symmetry():
    tetra = repose.quasi_static(repose.Particle.shape("tetrahedron:edge=1"))
    cube = repose.quasi_static(repose.Particle.shape("box:x=1,y=1,z=1"))
    # Exact basin areas: each face of a regular solid has the same share; 1e-12 is round-off.
    assert [round(p.quasi_static_probability, 12) for p in tetra] == [0.25] * 4
    assert np.allclose([p.quasi_static_probability for p in cube], 1 / 6, rtol=0, atol=1e-12)
    expected = cli_json("poses", "box:x=1,y=2,z=3", "-n", "1", "--method", "quasi-static")
    got = repose.quasi_static(repose.Particle.shape("box:x=1,y=2,z=3"))
    assert sorted(p.quasi_static_probability for p in got) == \
        sorted(p["quasi_static_probability"] for p in expected["poses"])


def test_unit_cube_from_arrays():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    p = repose.Particle.from_arrays(v, f, density=2.0)
    assert p.mass == pytest.approx(2.0, rel=1e-14)
    assert np.allclose(p.com, [0.5, 0.5, 0.5], atol=1e-15)
    # A cube of side a and mass m: I = m·a²/6 about every axis through its centre.
    assert np.allclose(p.inertia, np.eye(3) * 2.0 / 6, atol=1e-14)
    assert p.length == pytest.approx((6 / np.pi) ** (1 / 3), rel=1e-14)
    assert len(p.hull_vertices) == 8 and len(p.hull_faces) == 6


def cube_arrays(side=1.0, offset=(0.0, 0.0, 0.0)):
    v = np.array([[x, y, z] for x in (0, side) for y in (0, side) for z in (0, side)], dtype=float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v + np.array(offset), f


def test_a_point_cloud_in_millimetres_is_its_solid_hull_in_metres():
    # The corners of a 10 x 20 x 30 mm box and two points inside: 6e-6 m^3, 6 g at 1000 kg/m^3.
    corners = [[x, y, z] for x in (0, 10) for y in (0, 20) for z in (0, 30)]
    v = np.array(corners + [[5, 10, 15], [2, 3, 4]], dtype=float)
    p = repose.Particle.from_arrays(v, np.zeros((0, 3), dtype=int), density=1000, units="mm",
                                    inertia="convex")
    assert p.surface_is_hull and p.inertia_model == "convex" and p.scale == pytest.approx(1e-3)
    assert p.volume == pytest.approx(6e-6, rel=1e-12)
    assert p.mass == pytest.approx(6e-3, rel=1e-12)
    # m/12 (b^2 + c^2) about x, with b, c in metres
    assert p.inertia[0, 0] == pytest.approx(6e-3 / 12 * (0.02 ** 2 + 0.03 ** 2), rel=1e-12)
    assert p.file_report["vertices"] == 10
    with pytest.raises(ValueError, match="units and scale"):
        repose.Particle.from_arrays(v, np.zeros((0, 3), dtype=int), units="mm", scale=2.0, inertia="convex")


def test_a_hollow_cube_has_the_shells_inertia():
    # A thin-walled cube of side a and mass M: I = 5/18 M a^2 about every axis through its centre (six plates:
    # two of M/6 about their normal, M/6 a^2/6 each, and four edge-on, M/6 (a^2/12 + a^2/4) each).
    v, f = cube_arrays(2.0)
    p = repose.Particle.from_arrays(v, f, density=0.5, inertia="shell")
    mass = 0.5 * 6 * 2.0 ** 2
    assert p.mass == pytest.approx(mass, rel=1e-14)
    assert np.allclose(p.inertia, np.eye(3) * 5 / 18 * mass * 2.0 ** 2, rtol=0, atol=1e-13)


def test_repair_closes_a_hole_and_reports_it():
    v, f = cube_arrays()
    top = [i for i, t in enumerate(f) if all(v[k][2] == 1 for k in t)]
    assert len(top) == 2
    open_cube = np.delete(f, top, axis=0)
    with pytest.raises(ValueError, match="repair"):
        repose.Particle.from_arrays(v, open_cube)
    p = repose.Particle.from_arrays(v, open_cube, repair=True)
    assert p.volume == pytest.approx(1.0, rel=1e-12)  # a flat hole in a flat face: filled exactly
    assert p.repair_report["holes_filled"] == 1
    assert p.file_report["triangles"] == 10
    assert repose.Particle.from_arrays(*cube_arrays()).repair_report is None


def test_file_and_repair_reports_equal_the_cli_info_json():
    # One serialiser for both (output/report): the same keys and values as `repose info --repair --json`.
    path = str(DATA / "open_cube.off")
    expected = cli_json("info", path, "--repair")
    p = repose.Particle.load(path, repair=True)
    assert p.file_report == expected["file"]
    assert p.repair_report == expected["repair"]
    assert p.repair_report["holes_filled"] == 1


def test_largest_component_keeps_the_bigger_of_two_cubes():
    small_v, small_f = cube_arrays(1.0)
    big_v, big_f = cube_arrays(2.0, offset=(5.0, 0.0, 0.0))
    v = np.vstack([small_v, big_v])
    f = np.vstack([small_f, big_f + len(small_v)])
    both = repose.Particle.from_arrays(v, f, repair=True)
    assert both.volume == pytest.approx(9.0, rel=1e-12)  # one rigid body of two parts
    big = repose.Particle.from_arrays(v, f, largest_component=True)
    assert big.volume == pytest.approx(8.0, rel=1e-12)
    assert big.repair_report["input_components"] == 2 and big.repair_report["kept_components"] == 1


def test_a_mesh_in_millimetres():
    metres = repose.Particle.load(str(DATA / "cube.off"))
    mm = repose.Particle.load(str(DATA / "cube.off"), units="mm")
    assert mm.length == pytest.approx(metres.length * 1e-3, rel=1e-14)
    assert mm.volume == pytest.approx(metres.volume * 1e-9, rel=1e-13)


def test_the_time_series():
    p = repose.Particle.shape("box:x=1,y=2,z=3")
    r = repose.settle(p, "axis-angle:1,1,1,0.9", damping=1.0)
    s = r.series
    n = len(s)
    assert n > 10
    assert s.t.shape == (n,) and s.quaternion.shape == (n, 4) and s.omega.shape == (n, 3)
    assert s.com.shape == (n, 3) and s.contact.shape == (n,) and s.contact_count.shape == (n,)
    assert np.all(np.diff(s.t) > 0)
    assert np.allclose(np.linalg.norm(s.quaternion, axis=1), 1, atol=1e-12)
    # Damping only removes energy: the total never rises by more than the integrator's error (tolerance
    # 1e-9 relative to m·g·L per step; 1e-6·m·g·L over the run is a generous bound).
    energy = s.kinetic_energy + s.potential_energy
    assert np.all(np.diff(energy) <= 1e-6 * p.mass * 9.81 * p.length)
    assert s.t[-1] == pytest.approx(r.time_to_rest, rel=1e-12)
    assert set(s.contact) <= {"free_fall", "point", "line", "surface", "flight"}


def test_the_velocity_is_the_rate_of_the_centre_of_mass():
    # In the paper's rotation and in the frictional contact phase: the sampled velocity equals the central
    # difference of the sampled positions, where two 1 ms intervals hold no event (the same contact type, no
    # jump). The difference's error is O(dt^2 |v''|), below 1e-4 m/s for this metre-sized box (|v''| < 100 m/s^3);
    # the bound 1e-3 m/s stays far below what a sign, frame or lever-arm error gives, O(|v|) > 0.05 m/s.
    p = repose.Particle.shape("box:x=1,y=2,z=3")
    for params in ({"damping": 1.0}, {"friction": 0.3, "drop_height": 0.5}):
        r = repose.settle(p, "axis-angle:1,1,1,0.9", sample_dt=1e-3, **params)
        s = r.series
        assert s.velocity.shape == (len(s), 3)
        dt = s.t[2:] - s.t[:-2]
        regular = np.abs(dt - 2e-3) < 1e-9  # two steps of exactly 1 ms: no event between
        moving = np.linalg.norm(s.velocity[1:-1], axis=1) > 0.05
        rate = (s.com[2:] - s.com[:-2]) / dt[:, None]
        contact = np.asarray(s.contact)
        # Where the pivot changes or a vertex lands, the velocity jumps (by ~1 m/s here) and the positions have
        # no derivative: those intervals are left out, found by the velocity's own jump (over 2 ms a smooth
        # motion of this box changes it by < 0.05 m/s).
        jump = np.linalg.norm(s.velocity[2:] - s.velocity[:-2], axis=1) > 0.1
        # An impact (a small one: a rocking corner's, a Zeno capture's) between two samples is an event too.
        impact_times = np.array([i["t"] for i in r.impacts])
        struck = np.array([np.any((impact_times > a) & (impact_times <= b)) for a, b in zip(s.t[:-2], s.t[2:])])
        smooth = regular & moving & (contact[2:] == contact[:-2]) & ~jump & ~struck
        assert smooth.sum() > 50
        assert np.abs(rate - s.velocity[1:-1])[smooth].max() < 1e-3


def test_the_stepwise_engine_ends_as_settle_does():
    p = repose.Particle.shape("irregular:seed=3")
    s = repose.Settler(p, "axis-angle:0,1,1,2.0", damping=0.01)
    steps = 0
    while s.step():
        steps += 1
        assert steps < 1_000_000
    assert s.status == "rest"
    assert s.result().to_dict() == repose.settle(p, "axis-angle:0,1,1,2.0", damping=0.01).to_dict()


def test_advance_to_a_dem_step():
    p = repose.Particle.shape("tetrahedron:edge=1")
    s = repose.Settler(p, "axis-angle:1,0,0,0.5", damping=0.1)
    s.advance_to(0.05)
    assert s.sample()["t"] == pytest.approx(0.05, abs=1e-15)


@pytest.mark.parametrize("call,message", [
    (lambda: repose.Particle.shape("box:x=-1,y=1,z=1"), "box"),
    (lambda: repose.Particle.load("/nonexistent/grain.stl"), "/nonexistent/grain.stl"),
    (lambda: repose.Particle.shape("box:x=1,y=1,z=1", density=-2), "density"),
    (lambda: repose.settle(repose.Particle.shape("box:x=1,y=1,z=1"), damping=-1), "damping"),
    (lambda: repose.settle(repose.Particle.shape("box:x=1,y=1,z=1"), dampnig=1), "unknown parameter 'dampnig'"),
    (lambda: repose.settle(repose.Particle.shape("box:x=1,y=1,z=1"), "quat:0,0,0,0"), "quat"),
    (lambda: repose.poses(repose.Particle.shape("box:x=1,y=1,z=1"), n=0), "n >= 1"),
    (lambda: repose.Particle.load(str(DATA / "open_cube.off")), "--inertia"),
])
def test_bad_input_is_a_value_error_with_one_line(call, message):
    with pytest.raises(ValueError) as error:
        call()
    text = str(error.value)
    assert message in text and "\n" not in text


def test_ctrl_c_stops_a_long_study():
    # Python turns SIGINT into KeyboardInterrupt only if SIGINT was not ignored when it started, and a job run
    # in the background of a shell starts with it ignored (then interrupt_main does nothing and the study
    # below would run for an hour): install Python's handler for the test, as an interactive session has it.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        p = repose.Particle.shape("irregular:seed=3")
        timer = threading.Timer(0.3, _thread.interrupt_main)
        start = time.monotonic()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            repose.poses(p, n=10_000_000, threads=2)
        timer.cancel()
        assert time.monotonic() - start < 10  # the whole study would take minutes
    finally:
        signal.signal(signal.SIGINT, previous)


def test_the_gil_is_released_during_a_run():
    p = repose.Particle.shape("irregular:seed=3")
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    worker = threading.Thread(target=count)
    worker.start()
    repose.poses(p, n=2000, threads=1)
    stop.set()
    worker.join()
    assert len(ticks) > 10


def test_a_toss_with_friction_reports_its_whole_ledger_and_every_fallback():
    # Issue 48: with finite friction the energy ledger's terms close the change of mechanical energy to the
    # integrator's tolerance (1e-6 m g L, far below any one term's size here, ~0.1-10 m g L), and every
    # fallback is counted by kind; with friction infinite the output keeps its earlier form (no such keys).
    p = repose.Particle.shape("box:x=1,y=2,z=3")
    r = repose.settle(p, "axis-angle:1,1,1,0.9", friction=0.3, restitution=0.5, drop_height=0.5,
                      velocity=(1.0, 0.0, 0.0), spin=(0.0, 3.0, 0.0))
    mgl = p.mass * 9.81 * p.length
    e = r.energy
    assert e.change == pytest.approx(e.end - e.start, abs=1e-12 * mgl)
    assert abs(e.residual) < 1e-6 * mgl
    assert e.impact_losses > 1e-3 * mgl and e.friction_work >= 0
    for kind in ("handovers_stalled", "handovers_timed_out", "bounded_rounds", "pyramid_forces",
                 "unsolved_forces", "unresolved_forces"):
        assert r.fallbacks[kind] == 0, kind
    assert set(r.captures._data) == {"zeno", "painleve", "tip_offs"}
    paper = repose.settle(p, "axis-angle:1,1,1,0.9", drop_height=0.5)
    assert not hasattr(paper, "fallbacks")


def test_design_meets_a_cube_target_and_rejects_bad_options(tmp_path):
    target = [[[0, 0, -1], 0.4], [[0, 0, 1], 0.12], [[1, 0, 0], 0.12], [[-1, 0, 0], 0.12], [[0, 1, 0], 0.12],
              [[0, -1, 0], 0.12]]
    report = tmp_path / "design.html"
    d = repose.design(repose.Particle.shape("box:x=1,y=1,z=1"), target, html=str(report))
    assert d.reached and d.max_error < 1e-4
    page = report.read_text(encoding="utf-8")
    assert page.lower().startswith("<!doctype html>") and "box:x=1,y=1,z=1" in page
    assert abs(d.achieved()[0] - 0.4) < 1e-4
    assert d.vertices.shape[1] == 3 and d.triangles.shape[1] == 3 and len(d.triangles) >= 12
    with pytest.raises(ValueError, match="max_mvoe"):
        repose.design(repose.Particle.shape("box:x=1,y=1,z=1"), target, max_mvoe=0.2)
    with pytest.raises(ValueError, match="sum to"):
        repose.design(repose.Particle.shape("box:x=1,y=1,z=1"), [[[0, 0, 1], 0.5]])
    with pytest.raises(ValueError, match="keep_faces_flat"):
        repose.design(repose.Particle.shape("box:x=1,y=1,z=1"), target, keep_faces_flat=1)
    with pytest.raises(ValueError, match="outcome_normals"):
        repose.design(repose.Particle.shape("box:x=1,y=1,z=1"), target, outcome_normals="moving")
    followed = repose.design(repose.Particle.shape("box:x=1,y=1,z=1"), target, vary="vertices",
                             outcome_normals="follow", min_margin=0.02)
    assert followed.options["outcome_normals"] == "follow" and followed.options["min_margin"] == 0.02
    assert all("design_normal" in o and o["margin"] > 0 for o in followed.outcomes)


def test_design_for_the_toss_reports_its_checks_and_rejects_bad_toss_options():
    target = [[[0, 0, -1], 0.4], [[0, 0, 1], 0.12], [[1, 0, 0], 0.12], [[-1, 0, 0], 0.12], [[0, 1, 0], 0.12],
              [[0, -1, 0], 0.12]]
    cube = repose.Particle.shape("box:x=1,y=1,z=1")
    d = repose.design(cube, target, model="tossed",
                      toss=dict(drop_height=4, velocity_max=4, spin_max=4, restitution=0.1, friction=0.3,
                                drops=60, check_drops=80, iterations=1, threads=1))
    assert d.model == "tossed"
    assert d.tossed["check"]["drops"] == [60, 140]
    assert sum(d.tossed["check"]["counts"]) == 80
    assert d.tossed["toss"]["friction"] == 0.3
    assert d.vertices.shape[1] == 3
    with pytest.raises(ValueError, match="drops"):
        repose.design(cube, target, model="tossed", toss=dict(drops=0))
    with pytest.raises(ValueError, match="frictoin"):
        repose.design(cube, target, model="tossed", toss=dict(frictoin=0.3))
    with pytest.raises(ValueError, match="model"):
        repose.design(cube, target, toss=dict(drops=10))
