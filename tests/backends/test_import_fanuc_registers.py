"""`rmot import` of Fanuc TP numeric registers and flags (readers/fanuc_regs.py, lang/REFERENCE.md §14).

Witnesses: FANUC R-30iB Operator's Manual B-83284EN ("Register instructions": R[i] holds a number
every program may read and write, kept between runs; "IF ... THEN", "IF (...),JMP LBL[i]" and
"WAIT" with a register comparison; "Flag"). The meaning of each TP condition is evaluated here by
Python over the TP text itself (`=`/`<>` are `==`/`!=`, `!` is `not`, AND and OR one per
parenthesised level), not through the reader; the imported rmot condition is evaluated by Python
too (for these operators rmot's priorities are Python's), with `gin[k]` bound to the register the
cell stub names for port k. The imports must pass `rmot check` and compile back to TP that
imports to the same conditions and variables.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rmot.compiler.cli import cli
from tests.backends.test_import_blocks import POS


def _ls(name: str, body: list[str]) -> str:
    lines = "".join(f"{n:4d}:  {text} ;\n" for n, text in enumerate(body, 1))
    return f"/PROG  {name}\n/ATTR\n/MN\n{lines}{POS}"


def _import(folder: Path, files: dict[str, list[str]], args: tuple[str, ...] = ()) -> tuple[str, str, str]:
    """(the program `rmot import` writes from `program` on, its cell stub, what it prints)."""
    paths = []
    for name, body in files.items():
        path = folder / f"{name.lower()}.ls"
        path.write_text(_ls(name, body))
        paths.append(str(path))
    out = folder / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", *paths, "-o", str(out), *args], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    program = out.read_text()
    stub = folder / "imported_cell.rmot"  # none with --cell
    return program[program.index("\nprogram ") + 1:], stub.read_text() if stub.exists() else "", result.output


def _checks(folder: Path) -> None:
    result = CliRunner().invoke(cli, ["check", str(folder / "imported.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output


def test_a_register_the_program_only_tests_is_a_group_input(tmp_path: Path) -> None:
    """kamilkozdro/FanucProgramAnalyze `gratowanie.ls`: `IF (R[1:stan chwytaka 1]=1) THEN` on a
    register the program it calls sets; every arm is planned and verified."""
    program, cell, output = _import(tmp_path, {"REG": [
        "J P[1] 100% FINE", "IF (R[1:gripper state]=1) THEN", "L P[2] 100mm/sec FINE", "DO[108]=ON", "ENDIF",
        "WAIT R[1:gripper state]=2", "IF R[2]<>3,JMP LBL[1]", "J P[2] 100% FINE", "LBL[1]"]})
    assert "native fanuc" not in program
    assert "  if gin[1] == 1 {\n    move linear reg_p2 speed 100 mm/s zone fine\n    set out[108] = on\n  }\n" in program
    assert "  wait until gin[1] == 2\n" in program and "  if gin[2] == 3 {\n    move joint reg_p2" in program
    assert 'io gin[1] = "r[1]" on r1' in cell and 'io gin[2] = "r[2]" on r1' in cell
    assert re.findall(r"reg\.ls:(\d+):\d+: warning\[W535\]", output) == ["5", "10"]  # once per register
    assert "`R[1:gripper state]` is a register this program tests but never sets" in output
    _checks(tmp_path)


def test_registers_and_flags_the_program_sets_first_are_task_variables(tmp_path: Path) -> None:
    program, _, output = _import(tmp_path, {"VARS": [
        "R[11:count]=0", "F[5:box full]=(OFF)", "R[12:level]=0", "J P[1] 100% FINE", "IF (DI[1]=ON) THEN",
        "R[11:count]=R[11:count]+1", "F[5:box full]=(ON)", "R[12:level]=R[12:level]+2.5", "ENDIF",
        "IF (R[11:count]>=2 AND F[5:box full]) THEN", "DO[3]=ON", "ENDIF", "IF (!F[5:box full]),JMP LBL[2]",
        "DO[4]=ON", "LBL[2]"]})
    assert "native fanuc" not in program
    head = "\n".join(ln.strip() for ln in program.splitlines()[3:9])
    assert head == ("var count: int = 0\nvar box_full: bool = off\nvar level: num = 0\ncount = 0\nbox_full = off\n"
                    "level = 0")
    assert ("  if in[1] == on {\n    count = count + 1\n    box_full = on\n    level = level + 2.5\n  }\n"
            "  if (count >= 2) and (box_full) {\n    set out[3] = on\n  }\n  if box_full {\n    set out[4] = on\n") in program
    assert [m for m in re.findall(r"vars\.ls:(\d+):\d+: warning\[(W53\d)\]", output)] == [
        ("4", "W536"), ("5", "W536"), ("6", "W536")]
    _checks(tmp_path)


@pytest.mark.parametrize("body, why", [
    (["IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF", "R[1]=R[1]+1"], "read before the program sets it"),
    (["R[1]=0", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"], "only reset: another program raises it"),
    (["R[R[2]]=1", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"], "written through another register"),
    (["R[AR[1]]=1", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"], "written through an argument"),
    (["IF (R[1]=1.5) THEN", "DO[1]=ON", "ENDIF"], "a group input never holds a fraction"),
    (["IF (R[1]>-1) THEN", "DO[1]=ON", "ENDIF"], "a group input is never negative, a register may be"),
    (["IF (R[1]=1 AND DI[2] OR DI[3]) THEN", "DO[1]=ON", "ENDIF"], "AND and OR on one level"),
    (["F[1]=(OFF)", "IF (F[1]) THEN", "DO[1]=ON", "ENDIF"], "a flag only reset: a handshake another program raises"),
    (["IF (R[1]=R[2]) THEN", "DO[1]=ON", "ENDIF"], "two registers set elsewhere compared"),
    (["JMP LBL[1]", "R[1]=0", "LBL[1]", "R[1]=2", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"], "a jump skips the set"),
    (["IF (DI[1]=ON) THEN", "R[1]=1", "ENDIF", "R[1]=2", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"],
     "first set inside a block"),
    (["R[1]=0", "R[1]=$MCR.$GENOVERRIDE", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"], "set to a value not read"),
    (["FOR R[1]=1 TO 3", "ENDFOR", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"], "a FOR counter"),
    (["WAIT R[5]", "DO[1]=ON"], "a wait for R[5] seconds is no condition"),
])
def test_forms_whose_register_reading_is_not_certain_stay_native(tmp_path: Path, body: list[str], why: str) -> None:
    program, _, output = _import(tmp_path, {"NAT": ["J P[1] 100% FINE", *body]})
    native = [ln for ln in program.splitlines() if "native fanuc" in ln]
    assert any(f'"{line} ;"' in ln for ln in native for line in body if line.startswith(("IF", "WAIT"))), why
    if "WAIT" not in body[0]:
        assert "set out[1]" not in program, why
        assert "W535" not in output and "W536" not in output, why


def test_a_register_a_native_line_uses_is_no_task_variable(tmp_path: Path) -> None:
    """The backward jump keeps `R[1]=R[1]+1` native: compiled back it would count in R[1] while
    the variable is the register the backend numbers, so R[1] is read as no variable at all."""
    program, _, output = _import(tmp_path, {"LOOPED": [
        "R[1:count]=0", "R[3:other]=0", "LBL[1]", "R[1:count]=R[1:count]+1", "IF R[2]<5,JMP LBL[1]",
        "IF (R[1:count]=5) THEN", "DO[1]=ON", "ENDIF", "R[3:other]=1", "IF (R[3:other]=1) THEN", "DO[2]=ON", "ENDIF"]})
    assert "var count" not in program and "set out[1]" not in program
    assert 'native fanuc "R[1:count]=R[1:count]+1 ;"' in program and 'native fanuc "IF (R[1:count]=5) THEN ;"' in program
    assert "var other: int = 0" in program and "  if other == 1 {\n    set out[2] = on\n  }\n" in program
    assert output.count("W536") == 1


def test_a_register_another_program_of_the_job_mentions_is_no_task_variable(tmp_path: Path) -> None:
    """rmot's procs do not see a task's variables: SUB setting R[1] keeps MAIN's tests native;
    SUB's own test of R[2], which nothing of it sets, is a group input in the proc."""
    program, _, output = _import(tmp_path, {
        "MAIN": ["R[1]=0", "CALL SUB", "R[1]=1", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"],
        "SUB": ["R[1]=5", "IF (R[2]=4) THEN", "DO[2]=ON", "ENDIF"]})
    assert "var " not in program and "set out[1]" not in program and 'native fanuc "IF (R[1]=1) THEN ;"' in program
    assert "    if gin[1] == 4 {\n      set out[2] = on\n    }\n" in program  # in proc SUB
    assert "W536" not in output and output.count("W535") == 1


def test_variables_and_group_inputs_round_trip_through_the_fanuc_backend(tmp_path: Path) -> None:
    first, _, _ = _import(tmp_path, {"TRIP": [
        "R[3:count]=0", "J P[1] 100% FINE", "IF (R[7:part type]=2) THEN", "R[3:count]=R[3:count]+1", "ENDIF",
        "IF (R[3:count]<>4 AND DI[1]=ON) THEN", "J P[2] 100% FINE", "ENDIF", "WAIT R[7:part type]>=1"]})
    compiled = tmp_path / "out"
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "imported.rmot"), "--target", "fanuc", "-o",
                                      str(compiled)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    again = tmp_path / "again"
    again.mkdir()
    out = again / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", str(compiled / "fanuc" / "TRIP.ls"), "-o", str(out)],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    second = out.read_text()

    def logic(text: str) -> list[str]:
        return [ln.strip() for ln in text.splitlines() if ln.strip().startswith(("var ", "if ", "wait ", "count ="))]

    assert "native fanuc" not in second
    assert logic(first) == ["var count: int = 0", "count = 0", "if gin[1] == 2 {", "count = count + 1",
                            "if (count != 4) and in[1] == on {", "wait until gin[1] >= 1"]
    assert [ln for ln in logic(second) if ln != "count = 0"] == [ln for ln in logic(first) if ln != "count = 0"]


