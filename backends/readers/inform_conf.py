"""An INFORM position's whole configuration from its RCONF, with the arm's inverse kinematics.

`///RCONF l,m,n,o,p,q,..` (backends/inform.py `rconf`, NX100/DX100 "manipulator type"): m and n
are the elbow and shoulder (read by the reader itself), l is Yaskawa's flip on the R axis (J4)
position and o, p, q tell whether the R, T, S axis (J4, J6, J1) lies beyond ±180°. Which rmot
wrist (the J5 sign) and which turns those mean depends on the pose: of the arm's IK solutions
of the position (TCP pose in the robot base, the tool's TCP taken off) the ones whose RCONF,
computed by the backend's own `rconf`, is the one written are the joints the job meant. Where
they agree on one branch and one set of turns, the joint moves to that position get
`config(shoulder, elbow, wrist, jN=turn)`; otherwise (no --cell, an unknown tool or frame, no
or several matches) the wrist and turns stay free, as before.

The reader only reads text: the CLI loads the arm and hands its IK in as a function.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from rmot.backends.inform_text import rconf
from rmot.backends.readers.model import Document, Move, Stmt, Target
from rmot.backends.readers.writer import map_leaves
from rmot.lang import ir

__all__ = ["resolve_rconf"]

# the flange pose (4x4, robot base) -> the arm's IK solutions and their branches
Ik = Callable[[np.ndarray], tuple[Sequence[np.ndarray], Sequence[ir.Config]]]
TURN_JOINTS = (0, 3, 5)  # S, R, T: the joints RCONF's turn flags are about


def resolve_rconf(doc: Document, ik: Ik, tcp_of: dict[str, ir.Pose], wide: tuple[int, ...]) -> Document:
    """`doc` with the joint moves to INFORM positions configured from their RCONF (see the
    module docstring). `tcp_of`: each tool's TCP in the flange frame, by the name moves use;
    `wide`: the joints (0-based) whose range spans more than 360° (only those take a turn)."""
    if doc.vendor != "inform":
        return doc
    decls = {t.name: t for t in doc.targets}
    found: dict[tuple[str, str | None], ir.Config | None] = {}

    def config_of(move: Move) -> ir.Config | None:
        key = (move.target_name or "", move.tool)
        if key not in found:
            decl = decls.get(key[0])
            tcp = tcp_of.get(move.tool or "")
            found[key] = _config(decl, tcp, ik, wide) if decl is not None and tcp is not None and move.frame == "base" else None
        return found[key]

    def fix(s: Stmt) -> Stmt:
        if not isinstance(s, Move) or s.kind != "joint" or s.config is None:
            return s
        config = config_of(s)
        return replace(s, config=config) if config is not None else s

    routines = tuple(replace(r, body=map_leaves(r.body, fix)) for r in doc.routines)
    return replace(doc, routines=routines)


def _config(decl: Target, tcp: ir.Pose, ik: Ik, wide: tuple[int, ...]) -> ir.Config | None:
    if decl.pose is None or decl.rconf is None:
        return None
    flange = decl.pose * tcp.inverse()
    solutions, branches = ik(flange.matrix())
    matches = {(b.shoulder, b.elbow, b.wrist, _turns(q, wide)) for q, b in zip(solutions, branches)
               if b.shoulder is not None and b.elbow is not None and b.wrist is not None
               and _same(rconf(b, q), decl.rconf)}
    if len(matches) != 1:
        return None
    shoulder, elbow, wrist, turns = next(iter(matches))
    return ir.Config(shoulder, elbow, wrist, turns)


def _turns(q: np.ndarray, wide: tuple[int, ...]) -> tuple[tuple[int, int], ...]:
    """The turns of S, R, T where the joint's range allows more than one (rmot's `jN=turn`)."""
    return tuple((j, ir.turn_of(float(q[j]))) for j in TURN_JOINTS if j in wide)


def _same(written: str, read: str) -> bool:
    """Two RCONF strings alike on the flags the backend writes (the first six)."""
    return written.split(",")[:6] == [b.strip() for b in read.split(",")[:6]]


