"""Readers of vendor programs: RAPID, KRL, URScript, ... back into a neutral Document
(`model.py`), printed as .rmot by `writer.py` and compared by `diff.py`.

`read_files(paths)` picks the reader by each file's extension (`READERS`), reads every file
and merges them into one Document; a file that is not its vendor's language raises
`ImportError_` with a located E510, never a traceback.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable

from rmot.backends.readers import codes
from rmot.backends.readers.common import MAX_BYTES, ImportError_, Tally, read_text
from rmot.backends.readers.fanuc_german import english, is_german
from rmot.lang.ir import Pose
from rmot.backends.readers.model import Document, PulsePose, Routine, Stmt, Target, Where
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.input_file import NotRegularFile, read_regular
from rmot.lang.source import Pos, SourceFile, Span
from dataclasses import replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rmot.backends.readers.fanuc_va import Controller
    from rmot.backends.readers.krl_names import Params

__all__ = ["READERS", "vendor_of", "read_files", "ImportError_", "span_of", "companions"]


def _rapid(path: str, text: str, companion: tuple[str, str] | None) -> tuple[Document, Tally]:
    from rmot.backends.readers.position_records import rapid_records  # late: with the reader it serves
    from rmot.backends.readers.rapid import read_rapid  # late: loads numpy only when this runs

    m = read_rapid(path, text, _RAPID_TASK)
    main = next((r.name for r in m.routines if r.name.lower() == "main"), m.routines[0].name if m.routines else "main")
    doc = Document("rapid", m.name, main, tuple(m.targets.values()), tuple(m.tools.values()),
                   tuple(m.frames.values()), (*m.routines, *m.tally.unreached), tuple(m.consts.items()), (m.tally.count(),),
                   tuple(m.tally.diagnostics), tuple(m.tally.comments), records=rapid_records(m.module_data()))
    return doc, m.tally


def _krl(path: str, text: str, companion: tuple[str, str] | None) -> tuple[Document, Tally]:
    from rmot.backends.readers.krl import read_krl  # late: loads numpy only when this runs
    from rmot.backends.readers.position_records import krl_records  # late: with the reader it serves

    if path.lower().endswith(".dat"):
        raise ImportError_(Diagnostic(codes.NOT_VENDOR_LANGUAGE, Severity.ERROR,
                                      "a KRL .dat is read with its .src (give the .src, or both)",
                                      span_of(Where(path, 1))))
    m = read_krl((path, text), companion, _KRL_ROUTINES)
    main = next((r.name for r in m.routines if r.name.upper() == m.name.upper()), m.name)
    main = "" if any(r.params for r in m.routines if r.name == main) else main  # a module taking parameters: a proc
    targets = tuple(t for key, t in m.targets.items() if key not in m.work)  # loop work copies: shift
    doc = Document("krl", m.name, main, targets, tuple(m.tools.values()),
                   tuple(m.frames.values()), (*m.routines, *m.tally.unreached), (), (m.tally.count(),), tuple(m.tally.diagnostics),
                   tuple(m.tally.comments), m.named_loads(), records=krl_records(*companion) if companion else ())
    return doc, m.tally


def _urscript(path: str, text: str, companion: tuple[str, str] | None) -> tuple[Document, Tally]:
    from rmot.backends.readers.urscript import read_urscript  # late: loads numpy only when this runs

    m = read_urscript(path, text, _MODEL[0], _LIMITS[0])
    doc = Document("urscript", m.name, m.main, tuple(m.targets.values()), tuple(m.tools.values()), (),
                   (*m.routines, *m.tally.unreached), (), (m.tally.count(),), tuple(m.tally.diagnostics), tuple(m.tally.comments))
    return doc, m.tally


def _fanuc(path: str, text: str, companion: tuple[str, str] | None) -> tuple[Document, Tally]:
    from rmot.backends.readers.fanuc import read_fanuc  # late: loads numpy only when this runs
    from rmot.backends.readers.position_records import tp_records  # late: with the reader it serves

    m = read_fanuc(path, text, _FANUC_LABELS, _FANUC_PROGRAMS, _PULSE_POSE[0], _FANUC_SAVED[0])
    _FANUC_INLINED.update(m.inlined)
    if path in _GERMAN:
        m.tally.warn(codes.GERMAN_EXPORT_READ, "a German-language pendant wrote this program: it is read in the "
                     "English words the same program's English export has (WARTE is WAIT, E[n] DI[n], [&] AND); its "
                     "lines show and its native lines are kept in those words", Where(path, 1))
    doc = Document("fanuc", m.name, m.name, tuple(m.positions.values()), tuple(m.tools.values()),
                   tuple(m.frames.values()), (m.routine, *m.tally.unreached), (), (m.tally.count(),), tuple(m.tally.diagnostics),
                   tuple(m.tally.comments), tuple(m.loads), records=tp_records(path, text, m.tools, m.frames))
    return doc, m.tally


def _inform(path: str, text: str, companion: tuple[str, str] | None) -> tuple[Document, Tally]:
    from rmot.backends.readers.inform import read_inform  # late: loads numpy only when this runs

    m = read_inform(path, text, _FANUC_PROGRAMS, _PULSES[0], _PULSE_POSE[0])
    _FANUC_INLINED.update(m.inlined)
    doc = Document("inform", m.name, m.name, tuple(m.positions.values()), tuple(m.tools.values()),
                   tuple(m.frames.values()), (m.routine, *m.tally.unreached), (), (m.tally.count(),), tuple(m.tally.diagnostics),
                   tuple(m.tally.comments), records=m.records)
    return doc, m.tally


def _val3(path: str, text: str, companion: tuple[str, str] | None) -> tuple[Document, Tally]:
    from rmot.backends.readers.val3 import read_val3  # late: loads numpy only when this runs

    folder = os.path.dirname(os.path.abspath(path))
    data = [(p, _load(p)) for p in sorted(os.path.join(folder, f) for f in os.listdir(folder) if f.lower().endswith(".dtx"))]
    m = read_val3(path, text, data, _FANUC_PROGRAMS)
    _FANUC_INLINED.update(m.inlined)
    main = m.routines[0].name if m.routines else "start"
    name = os.path.basename(folder) if main == "start" else main  # the application is its folder
    doc = Document("val3", name, main, tuple(m.targets.values()), tuple(m.tools.values()),
                   tuple(m.frames.values()), (*m.routines, *m.tally.unreached), (), (m.tally.count(),), tuple(m.tally.diagnostics),
                   tuple(m.tally.comments))
    return doc, m.tally


def _project(paths: list[str]) -> list[str]:
    """A VAL3 project (`.pjx`) as the program files it names, `start.pgx` first."""
    out: list[str] = []
    for path in paths:
        if not path.lower().endswith(".pjx"):
            out.append(path)
            continue
        names = re.findall(r'<Program\s+file="([^"/\\]+\.pgx)"', _load(path))
        if not names:
            raise _fail(codes.NOT_VENDOR_LANGUAGE, path, "a VAL3 project must name its programs (`<Program file=..>`)")
        names.sort(key=lambda n: n.lower() != "start.pgx")
        out += [os.path.join(os.path.dirname(path), n) for n in names]
    return out


_MODEL: list[str | None] = [None]  # the robot model read_files was given (URScript joint speeds)
JointLimits = tuple[tuple[float, ...], tuple[float, ...]]  # each joint's speed rad/s, acceleration rad/s^2
_LIMITS: list[JointLimits | None] = [None]  # that model's joint limits (URScript movej rates)
_PULSES: list[tuple[float, ...] | None] = [None]  # the arm's pulses per degree, axis by axis (INFORM pulse positions)
_PULSE_POSE: list[PulsePose | None] = [None]  # the TCP pose of joints (deg) with a named tool, from the cell's arm
# Fanuc tool and frame numbers are the controller's, shared by every program: the names the
# files give them (`!UTOOL[1] = gripper`), collected from all the files before any is read
_FANUC_LABELS: dict[str, dict[int, str]] = {"UTOOL": {}, "UFRAME": {}}
# the TP programs (and INFORM jobs) of one import by name: a program CALLed inside a counting
# loop whose offset registers (shift variables) it uses is read again at the call, inlined with
# the loop's counter
_FANUC_PROGRAMS: dict[str, tuple[str, str]] = {}
_FANUC_INLINED: set[str] = set()  # the programs some caller inlined
_GERMAN: set[str] = set()  # the TP files a German pendant wrote, read in English words (W551)
_LOADED: dict[str, str] = {}  # the files of the import being read, by path
_KRL_ROUTINES: dict[str, Params | None] = {}  # ROUTINE -> its parameters (krl_names.signatures), over every .src given
_RAPID_TASK: dict[str, str] = {}  # the RAPID modules given: one task, their global data shared
# a Fanuc backup's saved registers and frames (NUMREG.VA, POSREG.VA, SYSFRAME.VA) given with its programs
_FANUC_SAVED: list[Controller | None] = [None]

Reader = Callable[[str, str, "tuple[str, str] | None"], "tuple[Document, Tally]"]

# extension (lower case) -> (vendor, reader)
READERS: dict[str, tuple[str, Reader]] = {
    ".mod": ("rapid", _rapid), ".modx": ("rapid", _rapid), ".prg": ("rapid", _rapid),
    ".src": ("krl", _krl), ".dat": ("krl", _krl), ".script": ("urscript", _urscript),
    ".urscript": ("urscript", _urscript), ".ls": ("fanuc", _fanuc),
    ".jbi": ("inform", _inform), ".pgx": ("val3", _val3), ".pjx": ("val3", _val3), ".va": ("fanuc", _fanuc),
}

_SOURCES: dict[str, SourceFile] = {}


def span_of(where: Where) -> Span:
    """A span at `where` in a file read by read_files (its text shows under diagnostics)."""
    source = _SOURCES.get(where.path) or SourceFile(where.path, "")
    pos = Pos(where.line, where.col)
    return Span(source, pos, pos)


def vendor_of(path: str) -> str | None:
    entry = READERS.get(os.path.splitext(path)[1].lower())
    return entry[0] if entry else None


def _fail(code: codes.Code, path: str, message: str) -> ImportError_:  # type: ignore[name-defined]
    return ImportError_(Diagnostic(code, Severity.ERROR, message, span_of(Where(path, 1))))


def _one_main(modules: dict[str, str]) -> None:
    """Refuse (E523) RAPID modules of which two define `PROC main`: the modules of one task have
    one main, so these are several robots' programs, whose barriers only `--task` reads (merged,
    the second main would be lost)."""
    mains = [(path, text.count("\n", 0, m.start()) + 1) for path, text in modules.items()
             for m in [re.search(r"(?im)^[ \t]*(?:LOCAL[ \t]+)?PROC[ \t]+main[ \t]*\(", text)] if m is not None]
    if len(mains) > 1:
        (first, _), (path, line) = mains[:2]
        raise ImportError_(Diagnostic(
            codes.TASK_SPEC_INVALID, Severity.ERROR, f"the modules of one task must have one PROC main (`{first}` has "
            "one too): several robots' programs are read with one --task ROBOT=FILE each and --cell",
            span_of(Where(path, line))))


def _load(path: str) -> str:
    """The text of a file given, read once per import (the index, the saved data and the reader
    all ask for it); a German pendant's TP in English words (fanuc_german)."""
    if path in _LOADED:
        return _LOADED[path]
    try:
        data = read_regular(path, MAX_BYTES)
    except NotRegularFile as exc:
        raise _fail(codes.IMPORT_UNREADABLE, path, f"a vendor file must be a regular file of at most {MAX_BYTES} bytes "
                    f"(got {exc.strerror})") from None
    try:
        text = read_text(data)
    except ValueError as exc:
        raise _fail(codes.IMPORT_UNREADABLE, path, f"a vendor file must be text ({exc})") from None
    if path.lower().endswith(".ls") and is_german(text):  # a German pendant's TP, in English words
        text = english(text)
        _GERMAN.add(path)
    _SOURCES[path] = SourceFile(path, text)
    _LOADED[path] = text
    return text


