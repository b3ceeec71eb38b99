"""The grammar's LALR(1) tables as plain data, cached as JSON in the user's cache directory.

lark computes the tables from lang/grammar/rmot.lark in ~0.3 s (its grammar loader and
`compute_lalr`), which every `rmot check` paid at start-up. The tables are a function of the
grammar text and of lark's version only, so they are kept as data: one JSON file per
(grammar, lark version, format) under `<cache>/lalr/<sha256>.json`, where <cache> is
$RMOT_CACHE_DIR, else $XDG_CACHE_HOME/rmot, else ~/.cache/rmot (the plan cache's folder).

JSON, never pickle (lark's own `cache=True` pickles, and a file in a user's cache folder is
input, not code). Loading it rebuilds lark's own objects (`Rule`, `TerminalDef`) through
lark's `Serialize` interface, which instantiates only lark's symbol and option classes. A
file that cannot be read, is not sealed by this cache for this key (lang/cache_seal.py: an
HMAC, a bounded regular file inside the cache), or does not have the expected shape is ignored
and rewritten (atomically: a temporary file renamed into place, so concurrent runs are safe);
a folder that cannot be written only costs the build time. The grammar text itself is part
of the key, so any change to the grammar (or to lark) builds new tables.

What the parse loop (lang/_lalr.py) needs is `LalrTables`: the terminals, the rules, and per
state the action for each terminal or rule name: ("s", next state) or ("r", rule index).
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from pathlib import Path
from typing import Any

from rmot.lang.cache_seal import cache_dir, read_sealed, seal
from rmot.lang.record import record

__all__ = ["FORMAT", "LARK_VERSIONS", "LalrTables", "build_tables", "cache_dir", "load_tables",
           "tables_key"]

FORMAT = "rmot-lalr-tables/1"
# The lark releases whose internals this module and lang/_lalr.py read (the parse table's
# layout, Rule/TerminalDef serialisation, ParseTreeBuilder's child filters), checked by
# tests/lang/test_lang_tables.py; pyproject.toml pins lark to them. Another release fails that
# test: read its internals, run tests/lang, then add it here and widen the pin.
LARK_VERSIONS = ("1.3.1",)
GRAMMAR = Path(__file__).with_name("grammar") / "rmot.lark"
MAX_ENTRY_BYTES = 16 * 1024 * 1024  # a table file read back is at most this (rmot's: ~0.3 MB)


@record(slots=True)
class LalrTables:
    """terminals: lark TerminalDefs; rules: lark Rules; states[i]: {symbol: ("s", state) or
    ("r", rule index)}; start / end: the start rule's first and accepting states."""

    terminals: tuple[Any, ...]
    rules: tuple[Any, ...]
    states: tuple[dict[str, tuple[str, int]], ...]
    start: int
    end: int


def tables_key(grammar: str) -> str:
    import lark  # late: loads lark only when this runs

    return hashlib.sha256(f"{FORMAT}\0{lark.__version__}\0{grammar}".encode()).hexdigest()


def load_tables(grammar: str | None = None, *, use_cache: bool = True) -> LalrTables:
    """The tables of `grammar` (default: rmot.lark), from the cache when it holds them."""
    text = GRAMMAR.read_text(encoding="utf-8") if grammar is None else grammar
    if not use_cache:
        return from_data(build_tables(text))
    key = tables_key(text)
    path = cache_dir() / "lalr" / f"{key}.json"
    data = _read(path, key)
    if data is not None:
        try:
            return from_data(data)
        except (KeyError, TypeError, ValueError, IndexError, AttributeError):
            pass  # not the shape this code writes: rebuilt and rewritten below
    data = build_tables(text)
    data["key"] = key
    _write(path, data)
    return from_data(data)


