"""Read Stäubli VAL3 applications back into a neutral Document (the shape backends/val3.py
writes: a project `.pjx` naming its `.pgx` programs and `.dtx` data).

Conventions are the VAL3 backend's, read in reverse (Stäubli VAL3 Reference Manual, s7):
`pointRx` x y z (mm) rx ry rz (deg, R = Rx(rx)·Ry(ry)·Rz(rz), moving axes) with shoulder
lefty|righty, elbow epositive|enegative, wrist wpositive|wnegative (= rmot front/back, up/down,
noflip/flip) in the frame its `fatherId` names; `jointRx` j1..j6 (deg); `tool` (its TCP in the
flange), `frame` (in world); `mdesc` vel (% joint speed) for joint moves, tmax (mm/s) for
linear ones, blend off | joint | Cartesian with leave = reach (mm) the blend radius;
`movej(p, tool, mdesc)`, `movel`, `movec(via, p, tool, mdesc)`; `dOut[n] = true|false`,
`aOut[n] = v`, `delay(s)`, `wait(dIn[n] == true|false)`, the backend's timed wait
`bOk = watch(dIn[n] == v, T)` with its stop block, `call name()`; `waitEndMove()` is the
motion queue's, not a statement. The files are data: XML with a DOCTYPE (entities) is refused.
"""

from __future__ import annotations

import math
import os
import re
import xml.etree.ElementTree as ET

from rmot.backends.readers.common import Tally, number, reaches, rmot_name, split_top
from rmot.backends.readers.model import (
    Call, Cond, For, FrameData, If, Move, Pulse, Routine, SetOut, Stmt, Target, ToolData, Wait, WaitIn, Where,
)
from rmot.backends.readers.rapid import mm
from rmot.lang import ir

__all__ = ["read_val3"]

_NS = re.compile(r"\{[^}]*\}")
_MOVE = re.compile(r"(movej|movel|movec)\((.*)\)")
_REF = r"(\w+)\[(\d+)\]"
# the remark the backend writes where the program attaches or detaches a part (VAL3 tool data
# carries no mass: backends/val3.py, W411): the tool and parts' mass
_PAYLOAD_REMARK = re.compile(r"// (?:attach|detach) \w+: payload \d+(?:\.\d+)? kg")
_COND = r"dIn\[(\d+)\] == (true|false)"


def _tag(e: ET.Element) -> str:
    return _NS.sub("", e.tag)


def _pose(v: dict[str, str]) -> ir.Pose | None:
    """x y z mm, rx ry rz deg with R = Rx·Ry·Rz (moving axes): the backend's trsf_attrs."""
    vals = [number(v.get(k, "")) for k in ("x", "y", "z", "rx", "ry", "rz")]
    if any(x is None or not math.isfinite(x) for x in vals):
        return None
    x, y, z, rx, ry, rz = (float(a) for a in vals)  # type: ignore[arg-type]
    half = [math.radians(a) / 2 for a in (rx, ry, rz)]
    qx = (math.cos(half[0]), math.sin(half[0]), 0.0, 0.0)
    qy = (math.cos(half[1]), 0.0, math.sin(half[1]), 0.0)
    qz = (math.cos(half[2]), 0.0, 0.0, math.sin(half[2]))
    w, i, j, k = (0.0 if abs(c) < 1e-12 else c for c in _qmul(_qmul(qx, qy), qz))  # cos(90 deg) noise
    return ir.Pose((x / 1000, y / 1000, z / 1000), (w, i, j, k))


def _qmul(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, float, float, float]:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)


def _branch(v: dict[str, str]) -> ir.Config | None:
    if not {"shoulder", "elbow", "wrist"} <= set(v):
        return None
    return ir.Config(ir.Shoulder.BACK if v["shoulder"] == "righty" else ir.Shoulder.FRONT,
                     ir.Elbow.DOWN if v["elbow"] == "enegative" else ir.Elbow.UP,
                     ir.Wrist.FLIP if v["wrist"] == "wnegative" else ir.Wrist.NOFLIP)