def read_files(paths: list[str], model: str | None = None, limits: JointLimits | None = None,
               pulses_per_degree: tuple[float, ...] | None = None, pulse_pose: PulsePose | None = None) -> Document:
    """Read and merge the files (one vendor): the first file's main routine runs. A KRL .src
    reads its .dat (given too, or beside it). `model`: the robot library name the program runs
    on, where a vendor writes speeds relative to the arm (URScript movej); `limits`: its joint
    speed and acceleration limits (the caller loads the arm: a reader only reads text)."""
    _LOADED.clear()  # a file changed since the last import is read again
    _GERMAN.clear()
    paths = _project(paths)
    _MODEL[0] = model
    _LIMITS[0] = limits
    _PULSES[0] = pulses_per_degree  # INFORM pulse positions read as joints (readers/inform.py)
    _PULSE_POSE[0] = pulse_pose  # and as TCP poses for linear and circular moves to them
    _FANUC_LABELS["UTOOL"].clear()
    _FANUC_LABELS["UFRAME"].clear()
    _FANUC_PROGRAMS.clear()
    _FANUC_INLINED.clear()
    _RAPID_TASK.clear()
    _KRL_ROUTINES.clear()
    _FANUC_SAVED[0] = _saved_data(paths)
    _index(paths)
    _one_main(_RAPID_TASK)
    docs: list[Document] = []
    consumed = set()
    for path in paths:
        if path in consumed or path.lower().endswith(".va"):
            continue
        entry = READERS.get(os.path.splitext(path)[1].lower())
        if entry is None:
            known = ", ".join(sorted(READERS))
            raise _fail(codes.UNKNOWN_FORMAT, path, f"`rmot import` reads {known} files (got `{os.path.basename(path)}`)")
        companion = None
        if entry[0] == "krl" and path.lower().endswith(".src"):
            stem = os.path.splitext(path)[0]
            dat = next((p for p in paths if os.path.splitext(p)[0] == stem and p.lower().endswith(".dat")), None)
            dat = dat or next((c for c in companions(path)[1:]), None)
            if dat is not None:
                consumed.add(dat)
                companion = (dat, _load(dat))
        doc, _ = entry[1](path, _load(path), companion)
        docs.append(doc)
    if not docs:
        raise _fail(codes.NOT_VENDOR_LANGUAGE, paths[0], "a Fanuc .VA file is read with the TP programs that use "
                    "its registers and frames (give the .ls too)")
    docs = _without_inlined(docs)
    vendors = {d.vendor for d in docs}
    if len(vendors) > 1:
        raise _fail(codes.DIFF_VENDORS_DIFFER, paths[-1], f"the files must be of one vendor (got {', '.join(sorted(vendors))})")
    from rmot.backends.readers.start_state import tool_not_set  # late: loads numpy only when this runs

    return tool_not_set(_unknown_calls_kept(_merge(docs)), span_of)


