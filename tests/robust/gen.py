"""Whole .rmot projects (a cell, a program, sometimes a library) generated from the grammar
(lang/grammar/rmot.lark, lang/REFERENCE.md), for the fuzz tests and `make fuzz`.

One generator, two sources of choices: `hypothesis_project()` is a Hypothesis strategy (the
suite: shrinking, the example database); `random_project(seed)` draws the same structure from
`random.Random(seed)` (`make fuzz`: a hundred thousand inputs, cheaply, reproducible by
seed). Most values are sane (reachable poses of the default cell's IRB 1600, ordinary speeds)
so programs get through to the planner, the verifier and every backend; a share of them are
absurd (0, huge, subnormal, overflowing, negative), and a share of the texts get hostile
bytes (line breaks of every convention, NUL, unicode) spliced in.
"""

from __future__ import annotations

import random
from rmot.backends import controllers
from collections.abc import Callable, Sequence
from typing import Any

from hypothesis import strategies as st

__all__ = ["Draw", "hypothesis_project", "project", "random_project"]

LIBRARY_ROBOTS = ("abb_irb1600", "ur5e", "kuka_kr16", "fanuc_m20ia", "abb_irb4600", "yaskawa_gp8", "staubli_tx2_60")
_ODD_NUMBERS = ("0", "1e308", "1e999", "1e-320", "123456789012", "9e15", "0.000001", "4294967296", "1e9")
_BREAKS = ("\n", "\r\n", "\r", "\f", "\v", "\u2028", "\u2029", "\x85", "\x00", "\t", ";", "\ufeff", "\u00e9", "\U0001f600")
_LENGTH_UNITS = ("mm", "cm", "m", "in")
_VENDORS = (*controllers(), "cobol")  # the last one is absurd
_NATIVE = ("WaitTime 1;", "x\\\\y", 'a\\"b')
_NAMES = ("home", "a", "b", "p1", "t", "x", "on", "in", "s", "m", "pose", "world", "base", "tool0", "move", "r1")


class Draw:
    """The choices a generator makes; backed by Hypothesis or by random.Random."""

    def __init__(self, integer: Callable[[int, int], int]) -> None:
        self._int = integer
        self.absurd = False  # this project may hold absurd numbers, names and bytes (set per project)

    def integer(self, lo: int, hi: int) -> int:
        return self._int(lo, hi)

    def chance(self, percent: int) -> bool:
        return self._int(0, 99) < percent

    def pick(self, items: Sequence[Any]) -> Any:
        return items[self._int(0, len(items) - 1)]


def _num(d: Draw, lo: float, hi: float) -> str:
    if d.absurd and d.chance(4):
        return d.pick(_ODD_NUMBERS)
    value = lo + (hi - lo) * d.integer(0, 1000) / 1000
    return f"{value:g}"


def _int(d: Draw, lo: int, hi: int) -> str:
    return d.pick(_ODD_NUMBERS) if d.absurd and d.chance(4) else str(d.integer(lo, hi))


def _len(d: Draw, lo: float, hi: float) -> str:
    if d.chance(3):
        return f"{_num(d, lo, hi)} {d.pick(_LENGTH_UNITS)}"
    if d.absurd and d.chance(2):
        return f"{_num(d, lo, hi)} / 1e-320 mm" if d.chance(50) else f"({_num(d, lo, hi)} mm - {_num(d, lo, hi)} mm) * {_num(d, -3, 3)}"
    return f"{_num(d, lo, hi)}mm"


def _pose(d: Draw) -> str:
    fields = [f"x={_len(d, 300, 1000)}", f"y={_len(d, -500, 500)}", f"z={_len(d, 200, 1200)}"]
    if d.chance(10):
        fields.append(f"q=({_num(d, -1, 1)}, {_num(d, -1, 1)}, {_num(d, -1, 1)}, {_num(d, -1, 1)})")
    else:
        fields.append(f"rx={_num(d, 150, 210)}deg")
        if d.chance(30):
            fields.append(f"ry={_num(d, -30, 30)} deg")
    if d.absurd and d.chance(5):
        fields = fields[: d.integer(0, len(fields))]
    return f"pose({', '.join(fields)})"


