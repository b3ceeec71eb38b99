"""Several robots' programs read back into one program with a task per robot.

`rmot import --task r1=A.mod --task r2=B.mod --cell CELL` reads each task's files as a
one-robot import does (its vendor reader, the cell's signals and tools of that robot); this
module then finds the barriers rmot's backends write for `sync NAME` and reads them back:

* RAPID (MultiMove): `WaitSyncTask NAME, LIST;` with `VAR syncident NAME;` and `PERS tasks
  LIST{n}:=[["T_ROB1"],...];` (Technical reference manual RAPID Instructions, WaitSyncTask;
  RAPID data types, syncident and tasks). The k-th robot given is task T_ROBk, as
  backends/rapid.py numbers a program's tasks, unless its task's name is given
  (`--task ROBOT:NAME=FILE`: a controller's own names, T_ROB_L). A list naming a task that is not imported, or
  leaving out the task that waits, is E524. A syncident the backend had to rename because its
  name is a RAPID word (`clear_`) gets its name back (`clear`).
* every other vendor: the I/O handshake of backends/handshake.py on the robot's "sync" signals:
  round k sets the own sync output on (odd k) or off (even k), then waits for the own sync input
  at that level; the comment `sync NAME (handshake k)` the backends write above the set names
  the barrier (`barrier_k` where it is missing). Rounds count in run order, into the routines
  the main body calls (a proc's sync: the backend writes it in the routine). Any other use of
  the sync signals: the task's sync I/O stays plain I/O (W533).

A barrier is read only where the tasks agree (every task a RAPID list names waits at that
syncident; every handshaking task passes the same number of rounds): otherwise it stays as it
is written (W531), never a one-sided `sync`.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from dataclasses import replace

from rmot.backends.handshake import HandshakePorts
from rmot.backends.rapid_text import RAPID_RULES
from rmot.backends.readers import codes
from rmot.backends.readers.common import ImportError_, rmot_name
from rmot.backends.readers.model import Call, Cond, Document, FileCount, Native, SetOut, Stmt, Sync, WaitIn, Where, walk
from rmot.backends.readers.writer import SignalMap, map_leaves, signal_uses, task_lines
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.record import record
from rmot.lang.source import Span

__all__ = ["TaskDoc", "read_barriers", "tasks_program_text", "rapid_task_name"]

SpanOf = Callable[[Where], Span]
WAIT_SYNC = re.compile(r"WaitSyncTask\s+(\w+)\s*,\s*(\w+)\s*;", re.IGNORECASE)
SYNCIDENT = r"(?im)^\s*(?:LOCAL\s+)?VAR\s+syncident\s+{}\s*;"
TASK_LIST = r"(?im)^\s*(?:LOCAL\s+|TASK\s+)?(?:PERS|VAR|CONST)\s+tasks\s+{}\s*\{{\s*\d+\s*\}}\s*:=\s*\[(.*)\]\s*;"
NOTE = re.compile(r"sync\s+(\w+)\s+\(handshake\s+(\d+)\)")


@record(slots=True)
class TaskDoc:
    """One task of the imported program: its robot, its files read as a Document, the cell's
    signals of that robot and its handshake ports (None: the cell declares none)."""

    robot: str
    doc: Document
    signals: SignalMap
    ports: HandshakePorts | None
    rapid_task: str = ""  # its RAPID task's name (`--task ROBOT:NAME=FILE`); "" = T_ROBk


def rapid_task_name(index: int, given: str = "") -> str:
    """The RAPID task of the `index`-th (0-based) task: the name given, else T_ROBk as
    backends/rapid.py names a program's tasks."""
    return (given or f"T_ROB{index + 1}").upper()


def _warn(code: Code, message: str, where: Where, span_of: SpanOf) -> Diagnostic:
    return Diagnostic(code, Severity.WARNING, message, span_of(where))


def _declared(doc: Document, pattern: str, span_of: SpanOf) -> tuple[re.Match[str], Where] | None:
    """The first declaration matching `pattern` in the task's files (a RAPID task's modules
    share their global data), with its place."""
    for c in doc.counts:
        text = span_of(Where(c.path, 1)).file.text
        m = re.search(pattern, text)
        if m is not None:
            return m, Where(c.path, text.count("\n", 0, m.start()) + 1)
    return None


