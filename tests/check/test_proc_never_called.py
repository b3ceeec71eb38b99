"""W153: a proc of the program's own file that no task calls is checked but neither planned,
verified nor written; the user is told, located at its name (lang/REFERENCE.md §5, §10). The
witness is the compiled file itself: the routine the warning names is absent from it, and the
one a task calls is there."""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

PROGRAM = """cell c {
  robot r1 = abb_irb1600
}
program demo on r1 {
  target home = joints(0, 0, 0, 0, 30, 0) deg
  proc side() {
    move joint joints(10, 0, 0, 0, 30, 0) deg
  }
  proc used() {
    move joint joints(-10, 0, 0, 0, 30, 0) deg
  }
  move joint home
  used()
}
"""


def test_a_proc_no_task_calls_is_warned_of_and_not_written(tmp_path: Path) -> None:
    (tmp_path / "p.rmot").write_text(PROGRAM)
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "rapid", "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert re.findall(r"p\.rmot:(\d+):(\d+): warning\[W153\]: proc '(\w+)' is never called", result.output) == [("6", "8", "side")]
    module = next((tmp_path / "out" / "rapid").glob("*.mod")).read_text()
    assert re.search(r"PROC used\b", module) and not re.search(r"PROC side\b", module)


def test_a_library_files_procs_are_not_warned_of(tmp_path: Path) -> None:
    """A file of procs with no program (examples/lib) is there for the programs that import it."""
    (tmp_path / "lib.rmot").write_text("proc spare() {\n  wait 1 s\n}\n")
    (tmp_path / "p.rmot").write_text('import "lib.rmot"\n' + PROGRAM)
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "p.rmot")])
    assert "spare" not in result.output and "proc 'side' is never called" in result.output, result.output
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "lib.rmot")])
    assert "W153" not in result.output, result.output
