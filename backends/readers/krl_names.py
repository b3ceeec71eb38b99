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

from rmot.backends.readers.common import MAX_BYTES, read_text

__all__ = ["signals", "port_of", "declared_names", "config_near"]

_TYPES = "INT|REAL|BOOL|CHAR|E6POS|POS|FRAME|E6AXIS|AXIS"


def signals(text: str) -> dict[str, tuple[str, int]]:
    """NAME -> ("IN" | "OUT", n) of every `[GLOBAL] SIGNAL name $IN[n]` / `$OUT[n]` of one bit (a
    group `$IN[n] TO $IN[m]` is a number, not a condition: left out)."""
    out: dict[str, tuple[str, int]] = {}
    for name, kind, n, rest in re.findall(r"(?im)^[ \t]*(?:GLOBAL\s+)?SIGNAL\s+(\w+)\s+\$(IN|OUT)\[(\d+)\]([^\n;]*)", text):
        if not rest.strip():
            out[name.upper()] = (kind.upper(), int(n))
    return out


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
    for _ in range(6):
        for candidate in (os.path.join(folder, "$config.dat"), os.path.join(folder, "System", "$config.dat")):
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
