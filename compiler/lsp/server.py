"""The pygls server: one Analysis per open document, plan jobs in the background.

On open and on every change the front end runs at once on the new text (analysis.py) and
its diagnostics are published; then, after a short pause without typing, a PlanJob
(planning.py) plans and verifies the same text in another process, and its findings are
published together with the front end's, if the text has not changed meanwhile. A change
cancels the job of the text before it. Every handler answers from the latest analysis;
an exception inside one is logged and answered as "nothing here", never a crash.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any, TypeVar

from lsprotocol import types as lsp
from pygls.lsp.server import LanguageServer

from rmot.compiler.lsp import features
from rmot.compiler.lsp.analysis import Analysis, analyze, path_of
from rmot.compiler.lsp.encoding import ClientUnits
from rmot.compiler.lsp.planning import PlanJob, PlanResult
from rmot.compiler.cli import _version

__all__ = ["RmotServer", "build_server"]

PLAN_DELAY_S = 0.3  # typing pause before a plan job starts
PLAN_WAIT_S = 20.0  # how long a hover waits for a running plan job
T = TypeVar("T")
log = logging.getLogger(__name__)


class RmotServer(LanguageServer):
    """A LanguageServer that keeps, per document URI, its analysis, plan and plan job."""

    def __init__(self) -> None:

        super().__init__("rmot", _version())
        self.analyses: dict[str, Analysis] = {}
        # the latest analysis whose document parsed: the features' names and positions while
        # the text being typed does not parse (a half-typed statement is a syntax error)
        self.parsed: dict[str, Analysis] = {}
        self.plans: dict[str, PlanResult] = {}
        self.jobs: dict[str, asyncio.Task[None]] = {}
        self.planning = True  # `rmot lsp --no-plan`: front-end diagnostics only

    def refresh(self, uri: str) -> None:
        """Analyse the document's current text, publish, and start its plan job."""
        document = self.workspace.get_text_document(uri)
        analysis = _safely(lambda: analyze(path_of(uri), document.source, document.version), None)
        if analysis is None:
            return
        self.analyses[uri] = analysis
        if analysis.module is not None or uri not in self.parsed:
            self.parsed[uri] = analysis
        self.plans.pop(uri, None)
        self._publish(uri, analysis, None)
        old = self.jobs.pop(uri, None)
        if old is not None:
            old.cancel()
        if self.planning and analysis.program is not None:
            self.jobs[uri] = asyncio.get_running_loop().create_task(self._plan(uri, analysis))

    async def planned(self, uri: str) -> None:
        """Wait (at most PLAN_WAIT_S) for the document's plan job, if one is running: a hover
        asked right after a change still names the planned joints. A client that gives up
        cancels the request; the job goes on."""
        job = self.jobs.get(uri)
        if job is None or job.done():
            return
        try:
            await asyncio.wait_for(asyncio.shield(job), PLAN_WAIT_S)
        except (asyncio.TimeoutError, asyncio.CancelledError):  # superseded or slow: answer without
            pass

    def completing(self, uri: str, text: str, line: int) -> Analysis | None:
        """The analysis completion needs while the statement being typed does not parse: the
        text with that line blanked (every other position unchanged). None when the current
        text parses (the usual analysis is right) or the blanked one does not either."""
        current = self.analyses.get(uri)
        if current is None or current.module is not None:
            return None
        lines = text.split("\n")
        if line < len(lines):
            lines[line] = ""
        blanked = analyze(current.path, "\n".join(lines))
        return blanked if blanked.module is not None else None

    def close(self, uri: str) -> None:
        job = self.jobs.pop(uri, None)
        if job is not None:
            job.cancel()
        self.analyses.pop(uri, None)
        self.parsed.pop(uri, None)
        self.plans.pop(uri, None)
        self.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri, []))

    async def _plan(self, uri: str, analysis: Analysis) -> None:
        await asyncio.sleep(PLAN_DELAY_S)
        job = PlanJob(analysis.path, analysis.text)
        try:
            result = await asyncio.get_running_loop().run_in_executor(None, job.result)
        finally:
            job.cancel()
        if result is None or self.analyses.get(uri) is not analysis:
            return
        self.plans[uri] = result
        self._publish(uri, analysis, result)
        workspace = self.client_capabilities.workspace
        hints = workspace.inlay_hint if workspace is not None else None
        if hints is not None and hints.refresh_support:
            self.workspace_inlay_hint_refresh(None)

    def _publish(self, uri: str, analysis: Analysis, plan: PlanResult | None) -> None:
        found = [analysis.to_lsp(d) for d in analysis.diagnostics]
        if plan is not None:
            found += plan.diagnostics
        found = self.units(uri).out(found)
        self.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri, found, version=analysis.version))

    def units(self, uri: str) -> ClientUnits:
        """Column conversion for a request about `uri` (encoding.py)."""
        document = self.workspace.get_text_document(uri)

        def lines_of(other: str) -> list[str]:
            if other == uri:
                return list(document.lines)
            analysis = self.parsed.get(uri)
            module = analysis.modules.get(path_of(other)) if analysis is not None else None
            if module is not None:
                return module.file.text.split("\n")
            try:
                with open(path_of(other), encoding="utf-8") as f:
                    return f.read().split("\n")
            except (OSError, ValueError):
                return []

        return ClientUnits(document.position_codec, uri, lines_of)


