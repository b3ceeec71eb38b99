"""The tool and base a program's first Cartesian move runs with where the program has not set
them: its caller's.

KRL's `$TOOL` and `$BASE` are global system variables: a program starts with the values the last
program or the operator set (KSS 8.x System Integrators, system variables; the inline forms set
them, a plain `LIN` does not). A URScript program runs with the installation's active TCP until
its `set_tcp` (URScript manual, set_tcp: "Sets the active tcp offset"), which the script file
does not hold. A move before the program sets them is read with rmot's defaults, the bare
flange and the robot base, which nothing in the file vouches for: W546 says so once, at the
first such Cartesian move of the routine that runs (a joint move to axis values goes where it
goes whatever the tool; a called routine's moves take its caller's, as an rmot proc's do).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from rmot.backends.readers import codes
from rmot.backends.readers.model import Document, Move, Where, walk
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Span

__all__ = ["tool_not_set"]


def tool_not_set(doc: Document, span_of: Callable[[Where], Span]) -> Document:
    """`doc` with W546 at the main routine's first Cartesian move read before a tool (KRL: or a
    base) is set, where there is one (KRL and URScript)."""
    if doc.vendor not in ("krl", "urscript"):
        return doc
    main = next((r for r in doc.routines if r.name == doc.main), None)
    moves = [s for s in walk(main.body) if isinstance(s, Move)] if main is not None else []
    first = next((m for m in moves if m.joints is None and (m.tool is None or m.frame is None)), None)
    if first is None:
        return doc
    unset = [name for name, value in (("$TOOL" if doc.vendor == "krl" else "TCP", first.tool),
                                      ("$BASE", first.frame)) if value is None]
    where = "the bare flange" + (" and the robot base" if "$BASE" in unset else "")
    caller = ("KRL keeps them from the program that ran before" if doc.vendor == "krl"
              else "the controller runs it with the installation's active TCP until a set_tcp")
    message = (f"this move is read before the program sets its {' or '.join(unset)} ({caller}): read with "
               f"{where}, rmot's defaults, which the file does not vouch for (set them in the program, or check "
               "the imported program's `tool` and `frame`)")
    return replace(doc, diagnostics=doc.diagnostics + (Diagnostic(codes.START_TOOL_UNKNOWN, Severity.WARNING, message,
                                                                  span_of(first.where)),))
