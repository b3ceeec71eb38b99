"""A lower bound on a task's duration, without IK or timing: the planner refuses a program
whose timelines are too long (E124) from it before it times any move.

Counted: waits, fixed move times, joint moves between two joint-space targets, each at
least the slowest joint's travel over its speed limit times the move's speed fraction, and
linear moves between two Cartesian targets of the same tool, each at least the straight TCP
travel over the programmed TCP speed (which the timing never exceeds), less the zone radii at
both ends where a blend may cut the corner (no acceleration phase: a bound from below). Only instructions that always run are counted (the
task body, every loop iteration, inlined proc bodies); an `if` or `while` counts nothing and
forgets the last joint position, as does a move to a Cartesian target; a `stop` ends the count.
"""

from __future__ import annotations

import numpy as np

from rmot.lang import ir

__all__ = ["least_duration_s"]


def least_duration_s(velocity_limits: np.ndarray, body: tuple[ir.Instr, ...]) -> float:
    """Seconds the instructions `body` take at least on a robot of these joint speed limits (rad/s, m/s)."""
    vmax = np.asarray(velocity_limits, dtype=float)
    total, last = 0.0, None
    corner: _Corner | None = None
    stack: list[ir.Instr] = list(reversed(body))
    while stack:
        instr = stack.pop()
        if isinstance(instr, ir.Loop):
            stack.extend(reversed([i for it in instr.iterations for i in it.body]))
        elif isinstance(instr, ir.ProcCall):
            stack.extend(reversed(instr.body))
        elif isinstance(instr, ir.WaitTime):
            total += instr.duration
        elif isinstance(instr, ir.Move):
            q = np.asarray(instr.target.values) if isinstance(instr.target, ir.JointTarget) else None
            if instr.motion.duration is not None:
                total += instr.motion.duration
            elif q is not None and last is not None and q.shape == last.shape == vmax.shape and instr.kind is ir.MotionKind.JOINT:
                total += float(np.max(np.abs(q - last) / (vmax * instr.motion.joint_speed)))
            elif corner is not None and instr.kind is ir.MotionKind.LINEAR:
                total += corner.linear_s(instr)
            last = q
            corner = _Corner.after(instr)
        elif isinstance(instr, (ir.If, ir.While)):
            last, corner = None, None
        elif isinstance(instr, ir.Stop):  # the task ends here: what follows never runs
            break
    return total


class _Corner:
    """Where the TCP ends a move to a Cartesian target: its position in the robot's base frame,
    the tool it is the point of, and the zone within which the next move may start."""

    def __init__(self, position: np.ndarray, tool: ir.ToolRef, zone_m: float) -> None:
        self.position, self.tool, self.zone_m = position, tool, zone_m

    @staticmethod
    def after(move: ir.Move) -> _Corner | None:
        if not isinstance(move.target, ir.CartesianTarget) or move.free is not None:
            return None
        return _Corner(np.asarray(move.target.pose.position, dtype=float), move.tool, move.motion.zone.radius)

    def linear_s(self, move: ir.Move) -> float:
        """Seconds a linear move from this corner takes at least (0 for another tool's TCP)."""
        if not isinstance(move.target, ir.CartesianTarget) or move.tool != self.tool or not move.motion.tcp_speed > 0:
            return 0.0
        travel = float(np.linalg.norm(np.asarray(move.target.pose.position, dtype=float) - self.position))
        return max(0.0, travel - self.zone_m - move.motion.zone.radius) / move.motion.tcp_speed
