"""The editor features over an Analysis (front end) and, when ready, a PlanResult (plan).

Positions come in as the LSP's (0-based line and character) and are turned into the front
end's 1-based line and column once, here. Every function answers from values already
computed: nothing here parses, plans or writes.
"""

from __future__ import annotations

import functools
import math
import os
import re
from collections.abc import Iterator
from dataclasses import is_dataclass
from typing import Any

from lsprotocol import types as lsp

from rmot.lang import ir, ir_tree
from rmot.compiler.lsp.analysis import Analysis, lsp_range, uri_of
from rmot.compiler.lsp.index import Symbol, contains, field_names
from rmot.compiler.lsp.planning import MovePlan, PlanResult
from rmot.lang import ast
from rmot.lang.source import Span
from rmot.lang.units import UNIT_NAMES, UNIT_TABLE
from rmot.lang.lexer import TokenKinds

__all__ = ["completion", "definition", "document_symbols", "hover", "inlay_hints", "references",
           "statement_keywords"]

_MAX_SHOWN = 4  # instances of a move (loops, proc calls) listed in one hover


def _at(analysis: Analysis, position: lsp.Position) -> Symbol | None:
    return analysis.index.at(analysis.path, position.line + 1, position.character + 1)


def _location(symbol: Symbol) -> lsp.Location:
    return lsp.Location(uri_of(symbol.path), lsp_range(symbol.span))


def definition(analysis: Analysis, position: lsp.Position) -> list[lsp.Location]:
    symbol = _at(analysis, position)
    found = analysis.index.definition(symbol) if symbol is not None else None
    return [_location(found)] if found is not None else []


def references(analysis: Analysis, position: lsp.Position, include_declaration: bool) -> list[lsp.Location]:
    symbol = _at(analysis, position)
    found = analysis.index.definition(symbol) if symbol is not None else None
    if found is None:
        return []
    return [_location(s) for s in analysis.index.references(found) if include_declaration or s is not found]


# --------------------------------------------------------------------------- hover

def hover(analysis: Analysis, plan: PlanResult | None, position: lsp.Position) -> lsp.Hover | None:
    line, col = position.line + 1, position.character + 1
    literal = _unit_at(analysis, line, col)
    if literal is not None:
        return _markdown(_unit_text(literal[0], literal[1]), literal[2])
    statement = _statement_at(analysis, line, col)
    moves = _moves_from(analysis, statement.span) if statement is not None else []
    symbol = _at(analysis, position)
    found = analysis.index.definition(symbol) if symbol is not None else None
    if symbol is not None and found is not None:
        text = _symbol_text(analysis, plan, found)
        if found.kind == "proc" and moves:  # a call: what its body does here
            text += "\n\n" + _moves_text(analysis, plan, moves)
        return _markdown(text, symbol.span)
    if statement is not None and moves:
        return _markdown(_moves_text(analysis, plan, moves), statement.span)
    return None


def _markdown(text: str, span: Span) -> lsp.Hover:
    return lsp.Hover(lsp.MarkupContent(lsp.MarkupKind.Markdown, text), lsp_range(span))


def _unit_text(value: float, unit: str) -> str:
    """`150 mm` = **0.15 m**: a literal's value in SI units (lang/units.py's table)."""
    factor, dim = UNIT_TABLE[unit]
    si = {(1, 0, 0, 0, 0): "m", (0, 1, 0, 0, 0): "rad", (0, 0, 1, 0, 0): "s", (0, 0, 0, 1, 0): "kg",
          (0, 0, 0, 0, 1): "(fraction)", (1, 0, -1, 0, 0): "m/s", (0, 1, -1, 0, 0): "rad/s",
          (1, 0, -2, 0, 0): "m/s^2", (0, 1, -2, 0, 0): "rad/s^2", (1, 0, -2, 1, 0): "N",
          (2, 0, -2, 1, 0): "N*m"}.get(dim, "SI")
    return f"`{value:g} {unit}` = **{value * factor:.6g} {si}**"


