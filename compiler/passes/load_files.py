"""Pass 1: read and parse every file the program names (imports, `use cell`, --cell).

Paths in a file are resolved relative to that file and must stay inside the project root
(default: the directory of the file given on the command line). Source files must be UTF-8
and at most MAX_SOURCE_BYTES (2 MiB, about 50,000 lines: a bigger .rmot file is almost
surely not a program). Imports are followed depth first; a cycle is reported at the import
that closes it, with the chain as notes. A file imported twice (a diamond) is read once.
"""

from __future__ import annotations

import errno
import os
from dataclasses import dataclass, field, replace
from pathlib import Path

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Reporter
from rmot.compiler.passes.state import FrontendState, LoadedModule
from rmot.lang import ast
from rmot.lang.input_file import read_regular
from rmot.lang.parse import parse_source
from rmot.lang.source import SourceFile, Span

__all__ = ["MAX_SOURCE_BYTES", "load_sources", "read_module", "resolve_path"]

MAX_SOURCE_BYTES = 2 * 1024 * 1024
DEFAULT_CELL = Path(__file__).resolve().parents[1] / "default_cell.rmot"


def resolve_path(written: str, relative_to: SourceFile, roots: tuple[str, ...], span: Span | None,
                 rep: Reporter, what: str = "file") -> str | None:
    """The absolute path of `written` (relative to the naming file), inside one of `roots`."""
    try:
        base = Path(relative_to.path).resolve().parent
        target = Path(os.path.normpath(base / written)) if not os.path.isabs(written) else Path(os.path.normpath(written))
        if roots and not any(_inside(target, Path(r)) for r in roots):
            rep.error(codes.PATH_ESCAPES, f"{what} path must stay inside the project directory {roots[0]} (got '{written}')", span)
            return None
        os.stat(target)
    except OSError as exc:  # a name longer than NAME_MAX, a folder that cannot be searched, ...
        missing = isinstance(exc, (FileNotFoundError, NotADirectoryError))
        code = codes.FILE_NOT_FOUND if missing or exc.errno == errno.ENAMETOOLONG else codes.UNREADABLE
        reason = "no file there" if missing else (exc.strerror or str(exc))
        rep.error(code, f"{what} '{_short(written)}' must exist and be readable (got {reason})", span)
        return None
    if not target.is_file():
        if target.exists():  # a FIFO would block its reader, a device never end: neither is read
            rep.error(codes.UNREADABLE, f"{what} '{_short(written)}' must be a regular file (got a FIFO, device or folder "
                      f"at {_short(str(target))})", span)
        else:
            rep.error(codes.FILE_NOT_FOUND, f"{what} '{_short(written)}' must exist (got no file at {_short(str(target))})", span)
        return None
    return str(target)


def resolve_folder(written: str, relative_to: SourceFile, roots: tuple[str, ...], span: Span | None,
                   rep: Reporter) -> str | None:
    """The absolute path of folder `written` (relative to the naming file), inside one of `roots`."""
    base = Path(relative_to.path).resolve().parent
    target = Path(os.path.normpath(written if os.path.isabs(written) else base / written))
    if roots and not any(_inside(target, Path(r)) for r in roots):
        rep.error(codes.PATH_ESCAPES, f"package folder must stay inside the project directory {roots[0]} (got '{_short(written)}')", span)
        return None
    if not target.is_dir():
        rep.error(codes.FILE_NOT_FOUND, f"package folder '{_short(written)}' must exist (got no folder at {_short(str(target))})", span)
        return None
    return str(target)


def _short(text: str, limit: int = 120) -> str:
    return text if len(text) <= limit else f"{text[:limit // 2]}...{text[-limit // 2:]} ({len(text)} characters)"


def _inside(path: Path, root: Path) -> bool:
    try:
        path.resolve().relative_to(root.resolve())
    except ValueError:
        return False
    return True


def shown_path(written: str, naming: SourceFile, resolved: str) -> str:
    """How diagnostics name a file that `naming` names as `written`: relative as the naming file
    is (`p.rmot` uses "c.rmot": `c.rmot`; `a/p.rmot`: `a/c.rmot`), else the resolved path."""
    if os.path.isabs(written) or os.path.isabs(naming.path) or naming.path.startswith("<"):
        return resolved
    return os.path.normpath(os.path.join(os.path.dirname(naming.path), written))


