"""Yaskawa INFORM words apart from the InformBackend class: limits and name rules, the
RCONF word and position values, and the helpers of its runtime logic (operators,
numbers, variable types, loop heads and the checks that decide whether a loop is
printed)."""

from __future__ import annotations

import math

import numpy as np

from rmot.backends.base import euler_zyx_deg, fmt, position_mm
from rmot.backends.loops import LoopTemplate, LoopVar
from rmot.backends.names import NameRules
from rmot.lang import ir, ir_tree


__all__ = [
    "PL_DISTANCES_MM", "MAX_POSITIONS", "MAX_TOOL_FILE", "MAX_USER_FRAME", "MAX_INSTRUCTIONS",
    "COMMENT_WIDTH", "INFORM_RULES", "DATE", "rconf", "position_values", "predecessors",
]


PL_DISTANCES_MM = (0.0, 12.5, 25.0, 50.0, 100.0)


MAX_POSITIONS = 999


MAX_TOOL_FILE = 63  # DX200/YRC1000 tool files 0..63 (YRC1000 INSTRUCTIONS, "Tool file")


MAX_USER_FRAME = 63  # user coordinates 1..63 (YRC1000 INSTRUCTIONS, "User coordinates")


MAX_INSTRUCTIONS = 300


COMMENT_WIDTH = 32


INFORM_RULES = NameRules(max_len=32, allowed="A-Za-z0-9_", first="A-Za-z", upper=True, prefix="J",
                         # INFORM instruction words (YRC1000 INSTRUCTIONS manual, instruction list)
                         reserved=frozenset({"NOP", "END", "CALL", "JUMP", "MOVJ", "MOVL", "MOVC",
                                             "MOVS", "IMOV", "DOUT", "DIN", "AOUT", "PULSE", "WAIT",
                                             "TIMER", "PAUSE", "MSG", "RET", "IF", "ENDIF", "ELSE",
                                             "WHILE", "ENDWHILE", "FOR", "NEXT", "SET", "ADD", "SUB",
                                             "MUL", "DIV", "INC", "DEC", "GETS", "CLEAR", "SFTON",
                                             "SFTOF", "TOOLON", "TOOLOF", "SPEED", "LABEL"}))


DATE = "2000/01/01 00:00"


def rconf(branch: ir.Config, q: np.ndarray) -> str:
    """`l,m,n,o,p,q,0,0` (NX100/DX100 "manipulator type").

    l: 0 flip / 1 no-flip by Yaskawa's rule on the R axis (J4) position: flip when
    -90 < R <= 90, 270 < R <= 360 or -360 < R <= -270 (not the J5 sign ir.Wrist uses);
    m: 0 upper arm (elbow UP) / 1 lower arm; n: 0 front / 1 rear (from the branch);
    o, p, q: 1 when the R, T, S axis angle lies outside -180 < angle <= 180.
    """
    r = math.degrees(q[3])
    flip = -90.0 < r <= 90.0 or r > 270.0 or r <= -270.0
    turn = [0 if -180.0 < math.degrees(q[i]) <= 180.0 else 1 for i in (3, 5, 0)]
    bits = [0 if flip else 1,
            0 if branch.elbow is ir.Elbow.UP else 1,
            0 if branch.shoulder is ir.Shoulder.FRONT else 1, *turn, 0, 0]
    return ",".join(str(b) for b in bits)


def position_values(pose: ir.Pose) -> str:
    """`X,Y,Z,Rx,Ry,Rz`: mm with 3 places, degrees with 4 places."""
    rz, ry, rx = euler_zyx_deg(pose)
    return ",".join([*(fmt(v, 3) for v in position_mm(pose)), *(fmt(v, 4) for v in (rx, ry, rz))])


def predecessors(body: tuple[ir.Instr, ...], last: ir.Move | None = None,
                 out: dict[int, ir.Move | None] | None = None) -> tuple[dict[int, ir.Move | None], ir.Move | None]:
    """For each move uid, the move executed just before it (None when unknown statically)."""
    out = {} if out is None else out
    for node in body:
        if isinstance(node, ir.Move):
            out[node.uid] = last
            last = node
            continue
        runs, bodies = ir_tree.flow(node)
        if runs.sure:  # a proc body, a loop's iterations: one after another
            for sub in bodies:
                _, last = predecessors(sub, last, out)
        elif runs is ir_tree.Runs.ONE_OF:  # if arms: known only when every arm ends alike
            ends = [predecessors(sub, last, out)[1] for sub in bodies]
            last = ends[0] if ends and all(e is ends[0] for e in ends) else None
        else:  # a while's body, a timeout branch: it may not run
            for sub in bodies:
                _, end = predecessors(sub, last, out)
                last = last if end is last else None
    return out, last


# ---------------------------------------------------------------- runtime logic helpers

_INFORM_OP = {"+": "ADD", "-": "SUB", "*": "MUL", "/": "DIV"}


_INFORM_CMP = {ir.CompareOp.EQ: "=", ir.CompareOp.NE: "<>", ir.CompareOp.LT: "<",
               ir.CompareOp.LE: "<=", ir.CompareOp.GT: ">", ir.CompareOp.GE: ">="}




_Shift = tuple[int, str, tuple[LoopVar, ...], tuple[tuple[int, int, int], ...]]


def _inform_number(value: float | bool) -> str:
    if isinstance(value, bool):
        return "1" if value else "0"
    return str(value) if isinstance(value, int) else (fmt(value, 6).rstrip("0").rstrip(".") or "0")


def _value_type(e: ir.RtExpr) -> ir.ValueType:
    if isinstance(e, ir.Const):
        return e.type
    if isinstance(e, (ir.VarRef, ir.Arith)):
        return e.type
    if isinstance(e, ir.AnalogInput):
        return ir.ValueType.NUM
    if isinstance(e, ir.GroupInput):
        return ir.ValueType.INT
    return ir.ValueType.BOOL


def _reads(e: object, name: str) -> bool:
    if isinstance(e, ir.VarRef):
        return e.name == name
    if isinstance(e, ir.Arith):
        return _reads(e.left, name) or _reads(e.right, name)
    if isinstance(e, ir.Compare):
        return _reads(e.left, name) or _reads(e.right, name)
    if isinstance(e, ir.Logic):
        return any(_reads(o, name) for o in e.operands)
    if isinstance(e, ir.Not):
        return _reads(e.operand, name)
    return False


def _rconf_key(q: np.ndarray, branch: ir.Config | None) -> object:
    """What an INFORM position stores of the configuration: its RCONF flags."""
    if branch is None or None in (branch.shoulder, branch.elbow, branch.wrist):
        return None
    return rconf(branch, q)


def _inform_blocker(template: LoopTemplate) -> str | None:
    """Why a loop the analysis accepts still cannot be one INFORM loop: a circular move (MOVC
    starts from the move before it, which a loop's first iteration does not know)."""
    for node in ir_tree.walk(template.body):
        if isinstance(node, ir.Move) and node.kind is ir.MotionKind.CIRCULAR:
            loop = template.loop
            return (f"loop 'for {loop.var} in {loop.first} .. {loop.last}' unrolled: an INFORM "
                    "circular move starts from the move before it")
    return None


def _loop_head(var: LoopVar) -> str:
    """The comment above a vendor loop: `for layer = 0 .. 2` (the values it runs) or
    `repeat 2`."""
    if var.name is None:
        return f"repeat {var.last - var.first + 1}"
    return f"for {var.name} = {var.first} .. {var.last}"
