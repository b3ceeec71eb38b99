"""Diagnostics: errors and warnings as values, with a code, a message and a source span.

Every stage reports through these types; only the CLI turns them into text, JSON, JUnit or
SARIF and into an exit code. Codes are registered objects (mypy's `ErrorCode` idea): each
stage declares its own in its `codes.py` with `Code(...)`, and `all_codes()` lists every
registered one for documentation and for the uniqueness test.

Code ranges (one per stage, so a code says where it came from):
  E0xx  syntax and lexical (lang)           E1xx  names, types, units (compiler check)
  E2xx  kinematics and planning             E3xx  verification findings (sim)
  E4xx  backends                            E5xx  files: cells, meshes, URDFs, I/O
  W...  warnings use the same numbering with a W.

Rendered form (like a modern compiler):

    cell.rmot:12:5: error[E101]: unknown name 'hme'; did you mean 'home'?
       12 |   move joint hme
          |              ^~~
"""

from __future__ import annotations

from dataclasses import field
from enum import Enum

from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = [
    "Amount",
    "Code",
    "Diagnostic",
    "DiagnosticSink",
    "Severity",
    "all_codes",
    "render",
    "render_all",
]


class Severity(Enum):
    ERROR = "error"
    WARNING = "warning"
    NOTE = "note"


_REGISTRY: dict[str, Code] = {}


@record(slots=True)
class Code:
    """A registered diagnostic code, e.g. Code("E101", "unknown-name", "a name is not defined").

    Creating a Code registers it; registering the same id twice with a different name is a
    programming error (caught by the registry test).
    """

    id: str
    name: str
    summary: str

    def __post_init__(self) -> None:
        known = _REGISTRY.get(self.id)
        if known is not None and known != self:
            raise ValueError(f"diagnostic code {self.id} registered twice: {known.name!r} and {self.name!r}")
        if known is None:  # an equal code declared again leaves the first one registered
            _REGISTRY[self.id] = self

    def __str__(self) -> str:
        return self.id


def all_codes() -> tuple[Code, ...]:
    """Every code registered so far, sorted by id (import the stages' codes modules first)."""
    return tuple(sorted(_REGISTRY.values(), key=lambda c: c.id))


@record(slots=True)
class Amount:
    """How much: a penetration depth, a clearance, a limit excess. `unit` as users read it."""

    value: float
    unit: str

    def __str__(self) -> str:
        return f"{self.value:.4g} {self.unit}"


@record(slots=True)
class Diagnostic:
    """One error, warning or note.

    `notes` point at other sites ("first defined here"). The time fields, `bodies` and
    `amount` are filled by verification findings (sim) and by the planner where they apply.
    """

    code: Code
    severity: Severity
    message: str
    span: Span | None
    notes: tuple[tuple[str, Span | None], ...] = ()
    time_s: float | None = None
    end_time_s: float | None = None
    bodies: tuple[str, ...] = ()
    amount: Amount | None = None
    task: str | None = field(default=None)
    peak_time_s: float | None = None  # the instant of the worst amount within [time_s, end_time_s]

    @property
    def is_error(self) -> bool:
        return self.severity is Severity.ERROR


class DiagnosticSink:
    """Collects diagnostics from a pass; the CLI decides what they mean for the exit code."""

    def __init__(self) -> None:
        self._items: list[Diagnostic] = []

    def add(self, diagnostic: Diagnostic) -> None:
        self._items.append(diagnostic)

    def error(self, code: Code, message: str, span: Span | None, **extra: object) -> None:
        self._items.append(Diagnostic(code, Severity.ERROR, message, span, **extra))  # type: ignore[arg-type]

    def warning(self, code: Code, message: str, span: Span | None, **extra: object) -> None:
        self._items.append(Diagnostic(code, Severity.WARNING, message, span, **extra))  # type: ignore[arg-type]

    def extend(self, diagnostics: object) -> None:
        self._items.extend(diagnostics)  # type: ignore[arg-type]

    @property
    def items(self) -> tuple[Diagnostic, ...]:
        return tuple(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def errors_since(self, start: int) -> bool:
        """Whether an error was added after the first `start` items (no copy of the list)."""
        return any(self._items[i].is_error for i in range(start, len(self._items)))

    @property
    def has_errors(self) -> bool:
        return any(d.is_error for d in self._items)


# Characters that some text layer (Python's str.splitlines, a terminal) takes as a line break
# or a cursor move: shown as one visible character each, so the caret stays under its column.
_INVISIBLE = {ord(c): " " for c in "\t\f\v"} | {ord(c): "\u240d" for c in "\r"} | {
    ord(c): "\ufffd" for c in "\x1c\x1d\x1e\x85\u2028\u2029"} | {i: "\ufffd" for i in range(0, 32) if i not in (9, 10, 11, 12, 13)}


def _visible(text: str) -> str:
    return text.translate(_INVISIBLE)


def _caret_block(span: Span) -> list[str]:
    """The source line and a caret line under the span (`^~~~`)."""
    text = _visible(span.file.line_text(span.start.line))
    if not text and span.start.line > 1 and not span.file.text:
        return []
    width = len(str(span.start.line))
    end_col = span.end.col if span.end.line == span.start.line else len(text) + 1
    length = max(1, end_col - span.start.col)
    gutter = " " * width
    caret = " " * (span.start.col - 1) + "^" + "~" * (length - 1)
    return [f" {span.start.line} | {text}", f" {gutter} | {caret}"]


def _timing(d: Diagnostic) -> str:
    if d.time_s is None:
        return ""
    if d.end_time_s is not None and d.end_time_s > d.time_s:
        return f" (at t={d.time_s:.3f}..{d.end_time_s:.3f} s)"
    return f" (at t={d.time_s:.3f} s)"


def render(d: Diagnostic) -> str:
    """Compiler-style text: `file:line:col: severity[CODE]: message`, source line, carets, notes."""
    where = f"{d.span}: " if d.span is not None else "rmot: "
    lines = [f"{where}{d.severity.value}[{d.code.id}]: {d.message}{_timing(d)}"]
    if d.span is not None:
        lines += _caret_block(d.span)
        for site in d.span.expansion_chain():
            lines.append(f"{site}: note: in the proc call here")
            lines += _caret_block(site)
    for text, span in d.notes:
        lines.append(f"{span}: note: {text}" if span is not None else f"  note: {text}")
        if span is not None:
            lines += _caret_block(span)
    return "\n".join(lines)


def render_all(diagnostics: tuple[Diagnostic, ...] | list[Diagnostic]) -> str:
    return "\n".join(render(d) for d in diagnostics)