def _index(paths: list[str]) -> None:
    """The programs of one import by name, and the tool and frame names and RAPID modules they
    share, collected from every file before any is read."""
    for path in paths:
        if path.lower().endswith(".ls"):
            text = _load(path)
            prog = re.match(r"\s*/PROG\s+([\w-]+)", text)
            if prog:
                _FANUC_PROGRAMS[prog.group(1).upper()] = (path, text)
            for kind, n, name in re.findall(r"!\s*(UTOOL|UFRAME)\[(\d+)\]\s*=\s*(\w+)", text):
                _FANUC_LABELS[kind][int(n)] = name
        if path.lower().endswith(".pgx"):  # VAL3 programs by name, the same way
            program = re.search(r'<Program\s+name="(\w+)"', _load(path))
            if program:
                _FANUC_PROGRAMS[program.group(1).upper()] = (path, _load(path))
        if path.lower().endswith(".src"):  # KRL routines another file calls with arguments
            from rmot.backends.readers.krl_names import file_signatures  # late: loads the KRL reader only for .src files

            _KRL_ROUTINES.update(file_signatures(path, _load(path)))
        if path.lower().endswith((".mod", ".modx", ".prg")):  # RAPID modules of one task share their global data
            _RAPID_TASK[path] = _load(path)
        if path.lower().endswith(".jbi"):  # INFORM jobs by name, as TP programs: inlined in a shifting loop
            job = re.search(r"(?m)^//NAME\s+(\w+)", _load(path))
            if job:
                _FANUC_PROGRAMS[job.group(1).upper()] = (path, _load(path))