# ---------------------------------------------------------------- conditions, by an independent evaluation

_ATOMS = st.one_of(
    st.tuples(st.sampled_from(["DI", "DO"]), st.integers(1, 3), st.sampled_from(["", "=ON", "=OFF", "!"])).map(
        lambda t: f"!{t[0]}[{t[1]}]" if t[2] == "!" else f"{t[0]}[{t[1]}]{t[2]}"),
    st.tuples(st.integers(1, 2), st.sampled_from(["=", "<>", "<", ">", "<=", ">="]), st.integers(0, 3), st.booleans()).map(
        lambda t: f"{t[2]}{t[1]}R[{t[0]}:r{t[0]}]" if t[3] else f"R[{t[0]}:r{t[0]}]{t[1]}{t[2]}"),  # either side
)


def _levels(inner: st.SearchStrategy[str]) -> st.SearchStrategy[str]:
    return st.tuples(st.lists(inner, min_size=2, max_size=3), st.sampled_from([" AND ", " OR "]), st.booleans()).map(
        lambda t: ("!" if t[2] else "") + "(" + t[1].join(t[0]) + ")")


_CONDITIONS = st.recursive(_ATOMS, _levels, max_leaves=6)


def _tp_truth(cond: str, env: dict[str, dict[int, object]]) -> bool:
    """The TP condition's value: its text as Python (the manual's operators), not the reader."""
    text = re.sub(r"(DI|DO)\[(\d+)\]=(ON|OFF)", lambda m: f"({m[1]}[{m[2]}]=={m[3] == 'ON'})", cond)
    text = re.sub(r"R\[(\d+):\w+\]", r"R[\1]", text).replace("<>", "!=")
    text = re.sub(r"(?<![<>!=])=(?!=)", "==", text).replace("!(", "not (").replace("AND", "and").replace("OR", "or")
    text = re.sub(r"!(D[IO])", r"not \1", text)
    return bool(eval(text, {}, env))  # noqa: S307 - the test's own evaluation of a generated TP text


