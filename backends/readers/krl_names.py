"""The names a KRL program reads that are not positions: its SIGNALs, its variables, and the
robot's `$config.dat`.

KRL (KUKA KSS 8.x Operating and Programming Instructions for System Integrators, "Variables and
declarations", "SIGNAL"): `SIGNAL name $IN[n]` / `$OUT[n]` gives an input or output a name (in
a `.src`, a `.dat` or `$config.dat`); `DECL [GLOBAL] TYPE name` declares a variable (`DECL` may
be left out for the simple types); a `DEF name(p1:IN, p2:OUT)`'s parameters are variables too.
`$config.dat` (folder `KRC/R1/System`) holds the global declarations every program sees: the
signals, the home positions (`XHOME`), the global variables. It is read where it lies beside the
program or in the `System` folder of the robot's tree (`R1/Program/..` → `R1/System`).
"""

from __future__ import annotations

import os
import re

from rmot.backends.readers.common import MAX_BYTES, number, read_text, rmot_name, split_top
from rmot.backends.readers.krl_text import Line, lines
from rmot.backends.readers.rapid import num_text

__all__ = ["group_globals", "group_names", "is_group_input"]
__all__ += ["signals", "port_of", "declared_names", "config_near", "Params", "signatures", "file_signatures", "call_args",
            "param_names", "switch_cases"]

Params = tuple[tuple[str, str], ...]  # (name as written, rmot type "number" or "bool")

_TYPES = "INT|REAL|BOOL|CHAR|E6POS|POS|FRAME|E6AXIS|AXIS"


def signals(text: str) -> dict[str, tuple[str, int]]:
    """NAME -> ("IN" | "OUT", n) of every `[GLOBAL] SIGNAL name $IN[n]` / `$OUT[n]` of one bit (a
    group `$IN[n] TO $IN[m]` is a number, not a condition: left out)."""
    out: dict[str, tuple[str, int]] = {}
    for name, kind, n, rest in re.findall(r"(?im)^[ \t]*(?:GLOBAL\s+)?SIGNAL\s+(\w+)\s+\$(IN|OUT)\[(\d+)\]([^\n;]*)", text):
        if not rest.strip():
            out[name.upper()] = (kind.upper(), int(n))
    return out


def group_globals(text: str) -> set[str]:
    """NAME of every whole number a `$config.dat` gives all programs: a SIGNAL of a group of
    inputs (`SIGNAL name $IN[a] TO $IN[b]`, read as an INT, KSS 8.x "SIGNAL") and a scalar INT
    global (`DECL INT name`, `INT a, b`: its declarations are global, such as PGNO, which the
    cell program fills from the program-number inputs)."""
    out = _group_signals(text)
    for names in re.findall(r"(?im)^[ \t]*(?:DECL\s+)?(?:GLOBAL\s+)?INT\s+([^=;\n]+)", text):
        out |= {n.upper() for n in re.findall(r"(?:^|,)\s*(\w+)\s*(?=,|$)", names.strip())}
    return out


def _group_signals(text: str) -> set[str]:
    return {n.upper() for n in re.findall(r"(?im)^[ \t]*(?:GLOBAL\s+)?SIGNAL\s+(\w+)\s+\$IN\[\d+\]\s+TO\b", text)}


def group_names(config: tuple[str, str] | None, texts: list[str]) -> set[str] | None:
    """The group inputs a program may read where a `$config.dat` was found (None where not):
    its INT globals and SIGNAL groups, and the SIGNAL groups of the program's own `texts`."""
    if config is None:
        return None
    return group_globals(config[1]).union(*(_group_signals(text) for text in texts))


def is_group_input(config_groups: set[str] | None, known: set[str], key: str) -> bool:
    """Whether NAME `key` (upper case), tested as a number, is a group input: the `$config.dat`
    found declares it as one (group_globals), or none was found and the program's own files do
    not know it (`known`: their SIGNALs, declarations, data and the names it assigns)."""
    return key in config_groups if config_groups is not None else key not in known


def port_of(found: dict[str, tuple[str, int]], name: str, kind: str) -> int | None:
    """The port of `name` where it is a SIGNAL of that kind ("IN" or "OUT")."""
    entry = found.get(name.upper())
    return entry[1] if entry is not None and entry[0] == kind else None


def declared_names(text: str) -> set[str]:
    """NAME of every variable a KRL text declares (`DECL [GLOBAL] TYPE a, b[3]`, `INT a`, a DEF's
    parameters): names that are variables, never inputs."""
    out: set[str] = set()
    for names in re.findall(rf"(?im)^[ \t]*(?:DECL\s+(?:GLOBAL\s+)?\w+|(?:GLOBAL\s+)?(?:{_TYPES}))\s+([^=;\n]+)", text):
        out |= {m.upper() for m in re.findall(r"(?:^|,)\s*(\w+)", names)}
    for params in re.findall(r"(?im)^[ \t]*(?:GLOBAL\s+)?DEF(?:FCT\s+\w+)?\s+\w+\s*\(([^)\n]*)\)", text):
        out |= {m.upper() for m in re.findall(r"(\w+)\s*:\s*(?:IN|OUT)\b", params, flags=re.I)}
    return out