def _symbol_text(analysis: Analysis, plan: PlanResult | None, symbol: Symbol) -> str:
    where = f"{os.path.relpath(symbol.path, os.path.dirname(analysis.path))}:{symbol.span.start.line}"
    head = f"**{symbol.kind}** `{symbol.name}` — declared at {where}"
    source = symbol.span.file.line_text(symbol.span.start.line).strip()
    lines = [head, "", f"```rmot\n{source}\n```"]
    if symbol.kind == "target":
        moves = [m for m in _all_moves(analysis) if m[1].target.name == symbol.name]
        if moves:
            lines += ["", _moves_text(analysis, plan, moves)]
    return "\n".join(lines)


def _moves_text(analysis: Analysis, plan: PlanResult | None, moves: list[tuple[ir.Task, ir.Move]]) -> str:
    planned = {m.uid: m for m in plan.moves} if plan is not None else {}
    bases = {r.name: r.base for r in analysis.program.cell.robots} if analysis.program else {}
    out: list[str] = []
    for task, move in moves[:_MAX_SHOWN]:
        out += [""] if out else []  # a blank line: each move its own Markdown paragraph
        out.append(f"**move {move.kind.name.lower()}** (task {task.name}, robot {task.robot})")
        target = move.target
        if isinstance(target, ir.CartesianTarget):
            frame = move.frame.name or "robot base"
            out.append(f"- in frame `{frame}`: {_pose_text(target.in_frame)}")
            world = bases[task.robot] * target.pose if task.robot in bases else None
            if world is not None:
                out.append(f"- in world: {_pose_text(world)}")
        p = planned.get(move.uid)
        if p is None:
            out.append("- planned joints: (planning...)" if plan is None else "- not planned")
            continue
        out.append(f"- joints: {_joints_text(p)}")
        if p.branch:
            out.append(f"- configuration: {p.branch}")
        if p.limit_margin[0]:
            joint, margin = p.limit_margin
            prismatic = joint <= len(p.joint_types) and p.joint_types[joint - 1] == "P"
            amount = f"{margin * 1000:.1f} mm" if prismatic else f"{math.degrees(margin):.1f}°"
            out.append(f"- joint-limit margin: J{joint} is {amount} from the end of its range")
        out.append(f"- time: {p.t_start:.3f} s → {p.t_end:.3f} s ({p.t_end - p.t_start:.3f} s)")
    if len(moves) > _MAX_SHOWN:
        out.append(f"\n… and {len(moves) - _MAX_SHOWN} more instances (loops, proc calls)")
    return "\n".join(out)


def _pose_text(pose: ir.Pose) -> str:
    x, y, z = (v * 1000 for v in pose.position)
    rx, ry, rz = (math.degrees(a) for a in pose.rpy())
    return f"x={x:.1f} y={y:.1f} z={z:.1f} mm, rx={rx:.1f} ry={ry:.1f} rz={rz:.1f} deg"


def _joints_text(p: MovePlan) -> str:
    parts = []
    for i, q in enumerate(p.joints):
        kind = p.joint_types[i] if i < len(p.joint_types) else "R"
        parts.append(f"J{i + 1} {q * 1000:.1f} mm" if kind == "P" else f"J{i + 1} {math.degrees(q):.2f}°")
    return ", ".join(parts)


def _all_moves(analysis: Analysis) -> list[tuple[ir.Task, ir.Move]]:
    if analysis.program is None:
        return []
    return [(task, i) for task in analysis.program.tasks for i in ir_tree.walk(task.body) if isinstance(i, ir.Move)]


def _moves_from(analysis: Analysis, statement: Span) -> list[tuple[ir.Task, ir.Move]]:
    """The moves a statement of this document lowered to: its own, or a proc call's body."""
    return [(t, m) for t, m in _all_moves(analysis) if m.span is not None and any(
        _same(s, statement) for s in (m.span, *m.span.expansion_chain()))]


def _same(a: Span, b: Span) -> bool:
    return a.start.offset == b.start.offset and os.path.abspath(a.path) == os.path.abspath(b.path)


