"""The front end's passes, in order, in one place (Cairo's default_pass_manager idea).

Each pass takes the FrontendState and returns a new one; diagnostics go to the shared
Reporter, so every pass runs even after errors and a file's problems come in one report.
"""

from __future__ import annotations

from collections.abc import Callable

from rmot.compiler.passes.assign_uids import assign_uids
from rmot.compiler.passes.check_syncs import check_syncs
from rmot.compiler.passes.load_files import load_sources
from rmot.compiler.passes.lower_cell import lower_cell
from rmot.compiler.passes.lower_program import lower_program
from rmot.compiler.passes.procs import check_recursion, check_uncalled_procs
from rmot.compiler.passes.scopes import declare_file_scopes
from rmot.compiler.passes.state import FrontendState

__all__ = ["PASSES", "Pass", "run"]

Pass = Callable[[FrontendState], FrontendState]

PASSES: tuple[Pass, ...] = (
    load_sources,          # read + parse the file, its imports and its cell (E0xx, E5xx)
    lower_cell,            # cell -> ir.Cell; robots from the library; cell scope
    declare_file_scopes,   # imports, consts, targets, procs of every file; duplicates
    lower_program,         # settings resolved, loops unrolled, procs inlined, frames composed
    check_uncalled_procs,  # unknown names in procs no task calls
    check_recursion,       # procs calling themselves (even if never called)
    check_syncs,           # sync barriers pair up across tasks
    assign_uids,           # unique instruction numbers in source order
)


def run(state: FrontendState, passes: tuple[Pass, ...] = PASSES) -> FrontendState:
    for p in passes:
        state = p(state)
    return state