def _joints(d: Draw, n: int = 6) -> str:
    if d.absurd and d.chance(5):
        n = d.integer(0, 8)
    ranges = [(-90, 90), (-60, 20), (-20, 60), (-90, 90), (20, 110), (-90, 90)] + [(-10, 10)] * 4
    return "joints(" + ", ".join(_num(d, *ranges[i]) for i in range(n)) + ") deg"


def _target(d: Draw, joints_ok: bool = True) -> str:
    roll = d.integer(0, 99)
    if roll < 35:
        return "home" if joints_ok else "t"
    if roll < 60:
        return _pose(d)
    if roll < 70:
        return f"shift(t, z={_len(d, -100, 100)})"
    if roll < 75:
        return f"t * pose(z={_len(d, -50, 50)})"
    if roll < 90 or not d.absurd:
        return _joints(d) if joints_ok else _pose(d)
    return d.pick(_NAMES)


def _modifiers(d: Draw) -> str:
    out = []
    for _ in range(d.integer(0, 2)):
        kind = d.integer(0, 6)
        if kind == 0:
            out.append(f"speed {_num(d, 10, 2000)} mm/s")
        elif kind == 1:
            out.append(f"zone {'fine' if d.chance(30) else _len(d, 0, 100)}")
        elif kind == 2:
            out.append(f"joint_speed {_num(d, 1, 100)} %")
        elif kind == 3:
            out.append(f"time {_num(d, 0.1, 10)} s")
        elif kind == 4:
            out.append(f"accel {_num(d, 0.1, 10)} m/s^2")
        elif kind == 5:
            out.append(f"config(elbow={d.pick(('up', 'down', 'sideways') if d.absurd else ('up', 'down'))})")
        else:
            out.append(f"tool {d.pick(('gripper', 'flange', 'nope') if d.absurd else ('gripper', 'flange'))}")
    return (" " + " ".join(out)) if out else ""


def _statement(d: Draw, depth: int, procs: list[str]) -> str:
    pad = "  " * (depth + 1)
    if d.chance(12):
        return _runtime_statement(d, depth, procs, pad)
    kind = d.integer(0, 99)
    if kind < 22:
        return f"{pad}move joint {_target(d)}{_modifiers(d)}"
    if kind < 38:
        return f"{pad}move linear {_target(d, d.absurd)}{_modifiers(d)}"
    if kind < 42:
        return f"{pad}move circular via {_pose(d)} to {_target(d, d.absurd)}{_modifiers(d)}"
    if kind < 48:
        if d.absurd:
            return f"{pad}{d.pick(('speed', 'zone', 'joint_speed', 'accel'))} " + d.pick(
                (f"{_num(d, 10, 1000)} mm/s", f"{_len(d, 0, 50)}", f"{_num(d, 1, 100)} %", "fine", f"{_num(d, 0.5, 5)} m/s^2"))
        return pad + d.pick((f"speed {_num(d, 10, 1000)} mm/s", f"zone {_len(d, 0, 50)}", f"joint_speed {_num(d, 1, 100)} %",
                             "zone fine", f"accel {_num(d, 0.5, 5)} m/s^2"))
    if kind < 54:
        return f"{pad}wait {_num(d, 0, 2)} {d.pick(('s', 'ms', 'min'))}"
    if kind < 60:
        return f"{pad}set out[{_int(d, 1, 4)}] = {d.pick(('on', 'off', 'true', '1'))}"
    if kind < 63:
        return f"{pad}pulse out[{_int(d, 1, 4)}] for {_num(d, 0.1, 1)} s"
    if kind < 67:
        t = f" timeout {_num(d, 1, 20)} s" if d.chance(50) else ""
        return f"{pad}wait until in[{_int(d, 1, 3)}] {d.pick(('==', '!='))} {d.pick(('on', 'off'))}{t}"
    if kind < 71 and depth < 2:  # small loops: a generated program stays a few dozen moves (seconds to plan)
        return f"{pad}for i in {_int(d, -1, 1)} .. {_int(d, 0, 2)} {{\n{_body(d, depth + 1, procs)}\n{pad}}}"
    if kind < 74 and depth < 2:
        return f"{pad}repeat {_int(d, 0, 2)} {{\n{_body(d, depth + 1, procs)}\n{pad}}}"
    if kind < 78 and depth < 3:
        other = f" else {{\n{_body(d, depth + 1, procs)}\n{pad}}}" if d.chance(50) else ""
        return f"{pad}if in[{_int(d, 1, 3)}] == on {{\n{_body(d, depth + 1, procs)}\n{pad}}}{other}"
    if kind < 82 and procs:
        return f"{pad}{d.pick(procs)}({d.pick(('', 'home', _pose(d), '1 mm'))})"
    if kind < 85:
        return f"{pad}target {d.pick(_NAMES) if d.absurd else 'tt' + str(depth)} = {_target(d)}"
    if kind < 88:
        return f"{pad}const c{d.integer(0, 3)} = {_len(d, -100, 100)}"
    if kind < 91:
        return f"{pad}frame {d.pick(('table_top', 'pallet', 'base', 'world') + (('nope',) if d.absurd else ()))}"
    if kind < 93:
        vendor, text = d.pick(_VENDORS[:len(_VENDORS) - 1 + d.absurd]), d.pick(_NATIVE)
        return f'{pad}native {vendor} "{text}"'
    if kind < 95:
        return f"{pad}sync s{d.integer(0, 2)}"
    return f"{pad}tool {d.pick(('gripper', 'flange', 'table') if d.absurd else ('gripper', 'flange'))}"


