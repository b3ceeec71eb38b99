"""Instructions inlined from a proc remember their call sites, and findings name them."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.lang import ir, ir_tree
from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_text

PROGRAM = """\
program calls on r1 {
  proc reach_out(p: pose) {
    move linear p
  }
  proc twice(p: pose) {
    reach_out(p)
    reach_out(shift(p, z=10mm))
  }
  move joint joints(0, 0, 0, 0, 30, 0) deg
  twice(pose(x=5000mm, z=900mm, rx=180deg))
}
"""


def _moves(body: tuple[ir.Instr, ...]) -> list[ir.Move]:
    return [i for i in ir_tree.walk(body) if isinstance(i, ir.Move)]


def test_inlined_moves_carry_their_call_chain() -> None:
    """A move two procs deep lists the inner call, then the outer call, as its span's parents."""
    result = load_text(PROGRAM, "calls.rmot")
    assert result.program is not None, result.diagnostics
    inner = _moves(result.program.tasks[0].body)[1:]
    assert len(inner) == 2
    chains = [[(s.start.line, s.start.col) for s in m.span.expansion_chain()] for m in inner]
    assert chains == [[(6, 5), (10, 3)], [(7, 5), (10, 3)]]
    assert all(m.span.start.line == 3 for m in inner)


def test_check_output_points_at_the_call_that_failed(tmp_path: Path) -> None:
    """`rmot check` shows the proc body line and, under it, each call it came through."""
    src = tmp_path / "calls.rmot"
    src.write_text(PROGRAM, encoding="utf-8")
    result = CliRunner().invoke(cli, ["check", str(src)], prog_name="rmot")
    assert result.exit_code == 1
    lines = result.output.splitlines()
    first = next(i for i, line in enumerate(lines) if "error[E220]" in line)
    assert lines[first].startswith(f"{src}:3:5: error[E220]:")
    assert lines[first + 3] == f"{src}:6:5: note: in the proc call here"
    assert lines[first + 6] == f"{src}:10:3: note: in the proc call here"
