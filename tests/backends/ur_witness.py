"""A small URScript interpreter for tests, written apart from rmot's reader and backend:
functions (`def f():` .. `end`, called as `f()`), `if` on a digital input (taken at the level
given: a condition `== True` holds when the input is on), `while` run once, `set_tcp(p[..])`,
and movej/movel/movep/movec, each recorded with the TCP z (m) active when it runs (URScript
manual: set_tcp sets the controller's active TCP offset until the next set_tcp).
"""

from __future__ import annotations

import re

__all__ = ["tcp_at_moves"]


def tcp_at_moves(script: str, level: bool, main: str = "u") -> list[float]:
    """The TCP z (m) each movel/movej of `script` runs with, input 1 at `level`."""
    lines = [ln.strip() for ln in script.splitlines() if ln.strip() and not ln.strip().startswith(("#", "$"))]
    funcs: dict[str, int] = {}
    for i, ln in enumerate(lines):
        m = re.fullmatch(r"def (\w+)\(\):", ln)
        if m:
            funcs[m.group(1)] = i + 1
    state = {"z": float("nan")}
    out: list[float] = []

    def block_end(i: int) -> int:
        depth = 0
        while True:
            ln = lines[i]
            if re.match(r"(def|if|while) ", ln):
                depth += 1
            elif ln == "end":
                if depth == 0:
                    return i
                depth -= 1
            i += 1

    def run(i: int) -> None:
        while lines[i] != "end":
            ln = lines[i]
            if ln.startswith("def "):
                i = block_end(i + 1) + 1
                continue
            if ln.startswith(("if ", "while ")):
                end = block_end(i + 1)
                taken = ln.startswith("while ") or ("== True" in ln) == level
                if taken:
                    run(i + 1)
                i = end + 1
                continue
            m = re.fullmatch(r"set_tcp\(p\[([^\]]*)\]\)", ln.replace(" ", ""))
            if m:
                state["z"] = float(m.group(1).split(",")[2])
            elif ln.startswith(("movel(", "movej(", "movep(", "movec(")):
                out.append(state["z"])
            elif re.fullmatch(r"\w+\(\)", ln) and ln[:-2] in funcs:
                run(funcs[ln[:-2]])
            i += 1

    run(funcs[main])
    return out