def _nodes(node: Any) -> Iterator[Any]:
    """Every AST node under `node`, depth first."""
    if isinstance(node, tuple):
        for item in node:
            yield from _nodes(item)
    elif is_dataclass(node) and hasattr(node, "span"):
        yield node
        for name in field_names(type(node)):
            yield from _nodes(getattr(node, name))


def _unit_at(analysis: Analysis, line: int, col: int) -> tuple[float, str, Span] | None:
    """A literal with a unit under the cursor: `150 mm`, or the unit of `joints(...) deg`
    (then the value of 1 of that unit)."""
    module = analysis.module
    if module is None:
        return None
    for node in _nodes(module.body):
        if isinstance(node, ast.Number) and node.unit in UNIT_TABLE and contains(node.span, line, col):
            return node.value, node.unit, node.span
        if isinstance(node, ast.Joints) and node.unit in UNIT_TABLE and node.span.end.line == line \
                and node.span.end.col - len(node.unit) <= col <= node.span.end.col:
            return 1.0, node.unit, node.span
    return None


def _statement_at(analysis: Analysis, line: int, col: int) -> ast.Move | ast.CallStmt | None:
    module = analysis.module
    if module is None:
        return None
    found = None
    for node in _nodes(module.body):
        if isinstance(node, (ast.Move, ast.CallStmt)) and contains(node.span, line, col):
            found = node
    return found


# --------------------------------------------------------------------------- completion

_AFTER_NUMBER = re.compile(r"(?<![A-Za-z_0-9.])[0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?\s*([A-Za-z/^*%]*)$")
_AFTER_MOVE = re.compile(r"\bmove\s+(?:joint|linear|circular\s+via|circular\s+via\s+.*\bto)\s+([A-Za-z_0-9]*)$")
_STATEMENT_START = re.compile(r"^\s*([A-Za-z_]*)$")
_WORD = re.compile(r"([A-Za-z_0-9]*)$")
_KINDS = {"target": lsp.CompletionItemKind.Constant, "const": lsp.CompletionItemKind.Constant,
          "proc": lsp.CompletionItemKind.Function, "tool": lsp.CompletionItemKind.Variable,
          "frame": lsp.CompletionItemKind.Struct, "fixture": lsp.CompletionItemKind.Struct,
          "part": lsp.CompletionItemKind.Struct, "robot": lsp.CompletionItemKind.Class}


@functools.cache
def statement_keywords() -> tuple[str, ...]:
    """The keywords a statement may start with, read from the grammar's LALR tables: the
    keyword terminals the parser accepts at the start of a file (every statement may stand
    there; where it may not is the front end's E1xx, not the grammar's)."""
    from rmot.lang._tables import load_tables  # late: loads lark only when this runs

    tables = load_tables()
    accepted = tables.states[tables.start]
    kinds = TokenKinds(tables.terminals)
    return tuple(sorted(w for w, t in kinds.keywords.items() if t in accepted))


def completion(analysis: Analysis, text: str, position: lsp.Position, typed_space: bool = False) -> list[lsp.CompletionItem]:
    """Targets after `move joint `, units after a number, keywords and procs where a statement
    starts, else the names in scope. `typed_space`: the client asks because a space was typed
    (the trigger character), and then only the first two answer (not after every space)."""
    lines = text.split("\n")
    line = lines[position.line] if position.line < len(lines) else ""
    before = line[:position.character]
    line1, col1 = position.line + 1, position.character + 1
    unit = _AFTER_NUMBER.search(before)
    if unit is not None:
        return [lsp.CompletionItem(u, kind=lsp.CompletionItemKind.Unit, detail=_unit_text(1.0, u))
                for u in UNIT_NAMES if u.startswith(unit.group(1))]
    if _AFTER_MOVE.search(before):
        targets = analysis.index.visible(analysis.path, line1, col1, frozenset({"target"}))
        return [_item(s) for s in targets]
    if typed_space:
        return []
    prefix = (_WORD.search(before) or _WORD.search("")).group(1)  # type: ignore[union-attr]
    names = [_item(s) for s in analysis.index.visible(analysis.path, line1, col1) if s.name.startswith(prefix)]
    if _STATEMENT_START.match(before):
        keywords = [lsp.CompletionItem(k, kind=lsp.CompletionItemKind.Keyword)
                    for k in statement_keywords() if k.startswith(prefix)]
        return keywords + [n for n in names if n.kind == lsp.CompletionItemKind.Function]
    return names


