"""Blended corners: the region a controller may drive, not only the one curve the plan verified.

The planner verifies one blend curve per corner (compiler/plan/blend.py). A controller drives
its own corner path, which the manuals bound but do not fix (lang/REFERENCE.md §8, corner
regions):

* RAPID zones, KRL `C_DIS`, URScript `r`, VAL3 blend, INFORM `PL`: the corner path stays inside
  the sphere of the zone radius around the programmed point. rmot prints the plan's blend
  radius, so that sphere has the record's `blend_radius`.
* Fanuc `CNT` (rounding grows with speed) and KRL `C_PTP` (a share of half the PTP motion; a
  robot whose cell declares KSS >= 8.2 writes `PTP .. C_DIS` instead, inside the sphere): the
  corner may start up to half the shorter neighbouring segment before the point.

The region swept by the robot is taken as every body that follows the TCP (the tool and the
links of the last three joints, or of every joint of a shorter arm) at the corner
configuration, grown by the region's radius: a fixture closer than that radius to one of them
may be touched by the controller's corner although the verified curve is clear (W340 for the
zone sphere, every controller; W341 for the bound, naming the vendors it applies to).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable

import numpy as np

from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.diagnostics import Amount, Diagnostic, Severity
from rmot.sim import codes
from rmot.sim.corner_vendors import BOUND_VENDORS, SPHERE_VENDORS
from rmot.sim.collide import candidate_pairs
from rmot.sim.exact import exact_distance
from rmot.sim.scene import Body, Scene

__all__ = ["corner_findings"]

_FOLLOWING_JOINTS = 3  # the links of the last three joints follow the TCP through a corner


def corner_findings(scene: Scene, tasks: Iterable[plan_types.TaskPlan],
                    exact_ptp: Collection[str] = ()) -> list[Diagnostic]:
    """W340/W341 at every blended move of every task (main timeline and variants); `exact_ptp`
    names the robots whose KRL PTP corner keeps to the zone sphere (KSS >= 8.2 declared:
    ir.RobotInstance.exact_ptp_approximation), so W341 does not name KRL C_PTP for them."""
    out: list[Diagnostic] = []
    for tp in tasks:
        moves = {i.uid: i for i in ir_tree.walk(tp.task.body) if isinstance(i, ir.Move)}
        pairs = _fixture_pairs(scene, tp.robot)
        if not pairs:
            continue
        variants = sorted({r.variant for r in tp.records})
        for variant in variants:
            records = sorted((r for r in tp.records if r.variant == variant and r.uid in moves
                              and r.tcp_pose is not None and r.q_target is not None),
                             key=lambda r: (r.t_start, r.t_end))
            for k, rec in enumerate(records):
                if rec.blend_radius <= 0.0 or k + 1 >= len(records):
                    continue
                prev = records[k - 1] if k > 0 else None
                krl_bound = moves[rec.uid].kind is ir.MotionKind.JOINT and tp.robot not in exact_ptp
                out += _corner(scene, tp, pairs, krl_bound, rec, prev, records[k + 1])
    return out


def _fixture_pairs(scene: Scene, robot: str) -> list[tuple[Body, Body]]:
    """(following body, fixture) pairs of `robot` that verification checks (allowed contacts out)."""
    dof = scene.robots[robot].robot.dof
    first = max(1, dof - _FOLLOWING_JOINTS + 1)
    out = []
    for a, b in candidate_pairs(scene, only_robot=robot):
        body, fixture = (a, b) if b.kind == "fixture" else (b, a)
        if fixture.kind != "fixture" or body.robot != robot:
            continue
        if body.kind == "tool" or (body.kind == "link" and body.joint >= first):
            out.append((body, fixture))
    return out


def _corner(scene: Scene, tp: plan_types.TaskPlan, pairs: list[tuple[Body, Body]], krl_bound: bool,
            rec: plan_types.InstructionRecord, prev: plan_types.InstructionRecord | None,
            nxt: plan_types.InstructionRecord) -> list[Diagnostic]:
    corner = _position(rec)
    before = float(np.linalg.norm(corner - _position(prev))) if prev is not None else np.inf
    after = float(np.linalg.norm(_position(nxt) - corner))
    sphere = rec.blend_radius
    bound = max(0.5 * min(before, after), sphere)
    poses = scene.poses(tp.robot, np.asarray(rec.q_target)[None])
    near: tuple[float, Body, Body] | None = None
    for body, fixture in pairs:
        d = exact_distance(body, fixture, poses[body.name][0], scene.fixture_pose(fixture))
        if d < bound and (near is None or d < near[0]):
            near = (d, body, fixture)
    if near is None:
        return []
    d, body, fixture = near
    amount = Amount(round(d * 1000, 3), "mm")
    if d < sphere:
        message = (f"'{body.name}' is {d * 1000:.1f} mm from '{fixture.name}' at this blended corner, "
                   f"inside its zone sphere ({sphere * 1000:.1f} mm): the {SPHERE_VENDORS} corner may "
                   "run anywhere in that sphere, not only on the verified blend; make the zone smaller "
                   "or the move fine")
        return [Diagnostic(codes.CORNER_SPHERE, Severity.WARNING, message, rec.span, (), rec.t_end,
                           rec.t_end, (body.name, fixture.name), amount, tp.task.name)]
    vendors = [BOUND_VENDORS["fanuc"]] + ([BOUND_VENDORS["krl"]] if krl_bound else [])
    message = (f"'{body.name}' is {d * 1000:.1f} mm from '{fixture.name}' at this blended corner: "
               f"{' and '.join(vendors)} may start the corner up to half the shorter neighbouring "
               f"segment ({bound * 1000:.1f} mm) before the point, beyond the verified "
               f"{sphere * 1000:.1f} mm blend; make the zone fine for that controller")
    return [Diagnostic(codes.CORNER_BOUND, Severity.WARNING, message, rec.span, (), rec.t_end,
                       rec.t_end, (body.name, fixture.name), amount, tp.task.name)]


def _position(rec: plan_types.InstructionRecord) -> np.ndarray:
    pose = rec.tcp_pose
    assert pose is not None  # records without a TCP pose are filtered out by the caller
    return np.asarray(pose.matrix()[:3, 3], dtype=float)