def _rmot_truth(program: str, cell: str, env: dict[str, dict[int, object]]) -> bool:
    """The imported program's first `if` condition's value, its ports bound as the stub names them."""
    cond = re.search(r"^  if (.*) \{$", program, re.M)
    assert cond is not None, program
    ports = {int(k): int(r) for k, r in re.findall(r'io gin\[(\d+)\] = "r\[(\d+)\]"', cell)}
    text = re.sub(r"gin\[(\d+)\]", lambda m: f"R[{ports[int(m[1])]}]", cond.group(1))
    text = text.replace("in[", "DI[").replace("out[", "DO[").replace("== on", "== True").replace("== off", "== False")
    return bool(eval(text, {}, env))  # noqa: S307 - the imported condition, over the test's own values


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(cond=_CONDITIONS, di=st.lists(st.booleans(), min_size=3, max_size=3),
       do=st.lists(st.booleans(), min_size=3, max_size=3), regs=st.lists(st.integers(0, 3), min_size=2, max_size=2))
def test_an_imported_condition_holds_exactly_when_the_tp_one_does(tmp_path: Path, cond: str, di: list[bool],
                                                                   do: list[bool], regs: list[int]) -> None:
    env: dict[str, dict[int, object]] = {"DI": dict(enumerate(di, 1)), "DO": dict(enumerate(do, 1)), "R": dict(enumerate(regs, 1))}
    truth = _tp_truth(cond, env)
    wrapped = cond if cond.startswith("(") else f"({cond})"
    for n, (body, runs_when) in enumerate(((["IF " + wrapped + " THEN", "DO[9]=ON", "ENDIF"], truth),
                                           (["IF " + wrapped + ",JMP LBL[1]", "DO[9]=ON", "LBL[1]"], not truth))):
        folder = tmp_path / f"c{len(cond)}_{n}_{abs(hash((cond, tuple(di), tuple(do), tuple(regs)))) % 10**6}"
        folder.mkdir(exist_ok=True)
        program, cell, output = _import(folder, {"PROP": body})
        assert "native fanuc" not in program, (cond, output)  # one operator per level: always read
        assert _rmot_truth(program, cell, env) == runs_when, (cond, program)


