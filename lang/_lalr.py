"""The parse loop: lang/lexer.py's tokens fed straight into lark's LALR(1) tables.

lark builds the tables (lang/_tables.py, cached as data) and the rule callbacks (child
filtering, `[x]` placeholders and the embedded AstBuilder); this module only runs them,
with the lexer, the post-lexer and the shift/reduce loop fused into one function. It is
lark's `ParserState.feed_token` loop without its per-token overheads (a generator per
stage, a Token built through `__new__`'s keyword checks, a dict keyed by `Rule` objects),
and the unit reductions of `?rules` (`expr -> product -> unary -> postfix -> atom`), which
return their single child unchanged, only move the parser state instead of calling a wrapper.

Same contract as `Lark.parse` with a lark Lexer and post-lexer doing the same (the tests keep
them as the reference: tests/lang/lang_reference_lexer.py): same token
types (a word is typed by what the state on top of the stack accepts), same tokens reach
the callbacks, and the same lark exceptions on bad input (UnexpectedCharacters,
UnexpectedToken with the expected terminal names, `$END` at the end of the file).
"""

from __future__ import annotations

from collections import deque
from functools import partial
from typing import Any

from lark import Token
from lark.exceptions import UnexpectedCharacters, UnexpectedToken
from lark.parse_tree_builder import ChildFilterLALR, ChildFilterLALR_NoPlaceholders

from rmot.lang._tables import LalrTables
from rmot.lang.lexer import (AXIS_CONTINUES, BLANKS, CONTINUES, INDEXED, IO_WORDS, MOUNT_CONTINUES, TOKEN, TokenKinds,
                             in_statement_of)
from rmot.lang.units import COMPOUND_CUT

__all__ = ["LalrDriver", "PostLexState"]


class PostLexState:
    """What the error messages need after a parse: open braces, a stray '}', the last tokens."""

    __slots__ = ("braces", "unmatched_close", "history")

    def __init__(self) -> None:
        self.braces: list[Token] = []
        self.unmatched_close: Token | None = None
        self.history: deque[Token] = deque(maxlen=3)  # only the last few: tokens are not kept alive


