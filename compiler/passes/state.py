"""The value the front-end passes hand on: each pass returns a copy with its results filled in.

The Reporter (diagnostics) and the robot loader are shared services, not results.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from rmot.lang import ir
from rmot.compiler.passes.context import Entry, Reporter, RobotInfo, RobotLoader, Scope
from rmot.lang import ast
from rmot.lang.record import record

__all__ = ["FrontendState", "LoadedModule"]


@dataclass
class LoadedModule:
    path: str  # absolute
    module: ast.Module
    imports: list[str] = field(default_factory=list)  # absolute paths, in source order


@record
class FrontendState:
    path: str  # the main file as given
    roots: tuple[str, ...]  # directories every named path must stay inside
    reporter: Reporter
    robot_loader: RobotLoader
    text: str | None = None  # load_text: the main file's text
    cell_path: str | None = None  # --cell
    main: LoadedModule | None = None
    libraries: tuple[LoadedModule, ...] = ()  # imported files, dependencies first
    modules: dict[str, LoadedModule | None] = field(default_factory=dict)
    cell_module: LoadedModule | None = None
    cell_is_default: bool = False
    cell: ir.Cell | None = None
    cell_scope: Scope | None = None
    robots: dict[str, RobotInfo] = field(default_factory=dict)
    module_scopes: dict[str, Scope] = field(default_factory=dict)  # path -> its top-level scope
    program: ir.Program | None = None
    procs: tuple[Entry, ...] = ()  # every proc declared in a module (scopes.declare_module_procs)
    called_procs: set[int] = field(default_factory=set)  # id() of procs some task calls (lowering)
