"""`rmot import` of RAPID task variables and the logic on them (lang/REFERENCE.md §12, §14).

Witnesses: a hand-written module (ABB RAPID reference: VAR num/bool, :=, Incr, WHILE, IF,
WaitDI \\MaxTime \\TimeFlag) whose import must compile with `rmot compile` (the compiler's own
type rules E150–E162), and a tiny RAPID expression evaluator written here from the RAPID
kernel manual's operator priorities (`* /`, `+ -`, comparisons, AND, OR), run against Python's
evaluation of the imported rmot text (rmot's priorities are Python's: or < and < not <
comparison < + - < * /) over every input level and a range of variable values.
"""

from __future__ import annotations

import itertools
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.backends.readers.rapid_logic import condition
from rmot.compiler.cli import cli
from vendor_expr_witness import RAPID_PRIORITY, evaluate

HAND = """MODULE Count
  ! written by hand from ABB's RAPID reference (VAR, :=, Incr, WHILE, IF, WaitDI \\TimeFlag)
  CONST robtarget p10:=[[600,0,500],[0,0.707107,0.707107,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST num limit := 3;
  VAR num count;
  VAR num level := 0.5;
  VAR bool late;
  VAR string msg := "x";
  PROC main()
    count := 0;
    WHILE count < limit AND DInput(di1) = 1 DO
      MoveL p10, v200, fine, tool0;
      WaitDI di2, 1\\MaxTime:=5\\TimeFlag:=late;
      IF late THEN
        SetDO do1, 0;
      ENDIF
      Incr count;
      level := level * 2 / 3;
    ENDWHILE
    IF count >= limit OR DInput(di2) = 0 THEN
      SetDO do2, 1;
    ELSE
      count := count DIV 2;
    ENDIF
    other;
  ENDPROC
  PROC other()
    Decr count;
  ENDPROC
ENDMODULE
"""



def test_hand_written_logic(tmp_path: Path) -> None:
    src = tmp_path / "count.mod"
    src.write_text(HAND)
    out = tmp_path / "count.rmot"
    result = CliRunner().invoke(cli, ["import", str(src), "-o", str(out), "--robot", "abb_irb1600"])
    assert result.exit_code == 0, result.output
    text = out.read_text()
    body = [ln.strip() for ln in text.splitlines()]
    for line in ["var count: int = 0", "var level: num = 0.5", "while count < limit and in[1] == on {",
                 "wait until in[2] == on timeout 5 s else {", "set out[1] = off", "count = count + 1",
                 "level = level * 2 / 3", "if count >= limit or in[2] == off {", "set out[2] = on"]:
        assert line in body, (line, text)
    assert "late" not in text.split("#   ")[0].replace("# ", "")  # the flag is the wait's own
    # no rmot form: DIV, a string, and a proc using a task variable (rmot procs do not see them)
    assert re.search(rf"{src}:23:7: warning\[W510\].*count DIV 2", result.output)
    assert re.search(rf"{src}:28:5: warning\[W510\].*Decr count", result.output)
    assert re.search(rf"{src}:8:3: warning\[W511\].*msg", result.output)
    stub = tmp_path / "count_cell.rmot"
    compiled = CliRunner().invoke(cli, ["compile", str(out), "--cell", str(stub), "--target", "rapid",
                                        "-o", str(tmp_path / "o"), "--allow-findings"])
    assert compiled.exit_code in (0, 1), compiled.output
    assert "error[" not in compiled.output


# ---------------------------------------------------------------- an independent evaluator

def _rapid_eval(text: str, env: dict[str, object], inputs: dict[str, int]) -> object:
    """RAPID's evaluation (vendor_expr_witness: the RAPID kernel priorities): `DInput(s)`, names, signals."""
    def leaf(tokens: list[str], i: int) -> tuple[object, int]:
        if tokens[i].upper() == "DINPUT":
            return float(inputs[tokens[i + 2]]), 4
        return (env[tokens[i]] if tokens[i] in env else float(inputs[tokens[i]])), 1

    return evaluate(text, RAPID_PRIORITY, leaf)


CONDITIONS = [
    "DInput(di1) = 1 AND n < 3",
    "n >= 2 OR DInput(di2) = 0 AND ok",
    "(n + 1) * 2 > m - 1 OR NOT ok",
    "di1 = 1 AND (NOT ok) OR n = m",
    "ok = FALSE AND n <> 2",
    "n * 2 + 1 < m / 2 + n",
    "NOT (n < 2 AND di2 = 1)",
]