class LalrDriver:
    """Runs LALR tables and lark's rule callbacks (keyed by the tables' Rule objects) over
    lang/lexer.py's tokens."""

    def __init__(self, tables: LalrTables, callbacks: dict[Any, Any]) -> None:
        rules = tables.rules
        self.kinds = TokenKinds(tables.terminals)
        self.axis_starts = frozenset(self.kinds.keywords[w] for w in ("track", "positioner"))
        self.mount_starts = frozenset(self.kinds.keywords[w] for w in ("robot", "fixture", "tool"))
        self.start_state = tables.start
        self.end_state = tables.end
        # Per state: terminal or rule name -> next state (a shift or a goto), or a reduction
        # (rule size, rule origin, callback; callback None for a unit reduction).
        reductions = [self._reduction(rule, callbacks[rule]) for rule in rules]
        self.actions: list[dict[str, Any]] = [
            {name: arg if kind == "s" else reductions[arg] for name, (kind, arg) in row.items()}
            for row in tables.states]
        # (state below, state on top, lookahead) -> the top state after a chain of unit reductions
        self.unit_chains: dict[tuple[int, int, str], int] = {}
        # Terminal names a state accepts (the lexer types words by them; errors list them).
        self.accepts = [frozenset(n for n in row if n.isupper()) for row in tables.states]

    @staticmethod
    def _reduction(rule: Any, callback: Any) -> tuple[int, str, Any]:
        size = len(rule.expansion)
        return size, str(rule.origin.name), None if _is_unit(rule) else _lean(rule, callback)

    def parse(self, text: str, post: PostLexState) -> Any:
        """The start rule's value (the Module); lark's exceptions on bad input.

        One long function on purpose: it runs once per token (~18 per line), and every
        call or generator step it does not make is time saved. Sections: match a token,
        type it, build the lark Token, track brackets, then feed it (reduce*, shift).
        """
        actions, accepts, kinds = self.actions, self.accepts, self.kinds
        punct = kinds.punct
        word_cache: list[dict[str, str]] = [{} for _ in actions]  # per state: word -> type
        match, continues, blanks = TOKEN.match, CONTINUES.match, BLANKS.match
        new_str = str.__new__
        unit_chains = self.unit_chains
        states: list[int] = [self.start_state]
        values: list[Any] = []
        history = post.history
        braces = post.braces
        depth = 0
        pos, line, line_start, n = 0, 1, 0, len(text)
        tok: Token | None = None
        while pos < n:
            m = match(text, pos)
            if m is None:  # only blanks and a comment left, or a character that starts no token
                blank = blanks(text, pos)
                assert blank is not None  # BLANKS matches the empty string
                pos = blank.end()
                if pos >= n:
                    break
                raise UnexpectedCharacters(  # type: ignore[no-untyped-call]  # lark's are untyped
                    text, pos, line, pos - line_start + 1, allowed=set(accepts[states[-1]]))
            kind, end = m.lastgroup, m.end()
            value = m.group(kind)  # type: ignore[arg-type]  # every TOKEN alternative is named
            start = end - len(value)
            col = start - line_start + 1
            # branches in order of frequency: words, punctuation, numbers, newlines
            if kind == "word":
                state = states[-1]
                cache = word_cache[state]
                # `ain[` may be a port read where `ain` alone is a name: cached apart
                indexed = value in IO_WORDS and INDEXED.match(text, end) is not None
                key = value + "[" if indexed else value
                ttype = cache.get(key)
                if ttype is None:
                    ttype = cache[key] = kinds.word_type(value, accepts[state], indexed)
                start_line = end_line = line
                end_col = col + (end - start)
            elif kind == "punct":
                ttype = punct[value]
                if ttype == "LPAR" or ttype == "LSQB":
                    depth += 1
                elif ttype == "RPAR" or ttype == "RSQB":
                    if depth > 0:
                        depth -= 1
                elif ttype == "LBRACE":
                    depth = 0  # a '{' ends any unclosed '(' before it: report there, not at EOF
                start_line = end_line = line
                end_col = col + (end - start)
            elif kind == "number":
                ttype = "NUMBER"
                start_line = end_line = line
                end_col = col + (end - start)
            elif kind == "nl":
                newlines = value.count("\n")
                start_line = line
                if newlines:
                    last_nl = value.rfind("\n")
                    end_line, end_col = line + newlines, end - (last_nl + start)
                    line, line_start = end_line, start + last_nl + 1
                else:
                    end_line, end_col = line, col + len(value)
                if depth > 0 or continues(text, end) is not None or (value[0] != ";" and (  # `;` ends a declaration
                        AXIS_CONTINUES.match(text, end) is not None and in_statement_of(values, self.axis_starts)
                        or MOUNT_CONTINUES.match(text, end) is not None and in_statement_of(values, self.mount_starts))):
                    pos = end
                    continue  # a newline inside ( ) or [ ], before `to` / `else`, or inside a declaration
                ttype = "_NL"
            else:
                if kind == "string":
                    ttype = "STRING"
                elif "UNIT" in accepts[states[-1]]:  # kind == "unit"
                    ttype = "UNIT"
                else:  # `m/s` where no unit fits: just the word `m`, then `/` and `s`
                    value = value[: COMPOUND_CUT.search(value).start()]  # type: ignore[union-attr]
                    end = start + len(value)
                    ttype = kinds.word_type(value, accepts[states[-1]])
                start_line = end_line = line
                end_col = col + (end - start)
            pos = end
            # a lark Token, built without Token.__new__'s keyword checks
            tok = new_str(Token, value)
            tok.type = ttype
            tok.value = value
            tok.start_pos = start
            tok.line = start_line
            tok.column = col
            tok.end_line = end_line
            tok.end_column = end_col
            tok.end_pos = end
            if ttype == "LBRACE":
                braces.append(tok)
            elif ttype == "RBRACE":
                if braces:
                    braces.pop()
                elif post.unmatched_close is None:
                    post.unmatched_close = tok
            history.append(tok)
            # -- feed the token: reduce while the table says so, then shift
            while True:
                state = states[-1]
                act = actions[state].get(ttype)
                if act is None:
                    raise UnexpectedToken(tok, set(accepts[state]))  # type: ignore[no-untyped-call]
                if act.__class__ is int:
                    states.append(act)
                    values.append(tok)
                    break
                size, origin, callback = act
                if callback is None:  # unit reduction(s): the value stays, the state moves
                    key = (states[-2], state, ttype)
                    top = unit_chains.get(key)
                    if top is None:
                        top = unit_chains[key] = self._unit_chain(*key)
                    states[-1] = top
                    continue
                if size:
                    children = values[-size:]
                    del states[-size:]
                    del values[-size:]
                else:
                    children = []
                values.append(callback(children))
                states.append(actions[states[-1]][origin])
        return self._finish(tok, states, values)

    def _unit_chain(self, below: int, top: int, ttype: str) -> int:
        """The state after every unit reduction `ttype` triggers on `top` (they never touch `below`)."""
        actions = self.actions
        while True:
            act = actions[top].get(ttype)
            if act is None or act.__class__ is int or act[2] is not None:
                return top
            top = actions[below][act[1]]

    def _finish(self, last: Token | None, states: list[int], values: list[Any]) -> Any:
        """Feed `$END` (positioned at the last token, as lark does) until the start rule is reduced.

        The reduce step below repeats the one inlined in `parse`'s loop on purpose: a method
        call per reduction there cost measurable time (see the module docstring)."""
        actions, end_state = self.actions, self.end_state
        tok = Token.new_borrow_pos("$END", "", last) if last is not None else Token("$END", "", 0, 1, 1)
        while True:
            state = states[-1]
            act = actions[state].get("$END")
            if act is None or act.__class__ is int:
                raise UnexpectedToken(tok, set(self.accepts[state]))  # type: ignore[no-untyped-call]
            size, origin, callback = act
            if callback is None:
                states[-1] = actions[states[-2]][origin]
            else:
                if size:
                    children = values[-size:]
                    del states[-size:]
                    del values[-size:]
                else:
                    children = []
                values.append(callback(children))
                states.append(actions[states[-1]][origin])
            if states[-1] == end_state:
                return values[-1]


