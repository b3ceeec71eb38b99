"""RAPID data the program changes, and what a move may read of it.

A datum assigned anywhere in the files given, whole (`tool1 := [..]`), by a component
(`tool1.tframe.trans.z := 100`) or by an element (`p{2} := ..`), is not constant: its
declaration is not its value at a move. For a PERS the declaration shows the value the last run
left (ABB RAPID Overview, 3HAC050947-001, "Data types": "Persistent data objects": "the value is
kept when the program is restarted"), so a routine starts with every part the files assign
unknown; the parts no statement assigns keep the declared value.

`DataFlow` follows the tool, work-object, speed and zone data that straight-line code sets with
a literal (RoboDK writes `rdkTool.tframe := [[..],[..]];`, `rdkWObj.uframe := ..`, `rdkSpeed :=
[200,500,5000,1000];` before its moves): a move reads such a datum where every part is known.
What may set it in between forgets it:
  * a block: its assignments are forgotten on entry (a loop's second turn, an arm not taken)
    and after it;
  * a label (a jump may arrive from where the datum differed), a call of a routine of the files
    (it may assign it): every datum is back at its start-of-routine state.
A routine of no file given is taken not to assign them, as the reader takes every datum no file
assigns to be constant.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Mapping
from itertools import product
from typing import TypeVar

from rmot.backends.rapid_text import cfx_of
from rmot.backends.readers import axes_slots
from rmot.backends.readers.model import FrameData, ToolData, Where
from rmot.backends.readers.rapid_text import Statement, literal
from rmot.lang import ir

__all__ = ["DataFlow", "LATE_CALL", "VELSET", "VELSET_AT_START", "ACCSET", "assigned_at", "branch_of", "changed_data", "frame_of",
           "in_document", "joints_of", "pose_of", "tool_of"]

D = TypeVar("D", ToolData, FrameData)

# The components of the data a move names (RAPID Instructions, Functions and Data types,
# 3HAC050917-001: tooldata, wobjdata, speeddata, zonedata, pose, pos, orient, loaddata), in
# their order in the aggregate; a component with its own structure names its type.
_PARTS: dict[str, tuple[tuple[str, str | None], ...]] = {
    "tooldata": (("robhold", None), ("tframe", "pose"), ("tload", "loaddata")),
    "wobjdata": (("robhold", None), ("ufprog", None), ("ufmec", None), ("uframe", "pose"), ("oframe", "pose")),
    "speeddata": (("v_tcp", None), ("v_ori", None), ("v_leax", None), ("v_reax", None)),
    "zonedata": tuple((n, None) for n in ("finep", "pzone_tcp", "pzone_ori", "pzone_eax", "zone_ori", "zone_leax",
                                         "zone_reax")),
    "pose": (("trans", "pos"), ("rot", "orient")),
    "pos": (("x", None), ("y", None), ("z", None)),
    "orient": (("q1", None), ("q2", None), ("q3", None), ("q4", None)),
    "loaddata": (("mass", None), ("cog", "pos"), ("aom", "orient"), ("ix", None), ("iy", None), ("iz", None)),
}
FOLLOWED = ("tooldata", "wobjdata", "speeddata", "zonedata")
_ASSIGN = re.compile(r"(?i)^(\w+)((?:\s*\.\s*\w+|\s*\{[^}]*\})*)\s*:=\s*(.*)$")
_OPENS = re.compile(r"(?i)^(IF\b.*\bTHEN|WHILE\b.*\bDO|FOR\b.*\bDO|TEST\b.*)$")
_CLOSES = ("ENDIF", "ENDWHILE", "ENDFOR", "ENDTEST")
LATE_CALL = r"%|CallByVar\b"  # a call of a routine by a name computed at run time (RAPID Overview, "late binding")
# VelSet Override, Max (RAPID Instructions, VelSet: the programmed speed of every later move scaled
# by Override %, its TCP speed at most Max mm/s; 100, 5000 when a program starts from the
# beginning), followed as a datum of its own: VelSet writes it as an assignment would
VELSET = "<VELSET>"
VELSET_AT_START = [100.0, 5000.0]
# AccSet Acc, Ramp (RAPID Instructions, AccSet: acceleration and its ramp in % of normal, for
# every later move; 100, 100 when a program starts from the beginning), followed the same way
ACCSET = "<ACCSET>"
ACCSET_AT_START = [100.0, 100.0]
# Program displacement (RAPID Instructions, PDispOn / PDispSet / PDispAdd: every later robtarget
# is moved by a frame, until PDispOff; off when a program starts from the beginning): followed
# as a datum that is known only where it is off
PDISP = "<PDISP>"
_MODAL = {"VELSET": VELSET, "ACCSET": ACCSET, "PDISPON": PDISP, "PDISPSET": PDISP, "PDISPADD": PDISP, "PDISPOFF": PDISP}
_OFF = [0.0]


class _Unknown:
    """A part whose value the text does not fix here."""

    def __repr__(self) -> str:
        return "?"


UNKNOWN = _Unknown()


def _path(type_: str, parts: str) -> tuple[int, ...] | None:
    """The index path of `.tframe.trans.z` in a `type_` aggregate; () for the whole; None
    where a part is an element (`{..}`) or not a component rmot knows."""
    path: list[int] = []
    for name in re.findall(r"\.\s*(\w+)|\{", parts):
        names = [n for n, _ in _PARTS.get(type_, ())]
        if not name or name.lower() not in names:
            return None
        k = names.index(name.lower())
        path.append(k)
        type_ = _PARTS[type_][k][1] or ""
    return tuple(path)


def changed_data(stmts: list[Statement]) -> dict[str, Statement]:
    """Upper-case name -> the first statement assigning it (whole, a component or an element)."""
    out: dict[str, Statement] = {}
    for st in stmts:
        m = _ASSIGN.match(st.text)
        if m:
            out.setdefault(m.group(1).upper(), st)
    return out


def assigned_at(name: str, first: Statement, path: str) -> str:
    """Where the datum `name` is first set: "`p` is assigned at line 4 (`p := Offs(..)`)" (the
    file named where it is not `path`)."""
    place = f"line {first.where.line}" if first.where.path == path else f"{first.where.path}:{first.where.line}"
    return f"`{name}` is assigned at {place} (`{first.text[:50]}`)"


def _known(value: object) -> bool:
    return value is not UNKNOWN and (not isinstance(value, list) or all(_known(v) for v in value))


def _with(value: object, path: tuple[int, ...], part: object) -> object:
    """`value` with the part at `path` replaced (UNKNOWN where the path does not fit it)."""
    if not path:
        return part
    if not isinstance(value, list) or path[0] >= len(value):
        return UNKNOWN
    return [_with(v, path[1:], part) if k == path[0] else v for k, v in enumerate(value)]


def pose_of(lit: object) -> ir.Pose | None:
    """[[x,y,z],[q1,q2,q3,q4], ...] in mm -> ir.Pose (metres), None if malformed."""
    if not (isinstance(lit, list) and len(lit) >= 2 and isinstance(lit[0], list) and isinstance(lit[1], list)):
        return None
    xyz, q = lit[0], lit[1]
    if len(xyz) != 3 or len(q) != 4 or not all(isinstance(v, float) for v in xyz + q):
        return None
    qf = [float(v) for v in q]
    norm = sum(v * v for v in qf) ** 0.5
    if norm < 1e-9:
        return None
    w, x, y, z = (v / norm for v in qf)
    if w < 0:
        w, x, y, z = -w, -x, -y, -z
    px, py, pz = (float(v) / 1000 for v in xyz)
    return ir.Pose((px, py, pz), (w, x, y, z))


def branch_of(lit: object) -> ir.Config | None:
    """The branch of a robtarget literal's confdata [cf1, cf4, cf6, cfx] (its cfx), named or
    inline (`MoveJ [[x,y,z],[q..],[0,-1,-1,0],[..]], ..` as RobotStudio and hand-written
    modules write it): the branch whose cfx (the backend's `cfx_of`) it is; None outside 0..7."""
    conf = lit[2] if isinstance(lit, list) and len(lit) > 2 and isinstance(lit[2], list) else None
    cfx = conf[3] if conf and len(conf) == 4 and isinstance(conf[3], float) else None
    return next((ir.Config(s, e, w) for s, e, w in product(ir.Shoulder, ir.Elbow, ir.Wrist)
                 if cfx is not None and cfx_of(ir.Config(s, e, w)) == int(cfx)), None)


def joints_of(lit: object) -> tuple[float, ...] | None:
    """The six joint values (deg) of a jointtarget `[[robax], [extax]]` written in place
    (`MoveAbsJ [[..],[..]], ..`) that rmot reads (axes_slots.robax_read), else None."""
    robax = lit[0] if isinstance(lit, list) and len(lit) == 2 and isinstance(lit[0], list) else []
    joints = tuple(v for v in robax if isinstance(v, float))
    return joints if len(joints) == len(robax) == 6 and axes_slots.robax_read([*lit]) else None  # type: ignore[misc]


def in_document(datum: D, data: dict[str, D]) -> D:
    """`datum`, among `data` (the module's tools or frames, which the document lists) also where
    straight-line code set it: under its name and `#`, which no RAPID name has, so that no move
    finds it by the datum's name."""
    if data.get(datum.name.upper()) is not datum:
        data.setdefault(f"{datum.name.upper()}#", datum)
    return datum


def tool_of(name: str, lit: object, where: Where) -> ToolData | None:
    """A tooldata literal held by the robot (robhold TRUE) as a tool; None otherwise (a
    stationary tool has no rmot form)."""
    if not (isinstance(lit, list) and len(lit) >= 3 and lit[0] == "TRUE"):
        return None
    tcp, load = pose_of(lit[1]), lit[2]
    if tcp is None or not (isinstance(load, list) and load and isinstance(load[0], float)):
        return None
    return ToolData(name, tcp, load[0], where)


def frame_of(name: str, lit: object, where: Where) -> FrameData | None:
    """A wobjdata literal not moved by the robot or a mechanical unit (robhold FALSE) as its
    object frame in the base (uframe · oframe); None otherwise."""
    if not (isinstance(lit, list) and len(lit) >= 5 and lit[0] == "FALSE"):
        return None
    uframe, oframe = pose_of(lit[3]), pose_of(lit[4])
    return FrameData(name, uframe * oframe, where) if uframe is not None and oframe is not None else None


class DataFlow:
    """The followed data's values where the statement being read runs (see the module's text)."""

    def __init__(self, stmts: list[Statement], declared: Mapping[str, tuple[str, str, object]], taken: set[str]) -> None:
        self.stmts = stmts
        self.declared = {**declared, VELSET: ("velset", "VelSet", VELSET_AT_START),  # upper name -> (type, name, literal)
                         ACCSET: ("accset", "AccSet", ACCSET_AT_START), PDISP: ("pdisp", "PDispOff", _OFF)}
        self.taken = taken  # names the module declares: a renamed value's name avoids them
        self.where: dict[str, list[tuple[int, tuple[int, ...] | None]]] = {}
        self.trapped: set[str] = set()
        self.bodies: dict[str, int] = {}  # routine (upper) -> the index of its first statement
        self.at_calls: dict[str, list[dict[str, object]]] = {}  # routine -> the values at each call read
        self.foreign: set[str] = set()  # words another module of the task writes as statements (calls)
        self.late = any(re.match(rf"(?i)^({LATE_CALL})", st.text) for st in stmts)
        self.mentions = Counter(w for st in stmts for w in set(re.findall(r"\w+", st.text.upper())))  # word -> statements
        self.leaving: dict[str, dict[str, object]] = {}  # routine -> what it leaves known (left_by)
        for k, st in enumerate(stmts):
            m = _ASSIGN.match(st.text)
            decl = declared.get(m.group(1).upper()) if m else None
            if m and decl:
                self.where.setdefault(m.group(1).upper(), []).append((k, _path(decl[0], m.group(2))))
            if st.word in _MODAL:
                self.where.setdefault(_MODAL[st.word], []).append((k, ()))
        self.sets = self._routine_sets()
        self.start = {name: self._at_start(name) for name in self.where}
        self.now = dict(self.start)
        self.made: dict[tuple[str, str], ToolData | FrameData] = {}  # (name, value) -> the datum it became

    def _at_start(self, name: str) -> object:
        """The declared value with every part the files assign unknown."""
        value = self.declared[name][2]
        for _, path in self.where[name]:
            value = _with(value, path, UNKNOWN) if path is not None else UNKNOWN
        return value

    def _routine_sets(self) -> dict[str, set[str]]:
        """Routine (upper) -> the followed data it or a routine it calls may assign; a TRAP's
        (it runs on an interrupt, between any two statements) are never known (`trapped`)."""
        own: dict[str, set[str]] = {}
        calls: dict[str, set[str]] = {}
        routine, kind = "", ""
        assigning = {k: name for name, places in self.where.items() for k, _ in places}  # statement -> its datum
        for k, st in enumerate(self.stmts):
            m = re.match(r"(?i)^(?:LOCAL\s+)?(PROC|FUNC|TRAP)\s+(?:\w+\s+)??(\w+)\s*(?:\(|$)", st.text)
            if m:
                routine, kind = m.group(2).upper(), m.group(1).upper()
                own.setdefault(routine, set()), calls.setdefault(routine, set())
                self.bodies[routine] = k + 1
            elif routine:
                own[routine] |= {assigning[k]} if k in assigning else set()
                calls[routine] |= {st.word} | ({"*"} if re.match(rf"(?i)^({LATE_CALL})", st.text) else set())
                if kind == "TRAP":
                    self.trapped |= own[routine]
        out: dict[str, set[str]] = {}
        for name in own:  # the routines it reaches through calls (a late-binding call: any)
            seen, todo = {name}, [name]
            while todo:
                for callee in calls.get(todo.pop(), set()):
                    reach = set(own) if callee == "*" else {callee} & set(own)
                    todo += list(reach - seen)
                    seen |= reach
            out[name] = set().union(*(own[r] for r in seen))
        return out

    def called(self, routine: str, record: bool = True) -> None:
        """After a call of a routine of the files: what it may assign is what its straight-line
        end leaves (`left_by`), or back at its start state. The values at the call are kept for
        the routine's own start (`enter_routine`)."""
        if record:
            self.at_calls.setdefault(routine.upper(), []).append(dict(self.now))
        left = self.left_by(routine.upper())
        for name in self.sets.get(routine.upper(), set(self.where)):
            self.now[name] = left.get(name, self.start[name])

    def left_by(self, routine: str) -> dict[str, object]:
        """The followed data a routine leaves known whatever its caller held: those its own
        outermost statements set last, read as the routine's body is (blocks forget what they
        assign, calls what their routine leaves unknown); none where it has a label, a jump or
        a return (it may end elsewhere) or calls itself."""
        if routine in self.leaving or routine not in self.bodies:
            return self.leaving.get(routine, {})
        self.leaving[routine] = {}  # a recursive call: nothing known
        saved, k = dict(self.now), self.bodies[routine]
        self.now = dict(self.start)
        while k < len(self.stmts) and self.stmts[k].word != "ENDPROC":
            st = self.stmts[k]
            if re.match(rf"(?i)^(\w+\s*:$|{LATE_CALL}|GOTO\b|RETURN\b|EXIT\b|RAISE\b|ERROR\b)", st.text):
                self.now, k = dict(self.start), len(self.stmts)
                break
            if _OPENS.match(st.text):
                self.skip(k)
                k = self.end_of(k + 1)
            elif st.word in self.bodies:
                self.called(st.word, record=False)
            else:
                self.assign(st)
            k += 1
        left = {n: v for n, v in self.now.items() if n in self.sets.get(routine, set()) and _known(v)}
        self.leaving[routine], self.now = left, saved
        return left

    def enter_routine(self, routine: str, main: bool) -> None:
        """A routine's start: a datum every call of it gives the same known value has it, where
        every mention of the routine in the module is a call read before it (a caller later in
        the file, a call another module, an interrupt or a late-binding call may make leaves
        its start state); the routine that runs first starts from the start state."""
        self.now, name = dict(self.start), routine.upper()
        self.now.update({n: v for n, v in ((VELSET, VELSET_AT_START), (ACCSET, ACCSET_AT_START), (PDISP, _OFF))
                         if main and n in self.where})
        seen = self.at_calls.get(name, [])
        if main or name in self.foreign or not seen or len(seen) != self.mentions[name] - 1 or self.late:  # - its PROC line
            return
        for datum in self.where:
            values = [state.get(datum, UNKNOWN) for state in seen]
            if all(_known(v) and v == values[0] for v in values):
                self.now[datum] = values[0]

    def restart(self) -> None:
        """A label (a jump may arrive from where the data differed) or a late-binding call."""
        self.now = dict(self.start)

    def enter(self, i: int, forget: bool = True) -> dict[str, object]:
        """Entering the block whose statements start at `i`: its own assignments are forgotten
        (not a routine's body: it runs once); the state before it is returned for `leave`."""
        before = dict(self.now)
        if forget:
            self._forget(i, self.end_of(i))
        return before

    def leave(self, before: dict[str, object], i: int, j: int) -> None:
        """After the block `i`..`j`: the state before it, less what the block assigns."""
        self.now = before
        self._forget(i, j)

    def skip(self, i: int) -> None:
        """After the block opened at `i`, kept native whole: what it assigns is not known."""
        self._forget(i, self.end_of(i + 1) + 1)

    def _forget(self, i: int, j: int) -> None:
        for name, places in self.where.items():
            if any(i <= k < j for k, _ in places):
                self.now[name] = self.start[name]

    def end_of(self, i: int) -> int:
        """The index of the statement closing the block that starts at `i`."""
        depth = 0
        for k in range(i, len(self.stmts)):
            st = self.stmts[k]
            if st.word in _CLOSES or st.word == "ENDPROC":
                if depth == 0:
                    return k
                depth -= 1
            elif _OPENS.match(st.text):
                depth += 1
        return len(self.stmts)

    def assign(self, st: Statement) -> bool | None:
        """Follow `st` when it assigns a followed datum: True where a literal sets a part of a
        value known but for it (the statement is read), False where the datum becomes unknown
        (kept native), None where `st` assigns no followed datum."""
        if _MODAL.get(st.word) == PDISP:  # followed, and the instruction stays in the program
            self.now[PDISP] = _OFF if st.word == "PDISPOFF" else UNKNOWN
            return None
        if st.word in ("VELSET", "ACCSET"):
            m = re.fullmatch(r"(?i)\w+\s+([^,]+),\s*(.+)", st.text)
            values = [literal(v) for v in m.groups()] if m else []
            known = len(values) == 2 and all(isinstance(v, float) and v > 0 for v in values)
            if st.word == "ACCSET":  # rmot's form: the joint share, Acc 20..100 % at the normal ramp
                known = known and values[1] == 100.0 and 20.0 <= values[0] <= 100.0  # type: ignore[operator]
            self.now[_MODAL[st.word]] = values if known else UNKNOWN
            return known
        m = _ASSIGN.match(st.text)
        decl = self.declared.get(m.group(1).upper()) if m else None
        if m is None or decl is None or decl[0] not in FOLLOWED:
            return None
        name, path, part = m.group(1).upper(), _path(decl[0], m.group(2)), literal(m.group(3))
        base = self.now.get(name, UNKNOWN)
        if path is None or not isinstance(part, (list, float)) or (path and not isinstance(base, list)):  # a name: its value
            self.now[name] = UNKNOWN if path is None or not path else _with(base, path, UNKNOWN)
            return False
        self.now[name] = _with(base, path, part)
        return True

    def value(self, name: str) -> object | None:
        """The followed datum's value here, None where a part of it is not known."""
        value = self.now.get(name.upper(), UNKNOWN)
        return value if _known(value) and name.upper() not in self.trapped else None

    def speed(self, kind: str, speed: list[str], speeds: Mapping[str, float]) -> tuple[float | None, float | None, float] | None:
        r"""(TCP mm/s, duration s, joint share %) of a move's speed argument (`v200`, a datum of
        `speeds` or followed here, `[200,500,5000,1000]`, `\T:=2`, `v1000\V:=50`: \V replaces
        the datum's TCP speed, RAPID Instructions, MoveL "[\V]"), with the VelSet here: its
        TCP speed at most Max and by Override %, a joint move's share the Override (its TCP
        Max has no joint form: W512 says it); None where a part is not known, or a time under
        a VelSet that changes speeds (what it makes of \T is not read)."""
        given: dict[str, float] = {}  # \T:=s, the move's duration; \V:=mm/s, its TCP speed in place of the datum's
        for switch in speed[1:]:
            m = re.fullmatch(r"(?i)(T|V)\s*:=\s*([0-9]+(?:\.[0-9]*)?)", switch)
            if m is None or m.group(1).upper() in given or float(m.group(2)) <= 0:
                return None
            given[m.group(1).upper()] = float(m.group(2))
        duration = given.get("T")
        v_tcp = given.get("V") or (5000.0 if speed[0].upper() == "VMAX" else speeds.get(speed[0].upper()) or self.v_tcp(speed[0]))
        override = self.value(VELSET) if VELSET in self.where else VELSET_AT_START
        if v_tcp is None or not isinstance(override, list) or (duration is not None and override != VELSET_AT_START):
            return None
        return min(v_tcp * override[0] / 100.0, override[1]), duration, override[0]

    def accel(self) -> tuple[bool, float | None]:
        """(whether the AccSet here is known and has rmot's form, Ramp 100 and Acc 20..100 %;
        the joint acceleration share it gives the moves, None for 100 %)."""
        value = self.value(ACCSET) if ACCSET in self.where else ACCSET_AT_START
        if not isinstance(value, list) or value[1] != 100.0 or not 20.0 <= value[0] <= 100.0:
            return False, None
        return True, None if value[0] == 100.0 else value[0]

    def velset_at(self) -> int | None:
        """The index of the first VelSet statement the files hold, None where none does."""
        return self.where[VELSET][0][0] if VELSET in self.where else None

    def displaced(self) -> int | None:
        """Where a program displacement may be on here: the index of the first statement that
        switches one on; None where it is off."""
        on = [k for k, _ in self.where.get(PDISP, []) if self.stmts[k].word != "PDISPOFF"]
        return on[0] if on and self.value(PDISP) != _OFF else None

    def v_tcp(self, text: str) -> float | None:
        """The TCP speed (mm/s) of a speeddata literal written in place (`[200,500,5000,1000]`) or
        of the datum `text` where it is known here; None otherwise."""
        value = literal(text) if text.strip().startswith("[") else self.value(text)
        speed = value[0] if isinstance(value, list) and value else None
        return speed if isinstance(speed, float) and speed > 0 else None

    def zone_of(self, zone: list[str], zones: Mapping[str, float | None]) -> float | None | str:
        r"""A move's zone argument in mm (`z10`, a datum of `zones` or followed here, `z10\Z:=3`:
        \Z replaces the zone's TCP corner path, RAPID Instructions, MoveL "[\Z]"); None a stop
        point; "bad" where it is not known here (or \Z on a stop point, which stays one)."""
        base = zones[zone[0].upper()] if zone[0].upper() in zones else self.zone(zone[0])
        z = re.fullmatch(r"(?i)Z\s*:=\s*([0-9]+(?:\.[0-9]*)?)", zone[1]) if len(zone) == 2 else None
        return base if len(zone) == 1 else float(z.group(1)) if z and isinstance(base, float) else "bad"

    def zone(self, text: str) -> float | None | str:
        """A zonedata literal's or known datum's radius in mm (None: `finep` TRUE, a stop
        point); "bad" where it is not known here."""
        lit = literal(text) if text.strip().startswith("[") else self.value(text)
        if isinstance(lit, list) and len(lit) > 1 and isinstance(lit[1], float) and lit[1] >= 0 and lit[0] in ("TRUE", "FALSE"):
            return None if lit[0] == "TRUE" else lit[1]
        return "bad"

    def tool(self, name: str, where: Where) -> ToolData | None:
        """The tool `name` holds here (`datum`)."""
        found = self._datum(name, where, "tooldata")
        return found if isinstance(found, ToolData) else None

    def frame(self, name: str, where: Where) -> FrameData | None:
        """The work object `name` holds here (`datum`)."""
        found = self._datum(name, where, "wobjdata")
        return found if isinstance(found, FrameData) else None

    def _datum(self, name: str, where: Where, type_: str) -> ToolData | FrameData | None:
        """The tool or work object `name` holds here, named `name` for its first value and
        `name_2`, `name_3`, .. for the others."""
        decl, value = self.declared.get(name.upper()), self.value(name)
        if decl is None or value is None or decl[0] != type_:
            return None
        key = (name.upper(), repr(value))
        if key not in self.made:
            count = sum(1 for n, _ in self.made if n == key[0])
            label = decl[1] if count == 0 else next((f"{decl[1]}_{k}" for k in range(count + 1, count + 1000)
                                                    if f"{decl[1]}_{k}".upper() not in self.taken), None)
            made = None if label is None else tool_of(label, value, where) if decl[0] == "tooldata" else \
                frame_of(label, value, where)
            if made is None:
                return None
            self.made[key] = made
        return self.made[key]