def _barrier_name(name: str) -> str:
    """A syncident's name as the barrier's: RAPID words the backend suffixed with `_` get it off."""
    if name.endswith("_") and name[:-1].upper() in RAPID_RULES.reserved:
        return name[:-1]
    return name


def _rapid_waits(index: int, t: TaskDoc, tasks: list[TaskDoc],
                 span_of: SpanOf) -> dict[int, tuple[Native, str, str, frozenset[int]]]:
    """id(native) -> (the WaitSyncTask, its syncident, its task list, the task indexes in that list)."""
    found: dict[int, tuple[Native, str, str, frozenset[int]]] = {}
    given = {rapid_task_name(k, task.rapid_task): k for k, task in enumerate(tasks)}
    for r in t.doc.routines:
        for s in walk(r.body):
            if not (isinstance(s, Native) and s.vendor == "rapid"):
                continue
            m = WAIT_SYNC.fullmatch(s.text.strip())
            if m is None:
                continue
            decl = _declared(t.doc, TASK_LIST.format(re.escape(m.group(2))), span_of)
            if decl is None:
                continue  # a list the task's files do not declare: the line stays native (W510)
            names = re.findall(r'"(\w+)"', decl[0].group(1))
            unknown = [n for n in names if n.upper() not in given]
            own = rapid_task_name(index, t.rapid_task)
            if unknown or own not in (n.upper() for n in names):
                why = (f"names task {unknown[0]}, which is not imported" if unknown
                       else f"leaves out {own}, the task that waits")
                raise ImportError_(Diagnostic(
                    codes.BARRIER_TASK_UNKNOWN, Severity.ERROR,
                    f"WaitSyncTask {m.group(1)}: its task list `{m.group(2)}` must name imported tasks only, "
                    f"the waiting one included ({why}; the tasks given are "
                    f"{', '.join(f'{name} = {tasks[k].robot}' for name, k in given.items())})",
                    span_of(s.where)))
            found[id(s)] = (s, m.group(1), m.group(2), frozenset(given[n.upper()] for n in names))
    return found


def _rapid_barriers(tasks: list[TaskDoc], span_of: SpanOf) -> tuple[list[TaskDoc], list[Diagnostic]]:
    """Each RAPID task's WaitSyncTask lines every task of their list passes as `sync`."""
    waits = [_rapid_waits(k, t, tasks, span_of) if t.doc.vendor == "rapid" else {} for k, t in enumerate(tasks)]
    names = [{ident.upper() for _, ident, _, _ in w.values()} for w in waits]
    diags: list[Diagnostic] = []
    out = []
    for k, t in enumerate(tasks):
        syncs: dict[int, Sync] = {}
        native_lists: set[str] = set()  # task lists a WaitSyncTask kept native still names
        for native, ident, task_list, peers in waits[k].values():
            lacking = [tasks[j].robot for j in sorted(peers) if ident.upper() not in names[j]]
            if lacking:
                native_lists.add(task_list.upper())
                diags.append(_warn(codes.BARRIER_ONE_SIDED,
                                   f"WaitSyncTask {ident} waits for {', '.join(lacking)}, whose program has no "
                                   f"WaitSyncTask {ident}: kept native, not read as `sync`", native.where, span_of))
            else:
                syncs[id(native)] = Sync(_barrier_name(ident), native.where)
        out.append(_with_rapid_syncs(t, syncs, native_lists, span_of) if syncs else t)
    return out, diags


