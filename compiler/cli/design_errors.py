"""How the design commands (`rmot reach`, `rmot place`, `rmot compare`) end on bad input: a
diagnostic with its registered code (compiler/design/codes.py), rendered `rmot: error[E80x]: ...`
(no span: the value came from a command-line option, which the message names), exit 2."""

from __future__ import annotations

import sys
from typing import Any, NoReturn

import click

from rmot.compiler.cli import EXIT_INPUT
from rmot.lang.diagnostics import render, Diagnostic, Severity
from rmot.compiler.cli.oserrors import output_failed
import errno
import os

__all__ = ["fail", "fail_code", "fail_output", "require_output_dir"]


def fail(diagnostic: Any) -> NoReturn:

    click.echo(render(diagnostic), err=True)
    sys.exit(EXIT_INPUT)


def fail_code(code: Any, message: str) -> NoReturn:

    fail(Diagnostic(code, Severity.ERROR, message, None))


def fail_output(what: str, path: str, exc: OSError) -> NoReturn:
    """An -o file that cannot be written: the project's E520 (rmot.lang.check_codes.OUTPUT_FAILED)."""

    click.echo(output_failed(what, path, exc), err=True)
    sys.exit(EXIT_INPUT)


def require_output_dir(what: str, path: str) -> None:
    """Before minutes of search: an -o file whose folder does not exist ends the command (E520) now,
    not after the work (the atomic write would fail the same way then)."""

    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        fail_output(what, path, FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), folder))