def _condition(d: Draw) -> str:
    """A runtime condition: inputs, analog inputs, variables, and/or/not."""
    leaves = (f"in[{_int(d, 1, 3)}] {d.pick(('==', '!='))} {d.pick(('on', 'off'))}",
              f"ain[{_int(d, 1, 2)}] {d.pick(('<', '<=', '>', '>='))} {_num(d, -1, 10)}",
              f"n {d.pick(('<', '==', '!=', '>='))} {_int(d, -2, 5)}", "flag", "not flag")
    out = d.pick(leaves)
    for _ in range(d.integer(0, 2)):
        out = f"{out} {d.pick(('and', 'or'))} {d.pick(leaves)}"
    return f"not ({out})" if d.chance(10) else out


def _runtime_statement(d: Draw, depth: int, procs: list[str], pad: str) -> str:
    """Runtime logic: assignments, while, wait with a timeout branch, stop, if on a
    general condition, joint-move speed shares and fixed turns. `var n` and `var flag` are
    declared at the top of every generated program; absurd draws assign to the wrong things."""
    kind = d.integer(0, 9)
    if kind < 2:
        if d.absurd:
            return f"{pad}{d.pick(('n', 'flag', 't', 'home', 'nope', 'i'))} = {d.pick(('n + 1', 'on', '2.5', 'n / 0', 'p'))}"
        return pad + d.pick(("n = n + 1", "n = n * 2 - 1", "flag = not flag", f"flag = n > {_int(d, 0, 3)}"))
    if kind < 4 and depth < 2:
        return f"{pad}while {_condition(d)} {{\n{_body(d, depth + 1, procs)}\n{pad}}}"
    if kind < 6 and depth < 3:
        other = f" else {{\n{_body(d, depth + 1, procs)}\n{pad}}}" if d.chance(70) else ""
        return f"{pad}wait until {_condition(d)} timeout {_num(d, 0.1, 20)} s{other}"
    if kind < 7:
        return f"{pad}stop"
    if kind < 8 and depth < 3:
        return f"{pad}if {_condition(d)} {{\n{_body(d, depth + 1, procs)}\n{pad}}}"
    if kind < 9:
        return f"{pad}move joint {_target(d)} speed {_num(d, 1, 100)} %"
    joint = d.pick(("j4", "j6", "j1", "j9") if d.absurd else ("j4", "j6"))
    return f"{pad}move joint {_target(d)} config({joint}={_int(d, -2, 2)})"


