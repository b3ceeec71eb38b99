"""rmot.compiler.plan: the planner, IR -> Plan (see planner.plan_program).

Modules, one concern each: cartesian (line/arc/SLERP geometry), dense (dense IK with branch
continuity), targets (IK branch selection), segments (one move's joint path), blend (zones),
timing (trapezoidal joint moves; path timing on the dense grid of topp), chain (timing a
blended chain), timeline (a task's instructions in time), sync (barrier alignment and sampling), codes (E220-E299, W220+).
"""

from __future__ import annotations

from rmot.compiler.plan.planner import plan_program

__all__ = ["plan_program"]