class _App:
    def __init__(self, path: str, text: str, data: list[tuple[str, str]],
                 programs: dict[str, tuple[str, str]] | None = None) -> None:
        self.tally = Tally(path, text, "val3")
        self.programs = programs or {}  # the import's programs by name (one called in a shifting loop is inlined)
        self.inlined: set[str] = set()
        self.counters: dict[str, str] = {}  # VAL3 loop variable -> rmot's, inside its loop
        self.shifts: dict[str, dict[str, str]] = {}  # trsf variable -> axis -> offset (mm)
        self.lines: list[tuple[str, Where]] = []
        self.path = path
        self.text = text
        self.data_files = data
        self.values: dict[str, dict[int, tuple[str, dict[str, str], Where]]] = {}  # name -> key -> (type, attrs)
        self.targets: dict[str, Target] = {}
        self.tools: dict[str, ToolData] = {}
        self.frames: dict[str, FrameData] = {}
        self.routines: list[Routine] = []
        self.name = os.path.splitext(os.path.basename(path))[0]

    def _xml(self, path: str, text: str) -> ET.Element:
        if re.search(r"<!DOCTYPE|<!ENTITY", text):
            raise self.tally.fail("a VAL3 file must be plain XML (got a DOCTYPE or entity)", Where(path, 1))
        try:
            return ET.fromstring(text)
        except ET.ParseError as exc:
            line = exc.position[0] if exc.position else 1
            raise self.tally.fail(f"a VAL3 file must be well-formed XML ({exc})", Where(path, line)) from None

    def read(self) -> None:
        for path, text in self.data_files:
            for data in self._xml(path, text).iter():
                if _tag(data) == "Data" and data.get("name"):
                    self._data(data, path, text)
        root = self._xml(self.path, self.text)
        programs = [p for p in root.iter() if _tag(p) == "Program" and p.get("name")]
        if not programs:
            raise self.tally.fail("a VAL3 program file must hold `<Program name=..>`", Where(self.path, 1))
        for program in programs:
            code = next((c for c in program.iter() if _tag(c) == "Code"), None)
            self._program(program.get("name", ""), code.text if code is not None and code.text else "")

    def _data(self, data: ET.Element, path: str, text: str) -> None:
        name, kind = data.get("name", ""), data.get("type", "")
        line = text[:text.find(f'name="{name}"')].count("\n") + 1
        for value in (v for v in data if _tag(v) == "Value"):
            key = int(value.get("key", "0")) if value.get("key", "0").isdigit() else 0
            attrs = dict(value.attrib)
            self.values.setdefault(name, {})[key] = (kind, attrs, Where(path, line))
            pose = _pose(attrs) if kind in ("pointRx", "tool", "frame") else None
            where = Where(path, line)
            label = re.sub(r"^[tf]_", "", name) if key == 0 else f"{name}_{key}"  # the backend's t_/f_ prefixes
            if kind == "tool" and pose is not None:
                self.tools[f"{name}[{key}]"] = ToolData(label, pose, 0.0, where)
            elif kind == "frame" and pose is not None and attrs.get("fatherId", "world[0]") == "world[0]":
                self.frames[f"{name}[{key}]"] = FrameData(label, pose, where)
            elif kind == "pointRx" and pose is not None:
                self.targets[f"{name}[{key}]"] = Target(f"{name}_{key}", pose, None, _branch(attrs), where)
            elif kind == "jointRx":
                joints = [number(attrs.get(f"j{i}", "")) for i in range(1, 7)]
                if all(j is not None for j in joints):
                    self.targets[f"{name}[{key}]"] = Target(f"{name}_{key}", None, tuple(joints), None, where)  # type: ignore[arg-type]

    def _program(self, name: str, code: str) -> None:
        start = self.text.find(code) if code else -1
        first = self.text[:start].count("\n") + 1 if start >= 0 else 1
        lines = [(ln.strip(), Where(self.path, first + n, len(ln) - len(ln.lstrip()) + 1))
                 for n, ln in enumerate(code.split("\n"))]
        lines = [(t, w) for t, w in lines if t and (not t.startswith("//") or _PAYLOAD_REMARK.fullmatch(t))
                 and t not in ("begin", "end")]
        if name == "stop" and not lines:
            return  # the application's empty stop handler (every VAL3 application has one)
        self.lines = lines
        body, _ = self._block(0, None)
        self.routines.append(Routine(name, (), tuple(body), Where(self.path, first)))

    def _block(self, i: int, end: str | None) -> tuple[list[Stmt], int]:
        """The statements from `i` to the line `end` (None: the program's end), nesting bounded."""
        def body() -> tuple[list[Stmt], int]:
            out: list[Stmt] = []
            j = i
            while j < len(self.lines) and self.lines[j][0] != end:
                stmts, j = self._statement(self.lines, j)
                out += stmts
            return out, j
        return self.tally.nested(self.lines[min(i, len(self.lines) - 1)][1] if self.lines else Where(self.path, 1), body)

    def _loop(self, i: int) -> tuple[list[Stmt], int] | None:
        """`for l_v = a to b` .. `endFor` (the backend's counted loop; `l_` its prefix)."""
        m = re.fullmatch(r"for (\w+) = (-?\d+) to (-?\d+)", self.lines[i][0])
        if m is None:
            return None
        name = rmot_name(re.sub(r"^l_", "", m.group(1)))
        self.counters[m.group(1)] = name
        body, j = self._block(i + 1, "endFor")
        del self.counters[m.group(1)]
        if j >= len(self.lines):
            raise self.tally.fail("missing endFor", self.lines[i][1])
        return [For(name, int(m.group(2)), int(m.group(3)) + 1, tuple(body), self.lines[i][1])], j + 1

    def _if(self, i: int) -> tuple[list[Stmt], int] | None:
        """`if dIn[n] == v` .. [`else` ..] `endIf` (nested blocks end at their own endIf)."""
        m = re.fullmatch(rf"if {_COND}", self.lines[i][0])
        if m is None:
            return None
        depth, k, middle = 0, i + 1, None
        while k < len(self.lines):  # this if's `else` and `endIf`
            head = self.lines[k][0]
            depth += head.startswith(("if ", "for ", "while "))
            if head == "else" and depth == 0:
                middle = k
            if head in ("endIf", "endFor", "endWhile"):
                if depth == 0:
                    break
                depth -= 1
            k += 1
        if k >= len(self.lines) or self.lines[k][0] != "endIf":
            return None
        then, _ = self._block_range(i + 1, middle if middle is not None else k)
        orelse, _ = self._block_range(middle + 1, k) if middle is not None else ([], k)
        return [If(Cond(int(m.group(1)), m.group(2) == "true"), tuple(then), tuple(orelse), self.lines[i][1])], k + 1

    def _block_range(self, i: int, stop: int) -> tuple[list[Stmt], int]:
        """The statements of lines i .. stop (exclusive)."""
        saved = self.lines
        self.lines = saved[:stop]
        try:
            return self._block(i, None)
        finally:
            self.lines = saved

    def _pulse(self, i: int) -> tuple[list[Stmt], int] | None:
        """`dOut[n] = true`, `delay(t)`, `dOut[n] = false`: the backend's pulse (VAL3 has none)."""
        texts = [t for t, _ in self.lines[i:i + 3]]
        on = re.fullmatch(r"dOut\[(\d+)\] = true", texts[0]) if len(texts) == 3 else None
        hold = re.fullmatch(r"delay\(([\d.]+)\)", texts[1]) if on else None
        if on is None or hold is None or texts[2] != f"dOut[{on.group(1)}] = false":
            return None
        return [Pulse(int(on.group(1)), float(hold.group(1)), self.lines[i][1])], i + 3

    def _shift(self, text: str) -> bool:
        """`trShiftN.x = l_v * d` (or `= 0`) inside the loop of l_v: the shift's offset along x."""
        m = re.fullmatch(r"(\w+)\.([xyz]) = (?:(\w+) \* (-?[\d.]+)|0)", text)
        if m is None or (m.group(3) is not None and m.group(3) not in self.counters):
            return False
        offsets = self.shifts.setdefault(m.group(1), {})
        if m.group(3) is None:
            offsets.pop(m.group(2), None)
        else:
            offsets[m.group(2)] = f"{self.counters[m.group(3)]} * {m.group(4)}"
        return True

    def _statement(self, lines: list[tuple[str, Where]], i: int) -> tuple[list[Stmt], int]:
        text, where = lines[i]
        if text in ("waitEndMove()", "bStop = false") or self._shift(text):  # the queue's; the stop flag's start
            return [], i + 1
        if _PAYLOAD_REMARK.fullmatch(text):
            return [self.tally.keep(text, where, "a payload remark (`rmot import --cell` reads an attach or detach)")], i + 1
        found = self._loop(i) or self._if(i) or self._pulse(i)
        if found is not None:
            self.tally.imported += 1
            return found
        call = re.fullmatch(r"call (\w+)\(\)", text)
        inlined = self._inline_body(call.group(1)) if call else None
        if inlined is not None:
            self.tally.imported += 1
            return list(inlined), i + 1
        watch = re.fullmatch(r"(\w+) = watch\(dIn\[(\d+)\] == (true|false), ([\d.]+)\)", text)
        # if !bOk, popUpMsg, logMsg, stopMove, resetMotion, [bStop = true (in a routine),] return, endIf
        for size, tail in ((7, ["resetMotion()", "return", "endIf"]),
                           (8, ["resetMotion()", "bStop = true", "return", "endIf"])):
            block = [t for t, _ in lines[i + 1:i + 1 + size]]
            if watch and len(block) == size and block[0] == f"if !{watch.group(1)}" and block[4:] == tail:
                self.tally.imported += 1
                cond = Cond(int(watch.group(2)), watch.group(3) == "true")
                return [WaitIn(cond, float(watch.group(4)), where)], i + 1 + size
        stmt = self._simple(text, where)
        if stmt is None:
            return [self.tally.keep(text, where, "no rmot form")], i + 1
        self.tally.imported += 1
        return [stmt], i + 1

    def _inline_body(self, name: str) -> tuple[Stmt, ...] | None:
        """The body of program `name` read with this program's loop counters and shifts, when it
        (or a program it calls) composes a target with one of them (else None: it is called)."""
        source = self.programs.get(name.upper())
        shifted = [rf"compose\([^)]*,\s*{t}\)" for t in self.shifts]
        if source is None or not self.counters or not reaches(
                self.programs, name, lambda text: any(re.search(p, text) for p in shifted), r"call (\w+)\(\)"):
            return None
        callee = _App(source[0], source[1], self.data_files, self.programs)
        callee.counters, callee.shifts = self.counters, self.shifts
        callee.read()
        self.inlined.add(name.upper())
        self.inlined |= callee.inlined
        return sum((r.body for r in callee.routines), ())

    def _simple(self, text: str, where: Where) -> Stmt | None:
        m = _MOVE.fullmatch(text)
        if m:
            return self._move(m.group(1), [a.strip() for a in m.group(2).split(",")], where)
        m = re.fullmatch(r"dOut\[(\d+)\] = (true|false)", text)
        if m:
            return SetOut(int(m.group(1)), 1.0 if m.group(2) == "true" else 0.0, where)
        m = re.fullmatch(r"aioSet\(aOut\[(\d+)\], (-?[\d.]+)\)|aOut\[(\d+)\] = (-?[\d.]+)", text)
        if m:
            return SetOut(int(m.group(1) or m.group(3)), float(m.group(2) or m.group(4)), where, analog=True)
        m = re.fullmatch(r"delay\(([\d.]+)\)", text)
        if m:
            return Wait(float(m.group(1)), where)
        m = re.fullmatch(r"wait\(dIn\[(\d+)\] == (true|false)\)", text)
        if m:
            return WaitIn(Cond(int(m.group(1)), m.group(2) == "true"), None, where)
        m = re.fullmatch(r"call (\w+)\(\)", text)
        return Call(m.group(1), (), where) if m else None

    def _move(self, func: str, args: list[str], where: Where) -> Move | None:
        kind = {"movej": "joint", "movel": "linear", "movec": "circular"}[func]
        joined = ",".join(args)
        shifts = [m.group(3) for m in re.finditer(r"compose\((\w+\[\d+\]),\s*(\w+),\s*(\w+)\)", joined)]
        args = split_top(re.sub(r"compose\((\w+\[\d+\]),\s*\w+,\s*\w+\)", r"\1", joined))
        if any(t not in self.shifts for t in shifts) or len(set(shifts)) > 1:
            return None
        refs = [re.fullmatch(_REF, a) for a in args]
        named = [a if r else f"{a}[0]" for a, r in zip(args, refs)]
        if len(args) != (4 if kind == "circular" else 3):
            return None
        points = [self.targets.get(p) for p in named[:-2]]
        tool = self.tools.get(named[-2])
        desc = self.values.get(named[-1].split("[")[0], {}).get(int(named[-1].split("[")[1][:-1]))
        if any(p is None for p in points) or tool is None or desc is None or desc[0] != "mdesc":
            return None
        target = points[-1]
        assert target is not None
        ref = re.fullmatch(_REF, named[-3])
        assert ref is not None  # a declared target's reference
        father = self.values[ref.group(1)][int(ref.group(2))][1].get("fatherId", "world[0]")
        frame = "base" if father == "world[0]" or target.pose is None else self.frames.get(father)
        if frame is None:
            return None
        m = desc[1]
        blend = m.get("blend", "off")
        zone = number(m.get("leave", "")) if blend != "off" else None
        speed = number(m.get("tmax", "")) if kind != "joint" else None
        pct = number(m.get("vel", "")) if kind == "joint" else None
        accel = number(m.get("accel", "")) if kind == "joint" and m.get("accel") == m.get("decel") else None
        if (blend != "off" and zone is None) or (kind != "joint" and speed is None) or \
                (kind == "joint" and m.get("accel") != m.get("decel")):
            return None
        offsets = self.shifts[shifts[0]] if shifts else {}
        terms = ", ".join(f"{a}={mm(e)}" for a, e in sorted(offsets.items()))

        def moved(n: str) -> str:
            return f"shift({n}, {terms})" if terms else n

        return Move(kind, moved(target.name), target.name, where,
                    via=moved(points[0].name) if kind == "circular" else None,  # type: ignore[union-attr]
                    speed=speed, joint_pct=pct if pct is not None and pct != 100.0 else None, zone=zone,
                    tool=tool.name, frame=frame if isinstance(frame, str) else frame.name,
                    config=target.config if kind == "joint" else None, pose=target.pose, joints=target.joints,
                    joint_accel=accel if accel is not None and accel != 100.0 else None)


def read_val3(path: str, text: str, data: list[tuple[str, str]],
              programs: dict[str, tuple[str, str]] | None = None) -> _App:
    """Read a VAL3 project (`.pjx`, its programs read from the files it names) or one `.pgx`
    with the `.dtx` data `data` gives; raises readers.common.ImportError_ (E510) when it is
    not VAL3."""
    app = _App(path, text, data, programs)
    app.read()
    return app