def _item(symbol: Symbol) -> lsp.CompletionItem:
    return lsp.CompletionItem(symbol.name, kind=_KINDS.get(symbol.kind, lsp.CompletionItemKind.Variable),
                              detail=symbol.kind)


# --------------------------------------------------------------------------- outline, inlay hints

_SYMBOL_KINDS = {"program": lsp.SymbolKind.Module, "cell": lsp.SymbolKind.Namespace, "proc": lsp.SymbolKind.Function,
                 "target": lsp.SymbolKind.Constant, "const": lsp.SymbolKind.Constant, "robot": lsp.SymbolKind.Class,
                 "tool": lsp.SymbolKind.Object, "frame": lsp.SymbolKind.Object, "fixture": lsp.SymbolKind.Object,
                 "part": lsp.SymbolKind.Object, "model": lsp.SymbolKind.Class, "io": lsp.SymbolKind.Event}


def document_symbols(analysis: Analysis) -> list[lsp.DocumentSymbol]:
    """Top-level declarations, each with the declarations directly in its block."""
    mine = [d for d in analysis.index.declarations if d.path == analysis.path and d.kind in _SYMBOL_KINDS]
    out = []
    for top in (d for d in mine if d.scope is None):
        node_span = getattr(top.node, "span", top.span)
        children = [_doc_symbol(d, []) for d in mine if d.scope is not None and d.scope == node_span]
        out.append(_doc_symbol(top, children))
    return out


def _doc_symbol(symbol: Symbol, children: list[lsp.DocumentSymbol]) -> lsp.DocumentSymbol:
    span = getattr(symbol.node, "span", symbol.span)
    return lsp.DocumentSymbol(symbol.name, _SYMBOL_KINDS[symbol.kind], lsp_range(span), lsp_range(symbol.span),
                              detail=symbol.kind, children=children or None)


def inlay_hints(analysis: Analysis, plan: PlanResult | None, window: lsp.Range) -> list[lsp.InlayHint]:
    """Each move's planned duration after it (the sum over a proc call's moves; `×n` when a
    loop or several calls run it more than once)."""
    if plan is None or analysis.program is None:
        return []
    planned = {m.uid: m for m in plan.moves}
    sites: dict[tuple[int, int], list[float]] = {}
    ends: dict[tuple[int, int], Span] = {}
    for _task, move in _all_moves(analysis):
        p = planned.get(move.uid)
        site = _site_here(move.span, analysis.path) if move.span is not None else None
        if p is None or site is None:
            continue
        sites.setdefault((site.start.offset, move.uid), []).append(p.t_end - p.t_start)
        ends[(site.start.offset, move.uid)] = site
    totals: dict[int, tuple[Span, float, int]] = {}
    for (offset, _uid), durations in sites.items():
        span, total, count = totals.get(offset, (ends[(offset, _uid)], 0.0, 0))
        totals[offset] = (span, total + sum(durations), count + len(durations))
    hints = []
    for span, total, count in totals.values():
        if not window.start.line <= span.end.line - 1 <= window.end.line:
            continue
        label = f" {total:.2f} s" + (f" in {count} moves" if count > 1 else "")
        hints.append(lsp.InlayHint(lsp.Position(span.end.line - 1, span.end.col - 1), label,
                                   kind=lsp.InlayHintKind.Parameter, padding_left=True))
    return sorted(hints, key=lambda h: (h.position.line, h.position.character))


def _site_here(span: Span, path: str) -> Span | None:
    """The span itself or the call site it was inlined at that lies in `path`."""
    return next((s for s in (span, *span.expansion_chain()) if os.path.abspath(s.path) == path), None)