def _safely(answer: Callable[[], T], default: T) -> T:
    """answer(); a bug in a feature is logged and answered with `default` (the server stays up)."""
    try:
        return answer()
    except Exception:
        log.exception("rmot lsp: a request failed")
        return default


def build_server(planning: bool = True) -> RmotServer:
    server = RmotServer()
    server.planning = planning
    _register_documents(server)
    _register_features(server)
    return server


def _register_documents(server: RmotServer) -> None:
    @server.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: RmotServer, params: lsp.DidOpenTextDocumentParams) -> None:
        ls.refresh(params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: RmotServer, params: lsp.DidChangeTextDocumentParams) -> None:
        ls.refresh(params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: RmotServer, params: lsp.DidSaveTextDocumentParams) -> None:
        """The saved file and every open document that reads it (an import, a cell)."""
        saved = path_of(params.text_document.uri)
        for uri, analysis in list(ls.analyses.items()):
            if uri == params.text_document.uri or saved in analysis.modules:
                ls.refresh(uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: RmotServer, params: lsp.DidCloseTextDocumentParams) -> None:
        ls.close(params.text_document.uri)


def _register_features(server: RmotServer) -> None:
    def analysis_of(uri: str) -> Analysis | None:
        return server.parsed.get(uri)

    def on(uri: str, answer: Callable[[Analysis, ClientUnits], Any], default: Any) -> Any:
        """answer(analysis, units) in client units; `default` when there is nothing to ask."""
        found = analysis_of(uri)
        if found is None:
            return default
        units = server.units(uri)
        return _safely(lambda: units.out(answer(found, units)), default)

    @server.feature(lsp.TEXT_DOCUMENT_DEFINITION)
    def definition(ls: RmotServer, params: lsp.DefinitionParams) -> list[lsp.Location]:
        return on(params.text_document.uri,  # type: ignore[no-any-return]
                  lambda a, u: features.definition(a, u.position_in(params.position)), [])

    @server.feature(lsp.TEXT_DOCUMENT_REFERENCES)
    def references(ls: RmotServer, params: lsp.ReferenceParams) -> list[lsp.Location]:
        return on(params.text_document.uri, lambda a, u: features.references(  # type: ignore[no-any-return]
            a, u.position_in(params.position), params.context.include_declaration), [])

    @server.feature(lsp.TEXT_DOCUMENT_HOVER)
    async def hover(ls: RmotServer, params: lsp.HoverParams) -> lsp.Hover | None:
        uri = params.text_document.uri
        await ls.planned(uri)
        return on(uri, lambda a, u: features.hover(  # type: ignore[no-any-return]
            a, ls.plans.get(uri), u.position_in(params.position)), None)

    @server.feature(lsp.TEXT_DOCUMENT_COMPLETION, lsp.CompletionOptions(trigger_characters=[" "]))
    def completion(ls: RmotServer, params: lsp.CompletionParams) -> lsp.CompletionList:
        uri = params.text_document.uri
        text = ls.workspace.get_text_document(uri).source
        typed_space = params.context is not None and params.context.trigger_character == " "
        position = ls.units(uri).position_in(params.position)
        found = _safely(lambda: ls.completing(uri, text, position.line), None) or analysis_of(uri)
        none: list[lsp.CompletionItem] = []
        items = none if found is None else _safely(
            lambda: features.completion(found, text, position, typed_space), none)
        return lsp.CompletionList(is_incomplete=False, items=items)

    @server.feature(lsp.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def symbols(ls: RmotServer, params: lsp.DocumentSymbolParams) -> list[lsp.DocumentSymbol]:
        return on(params.text_document.uri, lambda a, u: features.document_symbols(a), [])  # type: ignore[no-any-return]

    @server.feature(lsp.TEXT_DOCUMENT_INLAY_HINT)
    def inlay(ls: RmotServer, params: lsp.InlayHintParams) -> list[lsp.InlayHint]:
        uri = params.text_document.uri
        return on(uri, lambda a, u: features.inlay_hints(  # type: ignore[no-any-return]
            a, ls.plans.get(uri), lsp.Range(u.position_in(params.range.start), u.position_in(params.range.end))), [])
