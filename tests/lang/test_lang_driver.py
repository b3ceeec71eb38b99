"""The fused parse loop (lang/_lalr.py) behaves exactly as lark's own LALR loop with RmotLexer.

The reference (tests/lang/lang_reference_lexer.py) is a second Lark built by lark from the
grammar text, with a lark Lexer and post-lexer and its own AST builder, run through
`Lark.parse`; ours runs on the tables read back from the JSON cache (lang/_tables.py). Both
must give the same AST, spans included, and fail on the same token with the same expected
terminals.
"""

from __future__ import annotations

import dataclasses
import gc
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lang_reference_lexer import reference_parser
from lark.exceptions import UnexpectedCharacters, UnexpectedInput, UnexpectedToken

from rmot.lang import _build, parse
from rmot.lang import _build_nodes
from rmot.lang._lalr import PostLexState
from rmot.lang.source import Pos, SourceFile, Span

ROOT = Path(__file__).resolve().parents[2]
_REFERENCE, _REFERENCE_BUILDER, _REFERENCE_POSTLEX = reference_parser()


def _tree(x: Any) -> Any:
    """A node as nested tuples, spans (line, col, offset of both ends) included."""
    if isinstance(x, Span):
        return ("span", x.start.line, x.start.col, x.start.offset, x.end.line, x.end.col, x.end.offset)
    if isinstance(x, SourceFile):
        return ("file", x.path)
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return (type(x).__name__, *(_tree(getattr(x, f.name)) for f in dataclasses.fields(x)))
    if isinstance(x, tuple):
        return ("tuple", *(_tree(y) for y in x), _tree(getattr(x, "span", None)))
    return x


def _outcome(run: Any, text: str) -> Any:
    """The AST, or the failure: exception type, position, token type and expected terminals."""
    try:
        return _tree(run(text))
    except UnexpectedToken as exc:
        return ("token", exc.token.type, exc.token.start_pos, exc.line, exc.column, sorted(exc.expected))
    except UnexpectedCharacters as exc:
        return ("character", exc.pos_in_stream, exc.line, exc.column)
    except UnexpectedInput as exc:  # pragma: no cover - neither loop raises another kind
        return ("input", type(exc).__name__)


_OURS_POSTLEX = [PostLexState()]


def _ours(text: str) -> Any:
    _OURS_POSTLEX[0] = PostLexState()
    return parse._parser().parse(SourceFile("t.rmot", text), _OURS_POSTLEX[0])[0]


def _lark(text: str) -> Any:
    _REFERENCE_BUILDER.begin(SourceFile("t.rmot", text))
    return _REFERENCE.parse(text)


def _tokens(tokens: Any) -> list[Any]:
    return [None if t is None else (t.type, str(t), t.start_pos, t.line, t.column, t.end_line, t.end_column, t.end_pos)
            for t in tokens]


def _same(text: str) -> None:
    """Same AST or error, and the same post-lexer state the error messages read (last tokens, braces)."""
    ours, reference = _outcome(_ours, text), _outcome(_lark, text)
    assert ours == reference
    mine, theirs = _OURS_POSTLEX[0], _REFERENCE_POSTLEX
    assert _tokens(mine.history) == _tokens(theirs.history)
    assert _tokens(mine.braces) == _tokens(theirs.braces)
    assert _tokens([mine.unmatched_close]) == _tokens([theirs.unmatched_close])


def _corpus() -> list[Path]:
    return sorted([*ROOT.glob("examples/**/*.rmot"), *ROOT.glob("tests/data/**/*.rmot")])


def _readable(path: Path) -> str | None:
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return None
    return text if len(text) < 200_000 else None


@pytest.mark.parametrize("path", _corpus(), ids=lambda p: str(p.relative_to(ROOT)))
def test_every_shipped_file_parses_as_with_larks_loop(path: Path) -> None:
    """Examples and fixtures (good and bad) give the same AST, spans included, or the same error."""
    text = _readable(path)
    if text is None:
        text = "move linear p\n"  # binary or huge fixtures: parse.py rejects them before the parser
    _same(text)


