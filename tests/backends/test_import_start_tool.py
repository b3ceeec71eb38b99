"""A KRL or URScript program's first Cartesian move before the program sets its tool (KRL: or its
base) is read with rmot's defaults and says so: W546 (readers/start_state.py).

Witnesses: KSS keeps `$TOOL` and `$BASE` from the program that ran before (global system
variables); a URScript program runs with the installation's TCP until `set_tcp` (URScript manual,
set_tcp). The programs below are written by hand; each case says where the move's tool comes
from, and the test checks the warning is given exactly where the file leaves it to the controller.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli


def _import(path: Path) -> str:
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(path.with_suffix(".rmot"))], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return result.output


@pytest.mark.parametrize(("name", "text", "line", "what"), [
    ("a.script", "def prog():\n  movej([0, -1.57, 1.57, 0, 1.57, 0], a=1.4, v=1.0)\n"
                 "  movel(p[0.4, 0.1, 0.3, 0, 3.1416, 0], a=1.2, v=0.25)\nend\n", 3, "its TCP"),
    ("t.src", "DEF t( )\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}\nLIN {X 500, Y 0, Z 800, A 0, B 90, C 0}\nEND\n",
     3, "its $TOOL or $BASE"),
    ("b.src", "DEF b( )\n$TOOL = $NULLFRAME\nLIN {X 500, Y 0, Z 800, A 0, B 90, C 0}\nEND\n", 3, "its $BASE"),
])
def test_a_cartesian_move_before_the_tool_is_set_says_so(tmp_path: Path, name: str, text: str, line: int, what: str) -> None:
    """The first move to a pose before the program sets its tool or base: W546 there, once (the
    joint move to axis values before it goes where it goes whatever the tool)."""
    (tmp_path / name).write_text(text)
    output = _import(tmp_path / name)
    found = re.findall(rf"{re.escape(name)}:(\d+):\d+: warning\[W546\]: this move is read before the program sets "
                       rf"{re.escape(what)} ", output)
    assert found == [str(line)], output


@pytest.mark.parametrize(("name", "text"), [
    ("a.script", "def prog():\n  set_tcp(p[0, 0, 0.1, 0, 0, 0])\n  movel(p[0.4, 0.1, 0.3, 0, 3.1416, 0], a=1.2, v=0.25)\nend\n"),
    ("t.src", "DEF t( )\n$TOOL = $NULLFRAME\n$BASE = $NULLFRAME\nLIN {X 500, Y 0, Z 800, A 0, B 90, C 0}\nEND\n"),
    ("j.src", "DEF j( )\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}\nEND\n"),
])
def test_a_program_that_sets_its_tool_first_is_quiet(tmp_path: Path, name: str, text: str) -> None:
    """set_tcp, or $TOOL and $BASE, before the first Cartesian move (or only axis moves): no W546."""
    (tmp_path / name).write_text(text)
    assert "W546" not in _import(tmp_path / name)