def read_module(path: str, span: Span | None, rep: Reporter, shown: str | None = None) -> LoadedModule | None:
    """Read, decode and parse one source file; every problem becomes a diagnostic, which names
    the file as `shown` (the path the way the user wrote it; `path` is the resolved one)."""
    try:
        size = os.path.getsize(path)
        if size > MAX_SOURCE_BYTES:
            rep.error(codes.FILE_TOO_LARGE, f"source file must be at most {MAX_SOURCE_BYTES // 1024} KiB (got {size // 1024} KiB)",
                      span or Span.whole(SourceFile(path, "")))
            return None
        data = read_regular(path, MAX_SOURCE_BYTES)
    except OSError as exc:
        code = codes.FILE_NOT_FOUND if isinstance(exc, FileNotFoundError) else codes.UNREADABLE
        rep.error(code, f"file '{_short(path)}' must be readable (got {exc.strerror or exc})", span)
        return None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        where = SourceFile(shown or path, data[: exc.start].decode("utf-8", "replace"))
        bad = Span.from_offsets(where, len(where.text), len(where.text))
        rep.error(codes.NOT_UTF8, f"source file must be UTF-8 text (got byte 0x{data[exc.start]:02x} at offset {exc.start})", bad)
        return None
    loaded = parse_module(SourceFile(shown or path, text.removeprefix("\ufeff")), rep)
    return LoadedModule(path, loaded.module) if loaded is not None and shown is not None else loaded


def parse_module(file: SourceFile, rep: Reporter) -> LoadedModule | None:
    result = parse_source(file)
    for d in result.diagnostics:
        rep.sink.add(d)
    if result.module is None:
        return None
    return LoadedModule(file.path, result.module)


@dataclass
class _Walk:
    roots: tuple[str, ...]
    rep: Reporter
    done: dict[str, LoadedModule | None] = field(default_factory=dict)
    order: list[LoadedModule] = field(default_factory=list)


def _follow_imports(mod: LoadedModule, walk: _Walk, chain: list[tuple[str, Span | None]]) -> None:
    for stmt in mod.module.body:
        if not isinstance(stmt, ast.Import):
            continue
        path = resolve_path(stmt.path.value, mod.module.file, walk.roots, stmt.path.span, walk.rep, "imported file")
        if path is None:
            continue
        on_stack = [p for p, _ in chain]
        if path in on_stack:
            cycle = chain[on_stack.index(path):]
            notes = tuple((f"'{Path(p).name}' is imported here", s) for p, s in cycle[1:])
            names = " -> ".join(Path(p).name for p, _ in cycle) + f" -> {Path(path).name}"
            walk.rep.error(codes.IMPORT_CYCLE, f"imports must not form a cycle (got {names})", stmt.span, notes)
            continue
        mod.imports.append(path)
        if path in walk.done:
            continue
        child = read_module(path, stmt.path.span, walk.rep, shown_path(stmt.path.value, mod.module.file, path))
        walk.done[path] = child
        if child is not None:
            _follow_imports(child, walk, [*chain, (path, stmt.span)])
            walk.order.append(child)


def load_sources(state: FrontendState) -> FrontendState:
    """Main file, its imports (transitively) and the cell file; all parsed."""
    rep = state.reporter
    main = state.main
    if main is None:
        main = read_module(state.path, None, rep) if state.text is None else parse_module(SourceFile(state.path, state.text), rep)
    if main is None:
        return replace(state, main=None)
    walk = _Walk(state.roots, rep, {str(Path(state.path).resolve()): main})
    _follow_imports(main, walk, [(str(Path(state.path).resolve()), None)])
    cell_module, cell_is_default = _cell_module(main, state, rep)
    if cell_module is not None and cell_module is not main:
        _follow_imports(cell_module, walk, [(cell_module.path, None)])
    return replace(state, main=main, libraries=tuple(walk.order), modules=walk.done,
                   cell_module=cell_module, cell_is_default=cell_is_default)


def _cell_module(main: LoadedModule, state: FrontendState, rep: Reporter) -> tuple[LoadedModule | None, bool]:
    """--cell beats `use cell`, which beats a cell in the main file, which beats the default
    (loaded only for a file that holds a program)."""
    uses = [s for s in main.module.body if isinstance(s, ast.UseCell)]
    for extra in uses[1:]:
        rep.error(codes.DUPLICATE, "a file must use at most one cell (got a second 'use cell')", extra.span,
                  (("the first 'use cell' is here", uses[0].span),))
    if state.cell_path is not None:
        if not os.path.isfile(state.cell_path):
            rep.error(codes.FILE_NOT_FOUND, f"cell file '{state.cell_path}' must exist (got no such file)", None)
            return None, False
        return read_module(state.cell_path, None, rep), False
    if uses:
        path = resolve_path(uses[0].path.value, main.module.file, state.roots, uses[0].path.span, rep, "cell file")
        shown = shown_path(uses[0].path.value, main.module.file, path) if path else None
        return (read_module(path, uses[0].path.span, rep, shown) if path else None), False
    if any(isinstance(s, ast.CellDecl) for s in main.module.body):
        return main, False
    if not any(isinstance(s, ast.ProgramDecl) for s in main.module.body):
        return None, False  # a library of procs/targets/consts: no cell needed
    return read_module(str(DEFAULT_CELL), None, rep), True
