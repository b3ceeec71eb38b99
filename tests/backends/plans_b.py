"""Plans for the URScript, INFORM, VAL3 and neutral backend tests (plain module: import with
`from plans_b import ...`).

`demo_plan()` covers every instruction kind with hand-chosen joints (no robot library);
`fk_plan()` builds records the way the planner does — TCP pose = FK(q) · tool, branch =
robot.branch(q) — from the robot library, for the numeric round trips.
"""

from __future__ import annotations

import math

import numpy as np
from backend_fixtures import FRONT_UP_NOFLIP, deg, motion, span_at

from rmot.lang import ir, ir_tree, plan_types

GRIPPER_TCP = ir.Pose.from_xyz_rpy(0.01, -0.02, 0.15, 0.0, math.radians(10.0), math.radians(30.0))
GRIPPER = ir.ToolRef("gripper", GRIPPER_TCP)
TABLE_POSE = ir.Pose.from_xyz_rpy(0.5, -0.1, 0.2, 0.0, 0.0, math.radians(90.0))
TABLE = ir.FrameRef("table", TABLE_POSE, TABLE_POSE)
BASE = ir.FrameRef(None)
PICK_POSE = ir.Pose.from_xyz_rpy(0.45, 0.1, 0.3, math.pi, 0.0, 0.0)
PLACE_POSE = ir.Pose.from_xyz_rpy(0.4, -0.15, 0.25, math.pi, 0.0, math.radians(45.0))
HOME_Q = tuple(deg(0, -30, 30, 0, 60, 0))


def cart(pose: ir.Pose, frame: ir.FrameRef = BASE) -> ir.CartesianTarget:
    return ir.CartesianTarget(pose, frame.pose.inverse() * pose)


def move(uid: int, kind: ir.MotionKind, target: ir.CartesianTarget | ir.JointTarget, line: int,
         m: ir.Motion | None = None, via: ir.CartesianTarget | None = None,
         tool: ir.ToolRef = GRIPPER, frame: ir.FrameRef = BASE) -> ir.Move:
    return ir.Move(uid=uid, kind=kind, target=target, via=via, motion=m or motion(),
                   tool=tool, frame=frame, span=span_at(line))


def make_cell(robot: str, tools: tuple[ir.ToolRef, ...] = (GRIPPER,)) -> ir.Cell:
    r1 = ir.RobotInstance("r1", ir.RobotSource(ir.RobotSourceKind.LIBRARY, robot), ir.Pose(), 6)
    return ir.Cell("democell", (r1,), tools=tuple(
        ir.Tool(t.name, "r1", None, t.tcp) for t in tools if t.name is not None))


def make_plan(body: tuple[ir.Instr, ...], records: list[plan_types.InstructionRecord], robot: str,
              name: str = "demo") -> plan_types.Plan:
    t_end = max((r.t_end for r in records), default=0.0)
    t = np.array([0.0, max(t_end, 0.004)])
    q = np.zeros((2, 6))
    traj = plan_types.Trajectory(t, q, q.copy(), q.copy())
    task = ir.Task("main", "r1", body, span=span_at(1))
    program = ir.Program(name, make_cell(robot), (task,), span=span_at(1))
    return plan_types.Plan(program, (plan_types.TaskPlan(task, "r1", traj, tuple(records)),))


def record(node: ir.Move, t0: float, q: np.ndarray, branch: ir.Config | None,
           tcp: ir.Pose | None, blend: float = 0.0, q_via: np.ndarray | None = None) -> plan_types.InstructionRecord:
    return plan_types.InstructionRecord(uid=node.uid, span=node.span, t_start=t0, t_end=t0 + 1.0,
                                     q_target=np.asarray(q, float), branch=branch, tcp_pose=tcp,
                                     q_via=None if q_via is None else np.asarray(q_via, float),
                                     blend_radius=blend, accel_share=node.motion.joint_accel)


