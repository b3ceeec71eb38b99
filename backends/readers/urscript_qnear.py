"""URScript joint moves to a pose with `qnear`: the branch the controller takes, read exactly.

PolyScope writes a MoveJ waypoint as `movej(get_inverse_kin(Waypoint_1_p, qnear=Waypoint_1_q))`:
the pose and the joints recorded together when it was taught. The controller moves to the
inverse-kinematics solution of the pose nearest `qnear` (URScript manual, module kinematics,
`get_inverse_kin(x, qnear, ...)`: "qnear: list of joint positions ... the solution closest to
qnear"). rmot's joint move to a pose takes the solution nearest the current joints instead
(lang/REFERENCE.md §8), so where `qnear` lies on another branch or another turn the two differ.

With the arm (`rmot import --cell`, or `--robot` with the files' own tools), each such move gets the `config(shoulder, elbow,
wrist, jN=turn)` of the arm's solution nearest `qnear`, which selects exactly that solution.
Without it, or where `qnear` or the tool is not known from the file, the move keeps rmot's rule
and W529 says at its line that the controller's rule differs. The reader only reads text: the
CLI loads the arm and hands in its IK as a function.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from rmot.backends.readers import codes
from rmot.backends.readers.model import Document, Move, Stmt, Target, Where
from rmot.backends.readers.writer import map_leaves
from rmot.lang import ir
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Span

__all__ = ["qnear_of", "resolve_qnear"]

# the flange pose (4x4, robot base) and a seed (rad) -> the arm's solutions nearest the seed first,
# with their branches
NearIk = Callable[[np.ndarray, np.ndarray], tuple[Sequence[np.ndarray], Sequence[ir.Config]]]
_QNEAR = re.compile(r"get_inverse_kin\((.*),qnear=(\[[^\[\]]*\]|\w+)\)")
_TIE = 1e-6  # rad: two solutions this close in distance to qnear are a tie the file does not decide


def qnear_of(text: str, target: Callable[[str], tuple[str, str | None, Target | None] | None],
             ) -> tuple[str, tuple[float, ...] | None] | None:
    """A move's point written `get_inverse_kin(P, qnear=Q)`: (Q as written, Q's joints in degrees
    where `target` knows them), else None."""
    m = _QNEAR.fullmatch(text.replace(" ", ""))
    if m is None:
        return None
    found = target(m.group(2))
    decl = found[2] if found else None
    return m.group(2), decl.joints if decl is not None else None


def resolve_qnear(doc: Document, ik: NearIk | None, tcp_of: dict[str, ir.Pose], wide: tuple[int, ...],
                  span_of: Callable[[Where], Span]) -> Document:
    """`doc` with its qnear joint moves configured from the arm's solution nearest qnear (see the
    module docstring); `tcp_of`: each tool's TCP by the name moves use; `wide`: the joints whose
    range spans more than 360° (only those take a turn). Moves it cannot decide get W529."""
    if doc.vendor != "urscript":
        return doc
    diags: list[Diagnostic] = []
    flange_only = not doc.tools  # no set_tcp in the files: rmot plans every move with the bare flange

    def fix(s: Stmt) -> Stmt:
        if not isinstance(s, Move) or s.near is None:
            return s
        tcp = tcp_of.get(s.tool) if s.tool is not None else ir.Pose.identity() if flange_only else None
        found = _nearest(s, ik, tcp, wide) if ik is not None and tcp is not None else None
        if not isinstance(found, ir.Config):
            why = "the arm is not known (give --cell or --robot)" if ik is None else (
                "the active tool is not known here" if tcp is None else found or "")
            diags.append(_warning(s, why, span_of))
            return s
        return replace(s, config=found)

    routines = tuple(replace(r, body=map_leaves(r.body, fix)) for r in doc.routines)
    return replace(doc, routines=routines, diagnostics=doc.diagnostics + tuple(diags))


def _nearest(move: Move, ik: NearIk, tcp: ir.Pose, wide: tuple[int, ...]) -> ir.Config | str:
    """The branch and turns of the arm's solution of the move's pose nearest its qnear, or why
    it cannot be read: the pose or qnear not known, no solution within the limits, two equally
    near."""
    assert move.near is not None
    written, near = move.near
    if near is None:
        return f"`{written}` is not known here"
    if move.pose is None or move.frame != "base":
        return f"`{move.target}` is not a pose known here"
    seed = np.radians(np.asarray(near, dtype=float))
    solutions, branches = ik((move.pose * tcp.inverse()).matrix(), seed)
    if not solutions or branches[0].shoulder is None:
        return "the arm has no solution of the pose within its limits (is it the program's arm?)"
    distances = sorted(float(np.linalg.norm(np.asarray(q) - seed)) for q in solutions)
    if len(distances) > 1 and distances[1] - distances[0] < _TIE:
        return f"two solutions are equally near `{written}`"
    q, b = solutions[0], branches[0]
    turns = tuple((j, ir.turn_of(float(q[j]))) for j in wide)
    return ir.Config(b.shoulder, b.elbow, b.wrist, turns)


def _warning(move: Move, why: str, span_of: Callable[[Where], Span]) -> Diagnostic:
    assert move.near is not None
    return Diagnostic(codes.QNEAR_NOT_READ, Severity.WARNING,
                      f"the controller moves to the solution of `{move.target}` nearest qnear `{move.near[0]}`; "
                      f"rmot takes the one nearest the current joints, as the branch could not be read: {why}",
                      span_of(move.where))
