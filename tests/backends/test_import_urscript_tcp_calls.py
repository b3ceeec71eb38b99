"""A URScript function's `set_tcp` sets the controller's TCP: defining the function changes
nothing, calling it leaves the TCP it set. `rmot import` reads each move with the TCP it runs
with: after a definition the one before it, after a call the one the function ends with (a
`set_tcp` at its outermost level after every other setting), and where that is known only at
run time (set in a branch of the function) the moves after the call stay native.

Witness: tests/backends/ur_witness.py runs the source script (not rmot's reader) and records
the TCP each move runs with; every move the import reads must carry that TCP. A Hypothesis
property draws scripts of functions (a TCP set at the top, in an `if`, or not at all) and calls.
"""

from __future__ import annotations

import math
from pathlib import Path

from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st
from ur_witness import tcp_at_moves

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Call, Document, Move, Native, Stmt
from rmot.compiler.cli import cli

MOVE = "movel(p[0.4,{y},0.3,3.14159,0,0], a=1.2, v=0.25)"


def _read_tcps(doc: Document) -> list[float | None]:
    """The TCP z (m) of each move the import reads, in run order (calls followed into their
    procs, whose moves without a tool of their own run with the one active at the call, as
    rmot's procs do), None for a move kept native (and each move of a call kept native)."""
    z = {t.name: t.tcp.position[2] for t in doc.tools}
    procs = {r.name: r.body for r in doc.routines}

    def run(body: tuple[Stmt, ...], active: str) -> list[float | None]:
        out: list[float | None] = []
        for s in body:
            if isinstance(s, Move):
                active = s.tool or active
                out.append(z.get(active, math.nan))
            elif isinstance(s, Native) and s.text.startswith(("movel", "movej")):
                out.append(None)
            elif isinstance(s, Native) and s.text.rstrip("()") in procs:  # a call kept native: none of its moves read
                out += [None for _ in run(procs[s.text.rstrip("()")], active)]
            elif isinstance(s, Call):
                out += run(procs[s.name], s.tool or active)
        return out

    return run(procs[doc.main], "")


def _check(tmp_path: Path, script: str) -> list[float | None]:
    path = tmp_path / "prog.script"
    path.write_text(script)
    read = _read_tcps(read_files([str(path)]))
    ran = tcp_at_moves(script, False, main="prog")
    assert len(read) == len(ran), (read, ran)
    for r, w in zip(read, ran):
        assert r is None or math.isclose(r, w), (read, ran, script)
    return read


def test_a_definition_leaves_the_tcp_and_a_call_sets_the_one_its_function_ends_with(tmp_path: Path) -> None:
    script = f"""def prog():
  set_tcp(p[0,0,0.15,0,0,0])
  def probe_it():
    set_tcp(p[0,0,0.25,0,0,0])
    {MOVE.format(y=0.1)}
  end
  {MOVE.format(y=0.0)}
  probe_it()
  {MOVE.format(y=0.0)}
end
"""
    assert _check(tmp_path, script) == [0.15, 0.25, 0.25]  # every move read, each with the TCP it runs with


def test_a_tcp_a_function_sets_in_a_branch_leaves_the_moves_after_the_call_native(tmp_path: Path) -> None:
    """`maybe` sets a TCP at its top, then perhaps another in a branch: after the call the TCP
    is the run time's, so the next move and the call of `here` (whose move runs with the TCP at
    the call) stay native until the program sets one again."""
    script = f"""def prog():
  set_tcp(p[0,0,0.15,0,0,0])
  def maybe():
    set_tcp(p[0,0,0.2,0,0,0])
    if get_standard_digital_in(1) == True:
      set_tcp(p[0,0,0.25,0,0,0])
    end
  end
  def here():
    {MOVE.format(y=0.2)}
  end
  {MOVE.format(y=0.0)}
  maybe()
  {MOVE.format(y=0.1)}
  here()
  set_tcp(p[0,0,0.15,0,0,0])
  here()
  {MOVE.format(y=0.0)}
end
"""
    assert _check(tmp_path, script) == [0.15, None, None, 0.15, 0.15]


FUNCTION = st.sampled_from(["top", "branch", "top_then_branch", "none", "calls_f0"])
MAIN = st.lists(st.sampled_from(["move", "tcp15", "tcp25", "call0", "call1"]), min_size=1, max_size=8)


@settings(max_examples=60, deadline=None)
@given(kinds=st.lists(FUNCTION, min_size=2, max_size=2), main=MAIN)
def test_every_move_read_runs_with_its_tcp(tmp_path_factory, kinds: list[str], main: list[str]) -> None:  # type: ignore[no-untyped-def]
    lines = ["def prog():", "  set_tcp(p[0,0,0.1,0,0,0])"]
    for k, kind in enumerate(kinds):
        lines.append(f"  def f{k}():")
        if kind in ("top", "top_then_branch"):
            lines.append(f"    set_tcp(p[0,0,0.{3 + k},0,0,0])")
        if kind in ("branch", "top_then_branch"):
            lines += ["    if get_standard_digital_in(1) == True:", "      set_tcp(p[0,0,0.5,0,0,0])", "    end"]
        elif kind == "calls_f0" and k == 1:
            lines.append("    f0()")
        lines += [f"    {MOVE.format(y=0.2)}", "  end"]
    for step in main:
        lines.append({"move": f"  {MOVE.format(y=0.0)}", "tcp15": "  set_tcp(p[0,0,0.15,0,0,0])",
                      "tcp25": "  set_tcp(p[0,0,0.25,0,0,0])", "call0": "  f0()", "call1": "  f1()"}[step])
    lines += [f"  {MOVE.format(y=0.0)}", "end", ""]
    _check(tmp_path_factory.mktemp("ur"), "\n".join(lines))


def test_compiled_back_every_move_runs_with_the_tcp_it_ran_with(tmp_path: Path) -> None:
    """Import, then compile for URScript: the witness gives every move of the compiled script
    the TCP the source's move ran with (a function moving with its caller's TCP, called under
    two TCPs, becomes one routine per TCP)."""
    script = f"""def prog():
  set_tcp(p[0,0,0.15,0,0,0])
  def f0():
    {MOVE.format(y=0.2)}
  end
  def f1():
    set_tcp(p[0,0,0.25,0,0,0])
    {MOVE.format(y=0.1)}
  end
  {MOVE.format(y=0.0)}
  f0()
  f1()
  f0()
  {MOVE.format(y=0.0)}
end
"""
    source = tmp_path / "prog.script"
    source.write_text(script)
    runner = CliRunner()
    result = runner.invoke(cli, ["import", str(source), "-o", str(tmp_path / "prog.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = runner.invoke(cli, ["compile", str(tmp_path / "prog.rmot"), "--target", "urscript", "--allow-findings",
                                 "-o", str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    compiled = (tmp_path / "out" / "urscript" / "prog.script").read_text()
    ran = tcp_at_moves(script, False, main="prog")
    assert ran == [0.15, 0.15, 0.25, 0.25, 0.25]
    assert tcp_at_moves(compiled, False, main="prog") == ran