def test_a_generated_program_parses_as_with_larks_loop() -> None:
    """The benchmark's kind of program: every statement kind, many lines."""
    lines = ["program big on r1 {", "  tool gripper", "  speed 400 mm/s"]
    for i in range(40):
        lines += [f"  target t{i} = pose(x={i}mm, y=2mm, z=150mm, rx=180deg)", f"  move joint shift(t{i}, z=50mm) zone 10 mm",
                  "  if in[2] == on { set out[2] = on } else { wait until in[2] == on timeout 5 s }",
                  f"  move joint joints({i}, -20, 30, 0, 60, 0) deg joint_speed 50 %  # c", "  wait 200 ms; pulse out[1] for 1 s"]
    _same("\n".join(lines + ["}"]) + "\n")


@pytest.mark.parametrize("text", [
    "move linear p speed 1 m/s\n", "x = 1 m/s\n", "move linear p speed 1 m/s^2 zone 1 m/s\n", "speed 1 m/s^3\n",
    "move circular via a\n  to b\n", "if in[1] { wait 1 s }\n  else { wait 2 s }\n", "move joint f(1,\n 2)\n",
    "program p {\n  move linear p\n", "}\n", "move linear \"abc\n", "move @\n", "  # only a comment", "a\r\nb\r\n",
    "target t = pose(x=1mm) # end", "wait 1 s   ", "move linear p\t\f;;\n\n# c\n;move joint q", "set out[1] = on;",
    "track r = linear(axis x, range(0mm, 1mm))\n  speed 1 mm/s\n  accel 2 mm/s^2 # c\n\n  mass 3 kg\n  on q\n  at pose()\nspeed 1 mm/s\n",
    "positioner p = axes(revolute(axis z, range(0deg, 1deg)))\n  on r\n  at pose()\nmove linear p\n  speed 1 mm/s\n",
    "fixture f = box(1mm, 1mm, 1mm)\n  on p\n  at pose()\ntool t = none\n  on r1\nrobot r = kuka_kr16\n  on q\ntool x\n  on\n",
    "track r = linear(axis x, range(0mm, 1mm)); speed 1 mm/s\nfixture f = box(1mm, 1mm, 1mm) ;\n on p\n",
    "move joint out\nif ain [1] * 2 > ain { x = gin[1] + gin }\nvar v = 2 / aout\nout()\nin = 1\n",
    "if in\t[2] and out[3] == on { wait 1 s }\nset out [1] = on\nio gin = \"x\"\nvar w = 2 in\n",
], ids=repr)
def test_edge_cases_parse_as_with_larks_loop(text: str) -> None:
    """Units that do not fit, continued lines, unclosed braces, bad characters, trailing blanks."""
    _same(text)


_WORDS = ["move", "linear", "joint", "circular", "via", "to", "p", "pose", "(", ")", "x", "=", "1", "mm", "m/s", ",", "{",
          "}", "[", "]", "\n", ";", "if", "in", "else", "wait", "until", "set", "out", "on", "#c\n", "\"s\"", "speed", "fine",
          "zone", "joints", "deg", "%", "-", "*", ".", "..", "for", "program", "task", "cell", "@", "\t", "  ",
          "ain", "gin", "aout", "var", "+", "<"]


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(_WORDS), max_size=30))
def test_random_token_soup_parses_as_with_larks_loop(words: list[str]) -> None:
    """Any sequence of words, brackets, blanks and bad characters: same AST or the same error."""
    _same(" ".join(words))


def test_positions_made_without_init_equal_ordinary_ones() -> None:
    """The builder's fast Pos/Span equal constructed ones in every field (defaults included) and stay frozen."""
    f = SourceFile("a", "xyz")
    pairs = [(_build_nodes._make_pos(2, 3, 9), Pos(2, 3, 9)),
             (_build_nodes._make_span(f, Pos(1, 1, 0), Pos(1, 2, 1)), Span(f, Pos(1, 1, 0), Pos(1, 2, 1)))]
    for fast, ordinary in pairs:
        assert type(fast) is type(ordinary) and fast == ordinary and hash(fast) == hash(ordinary)
        for field in dataclasses.fields(ordinary):
            assert getattr(fast, field.name) == getattr(ordinary, field.name), field.name
    with pytest.raises(dataclasses.FrozenInstanceError):
        _build_nodes._make_pos(1, 1, 0).line = 2  # type: ignore[misc]


