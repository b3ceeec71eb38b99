"""URScript keeps the TCP a `set_tcp` set until the next one, across calls and blocks: after a
function, an `if` arm or a native line that sets another TCP, the next move must set its own,
or it runs with the one they left (a probe's 250 mm where rmot planned the gripper's 150 mm:
the flange 100 mm off the verified path, without a word).

Witness: a small interpreter of the compiled script written here (functions, `if` on a
digital input, `while` run once, `set_tcp`, movej/movel), independent of the backend, runs it
for both input levels and records the TCP each move runs with; the expected TCP is each rmot
move's tool, from the program text. A Hypothesis property draws programs of moves, tool
changes, calls, ifs and native set_tcp lines.
"""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rmot.compiler.cli import cli
from ur_witness import tcp_at_moves as _run

CELL = """cell c {
  robot r1 = ur5e
  tool gripper = none tcp pose(z=150mm) mass 1 kg on r1
  tool probe = none tcp pose(z=250mm) mass 0.5 kg on r1
}
"""
TCP_Z = {"gripper": 0.15, "probe": 0.25}
HEAD = """program u on r1 {
  target home = joints(0, -90, -90, -90, 90, 0) deg
  target a = pose(x=400mm, y=0mm, z=300mm, rx=180deg)
  target b = pose(x=400mm, y=100mm, z=300mm, rx=180deg)
  proc touch() {
    tool probe
    move linear b speed 100 mm/s
  }
  tool gripper
  move joint home
"""


def _compile(tmp_path: Path, body: str) -> str:
    (tmp_path / "c.rmot").write_text(CELL)
    src = tmp_path / "u.rmot"
    src.write_text('use cell "c.rmot"\n' + HEAD + body + "}\n")
    result = CliRunner().invoke(cli, ["compile", str(src), "--target", "urscript", "--allow-findings", "-o",
                                      str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return (tmp_path / "out" / "urscript" / "u.script").read_text()


def test_the_move_after_a_call_or_an_if_sets_its_own_tcp(tmp_path: Path) -> None:
    body = """  move linear a speed 100 mm/s
  touch()
  tool gripper
  move linear a speed 100 mm/s
  if in[1] == on {
    tool probe
    move linear b speed 100 mm/s
  }
  move linear a speed 100 mm/s
  native urscript "set_tcp(p[0,0,0.3,0,0,0])"
  move linear b speed 100 mm/s
"""
    script = _compile(tmp_path, body)
    assert _run(script, True) == [0.15, 0.15, 0.25, 0.15, 0.25, 0.15, 0.15]
    assert _run(script, False) == [0.15, 0.15, 0.25, 0.15, 0.15, 0.15]


STEP = st.sampled_from(["gripper", "probe", "call", "if", "native"])


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(steps=st.lists(STEP, min_size=1, max_size=5), level=st.booleans())
def test_every_move_runs_with_its_own_tool(tmp_path_factory, steps: list[str], level: bool) -> None:  # type: ignore[no-untyped-def]
    """Each drawn step is a move with a tool, a call of `touch` (probe), an `if` arm moving with
    the probe, or a native set_tcp; the witness's TCP at every move is the move's tool's."""
    body, expected, tool = [], [TCP_Z["gripper"]], "gripper"
    for k, step in enumerate(steps):
        target = "ab"[k % 2]
        if step in TCP_Z:
            tool = step
            body += [f"  tool {step}", f"  move linear {target} speed 100 mm/s"]
            expected.append(TCP_Z[step])
        elif step == "call":
            body.append("  touch()")
            expected.append(TCP_Z["probe"])
            body += [f"  tool {tool}"]  # the proc's tool change is its own scope's
        elif step == "if":
            body += ["  if in[1] == on {", "    tool probe", "    move linear b speed 100 mm/s", "  }"]
            expected += [TCP_Z["probe"]] if level else []
        else:
            body.append('  native urscript "set_tcp(p[0,0,0.3,0,0,0])"')
        body.append(f"  move linear {'ba'[k % 2]} speed 100 mm/s")
        expected.append(TCP_Z[tool])
    script = _compile(tmp_path_factory.mktemp("u"), "\n".join(body) + "\n")
    assert _run(script, level) == expected, script