def build_tables(grammar: str) -> dict[str, Any]:
    """lark's LALR analysis of `grammar` as JSON-ready data (lists, dicts, str, int, bool, None)."""
    from lark import Lark  # late: loads lark only when this runs
    from lark.lexer import Lexer  # late: loads lark only when this runs
    from lark.parsers.lalr_analysis import Shift  # late: loads lark only when this runs

    class _NoLexer(Lexer):  # the tables only: lang/_lalr.py lexes on its own
        def __init__(self, conf: Any) -> None:
            pass

        def lex(self, *args: Any) -> Any:
            raise NotImplementedError

    parser = Lark(grammar, parser="lalr", lexer=_NoLexer, propagate_positions=False,
                  maybe_placeholders=True, cache=False)
    table = parser.parser.parser.parser.parse_table  # ParsingFrontend -> LALR_Parser -> _Parser
    rules = list(parser.rules)
    index = {id(r): i for i, r in enumerate(rules)}
    states = []
    for s in range(len(table.states)):
        row = table.states[s]
        states.append([[str(name), "s", arg] if action is Shift
                       else [str(name), "r", index[id(arg)]]
                       for name, (action, arg) in row.items()])
    return {
        "format": FORMAT,
        "terminals": [[t.name, t.pattern.type, t.pattern.value, list(t.pattern.flags), t.priority]
                      for t in parser.terminals],
        "rules": [_plain(r.serialize()) for r in rules],
        "states": states,
        "start": table.start_states["start"],
        "end": table.end_states["start"],
    }


def from_data(data: dict[str, Any]) -> LalrTables:
    from lark.grammar import Rule  # late: loads lark only when this runs
    from lark.lexer import PatternRE, PatternStr, TerminalDef  # late: loads lark only when this runs

    if data.get("format") != FORMAT:
        raise ValueError("not an rmot LALR table file")
    patterns = {"str": PatternStr, "re": PatternRE}
    terminals = tuple(
        TerminalDef(str(name), patterns[kind](str(value), tuple(flags)), int(priority))
        for name, kind, value, flags, priority in data["terminals"])
    rules = tuple(Rule.deserialize(_tupled(r), {}) for r in data["rules"])
    states = []
    for row in data["states"]:
        out: dict[str, tuple[str, int]] = {}
        for name, kind, arg in row:
            if kind not in ("s", "r") or not isinstance(arg, int):
                raise ValueError("bad action")
            if kind == "r" and not 0 <= arg < len(rules):
                raise ValueError("bad rule index")
            out[str(name)] = (kind, arg)
        states.append(out)
    start, end = int(data["start"]), int(data["end"])
    if not (0 <= start < len(states) and 0 <= end < len(states)):
        raise ValueError("bad start or end state")
    return LalrTables(terminals, rules, tuple(states), start, end)


def _plain(x: Any) -> Any:
    """lark's serialized form with tuples as lists (JSON has no tuples)."""
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    return x


def _tupled(x: Any) -> Any:
    """Back from JSON: `empty_indices` (a tuple in lark) and nested dicts."""
    if isinstance(x, dict):
        return {k: (tuple(v) if k == "empty_indices" and isinstance(v, list) else _tupled(v))
                for k, v in x.items()}
    if isinstance(x, list):
        return [_tupled(v) for v in x]
    return x


def _read(path: Path, key: str) -> dict[str, Any] | None:
    payload = read_sealed(path, key, MAX_ENTRY_BYTES)
    if payload is None:  # missing, foreign, tampered with, not a bounded regular file: a miss
        return None
    try:
        data = json.loads(payload.decode("utf-8"))
    except (ValueError, RecursionError):
        return None
    if not isinstance(data, dict) or data.get("key") != key or data.get("format") != FORMAT:
        return None
    return data


def _write(path: Path, data: dict[str, Any]) -> None:
    try:
        sealed = seal(str(data["key"]), json.dumps(data, separators=(",", ":")).encode("utf-8"))
        if sealed is None:
            return  # no secret: an entry could never be read back
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=".tables-", suffix=".tmp", dir=path.parent)
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(sealed)
            os.replace(tmp, path)
        except BaseException:
            os.unlink(tmp)
            raise
    except OSError:
        pass  # an unwritable cache only costs the build time
