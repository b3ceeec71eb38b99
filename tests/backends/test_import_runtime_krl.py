"""`rmot import` of KRL task variables and the logic on them (lang/REFERENCE.md §12, §14).

Witnesses: a hand-written program (KUKA System Software 8.x: DECL INT/REAL/BOOL, assignments,
WHILE, IF, SWITCH, FOR) whose import must compile with `rmot compile` (the compiler's own type
rules E150–E162), and a tiny KRL expression evaluator written here from the KSS manual's
operator priorities (NOT, then `* /`, `+ -`, AND, OR, comparisons last), run against Python's
evaluation of the imported rmot text (rmot's priorities are Python's) over every input level
and a range of variable values.
"""

from __future__ import annotations

import itertools
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.backends.readers.krl_logic import KrlVars
from rmot.compiler.cli import cli
from vendor_expr_witness import KRL_PRIORITY, evaluate

SRC = """DEF t( )
  DECL INT count
  DECL REAL lvl
  BOOL late
  INT i
  count = 0
  late = FALSE
  PTP XHOME
  WHILE (count < 3) AND $IN[1]
    PTP XP1
    count = count + 1
    lvl = lvl * 2 / 3
    IF (count == 2) OR NOT $IN[2] THEN
      $OUT[1] = TRUE
    ELSE
      late = TRUE
    ENDIF
  ENDWHILE
  SWITCH count
  CASE 1, 2
    $OUT[2] = TRUE
  CASE 3
    $OUT[3] = TRUE
  DEFAULT
    $OUT[4] = FALSE
  ENDSWITCH
  count = count / 2
  IF late == FALSE AND $OUT[3] THEN
    $OUT[5] = TRUE
  ENDIF
  FOR i = 1 TO 3
    PTP XP1
  ENDFOR
  IF late THEN
    RETURN
  ENDIF
END
"""

DAT = """DEFDAT t
  DECL E6AXIS XHOME={A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0}
  DECL E6AXIS XP1={A1 10.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0}
  DECL REAL lvl=1.5
ENDDAT
"""


def test_hand_written_logic(tmp_path: Path) -> None:
    src = tmp_path / "t.src"
    src.write_text(SRC)
    (tmp_path / "t.dat").write_text(DAT)
    out = tmp_path / "t.rmot"
    result = CliRunner().invoke(cli, ["import", str(src), "-o", str(out), "--robot", "kuka_kr6_r900"])
    assert result.exit_code == 0, result.output
    body = [ln.strip() for ln in out.read_text().splitlines()]
    for line in ["var count: int = 0", "var lvl: num = 1.5", "var late: bool = off",
                 "while count < 3 and in[1] == on {", "count = count + 1", "lvl = lvl * 2 / 3",
                 "if count == 2 or in[2] == off {", "late = on", "if count == 1 or count == 2 {",
                 "if count == 3 {", "for i in 1 .. 4 {", "stop"]:
        assert line in body, (line, out.read_text())
    # no rmot form: an integer division; a comparison of an AND (KRL compares last) reading an output
    assert re.search(rf"{src}:27:3: warning\[W510\].*count = count / 2", result.output)
    assert re.search(rf"{src}:28:3: warning\[W510\].*IF late == FALSE AND \$OUT\[3\]", result.output)
    compiled = CliRunner().invoke(cli, ["compile", str(out), "--cell", str(tmp_path / "t_cell.rmot"),
                                        "--target", "krl", "-o", str(tmp_path / "o"), "--allow-findings"])
    assert "error[" not in compiled.output, compiled.output


# ---------------------------------------------------------------- an independent evaluator

def _krl_eval(text: str, env: dict[str, object], inputs: dict[int, bool]) -> object:
    """KRL's evaluation (vendor_expr_witness: the KSS 8.x priorities): `$IN[n]` and names."""
    return evaluate(text, KRL_PRIORITY, lambda tokens, i: (inputs[int(tokens[i][4:-1])] if tokens[i].startswith("$IN[")
                                                            else env[tokens[i]], 1))


CONDITIONS = [
    "(n < 3) AND $IN[1]",
    "(n >= 2) OR NOT $IN[2] AND ok",
    "((n + 1) * 2 > m - 1) OR NOT ok",
    "$IN[1] AND NOT ok OR (n == m)",
    "(ok == FALSE) AND (n <> 2)",
    "n * 2 + 1 < m / 2 + n",
    "NOT ((n < 2) AND $IN[2])",
    "$IN[2] == FALSE",
]


def _vars(text: str) -> KrlVars:
    lines_src = f"DEF x( )\n  INT n\n  REAL m\n  BOOL ok\n  n = 0\n  m = 0\n  ok = FALSE\n  IF {text} THEN\n  ENDIF\nEND\n"
    from rmot.backends.readers.krl_text import lines
    found = KrlVars(lines("x.src", lines_src), "x", None, set(), lambda n: None)
    found.visible = found.vars
    return found


