"""Print a neutral Document as a .rmot program (and a cell stub for the data it declares).

Settings are written where they change: `tool` and `frame` before the first move that needs
them in each block (rmot settings do not leak out of a block, so every block starts from what
its parent had; a proc body starts unknown and sets both). Speeds, zones, configurations and
times are each move's own modifiers, exactly as the vendor wrote them on that move.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Callable
from dataclasses import replace

from rmot.backends.readers import codes
from rmot.backends.readers.common import native_line, rmot_name, same_pose
from rmot.backends.readers.model import (
    Call, Cond, Conds, Document, FileCount, For, Grip, If, Move, Native, Pulse, SetOut, Signal, Stmt, Stop, Wait, WaitIn,
    Where, While, leaves, walk,
)
from rmot.backends.readers.model import Assign, GroupIn, VarDecl, group_reads
from rmot.backends.readers.model import Sync
from rmot.backends.readers.rapid import num_text, pose_expr
from rmot.lang import ir
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["SignalMap", "resolve_signals", "program_text", "cell_stub", "stub_signals", "stub_warnings", "match_tools",
           "rename_warnings"]
__all__ += ["task_lines", "signal_uses", "kept_native", "Keep"]

INDENT = "  "


@record(slots=True)
class SignalMap:
    """Signal name (upper case) -> port, per kind, as the cell declares them."""

    outputs: tuple[tuple[str, int], ...] = ()
    inputs: tuple[tuple[str, int], ...] = ()
    analog: tuple[tuple[str, int], ...] = ()
    groups: tuple[tuple[str, int], ...] = ()  # group inputs gin[n]

    def port(self, kind: str, signal: Signal) -> int | None:
        if isinstance(signal, int):
            return signal
        table = dict(getattr(self, kind))
        if signal.upper() in table:
            return int(table[signal.upper()])
        prefix = {"outputs": "DO", "inputs": "DI", "analog": "AO", "groups": "GI"}[kind]
        m = re.fullmatch(prefix + r"_?(\d+)", signal.upper())  # rmot's own generic names (do1, di2)
        return int(m.group(1)) if m else None


def _signal_uses(s: Stmt) -> list[tuple[str, Signal]]:
    if isinstance(s, SetOut):
        return [("analog" if s.analog else "outputs", s.signal)]
    if isinstance(s, Pulse):
        return [("outputs", s.signal)]
    if isinstance(s, (WaitIn, If, While, VarDecl, Assign)):
        value = s.cond if isinstance(s, (WaitIn, If, While)) else s.init if isinstance(s, VarDecl) else s.value
        return [("outputs" if c.output else "inputs", c.signal) for c in leaves(value)] + [("groups", g.signal) for g in group_reads(value)]
    return []


signal_uses = _signal_uses  # (kind, signal) of each signal a statement sets or reads


# the vendors' numbered signals as a native line writes them (RAPID names its signals): Fanuc
# DI[n]/DO[n]/GI[n]/AO[n], KRL $IN[n]/$OUT[n]/$ANOUT[n], INFORM IN#(n)/OT#(n)/IG#(n)/AOUT AO#(n),
# URScript ..digital_in(n)/..digital_out(n)/..analog_out(n)
_NATIVE_PORTS = {
    "inputs": re.compile(r"(?i)(?:\bDI\[|\$IN\[|\bIN#\(|digital_in\()\s*(\d+)"),
    "outputs": re.compile(r"(?i)(?:\bDO\[|\$OUT\[|\bOT#\(|digital_out\()\s*(\d+)"),
    "groups": re.compile(r"(?i)(?:\bGI\[|\bIG#\()\s*(\d+)"),
    "analog": re.compile(r"(?i)(?:\bAO\[|\$ANOUT\[|\bAO#\(|analog_out\()\s*(\d+)"),
}


def stub_signals(doc: Document) -> SignalMap:
    """Ports for a cell stub: numbered signals keep their port; named ones take the free ports
    1, 2, ... of their kind in order of first use, skipping every port a native line names (compiled
    back, that line still uses the vendor's signal of that number)."""
    named: dict[str, dict[str, int]] = {"outputs": {}, "inputs": {}, "analog": {}, "groups": {}}
    used: dict[str, set[int]] = {k: set() for k in named}
    uses = [u for r in doc.routines for s in walk(r.body) for u in _signal_uses(s)]
    for kind, sig in uses:
        if isinstance(sig, int):
            used[kind].add(sig)
    natives = [s.text for r in doc.routines for s in walk(r.body) if isinstance(s, Native)]
    for kind, pattern in _NATIVE_PORTS.items():
        used[kind] |= {int(n) for text in natives for n in pattern.findall(text) if len(n) < 7}
    for kind, sig in uses:
        if isinstance(sig, str) and sig.upper() not in named[kind]:
            n = SignalMap().port(kind, sig) or 1
            while n in used[kind]:
                n += 1
            used[kind].add(n)
            named[kind][sig.upper()] = n
    return SignalMap(*(tuple(named[k].items()) for k in ("outputs", "inputs", "analog", "groups")))


def map_leaves(body: tuple[Stmt, ...], fn: Callable[[Stmt], Stmt]) -> tuple[Stmt, ...]:
    """`body` with `fn` applied to every instruction that is not a block, at every depth (a
    block whose condition `fn` replaces is replaced whole)."""
    out: list[Stmt] = []
    for s in body:
        mapped = fn(s)  # once: `fn` may record what it replaced
        if isinstance(s, If) and mapped is s:
            s = replace(s, then=map_leaves(s.then, fn), orelse=map_leaves(s.orelse, fn))
        elif isinstance(s, (While, For)) and mapped is s:
            s = replace(s, body=map_leaves(s.body, fn))
        elif isinstance(s, WaitIn) and s.orelse and mapped is s:
            s = replace(s, orelse=map_leaves(s.orelse, fn))
        else:
            s = mapped
        out.append(s)
    return tuple(out)


def _with_routines(doc: Document, fn: Callable[[Stmt], Stmt], **changes: object) -> Document:
    routines = tuple(replace(r, body=map_leaves(r.body, fn)) for r in doc.routines)
    return replace(doc, routines=routines, **changes)  # type: ignore[arg-type]


# why a statement is kept native: (the code, its message given the native text, the text where
# the source line is not known)
Keep = tuple[Code, Callable[[str], str], str]


def kept_native(doc: Document, why: Callable[[Stmt], Keep | None], span_of: Callable[[Where], Span]) -> Document:
    """`doc` with every statement `why` names kept native: the source lines it was read from as the
    vendor wrote them (a block with its body), a warning there, and its file's count moved from
    imported to native."""
    diags: list[Diagnostic] = []
    moved: Counter[str] = Counter()

    def keep(s: Stmt) -> Stmt:
        found = why(s)
        if found is None:
            return s
        code, message, fallback = found
        w = s.where
        span = span_of(w)
        last = max([w.line] + [x.where.line + 1 for x in walk((s,)) if x is not s])
        text = "\n".join(native_line(doc.vendor, span.file.line_text(n)) for n in range(w.line, last + 1))
        diags.append(Diagnostic(code, Severity.WARNING, message(text or fallback), span))
        moved[w.path] += 1
        return Native(doc.vendor, text or fallback, w)

    fixed = _with_routines(doc, keep)
    if not diags:
        return doc
    counts = tuple(FileCount(c.path, c.imported - moved[c.path], c.native + moved[c.path]) for c in doc.counts)
    return replace(fixed, counts=counts, diagnostics=doc.diagnostics + tuple(diags))


def resolve_signals(doc: Document, signals: SignalMap, span_of: Callable[[Where], Span]) -> Document:
    """Every named signal the cell does not declare: its instruction is kept native (W513)."""

    def undeclared(s: Stmt) -> Keep | None:
        missing = [sig for kind, sig in _signal_uses(s) if signals.port(kind, sig) is None]
        return None if not missing else (
            codes.SIGNAL_UNKNOWN, lambda _: f"signal `{missing[0]}` must be declared in the cell (it is not): kept native",
            f"signal {missing[0]}")

    return kept_native(doc, undeclared, span_of)


def rename_warnings(doc: Document, span_of: Callable[[Where], Span]) -> tuple[Diagnostic, ...]:
    """W514 at each declared name the program writes under another name (an rmot keyword)."""
    named = [(t.name, t.where) for t in doc.targets] + [(t.name, t.where) for t in doc.tools] + \
        [(f.name, f.where) for f in doc.frames] + [(r.name, r.where) for r in doc.routines]
    return tuple(Diagnostic(codes.NAME_RENAMED, Severity.WARNING, f"`{name}` {_why_renamed(name)}: written as `{rmot_name(name)}`",
                            span_of(where)) for name, where in named if rmot_name(name) != name)


def stub_warnings(doc: Document, span_of: Callable[[Where], Span]) -> tuple[Diagnostic, ...]:
    """W511 at the first use of each tool and frame the program uses but no file sets (the
    controller's own): the cell stub puts it at identity, which `rmot check` would verify."""
    found = [("tool", t.name, t.controller, t.where, "flange") for t in doc.tools if t.controller] + \
        [("frame", f.name, f.controller, f.where, "robot base") for f in doc.frames if f.controller]
    return tuple(Diagnostic(codes.DECLARATION_KEPT, Severity.WARNING, f"{kind} `{name}` is the controller's {what}, "
                            f"not set in the files given: the cell stub puts it at the {at} (give --cell with its data)",
                            span_of(where)) for kind, name, what, where, at in found)


def _why_renamed(name: str) -> str:
    """Why a vendor name is not its rmot name (common.rmot_name): an array element (`P[1]`: a
    target per element), a keyword, or characters an rmot name has not."""
    if re.fullmatch(r"\w+\s*\[[\s\d,]+\]", name):
        return "is an array element, and an rmot name has no index"
    if re.fullmatch(r"[A-Za-z_]\w*", name):
        return "must not be an rmot keyword in a .rmot program"
    return "is not an rmot name (a letter or `_`, then letters, digits and `_`)"


def match_tools(doc: Document, cell_tools: tuple[tuple[str, ir.Pose], ...]) -> Document:
    """A vendor that selects tools by TCP value only (URScript set_tcp): name each tool after the
    cell's tool with the same TCP, where there is one."""
    names = {}
    for t in doc.tools:
        match = next((name for name, tcp in cell_tools if same_pose(tcp, t.tcp)), None)
        if match is not None and t.name != match:
            names[t.name] = match
    if not names:
        return doc

    def fix(s: Stmt) -> Stmt:
        return replace(s, tool=names[s.tool]) if isinstance(s, (Move, Call)) and s.tool in names else s

    return _with_routines(doc, fix, tools=tuple(t for t in doc.tools if t.name not in names))


def _num(v: float) -> str:
    return num_text(v)


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


class _Printer:
    def __init__(self, doc: Document, signals: SignalMap) -> None:
        self.doc = doc
        self.signals = signals
        self.lines: list[str] = []
        self.defined = {r.name for r in doc.routines}
        self.spelt = {r.name.upper(): r.name for r in reversed(doc.routines)}  # a call's routine as defined

    def emit(self, depth: int, text: str) -> None:
        self.lines.append(INDENT * depth + text)

    def body(self, body: tuple[Stmt, ...], depth: int, state: dict[str, str | None]) -> None:
        state = dict(state)
        for s in body:
            self.stmt(s, depth, state)

    def stmt(self, s: Stmt, depth: int, state: dict[str, str | None]) -> None:
        if isinstance(s, Move):
            self.move(s, depth, state)
        elif isinstance(s, SetOut):
            port = self.signals.port("analog" if s.analog else "outputs", s.signal)
            value = _num(s.value) if s.analog else ("on" if s.value else "off")
            self.emit(depth, f"set {'aout' if s.analog else 'out'}[{port}] = {value}")
        elif isinstance(s, Pulse):
            self.emit(depth, f"pulse out[{self.signals.port('outputs', s.signal)}] for {_num(s.seconds)} s")
        elif isinstance(s, Wait):
            self.emit(depth, f"wait {_num(s.seconds)} s")
        elif isinstance(s, WaitIn):
            timeout = f" timeout {_num(s.timeout)} s" if s.timeout is not None else ""
            self.emit(depth, f"wait until {self.cond(s.cond)}{timeout}{' else {' if s.orelse else ''}")
            if s.orelse:
                self.body(s.orelse, depth + 1, state)
                self.emit(depth, "}")
        elif isinstance(s, VarDecl):
            self.emit(depth, f"var {s.name}: {s.type} = {self.cond(s.init)}")
        elif isinstance(s, Assign):
            self.emit(depth, f"{s.name} = {self.cond(s.value)}")
        elif isinstance(s, Native):
            for n, line in enumerate(s.text.split("\n")):
                self.emit(depth, f"native {s.vendor} {_quote(line)}   # {replace(s.where, line=s.where.line + n, col=1) if n else s.where}")
        elif isinstance(s, Stop):
            self.emit(depth, "stop")
        elif isinstance(s, Sync):
            self.emit(depth, f"sync {rmot_name(s.name)}")
        elif isinstance(s, Grip):
            self.emit(depth, f"{'attach' if s.take else 'detach'} {s.part}")
        elif isinstance(s, Call):  # as the routine is spelt where it is defined (KRL, TP: names in any case)
            name = s.name if s.name in self.defined else self.spelt.get(s.name.upper(), s.name)
            self.settings(s, depth, state)
            self.emit(depth, f"{rmot_name(name)}({', '.join(s.args)})")
        else:
            self.block(s, depth, state)

    def block(self, s: Stmt, depth: int, state: dict[str, str | None]) -> None:
        if isinstance(s, For):
            self.emit(depth, f"for {s.var} in {s.first} .. {s.stop} {{")
            self.body(s.body, depth + 1, state)
        elif isinstance(s, While):
            self.emit(depth, f"while {self.cond(s.cond)} {{")
            self.body(s.body, depth + 1, state)
        elif isinstance(s, If):
            self.emit(depth, f"if {self.cond(s.cond)} {{")
            self.body(s.then, depth + 1, state)
            if s.orelse:
                self.emit(depth, "} else {")
                self.body(s.orelse, depth + 1, state)
        self.emit(depth, "}")

    def cond(self, c: Cond | Conds | GroupIn) -> str:
        if isinstance(c, GroupIn):
            return f"gin[{self.signals.port('groups', c.signal)}]"
        if isinstance(c, Cond):
            kind, io = ("outputs", "out") if c.output else ("inputs", "in")
            return f"{io}[{self.signals.port(kind, c.signal)}] == {'on' if c.on else 'off'}"
        if c.op == "expr":
            return c.text
        if c.op == "logic":
            return c.text.format(*(self.cond(p) for p in c.parts))
        parts = [self.cond(p) if isinstance(p, Cond) else f"({self.cond(p)})" for p in c.parts]
        return f"not {parts[0]}" if c.op == "not" else f" {c.op} ".join(parts)

    def settings(self, m: Move | Call, depth: int, state: dict[str, str | None]) -> None:
        """`tool` and `frame` where the move needs others; before a call, also the speeds and
        accelerations in force there, which the proc's moves that set none take."""
        for key in ("tool", "frame"):
            value: str | None = getattr(m, key, None)
            value = value if value is None or value in ("flange", "base", "world") else rmot_name(value)
            if value is not None and state.get(key) != value:
                self.emit(depth, f"{key} {value}")
                state[key] = value
        modal = {"speed": "mm/s", "joint_pct": "%", "accel": "mm/s^2", "joint_accel": "%"} if isinstance(m, Call) else {}
        for key, unit in modal.items():
            number = getattr(m, key)
            setting = f"{'accel' if 'accel' in key else 'speed'} {_num(number)} {unit}" if number is not None else None
            if setting is not None and state.get(key) != setting:
                self.emit(depth, setting)
                state[key] = setting

    def move(self, m: Move, depth: int, state: dict[str, str | None]) -> None:
        self.settings(m, depth, state)
        if m.axes_only:
            self.emit(depth, " ".join(f"move axes {name} to {value}" for name, value in m.ext)
                      + (f" time {_num(m.time)} s" if m.time is not None else ""))
            return
        head = f"move circular via {m.via} to {m.target}" if m.kind == "circular" else f"move {m.kind} {m.target}"
        mods = [f"ext({', '.join(f'{name}={value}' for name, value in m.ext)})"] if m.ext else []
        if m.config is not None and (m.config.shoulder or m.config.elbow or m.config.wrist or m.config.turns):
            mods.append(f"config({m.config})")
        if m.speed is not None:
            mods.append(f"speed {_num(m.speed)} mm/s")
        if m.joint_pct is not None:
            mods.append(f"speed {_num(m.joint_pct)} %")
        if m.accel is not None:
            mods.append(f"accel {_num(m.accel)} mm/s^2")
        if m.joint_accel is not None:
            mods.append(f"accel {_num(m.joint_accel)} %")
        if m.time is not None:
            mods.append(f"time {_num(m.time)} s")
        mods.append("zone fine" if m.zone is None or m.zone == 0 else f"zone {_num(m.zone)} mm")
        self.emit(depth, " ".join([head, *mods]))


def _target_line(t_name: str, pose: ir.Pose | None, joints: tuple[float, ...] | None) -> str:
    if joints is not None:
        return f"target {t_name} = joints({', '.join(_num(j) for j in joints)}) deg"
    return f"target {t_name} = {pose_expr(pose)}"  # type: ignore[arg-type]


def program_text(doc: Document, signals: SignalMap, robot: str, use_cell: str | None) -> str:
    """The .rmot program of `doc` on `robot` (a robot of the cell)."""
    p = _Printer(doc, signals)
    files = ", ".join(c.path for c in doc.counts)
    p.emit(0, f"# imported by `rmot import` from {files} ({doc.vendor})")
    for c in doc.counts:
        p.emit(0, f"#   {c.path}: {c.imported} instructions imported, {c.native} kept native")
    if use_cell is not None:
        p.emit(0, f"use cell {_quote(use_cell)}")
    driven = f" with {', '.join(doc.mechanisms)}" if doc.mechanisms else ""
    p.emit(0, f"program {rmot_name(doc.name)} on {robot}{driven} {{")
    _declarations_and_body(p, doc, 1)
    p.emit(0, "}")
    if doc.kept:
        p.emit(0, "")
        p.emit(0, "# kept from the vendor files (declarations and routines with no rmot form):")
        for k in doc.kept:
            p.emit(0, f"#   {k.where}: {k.text}")
    return "\n".join(p.lines) + "\n"


def _declarations_and_body(p: _Printer, doc: Document, depth: int) -> None:
    """`doc`'s consts, targets and procs, then its main routine's body, at `depth`."""
    for name, value in doc.consts:
        p.emit(depth, f"const {name} = {_num(value)}")
    for t in doc.targets:
        p.emit(depth, _target_line(rmot_name(t.name), t.pose, t.joints))
    main = None
    for r in doc.routines:
        if r.name == doc.main:
            main = r
            continue
        params = ", ".join(f"{rmot_name(n)}: {t}" for n, t in r.params)
        p.emit(depth, f"proc {rmot_name(r.name)}({params}) {{")
        p.body(r.body, depth + 1, {})
        p.emit(depth, "}")
    if main is not None:
        p.body(main.body, depth, {})


def task_lines(doc: Document, signals: SignalMap, robot: str) -> list[str]:
    """`task ROBOT { ... }` of a multi-robot program: `doc`'s declarations and main body, indented
    one level inside the program."""
    p = _Printer(doc, signals)
    p.emit(1, f"task {robot} {{")
    _declarations_and_body(p, doc, 2)
    p.emit(1, "}")
    return p.lines


def cell_stub(doc: Document, signals: SignalMap, model: str, robot: str = "r1") -> str:
    """A cell with `model` at the world origin (world = the robot base, where vendors write
    work objects) and the tools, frames and I/O names the vendor files declare."""
    lines = [f"# cell stub written by `rmot import` for {doc.name} ({doc.vendor})",
             f"cell {rmot_name(doc.name)}_cell {{", f"  robot {robot} = {model}"]
    for t in doc.tools:
        lines.append(f"  tool {rmot_name(t.name)} = none tcp {pose_expr(t.tcp)} mass {_num(t.mass)} kg"
                     + (f" number {t.number}" if t.number is not None else "") + f" on {robot}"
                     + (f"  # the controller's {t.controller}: not in the files, put at the flange" if t.controller else ""))
    for f in doc.frames:
        lines.append(f"  frame {rmot_name(f.name)} = {pose_expr(f.pose)}" + (f" number {f.number}" if f.number is not None else "")
                     + (f"  # the controller's {f.controller}: not in the files, put at the base" if f.controller else ""))
    for kind, word in (("outputs", "out"), ("inputs", "in"), ("analog", "aout"), ("groups", "gin")):
        for name, port in getattr(signals, kind):
            lines.append(f"  io {word}[{port}] = {_quote(name.lower())} on {robot}")
    lines.append("}")
    return "\n".join(lines) + "\n"
