"""What the passes share: scopes of named entities, the diagnostics sink, the robot loader.

An Entry is one named thing (const, target, proc, fixture, frame, robot, tool, loop variable,
parameter). Scopes chain to their parent; lookups walk outwards.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from rmot.lang import check_codes as codes
from rmot.lang.diagnostics import Code, Diagnostic, DiagnosticSink, Severity
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["Entry", "Reporter", "RobotInfo", "RobotLoader", "RobotLookupError", "Scope", "default_robot_loader"]


@record(slots=True)
class RobotInfo:
    """What the front end needs of a robot model: its joint count and joint types ('R'/'P')."""

    dof: int
    joint_types: tuple[str, ...]


@dataclass(slots=True)
class Entry:
    kind: str  # const target proc fixture frame robot tool var param
    name: str
    value: Any
    span: Span | None
    closure: Scope | None = None  # procs: the scope their body sees


@dataclass(slots=True)
class Scope:
    parent: Scope | None = None
    names: dict[str, Entry] = field(default_factory=dict)

    def lookup(self, name: str) -> Entry | None:
        scope: Scope | None = self
        while scope is not None:
            entry = scope.names.get(name)
            if entry is not None:
                return entry
            scope = scope.parent
        return None

    def visible(self) -> list[str]:
        out: list[str] = []
        scope: Scope | None = self
        while scope is not None:
            out.extend(scope.names)
            scope = scope.parent
        return out

    def child(self) -> Scope:
        return Scope(self)


class Reporter:
    """A DiagnosticSink that drops exact repeats (a loop body unrolled 10 times errs once)."""

    def __init__(self, sink: DiagnosticSink | None = None) -> None:
        self.sink = sink or DiagnosticSink()
        self._seen: set[tuple[str, str, int, int, str]] = set()
        # names whose declaration failed with an error: a later use is that error's
        # consequence, not an unknown name of its own
        self.failed_declarations: set[str] = set()

    def error(self, code: Code, message: str, span: Span | None, notes: tuple[tuple[str, Span | None], ...] = ()) -> None:
        key = (code.id, span.path if span else "", span.start.offset if span else -1,
               span.end.offset if span else -1, message)
        if key in self._seen:
            return
        self._seen.add(key)
        self.sink.add(Diagnostic(code, Severity.ERROR, message, span, notes))

    def warning(self, code: Code, message: str, span: Span | None, notes: tuple[tuple[str, Span | None], ...] = ()) -> None:
        key = (code.id, span.path if span else "", span.start.offset if span else -1,
               span.end.offset if span else -1, message)
        if key in self._seen:
            return
        self._seen.add(key)
        self.sink.add(Diagnostic(code, Severity.WARNING, message, span, notes))

    def unknown(self, name: str, what: str, span: Span | None, candidates: list[str], code: Code = codes.UNKNOWN_NAME,
                otherwise: str = "") -> None:
        """`unknown <what> 'x'; did you mean 'y'?` (the names that extend 'x' by `_...`, as a
        family name does its variants: `abb_irb2600` -> 'abb_irb2600_12_165'; else difflib's
        closest candidate, if close enough; else the hint `otherwise`); nothing for a name whose
        declaration failed (its error is reported there)."""
        if name in self.failed_declarations:
            return
        near = [c for c in sorted(set(candidates)) if c.startswith(name + "_")][:3] \
            or difflib.get_close_matches(name, sorted(set(candidates)), n=1, cutoff=0.6)
        hint = f"; did you mean {' or '.join(repr(n) for n in near)}?" if near else ""
        if not near and otherwise:
            hint = f"; {otherwise}"
        self.error(code, f"unknown {what} '{name}'{hint}", span)

    @property
    def has_errors(self) -> bool:
        return self.sink.has_errors


RobotLoader = Callable[[str], RobotInfo]


class RobotLookupError(Exception):
    """A robot the loader cannot give; `candidates` are the library names for suggestions."""

    def __init__(self, message: str, candidates: tuple[str, ...] = ()) -> None:
        super().__init__(message)
        self.candidates = candidates


def default_robot_loader(key: str) -> RobotInfo:
    """The robot library (sim.robots); imported on first use because pinocchio is heavy."""
    try:
        from rmot.sim.robots import RobotError, list_robots, load_robot  # late: optional, tried where used
    except ImportError as exc:  # the library is not built yet: say so as a diagnostic
        raise RobotLookupError(f"the robot library is not available ({exc})") from None
    try:
        robot = load_robot(key)
    except RobotError as exc:
        raise RobotLookupError(str(exc), tuple(list_robots())) from None
    return RobotInfo(int(robot.dof), tuple(robot.joint_types))