def test_registers_whose_typing_does_not_settle_in_a_few_passes_stay_native(tmp_path: Path) -> None:
    """A chain `R[k]=R[k+1]+1` ending at a register set from a system variable drops one variable
    per pass: beyond the bound (fanuc_regs._MAX_PASSES) none is read, the work stays linear."""
    n = 20
    body = ([f"R[{k}]=0" for k in range(1, n + 1)] + [f"R[{k}]=R[{k + 1}]+1" for k in range(1, n + 1)]
            + [f"R[{n + 1}]=$MCR.$GENOVERRIDE", "IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF"])
    program, _, output = _import(tmp_path, {"CHAIN": body})
    assert "var " not in program and "set out[1]" not in program and "W536" not in output
    short, _, _ = _import(tmp_path, {"CHAIN": body[:3] + body[n:n + 3] + body[-3:]})  # R[4]: set elsewhere
    assert short.count("  var ") == 3 and "r3 = {} + 1" not in short and "if r1 == 1 {" in short


def test_conditions_beyond_the_bound_stay_native(tmp_path: Path) -> None:
    """150 nested parentheses, 400 terms: more tokens than fanuc_regs reads (its work is bounded)."""
    deep = "(" * 150 + "R[1]=1" + ")" * 150
    wide = "(" + " AND ".join(f"R[{k}]=1" for k in range(1, 400)) + ")"
    program, _, _ = _import(tmp_path, {"DEEP": [f"IF {deep} THEN", "DO[1]=ON", "ENDIF", f"IF {wide} THEN", "DO[2]=ON",
                                                "ENDIF", "IF (R[1]=1) THEN", "DO[3]=ON", "ENDIF"]})
    assert "set out[1]" not in program and "set out[2]" not in program
    assert "  if gin[1] == 1 {\n    set out[3] = on\n  }\n" in program  # a short one beside them is read


def test_a_register_comment_naming_another_register_or_a_program_is_not_its_name(tmp_path: Path) -> None:
    """R[3:r5] beside R[5] (named r5), and R[4:sub] beside program SUB: each variable keeps a name
    of its own (a second `var r5` would be E153, a var named like a proc ambiguous)."""
    program, _, _ = _import(tmp_path, {"MAIN": ["R[3:r5]=0", "R[5]=0", "R[4:sub]=0", "CALL SUB", "R[3:r5]=1", "R[5]=1",
                                                "R[4:sub]=1", "IF (R[3:r5]=1 AND R[5]=1 AND R[4:sub]=1) THEN",
                                                "DO[1]=ON", "ENDIF"],
                                       "SUB": ["DO[2]=ON"]})
    decls = sorted(ln.strip() for ln in program.splitlines() if ln.strip().startswith("var "))
    assert decls == ["var r3_r5: int = 0", "var r4_sub: int = 0", "var r5: int = 0"]


def test_with_a_cell_a_register_it_does_not_declare_keeps_its_lines_native(tmp_path: Path) -> None:
    """--cell declares R[1] (gin[3]) but not R[2]: the jump on R[2] stays native as TP wrote it
    (no line numbers), with one W513; R[1]'s reads take the cell's port."""
    (tmp_path / "cell.rmot").write_text('cell c {\n  robot r1 = fanuc_m20ia\n  io gin[3] = "R[1]" on r1\n}\n')
    program, _, output = _import(tmp_path, {"CELLREG": ["IF (R[1]=1) THEN", "DO[1]=ON", "ENDIF", "IF R[2]<>3,JMP LBL[1]",
                                                        "J P[1] 100% FINE", "LBL[1]"]},
                                 ("--cell", str(tmp_path / "cell.rmot")))
    assert "  if gin[3] == 1 {\n    set out[1] = on\n  }\n" in program
    natives = [ln.strip().split("   #")[0] for ln in program.splitlines() if "native fanuc" in ln]
    assert natives[1:] == ['native fanuc "IF R[2]<>3,JMP LBL[1] ;"', 'native fanuc "J P[1] 100% FINE ;"',
                           'native fanuc "LBL[1] ;"']
    assert natives[0].startswith('native fanuc "P[1]{ GP1: UF : base, UT : ')  # the record the native move needs
    assert output.count("warning[W513]") == 1