@pytest.mark.parametrize("text", CONDITIONS)
def test_condition_means_the_same(text: str) -> None:
    names = {"N": ("n", "int"), "M": ("m", "num"), "OK": ("ok", "bool")}
    conds = condition(text, names)
    assert conds is not None, text
    for d1, d2, ok, n, m in itertools.product((0, 1), (0, 1), (False, True), range(-1, 5), (0.5, 2.0, 3.0)):
        inputs = {"di1": d1, "di2": d2}
        parts = [f"({int(inputs[str(c.signal)] == (1 if c.on else 0))} == 1)" for c in conds.parts]
        rmot = conds.text.format(*parts)
        assert not re.search(r"\bin\[", rmot)
        mine = eval(rmot, {}, {"n": n, "m": m, "ok": ok, "on": True, "off": False})  # noqa: S307 - test's own text
        assert mine == _rapid_eval(text, {"n": n, "m": m, "ok": ok}, inputs), (text, rmot, d1, d2, ok, n, m)


@pytest.mark.parametrize("text", ["n DIV 2 = 1", "NOT ok AND n < 2", "msg = \"x\"", "ok = (n < 2)", "n MOD 2 = 0"])
def test_no_rmot_form_is_refused(text: str) -> None:
    assert condition(text, {"N": ("n", "int"), "OK": ("ok", "bool")}) is None


TEST_CASE = """MODULE tc
  VAR num k := 0;
  PROC main()
    k := 2;
    TEST k
    CASE 1, 2:
      SetDO do1, 1;
    CASE 3:
      SetDO do3, 1;
    DEFAULT:
      SetDO do2, 0;
    ENDTEST
    TEST k
    CASE 1:
      SetDO do1, 0;
    ENDTEST
    Incr k;
  ENDPROC
ENDMODULE
"""


def _outputs(body: tuple, k: int) -> list[str]:
    """The outputs the imported statements set for a value of k (if chains on `k == v`)."""
    from rmot.backends.readers.model import If, SetOut
    out: list[str] = []
    for s in body:
        if isinstance(s, SetOut):
            out.append(f"{s.signal}={s.value:g}")
        elif isinstance(s, If):
            taken = eval(s.cond.text, {}, {"k": k})  # noqa: S307 - the test's own text
            out += _outputs(s.then if taken else s.orelse, k)
    return out


def test_test_case_is_an_if_chain(tmp_path: Path) -> None:
    """RAPID's TEST runs the first CASE equal to the value, else DEFAULT (RAPID Instructions, TEST)."""
    from rmot.backends.readers import read_files
    src = tmp_path / "tc.mod"
    src.write_text(TEST_CASE)
    doc = read_files([str(src)])
    assert doc.counts[0].native == 0
    body = tuple(s for s in doc.routines[0].body if type(s).__name__ == "If")
    reference = {1: ["do1=1", "do1=0"], 2: ["do1=1"], 3: ["do3=1"]}
    for k in range(-1, 6):
        assert _outputs(body, k) == reference.get(k, ["do2=0"]), k


def test_pers_is_a_variable_with_w541(tmp_path: Path) -> None:
    """A PERS keeps its value between runs (RAPID overview, "Persistent data"): read as a task
    variable at its stored value, W541 at its declaration unless main sets it first thing."""
    src = tmp_path / "pe.mod"
    src.write_text("MODULE pe\n  PERS num cnt := 4;\n  PERS bool seen := FALSE;\n  PROC main()\n    seen := TRUE;\n"
                   "    Incr cnt;\n    IF cnt > 10 THEN\n      SetDO do1, 1;\n    ENDIF\n  ENDPROC\nENDMODULE\n")
    out = tmp_path / "pe.rmot"
    result = CliRunner().invoke(cli, ["import", str(src), "-o", str(out), "--robot", "abb_irb1600"])
    assert result.exit_code == 0, result.output
    assert f"{src}:2:3: warning[W541]" in result.output and result.output.count("W541") == 1  # seen: set first
    body = [ln.strip() for ln in out.read_text().splitlines()]
    assert ["var cnt: int = 4", "var seen: bool = on", "cnt = cnt + 1"] == [ln for ln in body if "cnt" in ln or "seen" in ln][:3]