def test_fast_constructor_falls_back_where_init_matters() -> None:
    """A class that validates in __post_init__ or has a field without default keeps its own constructor."""

    @dataclasses.dataclass(frozen=True, slots=True)
    class Checked:
        a: int
        b: int
        c: int

        def __post_init__(self) -> None:
            if self.a < 0:
                raise ValueError

    @dataclasses.dataclass(frozen=True, slots=True)
    class Wider:
        a: int
        b: int
        c: int
        d: int

    assert _build_nodes._fast_constructor(Checked, ("a", "b", "c")) is Checked
    assert _build_nodes._fast_constructor(Wider, ("a", "b", "c")) is Wider


def test_the_parse_keeps_no_tokens_alive() -> None:
    """Only the last few tokens stay referenced during a parse (for the error messages)."""
    post = PostLexState()
    parse._parser().parse(SourceFile("t.rmot", "move linear p\n" * 200), post)
    assert len(post.history) <= 3 and post.history[-1].type == "_NL"


def test_parse_leaves_the_callers_collector_alone() -> None:
    """A library caller's GC is its own: parse and front end neither pause nor freeze it (only
    the command line pauses it, compiler/cli): the collector runs while each of them works."""
    from rmot.compiler.frontend import load_text

    def collections() -> int:
        return sum(s["collections"] for s in gc.get_stats())

    frozen = gc.get_freeze_count()
    before = collections()
    parse.parse_text("move linear p\n" * 2000, "t.rmot")
    middle = collections()
    load_text("program p on r1 {\n" + "  wait 1 ms\n" * 2000 + "}\n", "/t/p.rmot")
    after = collections()
    assert gc.isenabled() and gc.get_freeze_count() == frozen
    assert before < middle < after


def test_the_command_line_owns_the_collector_schedule(monkeypatch: pytest.MonkeyPatch) -> None:
    """`rmot` sets a sparse collection schedule for its own process; the library does not."""
    import sys

    from rmot.compiler import cli

    old = gc.get_threshold()
    monkeypatch.setattr(sys, "argv", ["rmot", "--help"])
    try:
        with pytest.raises(SystemExit):
            cli.main()
        assert gc.get_threshold() == cli.GC_THRESHOLDS != old and gc.isenabled()
    finally:
        gc.set_threshold(*old)


def test_fast_nodes_equal_ordinary_ones_in_every_field() -> None:
    """Each AST node class the builder makes through its slots (_build._fast_node) gives the
    object its own constructor gives: same class, every field (span included) the same value,
    and still frozen."""
    from rmot.lang import ast

    f = SourceFile("a", "xyz")
    made = 0
    for name in dir(ast):
        cls = getattr(ast, name)
        fast = getattr(_build, f"_{name}", None)
        if not (isinstance(cls, type) and dataclasses.is_dataclass(cls)) or fast is None or fast is cls:
            continue
        fields = dataclasses.fields(cls)
        args = [Span(f, Pos(1, i + 1, i), Pos(2, i + 2, i + 9)) if fl.name == "span" else (name, i)
                for i, fl in enumerate(fields)]
        a, b = fast(*args), cls(*args)
        assert type(a) is cls and a == b and hash(a) == hash(b), name
        for fl in fields:
            assert getattr(a, fl.name) is getattr(b, fl.name), (name, fl.name)
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(a, fields[0].name, None)
        made += 1
    assert made >= 20  # the hot classes (Number, Arg, Ident, Move, ...) take the fast path


def test_fast_node_falls_back_where_init_matters() -> None:
    """A node that validates in __post_init__ keeps its own constructor."""

    @dataclasses.dataclass(frozen=True, slots=True)
    class Checked:
        a: int
        b: int

        def __post_init__(self) -> None:
            if self.a < 0:
                raise ValueError

    assert _build_nodes._fast_node(Checked) is Checked