def _saved_data(paths: list[str]) -> Controller | None:
    """The registers and frames the .VA files among `paths` saved, with what the TP programs
    among them write (fanuc_va); None without a .VA file."""
    from rmot.backends.readers.fanuc_va import Controller, empty, read_va  # late: loads numpy only when this runs

    saved = [p for p in paths if p.lower().endswith(".va")]
    if not saved:
        return None
    data = empty()
    for path in saved:
        read_va(path, _load(path), data)
    return Controller(data, [_load(p) for p in paths if p.lower().endswith(".ls")])


def _unknown_calls_kept(doc: Document) -> Document:
    """A call of a routine none of the files given defines stays native with W510: the controller
    runs a program rmot does not see (what it moves is not planned), and a call of a proc the
    imported program lacks would not compile (E101)."""
    from rmot.backends.readers.model import Call  # late: loads numpy only when this runs
    from rmot.backends.readers.writer import Keep, kept_native  # late: loads numpy only when this runs

    known = {r.name.upper() for r in doc.routines}

    def unknown(s: Stmt) -> Keep | None:
        if not isinstance(s, Call) or (s.name.upper() in known and s.name.upper() != doc.main.upper()):
            return None
        why = (f"`{s.name}` is the routine that runs first, the program's own body in rmot: a call back to it has "
               "no rmot form" if s.name.upper() == doc.main.upper() else
               f"`{s.name}` is a routine none of the files given defines (give its file too)")
        return (codes.KEPT_NATIVE, lambda text: f"{why}; kept as `native {doc.vendor}`: {text[:60]}", f"{s.name}()")

    return kept_native(doc, unknown, span_of)


