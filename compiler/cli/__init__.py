"""The `rmot` command line: the only place with file I/O and exit codes.

Each subcommand lives in its own module and is imported only when it runs, so that
`rmot --help` stays fast (pinocchio, scipy and numba load only when needed).

Exit codes: 0 clean, 1 findings of severity error, 2 usage or input error.
"""

from __future__ import annotations

import gc
import importlib

import click
import errno
import os
import sys
from importlib.metadata import PackageNotFoundError, version

__all__ = ["main", "EXIT_OK", "EXIT_FINDINGS", "EXIT_INPUT"]

EXIT_OK = 0
EXIT_FINDINGS = 1
EXIT_INPUT = 2

# name -> (module, attribute, one-line help); the module defines a click command.
COMMANDS: dict[str, tuple[str, str, str]] = {
    "check": ("rmot.compiler.cli.check_cmd", "check", "Parse, plan and verify programs; report findings."),
    "compile": ("rmot.compiler.cli.compile_cmd", "compile_", "Verify, then emit vendor programs."),
    "render": ("rmot.compiler.cli.render_cmd", "render", "Render a program to PNG, GIF, MP4, SVG or HTML."),
    "plan": ("rmot.compiler.cli.plan_cmd", "plan", "Plan a program; write the sampled trajectory."),
    "ir": ("rmot.compiler.cli.ir_cmd", "ir", "Dump the checked IR of a program."),
    "robots": ("rmot.compiler.cli.robots_cmd", "robots", "The robot library: list, show, fk, ik."),
    "merge-reports": ("rmot.compiler.cli.merge_cmd", "merge_reports_cmd", "Merge the reports of `check --shard` runs."),
    "plot": ("rmot.compiler.cli.plot_cmd", "plot", "Plot joints, speeds, torques, TCP speed or the timeline."),
    "report": ("rmot.compiler.cli.report_cmd", "report", "Verify programs; write one HTML page with findings, plots, 3D view."),
    "reach": ("rmot.compiler.cli.reach_cmd", "reach", "Map a robot's reachable workspace and its singularities."),
    "place": ("rmot.compiler.cli.place_cmd", "place", "Find the best base pose for a robot in a region."),
    "compare": ("rmot.compiler.cli.compare_cmd", "compare", "Run one program on several arms and compare them."),
    "lsp": ("rmot.compiler.cli.lsp_cmd", "lsp_cmd", "Run the language server (LSP over stdio) for editors."),
    "import": ("rmot.compiler.cli.import_cmd", "import_", "Read RAPID, KRL, URScript, Fanuc TP or INFORM programs back into .rmot."),
    "diff": ("rmot.compiler.cli.diff_cmd", "diff", "What changed between two vendor programs (or one and its .rmot)."),
}


class LazyGroup(click.Group):
    """A click group that imports a subcommand's module only when that command runs."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        entry = COMMANDS.get(cmd_name)
        if entry is None:
            return None
        module_name, attr, _ = entry
        try:
            module = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:
            if exc.name != module_name:
                raise
            return _unavailable(cmd_name)
        return getattr(module, attr)  # type: ignore[no-any-return]

    def invoke(self, ctx: click.Context) -> object:
        """Run the subcommand; an exception it does not handle (a bug, not the input) is the
        one internal-error diagnostic E550 and exit 2, never a traceback (stages.py)."""
        try:
            return super().invoke(ctx)
        except (click.exceptions.ClickException, click.exceptions.Exit, click.exceptions.Abort):
            raise
        except Exception as exc:
            if _closed_output(exc):
                _end_quietly(ctx)
            from rmot.compiler.cli.stages import StageError, internal_error  # late: optional, tried where used
            from rmot.lang.diagnostics import render  # late: optional, tried where used

            where = f"`rmot {ctx.invoked_subcommand}`" if ctx.invoked_subcommand else "rmot"
            diag = exc.diagnostic if isinstance(exc, StageError) else internal_error(where, exc)
            click.echo(render(diag), err=True)
            ctx.exit(EXIT_INPUT)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = [(name, COMMANDS[name][2]) for name in self.list_commands(ctx)]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


# The exit status of a Unix tool killed by SIGPIPE as a shell reports it (128 + signal 13).
EXIT_CLOSED_OUTPUT = 128 + 13


def _closed_output(exc: BaseException) -> bool:
    """True when `exc` (or the error a stage wrapped) is a write to a pipe whose reader has gone
    (`rmot robots list | head -1`): not a bug, the reader had what it wanted."""

    while exc is not None:
        if isinstance(exc, OSError) and exc.errno == errno.EPIPE:
            return True
        exc = exc.__cause__  # type: ignore[assignment]
    return False


def _end_quietly(ctx: click.Context) -> None:
    """End as `yes | head -1` ends: no message, the SIGPIPE status; stdout is pointed at the
    null device first so that the interpreter's final flush does not fail on the closed pipe."""

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):  # stdout without a descriptor (a test runner's buffer)
        pass
    ctx.exit(EXIT_CLOSED_OUTPUT)


def _unavailable(name: str) -> click.Command:
    @click.command(name=name, help=COMMANDS[name][2])
    def cmd() -> None:
        raise click.ClickException(f"'{name}' is not available in this build")

    return cmd


def _version() -> str:

    try:
        return version("rmot")
    except PackageNotFoundError:  # running from a source tree without an install
        return "0+unknown"


class _LazyVersion:
    """The installed version, looked up only when --version prints it (importlib.metadata is slow)."""

    def __str__(self) -> str:
        return _version()


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(_LazyVersion(), "--version", prog_name="rmot", message="%(prog)s %(version)s")  # type: ignore[arg-type]
def cli() -> None:
    """rmot — an off-line robot programming compiler.

    Write a task once in .rmot; check it against the work cell; emit it for every controller.
    """


# The cyclic collector's schedule for an `rmot` process (see main).
GC_THRESHOLDS = (100_000, 50, 1000)


def main() -> None:
    """The console-script entry point; click maps usage errors to exit code 2."""
    tune_gc()
    cli(prog_name="rmot")


def tune_gc() -> None:
    """Collect cycles rarely: the command's process is the CLI's, so the CLI owns its collector
    (the library never touches a caller's). Parsing and lowering allocate hundreds of thousands
    of small acyclic objects (tokens, AST and IR nodes, spans), and Python's default schedule
    (a young collection every 700 allocations, the older generations walked again and again as
    those objects age) took half the front end's time on a 10,000-line file. Every object is
    still freed by reference counting, and garbage cycles by the next collection."""
    gc.set_threshold(*GC_THRESHOLDS)
