"""Positions declared in another module's data list, read where that data list is public.

KRL (KUKA KSS 8.x Operating and Programming Instructions for System Integrators, data lists): a
data object declared `DECL GLOBAL` in a data list opened with `DEFDAT name PUBLIC` is seen by every
module of the controller; without PUBLIC, or without GLOBAL, it belongs to its own module. The
import reads the data lists that sit in the program's folder (the files a project keeps together),
keeps only those public globals, and only positions no `.src` of that folder assigns (a data object
holds its data-list value until a statement assigns it). A name two public data lists declare is
left out: which one the controller took is not certain. The folder read is bounded (files, bytes).
"""

from __future__ import annotations

import os
import re

from rmot.backends.readers.common import MAX_BYTES, read_text
from rmot.backends.readers.krl_data import Data, data_list, position

__all__ = ["public_globals", "ASSIGNMENT"]

MAX_FILES = 1024  # .src and .dat files of the folder read at most; beyond, none is (a folder of archives)
MAX_TOTAL = 16 * MAX_BYTES  # their bytes read at most; beyond, none is used

# a statement assigning a data object, or one of its elements or components: `P = ..`, `P[2].Z = ..`
ASSIGNMENT = re.compile(r"(?im)^[ \t]*(\w+)[ \t]*(?:\[[^\]\n]*\])?[ \t]*(?:\.\w+)?[ \t]*=(?!=)")


def _text(path: str) -> str | None:
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_BYTES + 1)
        return read_text(data) if len(data) <= MAX_BYTES else None
    except (OSError, ValueError):
        return None


def _global_lines(text: str) -> str | None:
    """The lines of a public data list that declare GLOBAL data (with the elements of a GLOBAL array
    written on their own lines); None where the data list is not PUBLIC."""
    head = re.search(r"(?im)^[ \t]*DEFDAT[ \t]+\w+([^\n;]*)", text)
    if head is None or not re.search(r"(?i)\bPUBLIC\b", head.group(1)):
        return None
    kept: list[str] = []  # the other lines blank: each declaration keeps its line number
    arrays: set[str] = set()
    for line in text.splitlines():
        m = re.match(r"(?i)\s*DECL\s+GLOBAL\s+(?:CONST\s+)?\w+\s+(\w+)\s*(\[)?", line)
        element = re.match(r"\s*(\w+)\s*\[\s*\d+\s*\]\s*=", line)
        if m is not None and m.group(2):
            arrays.add(m.group(1).upper())
        keep = m is not None or (element is not None and element.group(1).upper() in arrays)
        kept.append(line if keep or re.match(r"(?i)\s*DEFDAT\b", line) else "")
    return "\n".join(kept + ["ENDDAT"])


def public_globals(src_path: str, own_dat: str | None) -> dict[str, Data]:
    """NAME -> the declaration of every position declared GLOBAL in a public data list of another
    module of the program's folder, which no .src there assigns (see the module's docstring)."""
    folder = os.path.dirname(os.path.abspath(src_path))
    try:
        names = sorted(n for n in os.listdir(folder) if n.lower().endswith((".src", ".dat")))
    except OSError:
        return {}
    if len(names) > MAX_FILES:
        return {}
    own = {os.path.abspath(p) for p in (src_path, own_dat) if p is not None}
    found: dict[str, Data] = {}
    twice: set[str] = set()
    assigned: set[str] = set()
    total = 0
    for name in names:
        path = os.path.join(folder, name)
        text = _text(path)
        if text is None:
            continue
        total += len(text)
        if total > MAX_TOTAL:
            return {}
        if name.lower().endswith(".src"):
            assigned |= {m.upper() for m in ASSIGNMENT.findall(text)}
            continue
        public = _global_lines(text) if os.path.abspath(path) not in own else None
        for key, decl in (data_list((path, public)) if public is not None else {}).items():
            if position(*decl) is None:
                continue
            if key in found:
                twice.add(key)
            found[key] = decl
    return {k: v for k, v in found.items() if k not in twice and k.split("[")[0] not in assigned}
