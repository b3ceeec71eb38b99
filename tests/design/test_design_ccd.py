"""python-fcl's continuous collision (conservative advancement over each sample interval, the
bodies' motion interpolated between the planned samples) as an independent witness of the
verifier's sampled no-miss guarantee (rmot.sim.collide: no contact deeper than 10 µm can fall
between two samples unseen).

For every moving box body of the robot (the tools) and every box fixture, every 4 ms interval of the
planned trajectory goes through fcl.continuousCollide. The verifier must report a collision of
that pair at every interval where fcl finds one (to within one sample), and fcl must find one
inside every window the verifier reports.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rmot.lang import ir

fcl = pytest.importorskip("fcl")

ROOT = Path(__file__).resolve().parents[2]


def _shape(shape: object):  # type: ignore[no-untyped-def]
    """Boxes only: python-fcl 0.7's conservative advancement gave intermittent false contacts for
    capsule, cylinder and sphere pairs in this suite (order-dependent), never for box pairs."""
    if isinstance(shape, ir.Box):
        return fcl.Box(*shape.size)
    return None  # other primitives and meshes: not part of this cross-check


def _tf(m: np.ndarray):  # type: ignore[no-untyped-def]
    """fcl.Transform from contiguous float64 copies (python-fcl reads the buffers as given)."""
    return fcl.Transform(np.array(m[:3, :3], dtype=np.float64, order="C"), np.array(m[:3, 3], dtype=np.float64))


def _swept(shape, tf0, tf1, still, still_tf, request) -> bool:  # type: ignore[no-untyped-def]
    moving = fcl.CollisionObject(shape, tf0)
    result = fcl.ContinuousCollisionResult()
    fcl.continuousCollide(moving, tf1, still, still_tf, request, result)
    return bool(result.is_collide)


def _ccd_intervals(scene, robot: str, q: np.ndarray) -> dict[tuple[str, str], list[int]]:  # type: ignore[no-untyped-def]
    """(body, fixture) -> sample indices k where the body touches the fixture during [k, k+1]."""
    request = fcl.ContinuousCollisionRequest(num_max_iterations=10, toc_err=1e-6,
                                             ccd_motion_type=fcl.CCDMotionType.CCDM_LINEAR,
                                             gjk_solver_type=fcl.GJKSolverType.GST_LIBCCD,
                                             ccd_solver_type=fcl.CCDSolverType.CCDC_CONSERVATIVE_ADVANCEMENT)
    poses = scene.poses(robot, q)
    fixtures = [(b, _shape(b.shape)) for b in scene.bodies if b.kind == "fixture"]
    allowed = {frozenset(p) for p in scene.cell.allowed_contacts}
    out: dict[tuple[str, str], list[int]] = {}
    for body in scene.robot_bodies(robot):
        shape = _shape(body.shape)
        if shape is None or not body.moves:
            continue
        p = poses[body.name]
        for fixture, fshape in fixtures:
            if fshape is None or frozenset((body.name, fixture.name)) in allowed:
                continue
            still_tf = _tf(fixture.local)  # every fcl object named, so none is freed while fcl uses it
            still = fcl.CollisionObject(fshape, still_tf)
            tfs = [_tf(m) for m in p]
            hits = []
            radius = 0.5 * float(np.linalg.norm(body.shape.size))  # the box's farthest point
            for k in range(len(p) - 1):
                if _swept(shape, tfs[k], tfs[k + 1], still, still_tf, request) and \
                        _reachable(shape, p[k], p[k + 1], radius, still):
                    hits.append(k)
            if hits:
                out[(body.name, fixture.name)] = hits
    return out


def _reachable(shape, m0: np.ndarray, m1: np.ndarray, radius: float, still, depth: int = 0) -> bool:  # type: ignore[no-untyped-def]
    """Whether the box touches the fixture while it moves from m0 to m1 (translation linear,
    rotation slerped, as fcl's linear motion), decided with fcl.distance alone: python-fcl
    0.7's conservative advancement rarely reports a contact in an interval where there is none
    (about 1 run in 10, more since). No point of the box moves farther than
    |dp| + angle * radius over the interval, and no farther than that share of it over a part of
    it, so with clearances d0, d1 at the ends a contact needs d0 + d1 <= that bound; otherwise
    the interval is free, else it is halved (12 times at most: 1 us of a 4 ms interval), and a
    clearance under 1 um at a sample is a contact. A real contact is never filtered out."""
    d0, d1 = _distance(shape, m0, still), _distance(shape, m1, still)
    if min(d0, d1) <= 1e-6:
        return True
    dp = float(np.linalg.norm(m1[:3, 3] - m0[:3, 3]))
    cos = (np.trace(m0[:3, :3].T @ m1[:3, :3]) - 1.0) / 2.0
    moved = dp + float(np.arccos(np.clip(cos, -1.0, 1.0))) * radius
    if d0 + d1 > moved + 1e-12:
        return False
    if depth >= 12:
        return True  # undecided at 1 us: count it (never hide a contact)
    mid = _halfway(m0, m1)
    return (_reachable(shape, m0, mid, radius, still, depth + 1)
            or _reachable(shape, mid, m1, radius, still, depth + 1))


def _halfway(m0: np.ndarray, m1: np.ndarray) -> np.ndarray:
    from scipy.spatial.transform import Rotation, Slerp

    out = np.eye(4)
    out[:3, 3] = 0.5 * (m0[:3, 3] + m1[:3, 3])
    out[:3, :3] = Slerp([0.0, 1.0], Rotation.from_matrix([m0[:3, :3], m1[:3, :3]]))(0.5).as_matrix()
    return out


def _distance(shape, m: np.ndarray, still) -> float:  # type: ignore[no-untyped-def]
    result = fcl.DistanceResult()
    d = fcl.distance(fcl.CollisionObject(shape, _tf(m)), still, fcl.DistanceRequest(), result)
    return max(float(d), 0.0)


def _run(path: str):  # type: ignore[no-untyped-def]
    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan import plan_program
    from rmot.sim import verify
    from rmot.sim.scene import build_scene

    program = load_program(path, require_program=True).program
    plan = plan_program(program)
    report = verify(plan)
    tp = plan.tasks[0]
    scene = build_scene(program.cell, {tp.robot: {t.name for t in program.cell.tools if t.robot == tp.robot}})
    return tp, report, _ccd_intervals(scene, tp.robot, np.asarray(tp.trajectory.q))


def test_fcl_continuous_collision_agrees_with_the_sampled_verifier_on_a_collision() -> None:
    """examples/collision.rmot: fcl's swept contacts and the verifier's collision windows cover each other."""
    tp, report, ccd = _run(str(ROOT / "examples" / "collision.rmot"))
    t = np.asarray(tp.trajectory.t)
    step = float(t[1] - t[0])
    windows: dict[frozenset[str], list[tuple[float, float]]] = {}
    for d in report.errors:
        if d.code.id == "E300":
            windows.setdefault(frozenset(d.bodies), []).append((d.time_s, d.end_time_s))
    assert windows and ccd
    for (body, fixture), ks in ccd.items():
        spans = windows.get(frozenset((body, fixture)), [])
        for k in ks:  # every swept contact lies in a reported window (one sample of slack)
            assert any(t0 - step - 1e-9 <= t[k + 1] and t[k] <= t1 + step + 1e-9 for t0, t1 in spans), (body, fixture, t[k])
    for pair, spans in windows.items():
        ks = next((v for k, v in ccd.items() if frozenset(k) == pair), [])
        for t0, t1 in spans:  # every reported window holds a swept contact
            assert any(t0 - step - 1e-9 <= t[k + 1] and t[k] <= t1 + step + 1e-9 for k in ks), (pair, t0, t1)


def test_fcl_continuous_collision_finds_nothing_where_the_verifier_finds_nothing() -> None:
    """examples/inspect.rmot verifies clean; fcl finds no swept contact of any moving body with any fixture."""
    tp, report, ccd = _run(str(ROOT / "examples" / "inspect.rmot"))
    assert not [d for d in report.errors if d.code.id in ("E300", "E301", "E302")]
    assert ccd == {}