def config_near(src_path: str) -> tuple[str, str] | None:
    """The robot's `$config.dat` for a program at `src_path`: beside it, or in the `System` folder
    of the tree it lies in (up to 5 folders up); None when there is none (or it is not text)."""
    folder = os.path.dirname(os.path.abspath(src_path))
    for level in range(6):
        beside = [os.path.join(folder, "$config.dat")] if level == 0 else []
        for candidate in beside + [os.path.join(folder, "System", "$config.dat")]:
            found = _existing(candidate)
            if found is not None:
                try:
                    with open(found, "rb") as f:
                        data = f.read(MAX_BYTES + 1)
                    if len(data) <= MAX_BYTES:
                        return found, read_text(data)
                except (OSError, ValueError):
                    return None
        parent = os.path.dirname(folder)
        if parent == folder:
            break
        folder = parent
    return None


def _existing(path: str) -> str | None:
    """`path` or the same name in another case (`$CONFIG.DAT`, a folder `SYSTEM`), if it exists."""
    if os.path.isfile(path):
        return path
    folder, name = os.path.split(path)
    parent, sub = os.path.split(folder)
    for base in ([folder] if os.path.isdir(folder) else
                 [os.path.join(parent, d) for d in _listdir(parent) if d.lower() == sub.lower()]):
        for entry in _listdir(base):
            if entry.lower() == name.lower() and os.path.isfile(os.path.join(base, entry)):
                return os.path.join(base, entry)
    return None


def _listdir(folder: str) -> list[str]:
    try:
        return sorted(os.listdir(folder))
    except OSError:
        return []


def signatures(found: list[Line]) -> dict[str, Params | None]:
    """ROUTINE -> its parameters where every one is `:IN` (by value) and declared INT or REAL
    (`number`) or BOOL (`bool`) in the routine; None where one is not (an `:OUT`, a position)."""
    out: dict[str, Params | None] = {}
    for i, ln in enumerate(found):
        m = re.fullmatch(r"(?i)(?:GLOBAL\s+)?DEF\s+(\w+)\s*\((.*)\)", ln.text)
        if m is None:
            continue
        types: dict[str, str] = {}
        for other in found[i + 1:]:
            if other.word == "END":
                break
            d = re.fullmatch(r"(?i)(?:DECL\s+)?(INT|REAL|BOOL)\s+(\w+(?:\s*,\s*\w+)*)", other.text)
            for name in re.split(r"\s*,\s*", d.group(2)) if d else []:
                types[name.upper()] = "bool" if d.group(1).upper() == "BOOL" else "number"  # type: ignore[union-attr]
        params = [re.fullmatch(r"(?i)(\w+)\s*:\s*IN", p.strip()) for p in m.group(2).split(",") if p.strip()]
        known = all(p is not None and p.group(1).upper() in types for p in params)
        out[m.group(1).upper()] = tuple((p.group(1), types[p.group(1).upper()]) for p in params  # type: ignore[union-attr]
                                        ) if known else None
    return out


def file_signatures(path: str, text: str) -> dict[str, Params | None]:
    """The routines a KRL .src defines with their parameters (`signatures`), for the other files
    of one import to call them with arguments."""
    return signatures(lines(path, text))


def call_args(text: str, params: Params, caller: dict[str, tuple[str, str]]) -> tuple[str, ...] | None:
    """A call's arguments as rmot expressions: number literals, TRUE/FALSE, or the caller's own
    parameters of the same type; None where one is anything else (a variable, an expression)."""
    args = split_top(text) if text.strip() else []
    if len(args) != len(params):
        return None
    out = []
    for arg, (_, type_) in zip(args, params):
        key, value = arg.strip().upper(), number(arg.strip())
        if key in caller and caller[key][1] == type_:
            out.append(caller[key][0])
        elif type_ == "bool" and key in ("TRUE", "FALSE"):
            out.append(key.lower())
        elif type_ == "number" and value is not None:
            out.append(num_text(value))
        else:
            return None
    return tuple(out)


def param_names(params: Params | None) -> dict[str, tuple[str, str]]:
    """NAME -> (rmot name, type) of a routine's parameters, for its conditions and calls."""
    return {n.upper(): (rmot_name(n), t) for n, t in params or ()}


def switch_cases(found: list[Line], i: int, params: dict[str, tuple[str, str]]) -> list[tuple[int, list[str]]] | None:
    """The CASE/DEFAULT lines of `SWITCH k` at `i` (index, values; DEFAULT: none) where k is a
    number parameter of the routine and every value a whole number; None otherwise."""
    m = re.fullmatch(r"(?i)SWITCH\s+(\w+)", found[i].text)
    if m is None or params.get(m.group(1).upper(), ("", ""))[1] != "number":
        return None
    cases: list[tuple[int, list[str]]] = []
    depth, j = 0, i + 1
    while j < len(found) and (depth or found[j].word != "ENDSWITCH"):
        ln = found[j]
        depth += (ln.word == "SWITCH") - (ln.word == "ENDSWITCH")
        values = re.fullmatch(r"(?i)CASE\s+(-?\d+(?:\s*,\s*-?\d+)*)", ln.text) if ln.word == "CASE" else None
        if depth == 0 and ln.word in ("CASE", "DEFAULT"):
            if ln.word == "CASE" and values is None:
                return None
            cases.append((j, re.split(r"\s*,\s*", values.group(1)) if values else []))
        elif depth == 0 and not cases and (ln.text or ln.fold):
            return None  # a statement before the first CASE
        j += 1
    return cases if j < len(found) and cases and all(v for _, v in cases[:-1]) else None
