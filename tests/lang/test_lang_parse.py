"""The .rmot parser: every construct of LANGUAGE.md parses; syntax errors name what was expected in words."""

from __future__ import annotations

import pytest

import rmot.lang
from rmot.lang import ast, codes, parse_text
from rmot.lang.diagnostics import render


def _body(text: str) -> tuple[ast.Stmt, ...]:
    result = parse_text(text, "t.rmot")
    assert result.diagnostics == (), [render(d) for d in result.diagnostics]
    assert result.module is not None
    return result.module.body


def _error(text: str) -> tuple[str, int, int, str]:
    result = parse_text(text, "t.rmot")
    assert result.module is None or result.diagnostics
    d = result.diagnostics[0]
    assert d.span is not None
    return d.code.id, d.span.start.line, d.span.start.col, d.message


class TestStatements:
    def test_move_with_every_modifier(self) -> None:
        """A move keeps its kind, target and each modifier in source order."""
        (move,) = _body("move linear p speed 100 mm/s accel 2 m/s^2 zone fine tool g frame f config(elbow=up) time 2 s joint_speed 50 %")
        assert isinstance(move, ast.Move)
        assert move.kind == "linear"
        assert [m.kind for m in move.modifiers] == ["speed", "accel", "zone", "tool", "frame", "config", "time", "joint_speed"]
        assert move.modifiers[2].value is None  # zone fine

    def test_circular_move_may_continue_on_the_next_line(self) -> None:
        """`move circular via A` NEWLINE `to B` is one statement."""
        (move,) = _body("move circular via pose(x=1mm)\n      to pose(x=2mm) speed 50 mm/s")
        assert isinstance(move, ast.Move) and move.via is not None and move.kind == "circular"

    def test_else_may_start_a_new_line(self) -> None:
        """`}` NEWLINE `else {` continues the if statement."""
        (stmt,) = _body("if in[2] == on { wait 1 s }\nelse { wait 2 s }")
        assert isinstance(stmt, ast.IfStmt) and len(stmt.otherwise) == 1

    def test_newlines_inside_parentheses_are_ignored(self) -> None:
        """A pose literal may span lines."""
        (stmt,) = _body("target t = pose(\n  x=1mm,\n  y=2mm,\n)")
        assert isinstance(stmt, ast.TargetDecl) and isinstance(stmt.value, ast.Call) and len(stmt.value.args) == 2

    def test_semicolons_separate_statements(self) -> None:
        """`;` ends a statement like a newline does."""
        assert len(_body("wait 1 s; wait 2 s;; sync a")) == 3

    @pytest.mark.parametrize(("text", "value", "unit"), [
        ("150 mm", 150, "mm"), ("150mm", 150, "mm"), ("2 m/s^2", 2, "m/s^2"), ("50 %", 50, "%"),
        ("90 deg/s", 90, "deg/s"), ("3 min", 3, "min"), ("1 in", 1, "in"), ("2.5e3 ms", 2500, "ms"), ("7", 7, None),
    ])
    def test_unit_literals(self, text: str, value: float, unit: str | None) -> None:
        """A number and its unit are one Number node, with or without a space."""
        (stmt,) = _body(f"const c = {text}")
        assert isinstance(stmt, ast.ConstDecl) and isinstance(stmt.value, ast.Number)
        assert (stmt.value.value, stmt.value.unit) == (value, unit)

    def test_joints_with_a_trailing_unit(self) -> None:
        """`joints(...) deg` keeps the unit for the bare values."""
        (stmt,) = _body("target h = joints(0, -90, 90, 0, 90, 0) deg")
        assert isinstance(stmt.value, ast.Joints) and stmt.value.unit == "deg" and len(stmt.value.args) == 6  # type: ignore[union-attr]

    def test_precedence_of_arithmetic(self) -> None:
        """`a + b * c` multiplies first; unary minus binds tighter than `*`."""
        (stmt,) = _body("const c = 1 + 2 * -3")
        value = stmt.value  # type: ignore[union-attr]
        assert isinstance(value, ast.BinOp) and value.op == "+"
        assert isinstance(value.right, ast.BinOp) and value.right.op == "*" and isinstance(value.right.right, ast.Neg)

    def test_component_access_and_pose_algebra(self) -> None:
        """`inv(a) * b` and `p.x` parse to Call/BinOp/Attr nodes."""
        (stmt,) = _body("const c = inv(a) * b.x")
        assert isinstance(stmt.value, ast.BinOp) and isinstance(stmt.value.right, ast.Attr)  # type: ignore[union-attr]

    def test_spans_do_not_take_part_in_equality(self) -> None:
        """Two layouts of the same program compare equal."""
        assert _body("wait 1 s") == _body("\n\n   wait   1 s  # comment")

    def test_string_escapes(self) -> None:
        """`\\"` and `\\\\` are the two escapes."""
        (stmt,) = _body('native rapid "say \\"hi\\" \\\\ done"')
        assert isinstance(stmt, ast.NativeStmt) and stmt.text.value == 'say "hi" \\ done'

    def test_statement_spans_cover_the_statement(self) -> None:
        """A move's span starts at `move` and ends after its last modifier."""
        (move,) = _body("  move joint home zone fine")
        assert (move.span.start.line, move.span.start.col, move.span.end.col) == (1, 3, 28)