def _without_inlined(docs: list[Document]) -> list[Document]:
    """TP programs every caller inlined (they moved by the caller's loop offsets) are not
    routines of the imported program: their lines are imported at the calls."""
    from rmot.backends.readers.model import Call, walk  # late: loads numpy only when this runs

    while True:  # a program only inlined programs call goes too
        called = {s.name.upper() for d in docs for r in d.routines for s in walk(r.body) if isinstance(s, Call)}
        kept = [d for i, d in enumerate(docs) if i == 0 or d.name.upper() not in _FANUC_INLINED - called]
        if len(kept) == len(docs):
            return kept
        docs = kept


def _unique_targets(docs: list[Document]) -> list[Document]:
    """Targets of one name in several files: one declaration when equal; otherwise the later
    file's is renamed `FILE_name` (its moves follow)."""

    from rmot.backends.readers.writer import map_leaves  # late: loads numpy only when this runs

    seen: dict[str, Target] = {}
    out = []
    for d in docs:
        renames: dict[str, str] = {}
        kept = []
        for t in d.targets:
            other = seen.get(t.name)
            if other is None:
                seen[t.name] = t
                kept.append(t)
            elif (other.pose, other.joints, other.config) != (t.pose, t.joints, t.config):
                renames[t.name] = f"{d.name.lower()}_{t.name}"
                kept.append(replace(t, name=renames[t.name]))
        routines = tuple(replace(r, body=map_leaves(r.body, _renamer(renames))) for r in d.routines)
        out.append(replace(d, targets=tuple(kept), routines=routines))
    return out


def _renamer(renames: dict[str, str]) -> Callable[[Stmt], Stmt]:
    """A function renaming the targets a move names (whole words of its expressions)."""

    from rmot.backends.readers.model import Move  # late: loads numpy only when this runs

    def sub(text: str) -> str:
        return re.sub(r"\b(\w+)\b", lambda m: renames.get(m.group(1), m.group(1)), text)

    def rename(s: Stmt) -> Stmt:
        if not isinstance(s, Move) or not renames:
            return s
        return replace(s, target=sub(s.target), via=sub(s.via) if s.via else None,
                       target_name=renames.get(s.target_name or "", s.target_name))

    return rename


def _merge(docs: list[Document]) -> Document:
    docs = _unique_targets(docs)
    first = docs[0]
    routines: list[Routine] = []
    for d in docs:
        routines += [r for r in d.routines if not (d is not first and r.name == d.main and r.name == first.main)]
    tools = {t.name: t for d in docs for t in d.tools if t.tcp != Pose() or t.mass}  # data where a file has it
    tools = {**{t.name: t for d in docs for t in d.tools}, **tools}
    frames = {f.name: f for d in docs for f in d.frames if f.pose != Pose()}
    frames = {**{f.name: f for d in docs for f in d.frames}, **frames}
    return Document(first.vendor, first.name, first.main, sum((d.targets for d in docs), ()),
                    tuple(tools.values()), tuple(frames.values()), tuple(routines),
                    sum((d.consts for d in docs), ()), sum((d.counts for d in docs), ()),
                    sum((d.diagnostics for d in docs), ()), sum((d.kept for d in docs), ()),
                    sum((d.loads for d in docs), ()), records=sum((d.records for d in docs), ()))


def companions(path: str) -> list[str]:
    """The files that make one program with `path`: a KRL `.src` and its `.dat`."""
    stem, ext = os.path.splitext(path)
    if ext.lower() == ".src":
        for dat in (stem + ".dat", stem + ".DAT"):
            if os.path.exists(dat):
                return [path, dat]
    return [path]
