"""`rmot lsp`: the language server over stdio (compiler/lsp), for any LSP client.

An editor starts it as `rmot lsp` and talks JSON-RPC on its stdin/stdout; nothing else may
be printed there, so the server logs to stderr (or to --log FILE). It reads the same files
and caches as `rmot check` and never writes a vendor program.
"""

from __future__ import annotations

import logging

import click

__all__ = ["lsp_cmd"]


@click.command("lsp")
@click.option("--stdio", is_flag=True, help="Talk on stdin/stdout (the default; accepted for clients that pass it).")
@click.option("--no-plan", is_flag=True, help="Front-end diagnostics only: never plan or verify in the background.")
@click.option("--log", "log_file", type=click.Path(dir_okay=False), default=None, help="Write the server's log to FILE.")
def lsp_cmd(stdio: bool, no_plan: bool, log_file: str | None) -> None:
    """Run the language server on stdin/stdout: diagnostics, hover, definition, completion."""
    from rmot.compiler.lsp.server import build_server  # late: loads coal only when this runs

    logging.basicConfig(filename=log_file, level=logging.INFO if log_file else logging.WARNING)
    build_server(planning=not no_plan).start_io()