class TestSyntaxErrors:
    @pytest.mark.parametrize(("text", "words"), [
        ("move joint", "expected an expression"),
        ("speed 100 mm/s +", "expected an expression"),
        ("move", "'joint', 'linear' or 'circular'"),
        ("set x[1] = on", "an I/O port such as in[1] or out[2]"),
    ])
    def test_expected_things_are_named_in_words(self, text: str, words: str) -> None:
        """No lark token names (NAME, LPAR, _NL) reach the user."""
        code, _, _, message = _error(text)
        assert words in message
        for token_name in ("LPAR", "_NL", "NUMBER", "$END", "RBRACE"):
            assert token_name not in message

    def test_unknown_unit_suggests_the_nearest(self) -> None:
        """`100 mmm` says the unit is unknown and suggests mm."""
        assert _error("speed 100 mmm") == ("E007", 1, 11, "unit must be one of mm, m, deg, rad, s, mm/s, ... (got 'mmm'); did you mean 'mm'?")

    def test_misspelt_keyword_at_statement_start(self) -> None:
        """`mvoe joint x` points at mvoe and suggests move."""
        assert _error("wait 1 s\nmvoe joint x")[:3] == ("E006", 2, 1)

    def test_unclosed_brace_points_at_the_brace(self) -> None:
        """The error is at the '{' that is never closed, with a note at the end of the file."""
        result = parse_text("program p on r1 {\n  wait 1 s\n", "t.rmot")
        d = result.diagnostics[0]
        assert (d.code, d.span.start.line, d.span.start.col) == (codes.UNBALANCED_BRACE, 1, 17)  # type: ignore[union-attr]
        assert d.notes and d.notes[0][0] == "the file ends here"

    def test_keyword_as_a_name(self) -> None:
        """Keywords are reserved even where the grammar could take a name."""
        assert _error("const zone = 3")[:3] == ("E008", 1, 7)

    @pytest.mark.parametrize("text", ["", "   \n\n", "# only a comment\n"])
    def test_empty_files(self, text: str) -> None:
        """A file with no statement is an error (E009) at line 1."""
        assert _error(text)[:3] == ("E009", 1, 1)

    def test_control_characters_mean_binary(self) -> None:
        """NUL bytes are reported as a binary file at their position."""
        assert _error("wait 1 s\n\x00\x01")[:3] == ("E010", 2, 1)


def test_public_api_is_exported() -> None:
    """rmot.lang's __all__ names exist and include the parse entry points."""
    for name in rmot.lang.__all__:
        assert hasattr(rmot.lang, name), name
    assert {"parse_text", "parse_source", "wrap_syntax_error", "ast", "codes"} <= set(rmot.lang.__all__)