def demo_body() -> tuple[ir.Instr, ...]:
    """Every instruction kind once, with source lines 3..20 of demo.rmot."""
    J, L, C = ir.MotionKind.JOINT, ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR
    slow = motion(speed=0.1, zone=0.0)
    blend = motion(speed=0.5, zone=0.025)
    return (
        move(1, J, ir.JointTarget(HOME_Q), 3, motion(joint=0.5)),
        move(2, L, cart(PICK_POSE), 4, blend),
        move(3, L, cart(PLACE_POSE, TABLE), 5, slow, frame=TABLE),
        ir.SetDigital(uid=4, port=1, value=True, signal="gripper_close", span=span_at(6)),
        ir.WaitTime(uid=5, duration=0.3, span=span_at(7)),
        ir.Pulse(uid=6, port=3, duration=0.2, span=span_at(8)),
        ir.WaitInput(uid=7, condition=ir.InputCondition(port=2, value=True), timeout=5.0, span=span_at(9)),
        ir.If(uid=8, condition=ir.InputCondition(port=2, value=True),
              then=(move(9, J, ir.JointTarget(HOME_Q), 11),),
              otherwise=(ir.WaitInput(uid=10, condition=ir.InputCondition(port=2, value=False), span=span_at(13)),),
              span=span_at(10)),
        ir.ProcCall(uid=11, proc="pick", args=("above",), span=span_at(14), body=(
            move(12, L, cart(PICK_POSE), 15, slow),
            ir.SetDigital(uid=13, port=1, value=False, span=span_at(16)),
        )),
        move(14, C, cart(PICK_POSE), 17, slow, via=cart(PLACE_POSE)),
        ir.Native(uid=15, vendor="urscript", text='textmsg("cycle done")', span=span_at(18)),
        ir.Native(uid=16, vendor="inform", text="MSG \"CYCLE DONE\"", span=span_at(19)),
        ir.Native(uid=17, vendor="val3", text='putln("cycle done")', span=span_at(20)),
    )


def demo_plan(robot: str = "ur5e") -> plan_types.Plan:
    """demo_body() with fixed joints (not FK-consistent: for text tables and golden files)."""
    body = demo_body()
    qs = {1: HOME_Q, 2: deg(10, -40, 50, 0, 80, 10), 3: deg(-20, -45, 60, 5, 75, 30),
          9: HOME_Q, 12: deg(10, -40, 50, 0, 80, 10), 14: deg(12, -38, 48, 0, 82, 12)}
    blends = {2: 0.025}
    recs, t = [], 0.0
    for node in ir_tree.walk(body):
        if isinstance(node, ir.Move):
            tcp = node.target.pose if isinstance(node.target, ir.CartesianTarget) else PICK_POSE
            recs.append(record(node, t, np.asarray(qs[node.uid]), FRONT_UP_NOFLIP, tcp,
                               blends.get(node.uid, 0.0), deg(0, -42, 55, 0, 78, 5) if node.via else None))
            t += 1.0
    return make_plan(body, recs, robot)


def fk_plan(robot_name: str, qs: np.ndarray, *, frame: ir.FrameRef = BASE) -> plan_types.Plan:
    """Moves cycling joint / linear / circular to FK(q)·tool of each q (circular via: q nudged).

    Records carry q, robot.branch(q), the TCP pose and the flange pose, as the planner's do.
    """
    from rmot.sim.robots import load_robot

    robot = load_robot(robot_name)
    kinds = (ir.MotionKind.JOINT, ir.MotionKind.LINEAR, ir.MotionKind.CIRCULAR)
    body: list[ir.Instr] = []
    recs: list[plan_types.InstructionRecord] = []
    for k, q in enumerate(qs):
        flange = ir.Pose.from_matrix(robot.fk(q))
        tcp = flange * GRIPPER_TCP
        kind = kinds[k % 3]
        q_via = q + np.array([0.03, 0.02, -0.02, 0.0, 0.03, 0.0]) if kind is ir.MotionKind.CIRCULAR else None
        via = cart(ir.Pose.from_matrix(robot.fk(q_via)) * GRIPPER_TCP, frame) if q_via is not None else None
        target = ir.JointTarget(tuple(q)) if kind is ir.MotionKind.JOINT else cart(tcp, frame)
        node = move(k + 1, kind, target, k + 3, via=via, frame=frame)
        body.append(node)
        rec = record(node, float(k), q, robot.branch(q), tcp, q_via=q_via)
        recs.append(plan_types.InstructionRecord(**{**{f: getattr(rec, f) for f in (
            "uid", "span", "t_start", "t_end", "q_target", "branch", "tcp_pose", "q_via", "blend_radius",
            "accel_share")},
            "flange_pose": flange}))
    return make_plan(tuple(body), recs, robot_name)


def sample_joints(robot_name: str, n: int, seed: int = 7) -> np.ndarray:
    """n joint vectors inside the limits (a 20 % margin), away from the wrist singularity."""
    from rmot.sim.robots import load_robot

    robot = load_robot(robot_name)
    rng = np.random.default_rng(seed)
    lo, hi = robot.joint_limits[:, 0], robot.joint_limits[:, 1]
    mid, half = (lo + hi) / 2, (hi - lo) / 2 * 0.8
    out = []
    while len(out) < n:
        q = mid + rng.uniform(-1, 1, robot.dof) * half
        if abs(math.sin(q[4])) > 0.2 and robot.branch(q).shoulder is not None:
            out.append(q)
    return np.array(out)

