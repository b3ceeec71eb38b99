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

from rmot.backends.readers.common import Tally, number
from rmot.backends.readers.model import (
    Call, Cond, FrameData, Move, Routine, SetOut, Stmt, Target, ToolData, Wait, WaitIn, Where,
)
from rmot.compiler import ir

__all__ = ["read_val3"]

_NS = re.compile(r"\{[^}]*\}")
_MOVE = re.compile(r"(movej|movel|movec)\((.*)\)")
_REF = r"(\w+)\[(\d+)\]"


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
    def __init__(self, path: str, text: str, data: list[tuple[str, str]]) -> None:
        self.tally = Tally(path, text, "val3")
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
        lines = [(t, w) for t, w in lines if t and not t.startswith("//") and t not in ("begin", "end")]
        if name == "stop" and not lines:
            return  # the application's empty stop handler (every VAL3 application has one)
        body: list[Stmt] = []
        i = 0
        while i < len(lines):
            stmts, i = self._statement(lines, i)
            body += stmts
        self.routines.append(Routine(name, (), tuple(body), Where(self.path, first)))

    def _statement(self, lines: list[tuple[str, Where]], i: int) -> tuple[list[Stmt], int]:
        text, where = lines[i]
        if text == "waitEndMove()":
            return [], i + 1
        watch = re.fullmatch(r"(\w+) = watch\(dIn\[(\d+)\] == (true|false), ([\d.]+)\)", text)
        block = [t for t, _ in lines[i + 1:i + 8]]  # if !bOk, popUpMsg, logMsg, stopMove, resetMotion, return, endIf
        if watch and len(block) == 7 and block[0] == f"if !{watch.group(1)}" and block[4:] == [
                "resetMotion()", "return", "endIf"]:
            self.tally.imported += 1
            return [WaitIn(Cond(int(watch.group(2)), watch.group(3) == "true"), float(watch.group(4)), where)], i + 8
        stmt = self._simple(text, where)
        if stmt is None:
            return [self.tally.keep(text, where, "no rmot form")], i + 1
        self.tally.imported += 1
        return [stmt], i + 1

    def _simple(self, text: str, where: Where) -> Stmt | None:
        m = _MOVE.fullmatch(text)
        if m:
            return self._move(m.group(1), [a.strip() for a in m.group(2).split(",")], where)
        m = re.fullmatch(r"dOut\[(\d+)\] = (true|false)", text)
        if m:
            return SetOut(int(m.group(1)), 1.0 if m.group(2) == "true" else 0.0, where)
        m = re.fullmatch(r"aOut\[(\d+)\] = (-?[\d.]+)", text)
        if m:
            return SetOut(int(m.group(1)), float(m.group(2)), where, analog=True)
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
        return Move(kind, target.name, target.name, where, via=points[0].name if kind == "circular" else None,  # type: ignore[union-attr]
                    speed=speed, joint_pct=pct if pct is not None and pct != 100.0 else None, zone=zone,
                    tool=tool.name, frame=frame if isinstance(frame, str) else frame.name,
                    config=target.config if kind == "joint" else None, pose=target.pose, joints=target.joints,
                    joint_accel=accel if accel is not None and accel != 100.0 else None)


def read_val3(path: str, text: str, data: list[tuple[str, str]]) -> _App:
    """Read a VAL3 project (`.pjx`, its programs read from the files it names) or one `.pgx`
    with the `.dtx` data `data` gives; raises readers.common.ImportError_ (E510) when it is
    not VAL3."""
    app = _App(path, text, data)
    app.read()
    return app

