"""The front end's public entry: a .rmot file (or text) -> checked ir.Program + ir.Cell.

    from rmot.compiler.frontend import load_program
    result = load_program("examples/pick_place.rmot")
    result.program   # ir.Program, or None when there are errors or the file holds only a cell
    result.cell      # ir.Cell in use (from --cell, `use cell`, the file itself, or the default)
    result.diagnostics

Never raises for bad input: every problem is a Diagnostic. When the program neither uses a
cell nor is given one, the built-in default cell (compiler/default_cell.rmot) is used.
Paths named in files must stay inside `project_root` (default: the directory of `path`);
an explicit `cell` file's directory is allowed too.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from rmot.lang.diagnostics import Diagnostic
from rmot.lang.record import record
from rmot.compiler.passes.context import Reporter, default_robot_loader

if TYPE_CHECKING:  # the passes (and the parser) load when a file is read, not with the result type
    from rmot.lang import ir
    from rmot.compiler.passes.context import RobotLoader
    from rmot.compiler.passes.state import FrontendState

__all__ = ["FrontendResult", "load_program", "load_text", "run_passes"]


@record(slots=True)
class FrontendResult:
    program: ir.Program | None
    cell: ir.Cell | None
    diagnostics: tuple[Diagnostic, ...]
    # absolute paths of the source files read (program, imports, cell): the CLI's load cache
    # (compiler/cli/load_cache.py) checks their bytes before it reuses a result
    sources: tuple[str, ...] = ()

    @property
    def has_errors(self) -> bool:
        return any(d.is_error for d in self.diagnostics)


def load_program(path: str, *, cell: str | None = None, project_root: str | None = None,
                 robot_loader: RobotLoader | None = None, require_program: bool = False) -> FrontendResult:
    """Parse, check and lower the program in `path` (see the module docstring).

    A missing file is E501. `require_program`: a file without a program (only a cell or
    declarations) is an error, E119 — what every command that plans a program wants.
    """
    return _load(path, None, cell, project_root, robot_loader, require_program)


def load_text(text: str, path: str = "<input>", *, cell: str | None = None, project_root: str | None = None,
              robot_loader: RobotLoader | None = None, require_program: bool = False) -> FrontendResult:
    """As load_program, from a string; relative paths resolve from `path`'s directory."""
    return _load(path, text, cell, project_root, robot_loader, require_program)


def run_passes(path: str, text: str | None = None, cell: str | None = None, project_root: str | None = None,
               robot_loader: RobotLoader | None = None) -> FrontendState:
    """The front end's passes over `path` (or `text` as its content), returning their whole
    state: what load_program returns and also the parsed modules of every file read (the
    language server's symbol index). Never raises for bad input."""
    from rmot.compiler.passes.state import FrontendState  # late: loads numpy only when this runs
    from rmot.compiler.pipeline import run  # late: loads coal only when this runs

    root = os.path.abspath(project_root) if project_root else os.path.dirname(os.path.abspath(path))
    roots = (root,) if cell is None else (root, os.path.dirname(os.path.abspath(cell)))
    state = FrontendState(path=path, roots=roots, reporter=Reporter(), robot_loader=robot_loader or default_robot_loader,
                          text=text, cell_path=cell)
    try:
        state = run(state)
    except RecursionError:  # absurdly deep nesting: still a diagnostic, not a traceback
        from rmot.lang import check_codes as codes  # late: optional, tried where used

        state.reporter.error(codes.TOO_LARGE_UNROLLED, "nesting must be at most a few hundred levels deep (got deeper)", None)
    return state


def _load(path: str, text: str | None, cell: str | None, project_root: str | None,
          robot_loader: RobotLoader | None, require_program: bool = False) -> FrontendResult:
    state = run_passes(path, text, cell, project_root, robot_loader)
    if require_program and state.program is None and not state.reporter.has_errors:
        from rmot.lang import check_codes as codes  # late: tests replace it (monkeypatch): read at call time

        state.reporter.error(codes.NO_PROGRAM, f"'{path}' must contain a program (got none: only a cell or declarations)", None)
    diagnostics = state.reporter.sink.items
    program = None if any(d.is_error for d in diagnostics) else state.program
    read = [state.main.path] if state.main is not None else []
    read += [*state.modules, *([state.cell_module.path] if state.cell_module is not None else [])]
    sources = tuple(sorted({os.path.abspath(p) for p in read}))
    return FrontendResult(program, state.cell, diagnostics, sources)