def _body(d: Draw, depth: int, procs: list[str]) -> str:
    return "\n".join(_statement(d, depth, procs) for _ in range(d.integer(0, 6 if depth == 0 else 3)))


def _cell(d: Draw) -> str:
    robots = ["r1"] + (["r2"] if d.chance(15) else [])
    lines = ["cell fuzz_cell {"]
    for i, r in enumerate(robots):
        lines.append(f"  robot {r} = {d.pick(LIBRARY_ROBOTS) if d.chance(40) else 'abb_irb1600'} at pose(x={i * 1500}mm, z={_len(d, 0, 500)})")
    for k in range(d.integer(0, 3)):
        shape = d.pick((f"box({_len(d, 10, 500)}, {_len(d, 10, 500)}, {_len(d, 10, 500)})",
                        f"cylinder(r={_len(d, 10, 200)}, h={_len(d, 10, 800)})",
                        f"sphere({_len(d, 10, 300)})", f"capsule(r={_len(d, 10, 100)}, length={_len(d, 10, 300)})",
                        'mesh("part.stl", scale=' + _num(d, 0.001, 2) + ")"))
        lines.append(f"  fixture f{k} = {shape} at pose(x={_len(d, 500, 1500)}, y={_len(d, -1500, 1500)}, z={_len(d, 0, 400)})")
    lines.append(f"  tool gripper = box(90mm, 70mm, 120mm) at pose(z=100mm) tcp pose(z={_len(d, 50, 250)}) mass {_num(d, 0, 5)} kg on r1")
    lines.append("  frame table_top = pose(x=850mm, z=750mm)")
    lines.append(f"  frame pallet = pose(y={_len(d, -1200, -800)}, z=400mm)")
    for p in range(d.integer(0, 3)):
        direction = d.pick(("out", "in"))  # the draws in the order of the original one-line f-string
        port = _int(d, 1, 4) if d.absurd else p + 1
        name = d.pick(("sig", "a b", "x]y", "s" * 40, "sync"))
        lines.append(f'  io {direction}[{port}] = "{name}{p}" on r1')
    lines.append("}")
    return "\n".join(lines) + "\n"


def project(d: Draw) -> dict[str, str]:
    """{file name: text}: main.rmot (a program using cell.rmot or the default cell), maybe a library."""
    d.absurd = d.chance(35)
    files: dict[str, str] = {}
    procs: list[str] = []
    head = []
    if d.chance(25):
        procs = ["approach", "lift"]
        files["lib.rmot"] = ("proc approach(p: pose) {\n  move linear shift(p, z=50mm)\n  move linear p\n}\n"
                             f"proc lift() {{\n{_body(d, 0, [])}\n}}\n")
        head.append('import "lib.rmot"')
    if d.chance(70):
        files["cell.rmot"] = _cell(d)
        files["part.stl"] = ("solid p\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\nendloop\n"
                             "endfacet\nendsolid p\n")
        head.append('use cell "cell.rmot"')
    if d.absurd and d.chance(10):
        head.append(d.pick(('import "../outside.rmot"', 'use cell "/etc/passwd"', 'import "' + "n" * 300 + '"', 'import "lib.rmot"')))
    body = (f"  tool gripper\n  target home = {_joints(d)}\n  target t = {_pose(d)}\n"
            "  var n: int = 0\n  var flag: bool = off\n  move joint home\n"
            + _body(d, 0, procs))
    files["main.rmot"] = "\n".join(head) + f"\nprogram fuzz on r1 {{\n{body}\n}}\n"
    if d.absurd and d.chance(20):  # hostile bytes spliced in anywhere
        text = files["main.rmot"]
        at = d.integer(0, len(text))
        files["main.rmot"] = text[:at] + d.pick(_BREAKS) + text[at:]
    return files


def random_project(seed: int) -> dict[str, str]:
    rng = random.Random(seed)
    return project(Draw(rng.randint))


@st.composite
def hypothesis_project(draw: st.DrawFn) -> dict[str, str]:
    return project(Draw(lambda lo, hi: draw(st.integers(lo, hi))))
