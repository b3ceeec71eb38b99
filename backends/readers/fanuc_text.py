"""Fanuc TP instruction forms beyond one signal: a WAIT on several inputs, and the words of a
German-language pendant.

`WAIT (!DI[33] AND !DI[34])`, `WAIT (DI[1] OR (DI[2] AND !DI[3]))`, `WAIT DI[1]=ON AND
DI[2]=OFF` (R-30iB Operator's Manual, wait instruction with a condition; mixed logic, `!` is
NOT): read as rmot's and/or/not condition where every parenthesised level joins its terms with
one operator — a level mixing AND and OR, a flag, register, timer or output stays native (its
priority, or what it reads, is not an input rmot can wait for). A German-language controller
writes the same instructions in its words (`A[15]=AN`, `WARTE (E[9])`: A Ausgang = DO, E
Eingang = DI, AN/AUS = ON/OFF, WARTE = WAIT; the pendant backups of VASC's body shop, German
program headers `KOMMENTAR`, `WKZ_NUM`): read as the English ones.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from bisect import bisect_left

from rmot.backends.fanuc_tp_text import COMMENT_MAX
from rmot.backends.readers.common import number, reaches
from rmot.backends.readers.model import Cond, Conds, GroupIn, Where
from rmot.lang import ir

__all__ = ["selected_by_call", "position_values", "wait_condition", "output_expression", "timed_wait", "group_test", "motion_options",
           "kept_option", "path_points", "tp_speed", "tp_pose", "tp_branch", "CALLERS", "caller_selection",
           "position_blocks", "label_of", "names_label"]

_TOKEN = re.compile(r"\s*(?:(!?)(DI|DO)\[(\d+)(?::[^\]]*)?\](?:\s*=\s*(ON|OFF))?|(\()|(\))|(AND|OR)\b)")

_Parsed = tuple["Cond | Conds", int] | None


# a TP comparison and the one that holds exactly when it does not (B-83284EN, IF / WAIT with a
# register or I/O: `=`, `<>`, `<`, `>`, `<=`, `>=`)
_TP_COMPARE = {"=": ("==", "!="), "<>": ("!=", "=="), "<": ("<", ">="), ">": (">", "<="), "<=": ("<=", ">"),
               ">=": (">=", "<")}


def group_test(text: str, negate: bool = False) -> Conds | None:
    """`GI[n(:comment)] op v` (a group input compared with a whole number) as rmot's `gin[n] op v`
    (its negation with `negate`: an `IF .. ,JMP` skips its arm when the test holds); None otherwise."""
    m = re.fullmatch(r"GI\[(\d+)(?::[^\]]*)?\]\s*(<>|<=|>=|=|<|>)\s*(\d+)", text.strip())
    if m is None:
        return None
    return Conds("logic", (GroupIn(int(m.group(1))),), f"{{0}} {_TP_COMPARE[m.group(2)][negate]} {int(m.group(3))}")


def wait_condition(text: str) -> Cond | Conds | None:
    """The input condition of `WAIT cond`, or None where it reads anything else or mixes AND and
    OR on one level (a German pendant's words are read in English: fanuc_german)."""
    m = re.fullmatch(r"WAIT\s*(.+?)\s*", text)
    if m is None:
        return None
    if m.group(1).startswith("GI["):
        return group_test(m.group(1))
    tokens: list[re.Match[str]] = []
    rest = m.group(1)
    while rest.strip():
        t = _TOKEN.match(rest)
        if t is None:
            return None
        tokens.append(t)
        rest = rest[t.end():]
    parsed = _level(tokens, 0)
    return parsed[0] if parsed is not None and parsed[1] == len(tokens) else None


def _level(tokens: list[re.Match[str]], i: int) -> _Parsed:
    parts: list[Cond | Conds] = []
    op: str | None = None
    while True:
        parsed = _term(tokens, i)
        if parsed is None:
            return None
        parts.append(parsed[0])
        i = parsed[1]
        if i < len(tokens) and tokens[i].group(7):
            if op not in (None, tokens[i].group(7)):
                return None  # AND and OR on one level: which binds first is not read
            op, i = tokens[i].group(7), i + 1
            continue
        return (parts[0] if op is None else Conds(op.lower(), tuple(parts))), i


def _term(tokens: list[re.Match[str]], i: int) -> _Parsed:
    if i >= len(tokens):
        return None
    t = tokens[i]
    if t.group(5):
        inner = _level(tokens, i + 1)
        if inner is None or inner[1] >= len(tokens) or not tokens[inner[1]].group(6):
            return None
        return inner[0], inner[1] + 1
    if t.group(3) is None:
        return None
    on = (t.group(4) or "ON") == "ON"
    return Cond(int(t.group(3)), on != bool(t.group(1)), t.group(2) == "DO"), i + 1  # DO[n]: the output's state


def timed_wait(text_at: Callable[[int], str], i: int, end: int) -> tuple[Cond, int] | None:
    """The backend's wait with a timeout at line `i` (`text_at` gives each instruction's text):
    `WAIT DI[n]=ON TIMEOUT,LBL[a]`, `JMP LBL[b]`, `LBL[a]`, `ABORT`, `LBL[b]` (comments between
    them allowed) as (the input's condition, the index after `LBL[b]`); None otherwise."""
    m = re.fullmatch(r"WAIT DI\[(\d+)(?::[^\]]*)?\]\s*=\s*(ON|OFF) TIMEOUT,LBL\[(\d+)\]", text_at(i))
    texts = [t for t in (text_at(k) for k in range(i + 1, min(i + 7, end))) if not t.startswith("!")] if m else []
    jmp = re.fullmatch(r"JMP LBL\[(\d+)\]", texts[0]) if texts else None
    if m is None or not (jmp and len(texts) >= 4 and texts[1] == f"LBL[{m.group(3)}]" and texts[2] == "ABORT"
                         and texts[3] == f"LBL[{jmp.group(1)}]"):
        return None
    end_label = next(k for k in range(i + 1, end) if text_at(k) == f"LBL[{jmp.group(1)}]")
    return Cond(int(m.group(1)), m.group(2) == "ON"), end_label + 1


def output_expression(text: str) -> tuple[int, str] | None:
    """`DO[n]=(cond)` (B-83284EN, mixed logic: the output takes the expression's value once, as
    the line runs) as (n, the condition, parenthesised); None for any other line and for
    `DO[n]=(ON)`."""
    m = re.fullmatch(r"DO\[(\d+)(?::[^\]]*)?\]\s*=\s*(\(.+\))", text)
    if m is None or re.fullmatch(r"\(\s*(?:ON|OFF)\s*\)", m.group(2)):
        return None
    return int(m.group(1)), m.group(2)


# Motion options (R-30iB Operator's Manual, "Motion option instructions"): the path is the
# move's with or without them; kept native after the move (W517). ACCn and Offset,PR[k] are read.
_KEPT_OPTION = re.compile(r"(?i)(PTH|COORD|(?:TB|TA|DB)\s+[\d.]+\s*(?:sec|mm)\s*,\s*.+$"
                          r"|Arc\s+(?:Start|End)\s*\[[^\]]*\]|Weave\s*(?:\w+\s*)?\[[^\]]*\]|Weave\s+End)")


def kept_option(text: str) -> str:
    """The line a motion option not read keeps after its move: Arc and Weave instructions, which
    TP also writes on their own line, as they are; anything else (PTH, COORD, which axes.py reads
    with its move where it can, an action TB/TA/DB times: `TB .10sec,P-SPS`, the point logic below
    it) as TP comments of at most 32 characters, since a motion option cannot stand on its own line."""
    if re.match(r"(?i)(?:Arc|Weave)\b", text):
        return text
    return "\n".join(f"!{text[k:k + COMMENT_MAX]} ;" for k in range(0, len(text), COMMENT_MAX))


def motion_options(rest: str) -> tuple[int | None, tuple[int, bool] | None, list[str]] | None:
    """(ACCn, the offset register with whether it is a tool offset (`Offset,PR[k]`,
    `Tool_Offset,PR[k]`), options kept native) of a motion line's options, or None where one has
    no reading (the whole move is kept native; so is a move with two offsets)."""
    acc: int | None = None
    offset: tuple[int, bool] | None = None
    kept: list[str] = []
    rest = rest.strip().lstrip(":").strip()
    while rest:
        m = re.match(r"(?i)ACC\s*(\d+)\b", rest)
        o = None if m else re.match(r"(?i)(Tool_)?Offset,\s*PR\[(\d+)(?::[^\]]*)?\]", rest)
        k = None if m or o else _KEPT_OPTION.match(rest)
        if m:
            acc = int(m.group(1))
        elif o and offset is None:
            offset = (int(o.group(2)), o.group(1) is not None)
        elif o:
            return None
        elif k:
            kept.append(re.sub(r"\s+", " ", k.group(0).strip()))
        else:
            return None
        rest = rest[(m or o or k).end():].strip().lstrip(":").strip()  # type: ignore[union-attr]
    return acc, offset, kept


def path_points(text: str) -> list[int]:
    """The points of a linear or circular motion line (`L P[n] ..`, `C P[a] : P[b] ..`)."""
    return [int(n) for n in re.findall(r"P\[(\d+)", text)] if re.match(r"(?i)[LC]\s", text) else []


def tp_speed(kind: str, text: str) -> tuple[float | None, float | None, float | None] | None:
    """(TCP mm/s, joint %, fixed time s) of a TP speed."""
    m = re.fullmatch(r"([\d.]+)(%|mm/sec|cm/min|inch/min|sec|msec)", text)
    if m is None or number(m.group(1)) is None:
        return None
    value = float(m.group(1))
    if m.group(2) in ("sec", "msec"):
        return (None, None, value / 1000 if m.group(2) == "msec" else value)
    if m.group(2) in ("cm/min", "inch/min"):  # the TP feedrate units (R-30iB manual, motion speed)
        value *= (10.0 if m.group(2) == "cm/min" else 25.4) / 60.0
        return (value, None, None) if kind != "joint" else None
    if (m.group(2) == "%") != (kind == "joint"):
        return None
    return (value, None, None) if m.group(2) == "mm/sec" else (None, value, None)


def tp_pose(v: list[float] | tuple[float, ...]) -> ir.Pose:
    """A TP X Y Z (mm) W P R (deg) as a pose (R = Rz(R)·Ry(P)·Rx(W))."""
    pose = ir.Pose.from_xyz_rpy(v[0] / 1000, v[1] / 1000, v[2] / 1000, *(math.radians(a) for a in v[3:]))
    return ir.Pose(pose.position, tuple(0.0 if abs(q) < 1e-12 else q for q in pose.quaternion))  # type: ignore[arg-type]  # cos(90 deg) noise


def tp_branch(text: str) -> ir.Config | None:
    m = re.match(r"\s*([FN])\s*([UD])\s*([TB])", text.upper())
    if m is None:
        return None
    return ir.Config(ir.Shoulder.FRONT if m.group(3) == "T" else ir.Shoulder.BACK,
                     ir.Elbow.UP if m.group(2) == "U" else ir.Elbow.DOWN,
                     ir.Wrist.FLIP if m.group(1) == "N" else ir.Wrist.NOFLIP)


# a UTOOL_NUM or UFRAME_NUM the program has not selected: its caller's selection holds
CALLERS = 1 << 30


def selected_by_call(programs: dict[str, tuple[str, str]], text: str) -> list[str]:
    """The selections (UTOOL, UFRAME) a line's `CALL PROG` may change: PROG, or a program it
    calls, of the job's files selects one (`UTOOL_NUM=2`), and the selection is the controller's,
    so it holds after the call returns (B-83284EN, UTOOL_NUM / UFRAME_NUM)."""
    called = re.search(r"\bCALL\s+(\w+)", text)

    def selects(kind: str) -> Callable[[str], bool]:
        return lambda program: re.search(rf"\b{kind}_NUM\s*=", program) is not None

    return [] if called is None else [kind for kind in ("UTOOL", "UFRAME")
                                      if reaches(programs, called.group(1), selects(kind), r"CALL\s+(\w+)")]


def caller_selection(state: dict[str, int], taught: list[dict[str, int] | None],
                     inherited: dict[str, int]) -> dict[str, int] | str:
    """The UFRAME and UTOOL numbers a move runs with: the program's selection, or where it has
    made none (CALLERS) the numbers its positions record (`UF : 1, UT : 2`, those selected when
    the position was taught: B-83284EN, position data), which the caller must have selected; one
    caller's selection holds until the program selects, so a move before it whose positions record
    other numbers than `inherited` (the earlier moves') is the reason it is not known, as is a
    position that records none or a move whose positions differ."""
    out = dict(state)
    for kind, short in (("UFRAME", "UF"), ("UTOOL", "UT")):
        if out[kind] == CALLERS:
            what = "frame" if short == "UF" else "tool"
            numbers = {t.get(kind) if t else None for t in taught}
            if len(numbers) != 1 or None in numbers:
                return (f"the program selects no {kind}_NUM before this move and its position records no single "
                        f"{short} number: the {what} is the caller's, known only at run time")
            n = numbers.pop()
            if kind in inherited and inherited[kind] != n:
                return (f"its position was taught in {short} {n}, but a move before it in this program was taught in "
                        f"{short} {inherited[kind]} with no {kind}_NUM between: which {what} the caller selected "
                        "is known only at run time")
            out[kind] = n  # type: ignore[assignment]
    return out


def position_blocks(text: str) -> list[tuple[int, str | None, str, int]]:
    """The /POS section's `P[n:"label"]{ .. };` blocks of a TP program: (n, label, body, line of
    its header); a block with no `};` before the next header (a damaged file) is left out. Linear
    in the text: each block ends at the first `};` after its header, found among all of them in
    one pass (a lazy match from each header would rescan a damaged file's tail for every block)."""
    start = max(text.find("/POS"), 0)
    pos = text[start:]
    heads = list(re.finditer(r"P\[(\d+)(?::\"([^\"\n]*)\")?\][ \t\r\n]*\{", pos))
    ends = [m.start() for m in re.finditer(r"\};", pos)]
    out: list[tuple[int, str | None, str, int]] = []
    line, at = text.count("\n", 0, start) + 1, 0
    for k, m in enumerate(heads):
        line, at = line + pos.count("\n", at, m.start()), m.start()
        i = bisect_left(ends, m.end())
        stop = heads[k + 1].start() if k + 1 < len(heads) else len(pos)
        if i < len(ends) and ends[i] <= stop:
            out.append((int(m.group(1)), m.group(2), pos[m.end():ends[i]], line))
    return out


def position_values(body: str, point: str, where: Where, fail: Callable[[str, Where], Exception]) -> dict[str, float]:
    """The arm's coordinates of `point`'s /POS block body, `X = 500.000 mm` .. `J6 = 0.000 deg`
    (upper case names); none where a value is `********`, the pendant's mark of a position never
    taught. Any other value that is not a finite number as written (`X = .4.965`, a damaged file)
    raises `fail(message, where)` rather than be read as a nearby number."""
    values: dict[str, float] = {}
    for name, text in re.findall(r"\b([XYZWPR]|J\d)\s*=\s*([^\s,;]+)", body):
        value = number(text)
        if re.fullmatch(r"\*+", text):
            return {}
        if value is None:
            raise fail(f"{point}'s `{name} = {text}` must be a number", where)
        values[name.upper()] = value
    return values


def label_of(text: str) -> str | None:
    """The label number of a `LBL[n]` line (with its comment, `LBL[2:skip]`)."""
    m = re.fullmatch(r"LBL\[(\d+)(?::[^\]]*)?\]\s*;?", text.strip())
    return m.group(1) if m else None


def names_label(text: str, label: str) -> bool:
    """Whether a TP instruction is label LBL[label] or jumps to it (`JMP LBL[n]`, `TIMEOUT,LBL[n]`)."""
    return re.search(rf"\bLBL\[{label}(?::[^\]]*)?\]", text) is not None
