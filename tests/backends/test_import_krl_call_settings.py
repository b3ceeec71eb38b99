"""KRL's $VEL.CP is the controller's: a routine's LIN that sets no speed of its own runs at its
caller's. `rmot import` gives the call the speeds and accelerations in force there (`speed
500 mm/s` before `sub()`), which rmot's proc takes from its caller, so the compiled-back program
runs every LIN at the speed the source did; where a block set the speed (known only at run time)
the call stays native.

Witness: a small KRL interpreter written here (DEF/END, calls, `$VEL.CP=`, IF on $IN[1] at a given
level, LIN) runs the source and the program rmot compiles back from the import, and records
$VEL.CP at each LIN; the two records must be equal. A Hypothesis property draws the programs.
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rmot.compiler.cli import cli

DAT = """DEFDAT k
  DECL E6POS XP1={X 500.0,Y 0.0,Z 600.0,A 0.0,B 90.0,C 0.0,S 6,T 50,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
  DECL E6POS XP2={X 500.0,Y 100.0,Z 600.0,A 0.0,B 90.0,C 0.0,S 6,T 50,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
ENDDAT
"""


def lin_speeds(src: str, level: bool = False) -> list[float]:
    """$VEL.CP (m/s) at each LIN the program's first DEF runs (2 m/s where none is set)."""
    lines = [re.sub(r";.*", "", ln).strip() for ln in src.splitlines()]
    lines = [ln for ln in lines if ln]
    defs = {m.group(1).upper(): k + 1 for k, ln in enumerate(lines) for m in [re.match(r"(?i)DEF\s+(\w+)\s*\(", ln)] if m}
    vel = [2.0]
    out: list[float] = []

    def run(i: int) -> None:
        skip = 0
        while not re.fullmatch(r"(?i)END", lines[i]):
            ln = lines[i]
            i += 1
            if re.match(r"(?i)IF\b", ln):
                skip += 0 if level else 1
            elif re.fullmatch(r"(?i)ENDIF", ln):
                skip = max(0, skip - 1)
            elif skip:
                continue
            elif m := re.fullmatch(r"(?i)\$VEL\.CP\s*=\s*([\d.]+)", ln):
                vel[0] = float(m.group(1))
            elif re.match(r"(?i)LIN\b", ln):
                out.append(vel[0])
            elif (m := re.fullmatch(r"(\w+)\s*\(\s*\)", ln)) and m.group(1).upper() in defs:
                run(defs[m.group(1).upper()])

    run(min(defs.values()))
    return out


def _round_trip(tmp_path: Path, src: str) -> str:
    (tmp_path / "k.src").write_text(src)
    (tmp_path / "k.dat").write_text(DAT)
    runner = CliRunner()
    result = runner.invoke(cli, ["import", str(tmp_path / "k.src"), "-o", str(tmp_path / "k.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = runner.invoke(cli, ["compile", str(tmp_path / "k.rmot"), "--target", "krl", "--allow-findings", "-o",
                                 str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return (tmp_path / "out" / "krl" / "k.src").read_text()


SOURCE = """DEF k()
  $TOOL = {X 0, Y 0, Z 150, A 0, B 0, C 0}
  $BASE = $NULLFRAME
  PTP XP1
  $VEL.CP = 0.5
  sub()
  LIN XP2
END

DEF sub()
  LIN XP1
  $VEL.CP = 0.1
  LIN XP2
END
"""


def test_a_routines_lin_runs_at_its_callers_speed(tmp_path: Path) -> None:
    compiled = _round_trip(tmp_path, SOURCE)
    assert lin_speeds(SOURCE) == [0.5, 0.1, 0.1]
    assert lin_speeds(compiled) == [0.5, 0.1, 0.1]
    assert "speed 500 mm/s" in (tmp_path / "k.rmot").read_text()


def test_a_call_where_the_speed_is_known_only_at_run_time_stays_native(tmp_path: Path) -> None:
    src = SOURCE.replace("  $VEL.CP = 0.5\n", "  IF $IN[1] THEN\n    $VEL.CP = 0.5\n  ENDIF\n")
    _round_trip(tmp_path, src)
    text = (tmp_path / "k.rmot").read_text()
    assert 'native krl "sub()"' in text and 'native krl "LIN XP2"' in text, text


def test_a_native_motion_after_a_routine_that_wrote_the_speed_gets_the_one_set_since(tmp_path: Path) -> None:
    """After `sub()` wrote 0.2 m/s, the caller sets 0.1 again, the value its last motion read
    had: the next motion is native (sub may have changed the tool), and the compiled program
    must restate 0.1 before it, or it would run at sub's 0.2."""
    src = "\n".join(["DEF k()", "  $TOOL = {X 0, Y 0, Z 150, A 0, B 0, C 0}", "  $BASE = $NULLFRAME", "  PTP XP1",
                     "  $VEL.CP = 0.1", "  LIN XP2", "  sub()", "  $VEL.CP = 0.1", "  LIN XP2", "END", "",
                     "DEF sub()", "  LIN XP1", "  $VEL.CP = 0.2", "  LIN XP2", "END", ""])
    assert lin_speeds(src) == [0.1, 0.1, 0.2, 0.1]
    assert lin_speeds(_round_trip(tmp_path, src)) == lin_speeds(src)


STEP = st.sampled_from(["lin", "vel1", "vel5", "call"])


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(steps=st.lists(STEP, min_size=1, max_size=6), sub_sets=st.booleans())
def test_the_compiled_back_program_runs_each_lin_at_the_sources_speed(tmp_path_factory, steps: list[str],  # type: ignore[no-untyped-def]
                                                                     sub_sets: bool) -> None:
    """The routine is called once: a second call after one that changed the speed is known only
    at run time and stays native, and a native call runs the routine as rmot compiled it for
    the call it read (its speed there), which this property does not cover."""
    body = ["  $TOOL = {X 0, Y 0, Z 150, A 0, B 0, C 0}", "  $BASE = $NULLFRAME", "  PTP XP1"]
    steps = [s for k, s in enumerate(steps) if s != "call" or "call" not in steps[:k]]
    for k, step in enumerate(steps):
        body += {"lin": [f"  LIN XP{1 + k % 2}"], "vel1": ["  $VEL.CP = 0.1"], "vel5": ["  $VEL.CP = 0.5"],
                 "call": ["  sub()"]}[step]
    sub = ["  LIN XP1"] + (["  $VEL.CP = 0.2", "  LIN XP2"] if sub_sets else [])
    src = "\n".join(["DEF k()", *body, "  LIN XP2", "END", "", "DEF sub()", *sub, "END", ""])
    compiled = _round_trip(tmp_path_factory.mktemp("krl"), src)
    assert lin_speeds(compiled) == lin_speeds(src), (src, compiled)
