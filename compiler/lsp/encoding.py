"""Columns as the client counts them: UTF-16 code units unless the client asked for another.

The front end counts columns in characters (code points: lang/source.py); the LSP's
`character` is in the negotiated position encoding (UTF-16 by default, where a character
beyond the Basic Multilingual Plane, e.g. an emoji in a string, is two units; UTF-8 where a
non-ASCII character is 2 to 4). `ClientUnits` converts at the server's boundary, with
pygls's PositionCodec: positions coming in, and the ranges of the values going out, each
against the lines of the file it points into.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence
from typing import Any

from lsprotocol import types as lsp
from pygls.workspace import PositionCodec

__all__ = ["ClientUnits"]


class ClientUnits:
    """Conversion for one request: `lines_of(uri)` gives the lines of any file it names."""

    def __init__(self, codec: PositionCodec, document_uri: str, lines_of: Callable[[str], Sequence[str]]) -> None:
        self.codec = codec
        self.uri = document_uri
        self.lines_of = lines_of
        self.identity = codec.encoding == lsp.PositionEncodingKind.Utf32

    def position_in(self, position: lsp.Position) -> lsp.Position:
        """A client position in this document -> lines and characters (code points)."""
        if self.identity:
            return position
        p = self.codec.position_from_client_units(self.lines_of(self.uri), position)
        return lsp.Position(p.line, p.character)

    def out(self, value: Any) -> Any:
        """`value` (a result the features made) with every range in client units."""
        if self.identity or value is None:
            return value
        if isinstance(value, list):
            return [self.out(v) for v in value]
        if isinstance(value, lsp.Location):
            return lsp.Location(value.uri, self._range(value.range, value.uri))
        value = copy.copy(value)  # the features' values may be kept (a plan's findings): never edited
        if isinstance(value, lsp.Diagnostic):
            value.range = self._range(value.range, self.uri)
            value.related_information = [lsp.DiagnosticRelatedInformation(self.out(r.location), r.message)
                                         for r in value.related_information or []] or None
        elif isinstance(value, lsp.Hover) and value.range is not None:
            value.range = self._range(value.range, self.uri)
        elif isinstance(value, lsp.DocumentSymbol):
            value.range = self._range(value.range, self.uri)
            value.selection_range = self._range(value.selection_range, self.uri)
            value.children = self.out(value.children)
        elif isinstance(value, lsp.InlayHint):
            value.position = self.codec.position_to_client_units(self.lines_of(self.uri), value.position)
        return value

    def _range(self, r: lsp.Range, uri: str) -> lsp.Range:
        return self.codec.range_to_client_units(self.lines_of(uri), r)