def _with_rapid_syncs(t: TaskDoc, syncs: dict[int, Sync], native_lists: set[str], span_of: SpanOf) -> TaskDoc:
    """`t` with the WaitSyncTask natives `syncs` replaced, their syncident and task list (unless
    `native_lists`: a native WaitSyncTask still names it) declarations no longer kept as
    comments, and the file counts moved to imported."""
    doc = t.doc
    lines = {(s.where.path, s.where.line) for s in syncs.values()}
    for s in syncs.values():
        wait = WAIT_SYNC.search(span_of(s.where).file.line_text(s.where.line))
        names = [] if wait is None else [SYNCIDENT.format(re.escape(wait.group(1)))] + (
            [] if wait.group(2).upper() in native_lists else [TASK_LIST.format(re.escape(wait.group(2)))])
        for pattern in names:
            decl = _declared(doc, pattern, span_of)
            if decl is not None:
                lines.add((decl[1].path, decl[1].line))
    kept = tuple(k for k in doc.kept if (k.where.path, k.where.line) not in lines)
    moved: dict[str, int] = {}
    for k in doc.kept:
        if k not in kept:
            moved[k.where.path] = moved.get(k.where.path, 0) + 1
    for s in syncs.values():
        moved[s.where.path] = moved.get(s.where.path, 0) + 1
    quiet = (codes.KEPT_NATIVE, codes.DECLARATION_KEPT)
    diagnostics = tuple(d for d in doc.diagnostics if not (
        d.code in quiet and d.span is not None and (d.span.file.path, d.span.start.line) in lines))
    counts = tuple(FileCount(c.path, c.imported + moved.get(c.path, 0), c.native - moved.get(c.path, 0))
                   for c in doc.counts)
    routines = tuple(replace(r, body=map_leaves(r.body, lambda s: syncs.get(id(s), s))) for r in doc.routines)
    return replace(t, doc=replace(doc, routines=routines, kept=kept, diagnostics=diagnostics, counts=counts))


def _sync_io(t: TaskDoc, s: Stmt) -> bool:
    """Whether `s` sets or reads the task's sync output or input."""
    ports = t.ports
    if ports is None:
        return False
    for kind, signal in signal_uses(s):
        port = t.signals.port(kind, signal)
        if (kind, port) in (("outputs", ports.out), ("inputs", ports.inp)):
            return True
    return False


def _scan(t: TaskDoc, body: tuple[Stmt, ...], procs: dict[str, tuple[Stmt, ...]],
          rounds: list[tuple[SetOut, WaitIn]], entered: set[str]) -> Stmt | None:
    """Collect the handshake rounds of `body` in run order, into the routines it calls that use
    the sync signals (each called once: a routine's levels are fixed); the statement where the
    pattern breaks, or None."""
    for i, a in enumerate(body):
        if isinstance(a, Call) and a.name.upper() in procs:
            if a.name.upper() in entered:
                return a
            entered.add(a.name.upper())
            stop = _scan(t, procs[a.name.upper()], procs, rounds, entered)
            if stop is not None:
                return stop
        elif isinstance(a, SetOut) and _sync_io(t, a) and t.ports is not None:
            level = len(rounds) % 2 == 0
            b = body[i + 1] if i + 1 < len(body) else None
            if not (isinstance(b, WaitIn) and not b.orelse and b.timeout is None and isinstance(b.cond, Cond)
                    and not a.analog and bool(a.value) == level and b.cond.on == level
                    and t.signals.port("inputs", b.cond.signal) == t.ports.inp):
                return a
            rounds.append((a, b))
    return None


def _handshake(t: TaskDoc, span_of: SpanOf) -> tuple[list[tuple[SetOut, WaitIn]], Diagnostic | None]:
    """The task's handshake rounds (set, wait) in run order, or none and why (W533)."""
    main = next((r for r in t.doc.routines if r.name == t.doc.main), None)
    uses = [s for r in t.doc.routines for s in walk(r.body) if _sync_io(t, s)]
    if main is None or t.ports is None or not uses:
        return [], None
    procs = {r.name.upper(): r.body for r in t.doc.routines
             if r is not main and any(_sync_io(t, s) for s in walk(r.body))}
    rounds: list[tuple[SetOut, WaitIn]] = []
    stop = _scan(t, main.body, procs, rounds, set())
    paired = {id(x) for pair in rounds for x in pair}
    stray = stop or next((s for s in uses if id(s) not in paired), None)
    if stray is None:
        return rounds, None
    return [], _warn(codes.HANDSHAKE_KEPT_IO,
                     f"this line must be round {len(rounds) + 1} of the handshake rmot writes on {t.robot}'s sync "
                     f"signals to be read as a barrier (set out[{t.ports.out}] = {'on' if len(rounds) % 2 == 0 else 'off'}, "
                     f"then wait until in[{t.ports.inp}] at that level, no timeout; in the main body or a routine it "
                     "calls once, not inside a block): the task's sync I/O is kept as I/O", stray.where, span_of)


def _note(where: Where, k: int, span_of: SpanOf) -> str | None:
    """The barrier's name from the `sync NAME (handshake k)` comment above the round's set."""
    m = NOTE.search(span_of(where).file.line_text(where.line - 1))
    return m.group(1) if m and int(m.group(2)) == k else None


