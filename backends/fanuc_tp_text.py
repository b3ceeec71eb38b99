"""Fanuc TP words apart from the FanucBackend class: name rules, turn numbers and
configuration strings, and the helpers of its runtime logic (operators, numbers,
loop words and the checks that decide whether a loop is printed)."""

from __future__ import annotations

import math
import textwrap

import numpy as np

from rmot.backends.base import fmt
from rmot.backends.loops import LoopTemplate, LoopVar
from rmot.backends.names import NameRules
from rmot.lang import ir, ir_tree
from rmot.backends.safe_text import tp_io_comment


__all__ = ["FANUC_RULES", "COMMENT_MAX", "turn_number", "config_string", "held_frame_values"]


FANUC_RULES = NameRules(max_len=36, upper=True, reserved=frozenset({"MAIN"}), prefix="P")


COMMENT_MAX = 32


def turn_number(angle: float) -> int:
    """Fanuc turn number: 0 for (-180, 180] deg, 1 for (180, 540], -1 for (-540, -180]."""
    return math.ceil((angle - math.pi) / (2 * math.pi) - 1e-12)


def config_string(branch: ir.Config, q: np.ndarray) -> str:
    """'N U T, t4, t5, t6' from the planned branch and joints (see the module docstring)."""
    # Fanuc's F (flip) is J5 >= 0 and N (no flip) J5 < 0, on Fanuc's own J5: RoboDK's Fanuc
    # post (Fanuc_R30iA.py, "F means axis 5 >= 0, N means axis 5 < 0") and SwRI's tesseract
    # (tesseract_motion_planners/robot_config.h: J5 >= 0 -> F.., J5 < 0 -> N..) agree, as does
    # the usual 'N U T' of a tool-down pose with J5 = -90 deg. rmot's FLIP is J5 < 0 -> 'N'.
    flip = "N" if branch.wrist is ir.Wrist.FLIP else "F"
    up = "U" if branch.elbow is ir.Elbow.UP else "D"
    top = "T" if branch.shoulder is ir.Shoulder.FRONT else "B"
    turns = ", ".join(str(turn_number(q[i])) for i in (3, 4, 5))
    return f"{flip} {up} {top}, {turns}"


# ---------------------------------------------------------------- runtime logic helpers

_TP_OP = {ir.CompareOp.EQ: "=", ir.CompareOp.NE: "<>", ir.CompareOp.LT: "<", ir.CompareOp.LE: "<=",
          ir.CompareOp.GT: ">", ir.CompareOp.GE: ">="}




def _tp_number(value: float | int | bool) -> str:
    """A TP constant: bool as 1/0, integers as written, reals without trailing zeros; a
    negative constant in parentheses (`R[1]=R[1]*(-1)`, as the pendant writes it)."""
    if isinstance(value, bool):
        return "1" if value else "0"
    text = str(value) if isinstance(value, int) else (fmt(value, 6).rstrip("0").rstrip(".") or "0")
    return f"({text})" if text.startswith("-") else text


def _leaf(c: object) -> bool:
    return isinstance(c, (ir.InputCondition, ir.OutputRead, ir.VarRef, ir.Compare)) or (
        isinstance(c, ir.Not) and _leaf(c.operand))


def _config_key(q: np.ndarray, branch: ir.Config | None) -> object:
    """What a TP position stores of the configuration: the CONFIG string (branch + turns)."""
    if branch is None or None in (branch.shoulder, branch.elbow, branch.wrist):
        return None
    return config_string(branch, q)


def _rounded(steps: tuple[tuple[float, float, float], ...]) -> tuple[tuple[float, ...], ...]:
    return tuple(tuple(round(v * 1000.0, 3) for v in s) for s in steps)


def _offset_signature(body: tuple[ir.Instr, ...],
                      offsets: dict[tuple[int, str], int]) -> tuple[object, ...] | None:
    """The offsets of a called body's moves in order, or None when none of them takes one."""
    sig = tuple(offsets.get((m.uid, "target")) for m in ir_tree.walk(body) if isinstance(m, ir.Move))
    return sig if any(s is not None for s in sig) else None


def _fanuc_blocker(template: LoopTemplate) -> str | None:
    """Why a loop the analysis accepts still cannot be one TP loop: a circular move whose
    points move (`Offset,PR[i]` shifts one destination per line), or a `repeat` loop (no
    variable)."""
    for node in ir_tree.walk(template.body):
        if isinstance(node, ir.Move) and node.kind is ir.MotionKind.CIRCULAR:
            offsets = [template.targets.get((node.uid, role)) for role in ("target", "via")]
            if any(o is not None and any(any(s) for s in o.steps) for o in offsets):
                return (f"{_loop_words(template.loop)} unrolled: a TP circular move takes one "
                        "Offset,PR for its via and end points (its points move from one "
                        "iteration to the next)")
    return None


def _loop_words(loop: ir.Loop) -> str:
    return f"loop 'for {loop.var} in {loop.first} .. {loop.last}'" if loop.var else "repeat loop"


def _sig(signal: str | None) -> str:
    """The cell's signal name as a TP I/O comment: DO[1:gripper_close]."""
    return f":{tp_io_comment(signal)[:24]}" if signal else ""


def _pieces(text: str) -> list[str]:
    """Comment text wrapped into lines of at most COMMENT_MAX characters."""
    return textwrap.wrap(text, COMMENT_MAX, break_long_words=True) or [""]


def _loop_head(var: LoopVar) -> str:
    """The comment above a vendor loop: `for layer = 0 .. 2` (the values it runs) or
    `repeat 2`."""
    if var.name is None:
        return f"repeat {var.last - var.first + 1}"
    return f"for {var.name} = {var.first} .. {var.last}"


def held_frame_values(x: float, y: float, z: float, w: float, p: float, r: float) -> list[str]:
    """The comment lines giving a taught frame's X, Y, Z (mm) and W, P, R (deg) to 0.001, as the
    pendant shows them: re-expanding a target through them stays within 0.01 mm. Each line fits
    a TP comment (COMMENT_MAX characters); X Y Z go on two lines when one cannot hold them."""
    xyz = f"X {fmt(x, 3)} Y {fmt(y, 3)} Z {fmt(z, 3)}"
    rows = [xyz] if len(xyz) <= COMMENT_MAX else [f"X {fmt(x, 3)} Y {fmt(y, 3)}", f"Z {fmt(z, 3)}"]
    return rows + [f"W {fmt(w, 3)} P {fmt(p, 3)} R {fmt(r, 3)}"]
