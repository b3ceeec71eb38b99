"""KRL globals the program itself sets and tests, read as rmot task variables (§12).

A KRL program may assign and test a scalar it does not declare: a global of the robot's
`$config.dat` (KSS 8.x Operating and Programming Instructions for System Integrators,
"Variables and declarations": a variable declared in `$config.dat` is known to every program;
it keeps its value when a program ends, as a data list's does). Such a name is a task variable
`var name: type = v` where what the program does with it is certain:
- its type is the `$config.dat` found's declaration (`DECL BOOL name`, `INT`, `REAL`), or,
  with no `$config.dat` found, BOOL where the main DEF assigns it only `TRUE` and `FALSE` and
  both (an INT and a REAL cannot be told apart from the assignments: those stay native);
- a BOOL the program only ever sets to one value (`SALIR=FALSE` after testing `IF SALIR ==
  TRUE`) is a handshake flag another program (the submit interpreter, a PLC) raises: it is
  never a task variable (the test stays native);
- no other routine of the file assigns it (rmot's procs do not see a task's variables).
Its start value is the `$config.dat`'s (else FALSE / 0); W542 at its first assignment says that
it is a global: its value at the start is what the last run or another program left (unless
the program sets it first thing), and another program's writes while this one runs are not
seen by the task variable (written back, the variable is the DEF's own `DECL`).
"""

from __future__ import annotations

import re

from rmot.backends.readers.common import rmot_name
from rmot.backends.readers.krl_text import Decl, Line, declarations, lines
from rmot.backends.readers.model import Where
from rmot.lang.record import record

__all__ = ["Global", "global_vars", "global_note"]

_TYPES = ("INT", "REAL", "BOOL")
_ASSIGN = re.compile(r"(?i)^([A-Za-z_]\w*)\s*=(?!=)\s*(.+)$")


@record(slots=True)
class Global:
    """A `$config.dat` global read as a task variable: its KRL type, name and declared value, its
    first assignment, and the path of the `$config.dat` that declares it (None: none found)."""

    type: str  # INT, REAL or BOOL
    name: str
    value: str | None
    where: Where
    config: str | None


def _assignments(found: list[Line]) -> dict[str, list[tuple[str, str, Where]]]:
    """NAME -> its assignments in `found` (the name as written, the value, where), in order."""
    out: dict[str, list[tuple[str, str, Where]]] = {}
    for ln in found:
        m = _ASSIGN.match(ln.text) if ln.fold is None else None
        if m:
            out.setdefault(m.group(1).upper(), []).append((m.group(1), m.group(2).strip(), ln.where))
    return out


def _bool_type(values: list[str]) -> bool:
    """Whether the assigned values are TRUE and FALSE literals only, both present."""
    words = {v.upper() for v in values}
    return words == {"TRUE", "FALSE"}


def _tested(found: list[Line], key: str) -> bool:
    """Whether a condition of `found` (IF, ELSE IF, WHILE, UNTIL, WAIT FOR) names `key`."""
    word = re.compile(rf"(?i)(?<![\w$]){re.escape(key)}(?!\w)")
    return any(re.match(r"(?i)(IF|WHILE|UNTIL|WAIT\s+FOR)\b", ln.text) and word.search(ln.text) for ln in found
               if ln.fold is None)


def global_vars(main: list[Line], others: list[Line], known: set[str],
                config: tuple[str, str] | None) -> list[Global]:
    """The globals the main DEF's lines `main` assign (never `others`, the file's other lines),
    declared neither in the program nor its .dat (`known`, upper case: their declarations,
    signals, data), whose type is certain (module docstring), in the order first assigned."""
    assigned, elsewhere = _assignments(main), _assignments(others)
    declared: dict[str, Decl] = {}
    for d in declarations(lines(*config)) if config is not None else []:
        declared.setdefault(d.name.upper(), d)
    out: list[Global] = []
    for key, found in assigned.items():
        if key in known or key in elsewhere or key.startswith("$"):
            continue
        values = [v for _, v, _ in found]
        decl = declared.get(key)
        if config is None:
            type_ = "BOOL" if _bool_type(values) and _tested(main, key) else None
        else:
            type_ = decl.type if decl is not None and decl.type in _TYPES else None
        if type_ is None or (type_ == "BOOL" and len({v.upper() for v in values}) < 2):
            continue
        value = decl.value.strip() if decl is not None and decl.value else None
        name = decl.name if decl is not None else found[0][0]
        out.append(Global(type_, name, value, found[0][2], config[0] if decl is not None and config else None))
    return out


def global_note(found: Global, init: str, folded: bool) -> str:
    """W542's message for the global `found` starting at `init` (rmot text; `folded`: the program
    sets it before it reads it)."""
    name = rmot_name(found.name)
    where = (f"declared in {found.config}" if found.config is not None else
             "no $config.dat found: a BOOL by its TRUE/FALSE assignments, unless it is an output SIGNAL there")
    stored = "the value the file stores" if found.value is not None else "no declaration found gives it a value"
    start = ("(the program sets it before it reads it)" if folded else
             f"starting at {init} ({stored}; on the controller it starts where the last run or another program "
             "left it)")
    return (f"`{name}` is a global of $config.dat ({where}) the program sets: read as a task variable {start}; "
            "another program (the submit interpreter, another task) writing it while this one runs is not seen"
            + ("" if found.config is not None else "; give the $config.dat beside the program to check it"))