def _handshake_barriers(tasks: list[TaskDoc], span_of: SpanOf) -> tuple[list[TaskDoc], list[Diagnostic]]:
    found = [_handshake(t, span_of) for t in tasks]
    diags = [d for _, d in found if d is not None]
    rounds = [r for r, _ in found]
    taking = [k for k, t in enumerate(tasks) if rounds[k] or found[k][1] is not None]
    counts = {len(rounds[k]) for k in taking}
    if not taking:
        return tasks, diags
    if len(taking) < 2 or len(counts) > 1:
        peers = ", ".join(f"{tasks[k].robot}: {len(rounds[k])}" for k in taking)
        first = next(r[0][0].where for r in rounds if r) if any(rounds) else None
        if first is not None:
            diags.append(_warn(codes.BARRIER_ONE_SIDED,
                               f"the tasks' handshakes on their sync signals must pair up, round by round, with "
                               f"a peer's (rounds read: {peers}): kept as I/O, not read as `sync`", first, span_of))
        return tasks, diags
    names = []
    for k in range(len(rounds[taking[0]])):
        said = [(j, _note(rounds[j][k][0].where, k + 1, span_of)) for j in taking]
        named = [(j, n) for j, n in said if n is not None]
        names.append(named[0][1] if named else f"barrier_{k + 1}")
        for j, n in named[1:]:
            if n != names[-1]:
                diags.append(_warn(codes.BARRIER_NAMES_DIFFER,
                                   f"handshake {k + 1} is barrier `{n}` here, `{names[-1]}` in {tasks[named[0][0]].robot}'s "
                                   f"program: read as `sync {names[-1]}`", rounds[j][k][0].where, span_of))
    return [_with_handshake_syncs(t, rounds[k], names) if k in taking else t for k, t in enumerate(tasks)], diags


def _with_handshake_syncs(t: TaskDoc, rounds: list[tuple[SetOut, WaitIn]], names: list[str]) -> TaskDoc:
    """`t` with each round's set as `sync NAME` and its wait gone (the sync waits)."""
    sets = {id(s): Sync(name, s.where) for (s, _), name in zip(rounds, names)}
    waits = {id(w) for _, w in rounds}
    routines = tuple(replace(r, body=tuple(sets.get(id(s), s) for s in r.body if id(s) not in waits))
                     for r in t.doc.routines)
    return replace(t, doc=replace(t.doc, routines=routines))


def read_barriers(tasks: list[TaskDoc], span_of: SpanOf) -> tuple[list[TaskDoc], list[Diagnostic]]:
    """The tasks with their barriers read as `sync`, and the warnings about those kept as they
    are written. Raises ImportError_ (E524) for a RAPID task list naming a task not imported."""
    tasks, rapid = _rapid_barriers(tasks, span_of)
    tasks, handshake = _handshake_barriers(tasks, span_of)
    return tasks, rapid + handshake


def _program_name(tasks: list[TaskDoc]) -> str:
    """The program's name: the files' common name without the `_ROBOT` suffix the backends add."""
    stems = {re.sub(f"(?i)_{re.escape(t.robot)}$", "", t.doc.name) for t in tasks}
    return stems.pop() if len(stems) == 1 else tasks[0].doc.name


def tasks_program_text(tasks: list[TaskDoc], use_cell: str) -> str:
    """The .rmot program with a task per robot (declarations of each task's files inside it)."""
    files = ", ".join(f"{os.path.basename(c.path)}" for t in tasks for c in t.doc.counts)
    lines = [f"# imported by `rmot import` from {files} ({', '.join(sorted({t.doc.vendor for t in tasks}))})"]
    for t in tasks:
        for c in t.doc.counts:
            lines.append(f"#   {c.path} ({t.robot}): {c.imported} instructions imported, {c.native} kept native")
    lines += [f'use cell "{use_cell}"', f"program {rmot_name(_program_name(tasks))} {{"]
    for t in tasks:
        lines += task_lines(t.doc, t.signals, t.robot)
    lines.append("}")
    kept = [k for t in tasks for k in t.doc.kept]
    if kept:
        lines += ["", "# kept from the vendor files (declarations and routines with no rmot form):"]
        lines += [f"#   {k.where}: {k.text}" for k in kept]
    return "\n".join(lines) + "\n"