def _is_unit(rule: Any) -> bool:
    """A `?rule` alternative of one kept symbol and no placeholders: lark returns that child as is."""
    options = rule.options
    if not options.expand1 or rule.alias or len(rule.expansion) != 1 or options.empty_indices:
        return False
    sym = rule.expansion[0]
    if sym.is_term:
        return options.keep_all_tokens or not sym.filter_out
    return not sym.name.startswith("_")


class _Inlined:
    """What an `_rule` (inlined into its parent) reduces to: lark's filters only read `.children`."""

    __slots__ = ("children",)

    def __init__(self, children: list[Any]) -> None:
        self.children = children


def _lean(rule: Any, callback: Any) -> Any:
    """lark's callback for a rule, with its generic child filter replaced by a direct one.

    lark's ChildFilter walks a (index, inline?, placeholders) list on every reduction; most
    rules only pick fixed children or add trailing `None` placeholders, which one list
    expression does. `_rule` helpers (always inlined into their parent) build a `_Inlined`
    instead of a parse-tree node. Anything else keeps lark's callback.
    """
    inlined = str(rule.origin.name).startswith("_")
    if inlined and _is_tree_builder(callback):
        return _Inlined
    kind = type(callback)
    if kind is ChildFilterLALR_NoPlaceholders:
        build = callback.node_builder
        if _is_tree_builder(build):
            if not inlined:
                return callback
            build = _Inlined
        picks = tuple(i for i, _ in callback.to_include)
        inline = [i for i, expand in callback.to_include if expand]
        if not inline:
            return _picker(build, picks)
        if inline == [0] and picks[0] == 0:  # left recursion: extend the first child's list, as lark does
            rest = picks[1:]

            def extend(c: list[Any]) -> Any:
                out = c[0].children
                out += [c[i] for i in rest]
                return build(out)

            return extend
    elif kind is ChildFilterLALR and not any(expand for _, expand, _ in callback.to_include):
        build = callback.node_builder
        if _is_tree_builder(build):
            return callback
        template: list[int | None] = []
        for i, _, nones in callback.to_include:
            template += [None] * nones + [i]
        template += [None] * callback.append_none
        keep = len(template) - callback.append_none
        if template[:keep] == list(range(keep)):  # the first `keep` children, then placeholders
            tail = [None] * callback.append_none
            return lambda c: build(c[:keep] + tail)
        return lambda c: build([None if i is None else c[i] for i in template])
    return callback


def _picker(build: Any, picks: tuple[int, ...]) -> Any:
    """`build([c[i] for i in picks])`, spelt out for one to three picks (no comprehension)."""
    if len(picks) == 1:
        (a,) = picks
        return lambda c: build([c[a]])
    if len(picks) == 2:
        a, b = picks
        return lambda c: build([c[a], c[b]])
    if len(picks) == 3:
        a, b, d = picks
        return lambda c: build([c[a], c[b], c[d]])
    return lambda c: build([c[i] for i in picks])


def _is_tree_builder(f: Any) -> bool:
    """lark's default callback (no AstBuilder method for the rule): a parse-tree node."""
    return isinstance(f, partial) and getattr(f.func, "__name__", "") == "default_callback"
