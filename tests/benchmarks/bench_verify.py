"""Verification speed: configurations checked per second (6-axis arm, 20 fixtures), the time
to verify a 100-instruction program, and coal vs python-fcl on the same exact checks.

Run: .venv/bin/python -m pytest tests/benchmarks/bench_verify.py --benchmark-only -s
(the numbers of interest are printed and stored in each benchmark's extra_info).
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from rmot.lang import ir, plan_types
from rmot.sim.robots import load_robot
from rmot.sim.collide import Timeline, candidate_pairs, check_timeline
from rmot.sim.exact import coal_shapes
from rmot.sim.scene import build_scene

N_SAMPLES = 20_000


def _twenty_fixture_cell(rings: tuple[float, float] = (0.55, 0.95)) -> ir.Cell:
    """A UR5e at the origin amid 20 boxes and cylinders on two rings (radii in m)."""
    rng = np.random.default_rng(7)
    fixtures = []
    for k in range(20):
        angle = 2 * np.pi * k / 20
        radius = rings[0] if k % 2 else rings[1]
        at = (radius * np.cos(angle), radius * np.sin(angle), float(rng.uniform(-0.2, 0.6)))
        geometry: ir.Geometry = (ir.Box((0.12, 0.12, float(rng.uniform(0.1, 0.4)))) if k % 3
                                 else ir.Cylinder(0.05, float(rng.uniform(0.2, 0.5))))
        fixtures.append(ir.Fixture(f"f{k:02d}", geometry, ir.Pose(at)))
    robot = ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.LIBRARY, "ur5e"), ir.Pose(), 6)
    return ir.Cell("bench", (robot,), tuple(fixtures))


def _joint_path(robot, n: int) -> np.ndarray:
    """A smooth path through random configurations within a third of the joint ranges."""
    rng = np.random.default_rng(3)
    lo, hi = robot.joint_limits[:, 0] / 3, robot.joint_limits[:, 1] / 3
    waypoints = lo + rng.random((n // 500 + 1, robot.dof)) * (hi - lo)
    s = np.linspace(0, len(waypoints) - 1, n)
    return np.stack([np.interp(s, np.arange(len(waypoints)), waypoints[:, j]) for j in range(robot.dof)], axis=1)


RINGS = {"busy": (0.55, 0.95), "clear": (0.95, 1.25)}


@pytest.fixture(scope="module", params=sorted(RINGS))
def setting(request):
    """busy: fixtures inside the reach, the path hits some (~100 contact intervals);
    clear: the same fixtures just outside the path (no contact; most blocks pruned)."""
    cell = _twenty_fixture_cell(RINGS[request.param])
    robot = load_robot("ur5e")
    scene = build_scene(cell, {}, {"r1": robot})
    q = _joint_path(robot, N_SAMPLES)
    t = np.arange(N_SAMPLES) * 0.004
    timeline = Timeline(t, {"r1": q}, {"r1": np.full_like(q, 5.0)})
    return scene, timeline, candidate_pairs(scene), robot, q


def test_configurations_per_second(benchmark, setting) -> None:
    """All fixture and self pairs of every sample, with the no-miss bound between samples."""
    scene, timeline, pairs, _, _ = setting
    hits = benchmark.pedantic(check_timeline, args=(scene, timeline, pairs), rounds=5, iterations=1)
    rate = N_SAMPLES / benchmark.stats.stats.median
    # CPU time of this process as well: the wall clock suffers when the machine is shared
    cpu = min(_timed(lambda: check_timeline(scene, timeline, pairs), time.process_time) for _ in range(3))
    benchmark.extra_info.update(configs_per_s=round(rate), configs_per_cpu_s=round(N_SAMPLES / cpu),
                                pairs=len(pairs), fixtures=20, hits=len(hits))
    print(f"\n{len(pairs)} pairs, {N_SAMPLES} samples, {len(hits)} contact intervals: {rate:,.0f} configurations/s "
          f"(wall median), {N_SAMPLES / cpu:,.0f} per CPU second")


def test_engine_ratio_coal_vs_fcl(benchmark, setting) -> None:
    """Exact collision of every solid against every fixture per configuration: coal through
    pinocchio's GeometryModel, coal pair by pair, and python-fcl pair by pair."""
    import coal
    import fcl
    import pinocchio as pin

    scene, _, _, robot, q = setting
    configs = q[:: N_SAMPLES // 400][:400]
    links = [b for b in scene.bodies if b.kind == "link" and b.moves]
    fixtures = [b for b in scene.bodies if b.kind == "fixture"]
    model = robot.model
    geom = pin.GeometryModel()
    ids_l = [geom.addGeometryObject(pin.GeometryObject(b.name, robot.solids[b.solid_index].joint_id, 0,
                                                       pin.SE3(robot.solids[b.solid_index].placement.matrix()),
                                                       coal_shapes(b.shape)[0])) for b in links]
    ids_f = [geom.addGeometryObject(pin.GeometryObject(b.name, 0, 0, pin.SE3(b.local), coal_shapes(b.shape)[0]))
             for b in fixtures]
    for i in ids_l:
        for j in ids_f:
            geom.addCollisionPair(pin.CollisionPair(i, j))
    gdata = geom.createData()
    data = model.createData()
    qm = robot.to_model(configs)

    def pin_coal() -> int:
        return sum(bool(pin.computeCollisions(model, data, geom, gdata, qk, False)) for qk in qm)

    solid_poses = robot.solid_poses_batch(configs)
    fcl_links = [fcl.CollisionObject(_fcl_shape(fcl, b.shape)) for b in links]
    fcl_fix = [fcl.CollisionObject(_fcl_shape(fcl, b.shape), fcl.Transform(b.local[:3, :3], b.local[:3, 3])) for b in fixtures]
    coal_links = [coal_shapes(b.shape)[0] for b in links]
    coal_fix = [(coal_shapes(b.shape)[0], coal.Transform3s(b.local[:3, :3], b.local[:3, 3])) for b in fixtures]

    def python_fcl() -> int:
        hits = 0
        req = fcl.CollisionRequest()
        for k in range(len(configs)):
            for obj, body in zip(fcl_links, links, strict=True):
                pose = solid_poses[k, body.solid_index]
                obj.setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
                for other in fcl_fix:
                    hits += fcl.collide(obj, other, req, fcl.CollisionResult())
        return hits

    def coal_pairs() -> int:
        hits = 0
        req = coal.CollisionRequest()
        res = coal.CollisionResult()
        for k in range(len(configs)):
            for shape, body in zip(coal_links, links, strict=True):
                pose = solid_poses[k, body.solid_index]
                tf = coal.Transform3s(pose[:3, :3], pose[:3, 3])
                for other, otf in coal_fix:
                    res.clear()
                    hits += coal.collide(shape, tf, other, otf, req, res)
        return hits

    timings = {}
    for name, fn in (("pin_coal", pin_coal), ("coal_pairs", coal_pairs), ("python_fcl", python_fcl)):
        best = min(_timed(fn) for _ in range(3))
        timings[name] = best / len(configs) * 1e6
    benchmark.pedantic(pin_coal, rounds=3, iterations=1)
    ratio = timings["python_fcl"] / timings["pin_coal"]
    benchmark.extra_info.update({k + "_us_per_config": round(v, 2) for k, v in timings.items()})
    benchmark.extra_info["fcl_over_pin_coal"] = round(ratio, 2)
    print(f"\n{len(links)}x{len(fixtures)} pairs per config: " +
          ", ".join(f"{k} {v:.1f} us" for k, v in timings.items()) + f"; python-fcl / coal = {ratio:.2f}")


def _timed(fn, clock=time.perf_counter) -> float:
    t0 = clock()
    fn()
    return clock() - t0


def _fcl_shape(fcl, shape):
    if isinstance(shape, ir.Box):
        return fcl.Box(*shape.size)
    if isinstance(shape, ir.Cylinder):
        return fcl.Cylinder(shape.radius, shape.height)
    if isinstance(shape, ir.Capsule):
        return fcl.Capsule(shape.radius, shape.length)
    if isinstance(shape, ir.Sphere):
        return fcl.Sphere(shape.radius)
    raise TypeError(type(shape).__name__)


HUNDRED_MOVES = """
program hundred on r1 {
  tool gripper
  frame table_top
  speed 800 mm/s
  zone 5 mm
  target home = joints(0, -20, 20, 0, 60, 0) deg
  move joint home
BODY
  move joint home
}
"""


def _hundred_instruction_program() -> str:
    rng = np.random.default_rng(11)
    lines = []
    for k in range(49):
        x, y = rng.uniform(-250, 250), rng.uniform(-200, 200)
        lines.append(f"  move linear pose(x={x:.0f}mm, y={y:.0f}mm, z=150mm, rx=150deg)")
        lines.append(f"  move linear pose(x={x:.0f}mm, y={y:.0f}mm, z=60mm, rx=150deg)" + (" zone fine" if k % 5 == 0 else ""))
    return HUNDRED_MOVES.replace("BODY", "\n".join(lines))


def test_verify_hundred_instruction_program(benchmark, tmp_path) -> None:
    """verify() of a 100-move pick-and-place program in the default cell (planning not timed)."""
    from rmot.compiler.frontend import load_text
    from rmot.compiler.plan import plan_program
    from rmot.sim import verify

    front = load_text(_hundred_instruction_program(), str(tmp_path / "hundred.rmot"))
    assert not front.has_errors, [d.message for d in front.diagnostics]
    t0 = time.perf_counter()
    plan: plan_types.Plan = plan_program(front.program)
    planning = time.perf_counter() - t0
    report = benchmark.pedantic(verify, args=(plan,), rounds=5, iterations=1)
    samples = sum(tp.trajectory.t.size for tp in plan.tasks)
    benchmark.extra_info.update(planning_s=round(planning, 3), samples=samples, findings=len(report.diagnostics))
    print(f"\n100 moves: planning {planning:.2f} s, verify median {benchmark.stats.stats.median * 1000:.0f} ms "
          f"for {samples} samples ({len(report.errors)} errors)")
