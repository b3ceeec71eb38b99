"""`rmot lsp` driven over stdio by a real LSP client (pytest-lsp), as an editor would.

One session: initialize, open a program with a typo and a collision, fix the typo, hover a
target, go to a proc's definition in an imported file, complete after `move joint `. The
independent witness of the diagnostics is `rmot check --format json` run as its own process
on the same text saved to disk: same codes, same ranges (the LSP's are 0-based).
"""

from __future__ import annotations

import asyncio
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlparse

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient

_RMOT = shutil.which("rmot", path=os.path.dirname(sys.executable)) or "rmot"

LIB = """\
# procs the program imports
proc lift(p: pose) {
  move linear shift(p, z=100mm)
}

proc put(p: pose) {
  move linear p frame pallet
}
"""

# examples/collision.rmot's program (the gripper hits the table on the way to `slot`, here
# in the imported proc `put`), with the typo `hme` on its last line
PROGRAM = """\
import "lib/moves.rmot"

program collide on r1 {
  tool gripper
  speed 250 mm/s
  zone fine

  target home = joints(0, -10, 10, 0, 90, 0) deg
  target nest = pose(x=-100mm, z=30mm, rx=180deg)
  target slot = pose(x=100mm, y=100mm, z=30mm, rx=180deg)

  move joint home
  move joint shift(nest, z=100mm) frame table_top
  move linear nest frame table_top speed 100 mm/s
  set out[1] = on
  wait 300 ms
  put(slot)
  set out[1] = off
  frame pallet
  lift(slot)
  move joint hme
}
"""
TYPO_LINE = 20  # 0-based line of `move joint hme`
CAPABILITIES = types.ClientCapabilities(
    text_document=types.TextDocumentClientCapabilities(
        hover=types.HoverClientCapabilities(content_format=[types.MarkupKind.Markdown, types.MarkupKind.PlainText]),
        publish_diagnostics=types.PublishDiagnosticsClientCapabilities(related_information=True, version_support=True),
        completion=types.CompletionClientCapabilities(),
        definition=types.DefinitionClientCapabilities(),
        document_symbol=types.DocumentSymbolClientCapabilities(hierarchical_document_symbol_support=True),
        inlay_hint=types.InlayHintClientCapabilities(),
    ),
)


@pytest_lsp.fixture(config=ClientServerConfig(server_command=[_RMOT, "lsp"]))
async def client(lsp_client: LanguageClient) -> Any:
    await lsp_client.initialize_session(types.InitializeParams(capabilities=CAPABILITIES))
    yield
    await lsp_client.shutdown_session()


@pytest.fixture
def project(tmp_path: Path) -> Path:
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "moves.rmot").write_text(LIB, encoding="utf-8")
    main = tmp_path / "collide.rmot"
    main.write_text(PROGRAM, encoding="utf-8")
    return main


async def _diagnostics_until(client: LanguageClient, uri: str, done: Any, timeout: float = 120.0) -> list[types.Diagnostic]:
    """Wait for published diagnostics of `uri` for which done(diagnostics) holds."""
    async def wait() -> list[types.Diagnostic]:
        while not (uri in client.diagnostics and done(list(client.diagnostics[uri]))):
            await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        return list(client.diagnostics[uri])

    return await asyncio.wait_for(wait(), timeout)


def _cli_check(path: Path) -> list[dict[str, Any]]:
    """The witness: `rmot check --format json` in its own process on the saved file."""
    run = subprocess.run([_RMOT, "check", str(path), "--format", "json"], capture_output=True, text=True, timeout=300)
    return json.loads(run.stdout)["programs"][0]["diagnostics"]  # type: ignore[no-any-return]


def _same_as_cli(lsp_diags: list[types.Diagnostic], cli: list[dict[str, Any]], uri: str) -> None:
    """Same codes at the same places: the CLI's file:line:col is the LSP's range in the
    document, or its "reported here" related location for a finding in an imported file."""
    ours = []
    for d in lsp_diags:
        here = [r.location for r in d.related_information or [] if r.message == "reported here"]
        where = here[0] if here else types.Location(uri, d.range)
        r = where.range
        ours.append((d.code, unquote(urlparse(where.uri).path),
                     r.start.line + 1, r.start.character + 1, r.end.line + 1, r.end.character + 1))
    theirs = [(d["code"], d["file"], d["line"], d["col"], d["end_line"], d["end_col"]) for d in cli]
    assert sorted(map(str, ours)) == sorted(map(str, theirs))


def _change(client: LanguageClient, uri: str, version: int, text: str) -> None:
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        types.VersionedTextDocumentIdentifier(version=version, uri=uri),
        [types.TextDocumentContentChangeWholeDocument(text=text)]))