@pytest.mark.parametrize("text", CONDITIONS)
def test_condition_means_the_same(text: str) -> None:
    conds = _vars(text).condition(text)
    assert conds is not None, text
    for i1, i2, ok, n, m in itertools.product((False, True), (False, True), (False, True), range(-1, 5), (0.5, 2.0, 3.0)):
        inputs = {1: i1, 2: i2}
        parts = [f"({inputs[int(c.signal)] == c.on})" for c in conds.parts]
        rmot = conds.text.format(*parts)
        mine = eval(rmot, {}, {"n": n, "m": m, "ok": ok, "on": True, "off": False})  # noqa: S307 - test's own text
        assert mine == _krl_eval(text, {"n": n, "m": m, "ok": ok}, inputs), (text, rmot, i1, i2, ok, n, m)


@pytest.mark.parametrize("text", ["n / 2 == 1", "n == 2 OR ok", "$OUT_C[1]", "$IN[1] AND $IN[2] == FALSE",
                                  "n EXOR 1", "ok == (n < 2)", "n B_AND 2 == 0"])
def test_no_rmot_form_is_refused(text: str) -> None:
    assert _vars(text).condition(text) is None


LOOPS = """DEF e( )
  INT n
  n = 0
  REPEAT
    $OUT[1] = TRUE
    n = n + 1
  UNTIL (n >= 3) OR $IN[4]
  LOOP
    $OUT[2] = TRUE
    IF $IN[2] THEN
      EXIT
    ENDIF
  ENDLOOP
  LOOP
    IF $IN[3] AND (n > 5) THEN
      EXIT
    ENDIF
    $OUT[3] = TRUE
    n = n + 1
  ENDLOOP
END
"""


def _reference(on_after: dict[int, int]) -> list[int]:
    """LOOPS run as KSS 8.x says (REPEAT: the body, then until; LOOP: until an EXIT), written by
    hand; input k reads TRUE once `on_after[k]` outputs were set."""
    trace: list[int] = []

    def inp(k: int) -> bool:
        return len(trace) >= on_after[k]

    n = 0
    while True:
        trace.append(1)
        n += 1
        if n >= 3 or inp(4):
            break
    while True:
        trace.append(2)
        if inp(2):
            break
    while True:
        if inp(3) and n > 5:
            break
        trace.append(3)
        n += 1
    return trace


def _run(body: tuple, env: dict, trace: list[int], on_after: dict[int, int]) -> None:
    """The imported statements run: outputs set, assignments, while and if on their conditions."""
    from rmot.backends.readers.model import Assign, If, SetOut, VarDecl, While

    def value(c: object) -> object:
        from rmot.backends.readers.model import Cond
        if isinstance(c, Cond):
            return (len(trace) >= on_after[int(c.signal)]) == c.on
        parts = [f"({value(p)})" for p in c.parts]  # type: ignore[attr-defined]
        return eval(c.text.format(*parts), {}, {**env, "on": True, "off": False})  # type: ignore[attr-defined]  # noqa: S307

    for s in body:
        assert len(trace) < 200
        if isinstance(s, SetOut):
            trace.append(int(s.signal))
        elif isinstance(s, (VarDecl, Assign)):
            env[s.name] = value(s.init if isinstance(s, VarDecl) else s.value)
        elif isinstance(s, While):
            while value(s.cond):
                _run(s.body, env, trace, on_after)
        elif isinstance(s, If):
            _run(s.then if value(s.cond) else s.orelse, env, trace, on_after)
        else:
            raise AssertionError(s)


def test_loops_run_as_the_controller_runs_them(tmp_path: Path) -> None:
    from rmot.backends.readers import read_files
    src = tmp_path / "e.src"
    src.write_text(LOOPS)
    doc = read_files([str(src)])
    assert doc.counts[0].native == 0
    for t2, t3, t4 in itertools.product(range(0, 6), range(0, 9), range(0, 4)):
        on_after = {2: t2, 3: t3, 4: t4}
        trace: list[int] = []
        _run(doc.routines[0].body, {}, trace, on_after)
        assert trace == _reference(on_after), on_after


def test_dat_variable_is_persistent_w541(tmp_path: Path) -> None:
    """A .dat variable keeps the value the last run left (KSS 8.x, data lists): W541 at the .dat's
    declaration when the DEF reads it before setting it; not where the DEF sets it first thing."""
    src = tmp_path / "pd.src"
    src.write_text("DEF pd( )\n  n = n + 1\n  IF n > 3 THEN\n    $OUT[1] = TRUE\n  ENDIF\nEND\n")
    (tmp_path / "pd.dat").write_text("DEFDAT pd\n  DECL INT n=2\nENDDAT\n")
    result = CliRunner().invoke(cli, ["import", str(src), "-o", str(tmp_path / "pd.rmot")])
    assert result.exit_code == 0, result.output
    assert f"{tmp_path / 'pd.dat'}:2:3: warning[W541]" in result.output
    assert "var n: int = 2" in (tmp_path / "pd.rmot").read_text()
    src.write_text("DEF pd( )\n  n = 0\n  n = n + 1\nEND\n")
    result = CliRunner().invoke(cli, ["import", str(src), "-o", str(tmp_path / "pd.rmot")])
    assert "W541" not in result.output and "var n: int = 0" in (tmp_path / "pd.rmot").read_text()
