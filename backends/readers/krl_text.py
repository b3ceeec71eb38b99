"""KRL source as located lines, `.dat` declarations and `{..}` aggregates.

KRL (KUKA KSS 8.x Operating and Programming Instructions for System Integrators, "KRL
syntax"): one statement per line, `;` starts a comment, `&ACCESS`/`&REL`/`&PARAM` header
lines, `DEF name( ) .. END` routines in the `.src`, `DEFDAT name .. ENDDAT` data in the
`.dat`, `DECL [GLOBAL] TYPE name=value`; names and keywords are case-insensitive. Inline forms
are `;FOLD header;%{PE}...` .. `;ENDFOLD` around the statements they stand for.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from itertools import product

from rmot.backends.krl_text import status_of
from rmot.backends.readers.common import number, split_top
from rmot.backends.readers.model import Cond, Conds, Native, Signal, Where
from rmot.lang import ir
from rmot.lang.record import record

__all__ = ["Line", "lines", "aggregate", "Decl", "declarations", "krl_pose", "fold_end", "in_cond", "has_test", "MotionState",
           "branch_of_status", "DEFAULT_VEL_CP"]


@record(slots=True)
class Line:
    text: str  # without its comment; a fold line keeps its header in `fold`
    where: Where
    fold: str | None = None  # the header of a `;FOLD` line
    endfold: bool = False

    @property
    def word(self) -> str:
        m = re.match(r"\s*(\$?[A-Za-z_][\w.]*)", self.text)
        return m.group(1).upper() if m else ""


def _strip_comment(line: str) -> str:
    quote = False
    for i, ch in enumerate(line):
        if ch in "\"'":
            quote = not quote
        elif ch == ";" and not quote:
            return line[:i]
    return line


def lines(path: str, text: str) -> list[Line]:
    out: list[Line] = []
    for n, raw in enumerate(text.split("\n"), 1):
        stripped = raw.strip()
        col = len(raw) - len(raw.lstrip()) + 1
        fold = re.match(r"(?i);\s*FOLD\b\s*(.*)", stripped)
        if fold:
            out.append(Line("", Where(path, n, col), fold=fold.group(1).split(";%")[0].strip()))
            continue
        if re.match(r"(?i);\s*ENDFOLD\b", stripped):
            out.append(Line("", Where(path, n, col), endfold=True))
            continue
        code = _strip_comment(raw).strip()
        if code and not code.startswith("&"):
            out.append(Line(code, Where(path, n, col)))
    return out


Aggregate = dict[str, "float | str | Aggregate"]


def aggregate(text: str, depth: int = 0) -> Aggregate | None:
    """`{X 1.0,Y 2,A 0.0, CM {X 0}}` (an optional `TYPE:` prefix) as a dict, keys upper case;
    None beyond 8 levels (LOAD nests 2 deep)."""
    text = text.strip()
    if depth >= 8:
        return None
    m = re.fullmatch(r"(?s)\{\s*(?:\w+\s*:)?(.*)\}", text)
    if m is None:
        return None
    out: Aggregate = {}
    for item in split_top(m.group(1)):
        if not item:
            continue
        km = re.fullmatch(r"(?s)([A-Za-z_]\w*(?:\[\])?)\s+(.*)", item)
        if km is None:
            return None
        key, value = km.group(1).upper(), km.group(2).strip()
        if value.startswith("{"):
            sub = aggregate(value, depth + 1)
            if sub is None:
                return None
            out[key] = sub
        else:
            num = number(value)
            out[key] = num if num is not None else value
    return out


@record(slots=True)
class Decl:
    type: str  # upper case
    name: str
    value: str | None
    where: Where


def declarations(found: list[Line]) -> list[Decl]:
    """Every `[DECL] [GLOBAL] [CONST] TYPE name[=value]` line of a data list, and every element of an
    array, `DECL TYPE name[n]` then `name[i]=value` (KSS 8.x, arrays in data lists: the pendant
    writes each initialised element on its own line), as `name[i]`."""
    out = []
    arrays: dict[str, str] = {}
    for ln in found:
        m = re.fullmatch(r"(?is)(?:DECL\s+)?(?:GLOBAL\s+)?(?:CONST\s+)?([A-Za-z_]\w*)\s+([A-Za-z_]\w*)\s*(?:=\s*(.*))?", ln.text)
        if m and m.group(1).upper() not in ("DEFDAT", "ENDDAT", "EXT", "EXTFCT", "SIGNAL", "STRUC", "ENUM"):
            out.append(Decl(m.group(1).upper(), m.group(2), m.group(3), ln.where))
            continue
        m = re.fullmatch(r"(?i)(?:DECL\s+)?(?:GLOBAL\s+)?([A-Za-z_]\w*)\s+([A-Za-z_]\w*)\s*\[\s*\d+\s*\]", ln.text)
        if m:
            arrays[m.group(2).upper()] = m.group(1).upper()
            continue
        m = re.fullmatch(r"(?is)([A-Za-z_]\w*)\s*\[\s*(\d+)\s*\]\s*=\s*(.*)", ln.text)
        if m and m.group(1).upper() in arrays:
            out.append(Decl(arrays[m.group(1).upper()], f"{m.group(1)}[{int(m.group(2))}]", m.group(3), ln.where))
    return out


def krl_pose(agg: Mapping[str, object]) -> ir.Pose | None:
    """X Y Z (mm) A B C (deg) of an aggregate as an ir.Pose, None if a component is missing."""
    values = [agg.get(k) for k in ("X", "Y", "Z", "A", "B", "C")]
    floats = [v for v in values if isinstance(v, float)]
    if len(floats) != 6:
        return None
    x, y, z, a, b, c = floats
    pose = ir.Pose.from_xyz_rpy(x / 1000, y / 1000, z / 1000, math.radians(c), math.radians(b), math.radians(a))
    # cos(90 deg) is 6e-17 in floating point: a component below 1e-12 (far below the 1e-4 deg
    # KRL prints) is zero, so C 180 reads as the exact half turn rmot wrote
    q = tuple(0.0 if abs(v) < 1e-12 else v for v in pose.quaternion)
    return ir.Pose(pose.position, q)  # type: ignore[arg-type]


def fold_end(found: list[Line], i: int) -> int:
    depth = 0
    for j in range(i, len(found)):
        depth += found[j].fold is not None
        depth -= found[j].endfold
        if depth == 0:
            return j
    return len(found) - 1


Named = Callable[[str], "Signal | None"]
Param = Callable[[str], "tuple[str, str] | None"]  # NAME -> (rmot name, "number" | "bool") of a parameter
_OPS = {"==": "==", "<>": "!=", "<": "<", "<=": "<=", ">": ">", ">=": ">="}


def in_cond(text: str, named: Named | None = None, param: Param | None = None) -> Cond | Conds | None:
    """`$IN[n]`, `$IN[n]==TRUE|FALSE`, `NOT`, `AND`, `OR` and parentheses (KSS 8.x operator
    priority: NOT before AND before OR); a name where `named` gives the input it stands for (a
    SIGNAL), alone or `==TRUE|FALSE`; a routine's parameter where `param` knows it (`k == 3`,
    `k <> 2`, a BOOL alone): a test the compiler decides; None for anything else (EXOR,
    variables, other comparisons)."""
    tokens = re.findall(r"(?i)\$IN\[\d+\]\s*(?:==\s*(?:TRUE|FALSE)\b)?|\(|\)|\bNOT\b|\bAND\b|\bOR\b"
                        r"|[A-Za-z_]\w*\s*(?:(?:==|<>|<=|>=|<|>)\s*(?:TRUE\b|FALSE\b|[-+]?\d+(?:\.\d+)?))?|\S+", text)
    parsed = _or(tokens, 0, named or (lambda name: None), param or (lambda name: None))
    return parsed[0] if parsed is not None and parsed[1] == len(tokens) else None


_Parsed = tuple[Cond | Conds, int] | None


def _or(tokens: list[str], i: int, named: Named, param: Param, op: str = "OR") -> _Parsed:
    parts: list[Cond | Conds] = []
    while True:
        parsed = _or(tokens, i, named, param, "AND") if op == "OR" else _unary(tokens, i, named, param)
        if parsed is None:
            return None
        parts.append(parsed[0])
        i = parsed[1]
        if i >= len(tokens) or tokens[i].upper() != op:
            return (parts[0] if len(parts) == 1 else Conds(op.lower(), tuple(parts))), i
        i += 1


def _unary(tokens: list[str], i: int, named: Named, param: Param) -> _Parsed:
    if i >= len(tokens):
        return None
    word = tokens[i].upper()
    if word == "NOT":
        inner = _unary(tokens, i + 1, named, param)
        if inner is None:
            return None
        c = inner[0]
        return (c.negated() if isinstance(c, Cond) else Conds("not", (c,))), inner[1]
    if word == "(":
        inner = _or(tokens, i + 1, named, param)
        return (inner[0], inner[1] + 1) if inner and inner[1] < len(tokens) and tokens[inner[1]] == ")" else None
    m = re.fullmatch(r"(?i)\$IN\[(\d+)\]\s*(?:==\s*(TRUE|FALSE))?", tokens[i])
    name = re.fullmatch(r"(?i)([A-Za-z_]\w*)\s*(?:(==|<>|<=|>=|<|>)\s*(\S+))?", tokens[i]) if m is None else None
    signal: Signal | None = int(m.group(1)) if m else None
    level = ((m.group(2) if m else None) or "TRUE").upper()
    test = _param_test(param(name.group(1)), name.group(2), name.group(3)) if name else None
    if name is not None and test is None and name.group(2) in (None, "==") and \
            name.group(1).upper() not in ("TRUE", "FALSE", "NOT", "AND", "OR", "EXOR"):
        signal, m, level = named(name.group(1)), name, (name.group(3) or "TRUE").upper()
    m = name if test is not None else m
    if m is None or (test is None and (signal is None or level not in ("TRUE", "FALSE"))):
        return None
    # `==` binds after AND/OR (KSS 8.x operator priority: NOT 1, AND 4, EXOR 5, OR 6, comparisons 7):
    # `$IN[1] AND $IN[2]==FALSE` compares the AND; a comparison is read only alone in its parentheses
    start = i
    while start > 0 and tokens[start - 1].upper() == "NOT":
        start -= 1
    alone = (start == 0 or tokens[start - 1] == "(") and (i + 1 == len(tokens) or tokens[i + 1] == ")")
    if m.group(2) and not alone:
        return None
    if test is not None:
        return test, i + 1
    return Cond(signal, level == "TRUE"), i + 1  # type: ignore[arg-type]


def has_test(c: object) -> bool:
    """Whether a condition holds a test the compiler decides (a parameter's)."""
    return isinstance(c, Conds) and (c.op == "expr" or any(has_test(p) for p in c.parts))


def _param_test(found: tuple[str, str] | None, op: str | None, value: str | None) -> Conds | None:
    """A routine parameter's test in rmot: `k == 3` (a number compared with a number), `flag` /
    `not flag` (a BOOL alone or compared with TRUE/FALSE)."""
    if found is None:
        return None
    name, type_ = found
    literal = number(value) if value is not None else None
    if type_ == "number" and op is not None and literal is not None:
        return Conds("expr", (), f"{name} {_OPS[op]} {literal:g}")
    level = None if op not in (None, "==", "<>") else (value or "TRUE").upper()
    if type_ != "bool" or level not in ("TRUE", "FALSE"):
        return None
    return Conds("expr", (), name if (level == "TRUE") == (op != "<>") else f"not {name}")


DEFAULT_VEL_CP = 2000.0  # mm/s: BAS(#INITMOV) sets $VEL.CP to DEF_VEL_CP = 2 m/s (KSS 8.x, BAS.SRC)


def branch_of_status(s: int) -> ir.Config:
    """The branch whose Status (the backend's `status_of`) has the low 3 bits of `s`."""
    for sh, el, wr in product(ir.Shoulder, ir.Elbow, ir.Wrist):
        branch = ir.Config(sh, el, wr)
        if status_of(branch) == s & 7:
            return branch
    raise AssertionError("status_of covers 0..7")


_UNSET = object()  # a setting's value while a line that may set it is read (MotionState.setting)


class MotionState:
    """The modal motion variables a plain KRL motion reads."""

    def __init__(self, inherited: bool = False) -> None:
        # a routine other than the module's own starts with its caller's settings ($VEL is global,
        # KSS 8.x System Integrators): None, so its motions take the proc caller's in rmot too
        self.vel_cp: float | None = None if inherited else DEFAULT_VEL_CP
        self.vel_ptp: float | None = None if inherited else 100.0
        self.acc_cp: float | None = None  # mm/s^2; None = 2 m/s^2, rmot's default
        self.acc_ptp: float | None = None  # %; None = 100 %
        self.cdis: float | None = None
        self.cptp: float | None = None
        self.tool: str | None = None
        self.frame: str | None = None
        # a setting a block changed (an arm may not run, a loop may not turn) or a line set to a value
        # not read: where, and the value it had then; a motion reading it while it has that value is native
        self.unsure: dict[str, tuple[str, object]] = {}
        self.written: dict[str, object] = {}
        self.wrote()

    def wrote(self) -> None:
        """A motion was read: the compiled program writes its settings before it (what a native
        motion after it finds on the controller, restate); at a routine's start, its assumed values."""
        self.written = {n: getattr(self, n) for n in self.SETTINGS}

    SETTINGS = {"vel_cp": "$VEL.CP", "vel_ptp": "$VEL_AXIS", "acc_cp": "$ACC.CP", "acc_ptp": "$ACC_AXIS",
                "cdis": "$APO.CDIS", "cptp": "$APO.CPTP", "tool": "$TOOL", "frame": "$BASE"}

    def setting(self, read: Callable[[], bool]) -> bool:
        """`read()` a line that may set motion settings: one it sets is no longer unsure (even to
        the value it had after the block); what `read` marks unsure holds the value before it."""
        held = {n: getattr(self, n) for n in self.unsure}
        for n in held:
            setattr(self, n, _UNSET)
        found = read()
        for n, v in held.items():
            if getattr(self, n) is _UNSET:
                setattr(self, n, v)
                self.unsure[n] = (self.unsure[n][0], v) if self.unsure[n][1] is _UNSET else self.unsure[n]
            else:
                del self.unsure[n]
        return found

    def restate(self, text: str, where: Where) -> list[Native]:
        """A motion kept native reads $VEL.CP, $ACC.CP and its blend distance from the controller,
        where the compiled program writes them only before rmot's own motions: the values known
        here and set by a line since the last motion read, restated as KRL lines before it, so a
        setting line the import read (and so left out) still reaches it."""
        joint = re.match(r"(?i)S?PTP\b", text) is not None
        known = {n: getattr(self, n) for n in (("cptp", "cdis") if joint else ("vel_cp", "acc_cp", "cptp", "cdis"))
                 if getattr(self, n) is not None and n not in self.unsure and getattr(self, n) != self.written[n]}
        lines = {"vel_cp": "$VEL.CP={:.4f}", "acc_cp": "$ACC.CP={:.4f}", "cdis": "$APO.CDIS={:.3f}", "cptp": "$APO.CPTP={:g}"}
        scale = {"vel_cp": 1000.0, "acc_cp": 1000.0}  # mm/s, mm/s^2 here; m/s, m/s^2 in KRL
        return [Native("krl", lines[n].format(v / scale.get(n, 1.0)), where) for n, v in known.items()]

    def set_by_call(self, name: str, where: Where) -> None:
        """After a call of a routine that sets motion settings ($VEL, $ACC, $APO, $TOOL, $BASE are
        global: they keep its values after it returns): each is known only at run time, so the
        motions reading one stay native until a line sets it again."""
        for n in self.SETTINGS:
            self.unsure[n] = (f"by `{name}(..)` at line {where.line}", getattr(self, n))
        self.forget_written()

    def forget_written(self) -> None:
        """A routine ran that writes settings of its own: what the controller holds is not what
        the last motion read here wrote (restate then restates every value known)."""
        self.written = {n: _UNSET for n in self.SETTINGS}

    def at_call(self) -> dict[str, float | None]:
        """The speeds and accelerations in force here, which a called routine's motions run with
        where they set none (rmot's proc takes them from the call)."""
        return {"speed": self.vel_cp, "joint_pct": self.vel_ptp, "accel": self.acc_cp, "joint_accel": self.acc_ptp}

    def unsure_of(self, joint: bool, text: str) -> str | None:
        """Why a PTP (`joint`) or CP motion `text` here cannot be read: a setting it reads (the
        blend distances only where it blends) that is unsure; None where there is none."""
        blends = {"cdis": re.search(r"(?i)\bC_(DIS|SPL)\b", text), "cptp": re.search(r"(?i)\bC_PTP\b", text)}
        reads = [n for n in (("vel_ptp", "acc_ptp") if joint else ("vel_cp", "acc_cp")) + ("cptp", "cdis", "tool", "frame")
                 if blends.get(n, True)]
        for name in reads:
            where, value = self.unsure.get(name, ("", None))
            if where and getattr(self, name) == value:
                return f"its {self.SETTINGS[name]} is set {where}: which value holds here is known only at run time"
        return None