@pytest.mark.asyncio
async def test_session(client: LanguageClient, project: Path) -> None:
    uri = project.as_uri()
    client.text_document_did_open(types.DidOpenTextDocumentParams(
        types.TextDocumentItem(uri=uri, language_id="rmot", version=1, text=PROGRAM)))
    first = await _diagnostics_until(client, uri, lambda ds: any(d.code == "E101" for d in ds))
    typo = next(d for d in first if d.code == "E101")
    assert (typo.range.start.line, typo.range.start.character, typo.range.end.character) == (TYPO_LINE, 13, 16)
    assert "did you mean 'home'" in typo.message
    _same_as_cli(first, _cli_check(project), uri)

    fixed = PROGRAM.replace("move joint hme", "move joint home")
    _change(client, uri, 2, fixed)
    found = await _diagnostics_until(client, uri, lambda ds: any(d.code == "E300" for d in ds))
    assert not any(d.code == "E101" for d in found)
    collision = next(d for d in found if d.code == "E300")
    assert collision.range.start.line == 16  # shown at the call `put(slot)` in this document,
    (inside,) = collision.related_information or []  # with the proc's move as related location
    assert inside.location.uri == (project.parent / "lib" / "moves.rmot").as_uri()
    assert inside.location.range.start.line == 6  # `move linear p frame pallet`
    assert "table" in collision.message
    project.write_text(fixed, encoding="utf-8")
    _same_as_cli(found, _cli_check(project), uri)

    await _hover_target(client, uri)
    await _definition_in_import(client, uri, project)
    await _complete_after_move_joint(client, uri)
    # the server wrote nothing beside the sources (no vendor program, no report)
    assert sorted(str(p.relative_to(project.parent)) for p in project.parent.rglob("*")) == [
        "collide.rmot", "lib", "lib/moves.rmot"]


async def _hover_target(client: LanguageClient, uri: str) -> None:
    """`home` on `move joint home`: its joints (J1..J6 in degrees, as written) and times."""
    hover = await client.text_document_hover_async(types.HoverParams(
        types.TextDocumentIdentifier(uri), types.Position(line=11, character=14)))
    assert hover is not None
    text = hover.contents.value  # type: ignore[union-attr]
    assert "target" in text and "home" in text
    for joint, degrees in zip(("J1", "J2", "J3", "J4", "J5", "J6"), (0, -10, 10, 0, 90, 0)):
        assert f"{joint} {degrees:.2f}°" in text
    assert "configuration:" in text and "time:" in text


async def _definition_in_import(client: LanguageClient, uri: str, project: Path) -> None:
    found = await client.text_document_definition_async(types.DefinitionParams(
        types.TextDocumentIdentifier(uri), types.Position(line=19, character=3)))  # `lift(slot)`
    assert isinstance(found, list) and len(found) == 1
    location = found[0]
    assert isinstance(location, types.Location)
    assert location.uri == (project.parent / "lib" / "moves.rmot").as_uri()
    # `proc lift(...)` is line 2 of lib/moves.rmot, the name at columns 6..9 (1-based)
    assert (location.range.start.line, location.range.start.character, location.range.end.character) == (1, 5, 9)


async def _complete_after_move_joint(client: LanguageClient, uri: str) -> None:
    text = PROGRAM.replace("move joint hme", "move joint home") .replace("  move joint home\n}", "  move joint \n}")
    _change(client, uri, 3, text)
    await _diagnostics_until(client, uri, lambda ds: True)
    result = await client.text_document_completion_async(types.CompletionParams(
        types.TextDocumentIdentifier(uri), types.Position(line=TYPO_LINE, character=13)))
    items = result.items if isinstance(result, types.CompletionList) else result or []
    assert sorted(i.label for i in items) == ["home", "nest", "slot"]


def _open(client: LanguageClient, uri: str, text: str) -> None:
    client.text_document_did_open(types.DidOpenTextDocumentParams(
        types.TextDocumentItem(uri=uri, language_id="rmot", version=1, text=text)))


@pytest.mark.asyncio
async def test_completion_in_a_document_that_never_parsed(client: LanguageClient, project: Path) -> None:
    """`move joint ` half typed from the first keystroke: the targets in scope all the same."""
    uri = project.as_uri()
    _open(client, uri, PROGRAM.replace("move joint hme", "move joint "))
    (syntax,) = await _diagnostics_until(client, uri, lambda ds: bool(ds))
    assert syntax.code is not None and str(syntax.code).startswith("E0")
    result = await client.text_document_completion_async(types.CompletionParams(
        types.TextDocumentIdentifier(uri), types.Position(line=TYPO_LINE, character=13)))
    items = result.items if isinstance(result, types.CompletionList) else result or []
    assert sorted(i.label for i in items) == ["home", "nest", "slot"]


