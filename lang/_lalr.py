"""The parse loop: lang/lexer.py's tokens fed straight into lark's LALR(1) tables.

lark builds the tables and the rule callbacks (child filtering, `[x]` placeholders and the
embedded AstBuilder); this module only runs them, with the lexer, the post-lexer and the
shift/reduce loop fused into one function. It is lark's `ParserState.feed_token` loop
without its per-token overheads (a generator per stage, a Token built through `__new__`'s
keyword checks, a dict keyed by `Rule` objects), and the unit reductions of `?rules`
(`expr -> product -> unary -> postfix -> atom`), which return their single child
unchanged, only move the parser state instead of calling a wrapper.

Same contract as `Lark.parse` with `RmotLexer` and `_PostLexer` (lang/parse.py): same token
types (a word is typed by what the state on top of the stack accepts), same tokens reach
the callbacks, and the same lark exceptions on bad input (UnexpectedCharacters,
UnexpectedToken with the expected terminal names, `$END` at the end of the file).
"""

from __future__ import annotations

from typing import Any

from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters, UnexpectedToken
from lark.parsers.lalr_analysis import Shift

from rmot.lang.lexer import CONTINUES, MASTER, TokenKinds

__all__ = ["LalrDriver", "PostLexState"]

_new_token = Token._future_new  # skips Token.__new__'s deprecated-keyword checks


class PostLexState:
    """What the error messages need after a parse: open braces, a stray '}', the last tokens."""

    __slots__ = ("braces", "unmatched_close", "history")

    def __init__(self) -> None:
        self.braces: list[Token] = []
        self.unmatched_close: Token | None = None
        self.history: list[Token] = []


class LalrDriver:
    """Runs one lark LALR parser's tables and callbacks over lang/lexer.py's tokens."""

    def __init__(self, parser: Lark) -> None:
        lalr = parser.parser.parser.parser  # ParsingFrontend -> LALR_Parser -> _Parser
        table = lalr.parse_table
        callbacks = lalr.callbacks
        self.kinds = TokenKinds(parser.terminals)
        self.start_state = table.start_states["start"]
        self.end_state = table.end_states["start"]
        # Per state: terminal or rule name -> next state (a shift or a goto), or a reduction
        # (rule size, rule origin, callback; callback None for a unit reduction).
        self.actions: list[dict[str, Any]] = [{} for _ in range(len(table.states))]
        for state, row in table.states.items():
            out = self.actions[state]
            for name, (action, arg) in row.items():
                # str(): lark's names may be Tokens, whose Python-level __eq__ slows every lookup
                out[str(name)] = arg if action is Shift else self._reduction(arg, callbacks[arg])
        # Terminal names a state accepts (the lexer types words by them; errors list them).
        self.accepts = [frozenset(str(n) for n in table.states[s] if n.isupper()) for s in range(len(self.actions))]

    @staticmethod
    def _reduction(rule: Any, callback: Any) -> tuple[int, str, Any]:
        size = len(rule.expansion)
        return size, str(rule.origin.name), None if _is_unit(rule) else callback

    def parse(self, text: str, post: PostLexState) -> Any:
        """The start rule's value (the Module); lark's exceptions on bad input."""
        actions, accepts, kinds = self.actions, self.accepts, self.kinds
        keywords, punct, word_cache = kinds.keywords, kinds.punct, [dict() for _ in actions]
        match, continues = MASTER.match, CONTINUES.match
        states: list[int] = [self.start_state]
        values: list[Any] = []
        history = post.history
        braces = post.braces
        depth = 0
        pos, line, line_start, n = 0, 1, 0, len(text)
        tok: Token | None = None
        while pos < n:
            m = match(text, pos)
            if m is None:
                raise UnexpectedCharacters(text, pos, line, pos - line_start + 1, allowed=set(accepts[states[-1]]))
            kind, end = m.lastgroup, m.end()
            if kind == "ws" or kind == "comment":
                pos = end
                continue
            value = m.group()
            col = pos - line_start + 1
            if kind == "nl":
                newlines = value.count("\n")
                if newlines:
                    last_nl = value.rfind("\n")
                    end_line, end_col = line + newlines, end - (last_nl + pos)
                else:
                    end_line, end_col = line, col + len(value)
                tok_pos = pos
                if newlines:
                    line, line_start = end_line, pos + last_nl + 1
                pos = end
                if depth > 0 or continues(text, end) is not None:
                    continue  # a newline inside ( ) or [ ], or before `to` / `else`
                ttype = "_NL"
                tok = _new_token(ttype, value, tok_pos, end_line - newlines, col, end_line, end_col, end)
            else:
                state = states[-1]
                if kind == "word":
                    cache = word_cache[state]
                    ttype = cache.get(value)
                    if ttype is None:
                        ttype = cache[value] = kinds.word_type(value, accepts[state])
                elif kind == "number":
                    ttype = "NUMBER"
                elif kind == "punct":
                    ttype = punct[value]
                elif kind == "string":
                    ttype = "STRING"
                elif "UNIT" in accepts[state]:  # kind == "unit"
                    ttype = "UNIT"
                else:  # `m/s` where no unit fits: just the word `m`, then `/` and `s`
                    value = value[: value.index("/")]
                    end = pos + len(value)
                    ttype = kinds.word_type(value, accepts[state])
                tok = _new_token(ttype, value, pos, line, col, line, col + (end - pos), end)
                if kind == "punct":
                    if ttype == "LPAR" or ttype == "LSQB":
                        depth += 1
                    elif ttype == "RPAR" or ttype == "RSQB":
                        if depth > 0:
                            depth -= 1
                    elif ttype == "LBRACE":
                        depth = 0  # a '{' ends any unclosed '(' before it: report there, not at EOF
                        braces.append(tok)
                    elif ttype == "RBRACE":
                        if braces:
                            braces.pop()
                        elif post.unmatched_close is None:
                            post.unmatched_close = tok
                pos = end
            history.append(tok)
            # -- feed the token: reduce while the table says so, then shift
            while True:
                state = states[-1]
                act = actions[state].get(ttype)
                if act is None:
                    raise UnexpectedToken(tok, set(accepts[state]))
                if act.__class__ is int:
                    states.append(act)
                    values.append(tok)
                    break
                size, origin, callback = act
                if callback is None:  # unit reduction: the value stays, the state moves
                    states[-1] = actions[states[-2]][origin]
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

    def _finish(self, last: Token | None, states: list[int], values: list[Any]) -> Any:
        """Feed `$END` (positioned at the last token, as lark does) until the start rule is reduced."""
        actions, end_state = self.actions, self.end_state
        tok = Token.new_borrow_pos("$END", "", last) if last is not None else Token("$END", "", 0, 1, 1)
        while True:
            state = states[-1]
            act = actions[state].get("$END")
            if act is None or act.__class__ is int:
                raise UnexpectedToken(tok, set(self.accepts[state]))
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
