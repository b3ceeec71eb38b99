"""Legal vendor names with deterministic clash resolution.

Each vendor limits identifiers (length, characters, first character, reserved words, case).
`legalize` makes one name legal; `NameTable` assigns legal names to a sequence of source names
in order: the first to claim a legal name keeps it, later ones get `_2`, `_3`, ... (cut to fit),
and every change is reported as a warning so nothing is renamed silently.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from rmot.backends import codes
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["DataPool", "NameRules", "NameTable", "legalize"]


@record
class NameRules:
    """A vendor's identifier rules.

    max_len: longest legal name. allowed: regex character class of legal characters (without
    brackets). first: class of legal first characters. upper: the vendor is case-insensitive
    and names are printed upper-case (clashes compare upper-case). reserved: words that may not
    be used (compared upper-case). prefix: prepended when the first character is illegal.
    """

    max_len: int
    allowed: str = "A-Za-z0-9_"
    first: str = "A-Za-z"
    upper: bool = False
    reserved: frozenset[str] = frozenset()
    prefix: str = "R"


def legalize(name: str, rules: NameRules) -> str:
    """One legal name for `name` under `rules` (clashes are the NameTable's job)."""
    text = re.sub(f"[^{rules.allowed}]", "_", name)
    if rules.upper:
        text = text.upper()
    if not text or not re.match(f"[{rules.first}]", text[0]):
        text = rules.prefix + text
    if text.upper() in rules.reserved:
        text = text + "_"
    return text[: rules.max_len]


def _key(name: str, rules: NameRules) -> str:
    """Clash key: every controller here compares identifiers case-insensitively."""
    return name.upper()


@dataclass
class NameTable:
    """Assigns legal, unique names in call order; collects warnings for every change.

    The same source name asked twice gets the same legal name.
    """

    rules: NameRules
    vendor: str
    taken: dict[str, str] = field(default_factory=dict)  # key(legal) -> source name
    assigned: dict[str, str] = field(default_factory=dict)  # source name -> legal
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def reserve(self, legal: str) -> None:
        """Mark a legal name as used by the backend itself (e.g. 'main')."""
        self.taken[_key(legal, self.rules)] = legal

    def name(self, source: str, span: Span | None = None) -> str:
        if source in self.assigned:
            return self.assigned[source]
        base = legalize(source, self.rules)
        legal = base
        n = 2
        while _key(legal, self.rules) in self.taken:
            suffix = f"_{n}"
            legal = base[: self.rules.max_len - len(suffix)] + suffix
            n += 1
        if legal != base and source.upper() not in self.rules.reserved:
            other = self.taken[_key(base, self.rules)]
            self._warn(codes.NAME_CLASH, f"name '{source}' must be unique for {self.vendor} after "
                       f"legalisation (clashes with '{other}' as '{base}'); renamed to '{legal}'", span)
        if source.upper() in self.rules.reserved:
            self._warn(codes.RESERVED_RENAMED, f"name '{source}' is a reserved word, instruction, "
                       f"function, type or predefined datum of {self.vendor}; renamed to '{legal}'", span)
        elif legal != base:
            pass  # the clash warning above
        elif legal != source and legal != source.upper():
            self._warn(codes.NAME_CHANGED, f"name '{source}' is not a legal {self.vendor} name; "
                       f"emitted as '{legal}'", span)
        self.taken[_key(legal, self.rules)] = source
        self.assigned[source] = legal
        return legal

    def _warn(self, code: Code, message: str, span: Span | None) -> None:
        self.diagnostics.append(Diagnostic(code, Severity.WARNING, f"{self.vendor}: {message}", span))


@dataclass
class DataPool:
    """Named data declarations (targets, speed data, ...) of one output program, in first-use order.

    `add(hint, value)` returns a name for `value`: an identical value declared before gets the
    same name; a different value with the same hint gets `hint_2`, `hint_3`, ... (legal under
    `rules`). `items` keeps (name, value) in declaration order, so output is deterministic.
    Names must not clash with `table`'s (routines, signals): both share `table.taken`.
    """

    table: NameTable
    items: list[tuple[str, str]] = field(default_factory=list)
    _by_value: dict[tuple[str, str], str] = field(default_factory=dict)
    warned: set[str] = field(default_factory=set)  # reserved hints already reported

    def add(self, hint: str, value: str, span: Span | None = None) -> str:
        key = (hint, value)
        if key in self._by_value:
            return self._by_value[key]
        base = legalize(hint, self.table.rules)
        if hint.upper() in self.table.rules.reserved and hint not in self.warned:
            self.warned.add(hint)
            self.table._warn(codes.RESERVED_RENAMED, f"name '{hint}' is a reserved word, instruction, "
                             f"function, type or predefined datum of {self.table.vendor}; declared "
                             f"as '{base}'", span)
        legal, n = base, 2
        while _key(legal, self.table.rules) in self.table.taken:
            suffix = f"_{n}"
            legal = base[: self.table.rules.max_len - len(suffix)] + suffix
            n += 1
        self.table.taken[_key(legal, self.table.rules)] = hint
        self._by_value[key] = legal
        self.items.append((legal, value))
        return legal