@pytest.mark.asyncio
async def test_hover_right_after_a_change_waits_for_the_plan(client: LanguageClient, project: Path) -> None:
    """A hover sent before the plan's diagnostics arrived still names the planned joints."""
    uri = project.as_uri()
    _open(client, uri, PROGRAM.replace("move joint hme", "move joint home"))
    await _diagnostics_until(client, uri, lambda ds: True)  # the front end's (no E300 yet)
    hover = await client.text_document_hover_async(types.HoverParams(
        types.TextDocumentIdentifier(uri), types.Position(line=9, character=10)))  # `target slot`
    assert hover is not None
    text = hover.contents.value  # type: ignore[union-attr]
    assert "in frame `pallet`" in text and "in world" in text
    assert all(f"J{j} " in text for j in range(1, 7)) and "(planning...)" not in text


@pytest.mark.asyncio
async def test_saving_an_import_refreshes_the_program(client: LanguageClient, project: Path) -> None:
    """The proc renamed in the saved library: the program calling it gets E1xx at once."""
    uri, lib = project.as_uri(), project.parent / "lib" / "moves.rmot"
    _open(client, uri, PROGRAM)
    await _diagnostics_until(client, uri, lambda ds: any(d.code == "E101" for d in ds))
    lib.write_text(LIB.replace("proc put(", "proc place("), encoding="utf-8")
    client.text_document_did_save(types.DidSaveTextDocumentParams(types.TextDocumentIdentifier(lib.as_uri())))
    found = await _diagnostics_until(client, uri, lambda ds: any("put" in d.message for d in ds))
    (call,) = [d for d in found if "put" in d.message]
    assert call.range.start.line == 16 and str(call.code).startswith("E1")


@pytest.mark.asyncio
async def test_typing_fast_never_breaks_the_server(client: LanguageClient, project: Path) -> None:
    """The program typed in 60 quick changes (each a prefix, most of them not parsing): the
    server stays up, the last version's diagnostics are the ones shown, requests answer."""
    uri = project.as_uri()
    text = PROGRAM.replace("move joint hme", "move joint home")
    _open(client, uri, "")
    step = max(1, len(text) // 60)
    versions = list(range(2, 2 + len(range(step, len(text), step))))
    for version, cut in zip(versions, range(step, len(text), step)):
        _change(client, uri, version, text[:cut])
        hover = await client.text_document_hover_async(types.HoverParams(
            types.TextDocumentIdentifier(uri), types.Position(line=cut % 20, character=3)))
        assert hover is None or hover.contents is not None
    _change(client, uri, versions[-1] + 1, text)
    found = await _diagnostics_until(client, uri, lambda ds: any(d.code == "E300" for d in ds))
    assert [d.code for d in found] == ["E300"]
    symbols = await client.text_document_document_symbol_async(types.DocumentSymbolParams(
        types.TextDocumentIdentifier(uri)))
    assert [s.name for s in symbols or []] == ["collide"]


@pytest.mark.asyncio
async def test_columns_are_utf16_code_units(client: LanguageClient, project: Path) -> None:
    """An emoji (two UTF-16 units) before a name on its line: the range is in the client's
    units (UTF-16, the LSP's default), counted here by Python's own UTF-16 encoder."""
    uri = project.as_uri()
    prefix = "  native rapid \"\U0001F600\"; move joint "
    before_lift = "  native rapid \"\U0001F600\U0001F600\"; "
    text = PROGRAM.replace("  move joint hme", prefix + "hme").replace("  lift(slot)", before_lift + "lift(slot)")
    _open(client, uri, text)
    found = await _diagnostics_until(client, uri, lambda ds: any(d.code == "E101" for d in ds))
    (typo,) = [d for d in found if d.code == "E101"]
    start = len(prefix.encode("utf-16-le")) // 2
    assert (typo.range.start.line, typo.range.start.character, typo.range.end.character) == (TYPO_LINE, start, start + 3)
    # and a position coming in: the `t` of `lift` in UTF-16 units (in code points it would
    # be two characters further, on `slot`)
    at = len(before_lift.encode("utf-16-le")) // 2 + 3
    (location,) = await client.text_document_definition_async(types.DefinitionParams(
        types.TextDocumentIdentifier(uri), types.Position(line=TYPO_LINE - 1, character=at))) or []
    assert location.uri.endswith("lib/moves.rmot")
    assert location.range.start.line == 1  # `lift` in lib/moves.rmot
