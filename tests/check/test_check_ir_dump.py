"""The IR text dump is stable (golden file) and the JSON form holds the same program."""

from __future__ import annotations

import json
import os
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_program
from rmot.compiler.ir_dump import dump_program, to_json

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "pick_place.rmot"
GOLDEN = ROOT / "tests" / "data" / "golden" / "pick_place.ir.txt"


def test_dump_matches_the_golden_file() -> None:
    """examples/pick_place.rmot dumps exactly as recorded (set RMOT_UPDATE_GOLDEN=1 to re-record)."""
    prog = load_program(str(EXAMPLE)).program
    assert prog is not None
    text = dump_program(prog)
    if os.environ.get("RMOT_UPDATE_GOLDEN"):
        GOLDEN.write_text(text, encoding="utf-8")
    assert text == GOLDEN.read_text(encoding="utf-8")


def test_json_round_trips_the_instruction_count() -> None:
    """The JSON has one object per instruction, with its uid, in the same order as the dump."""
    prog = load_program(str(EXAMPLE)).program
    assert prog is not None
    data = json.loads(to_json(prog))
    uids: list[int] = []

    def collect(body: list[dict]) -> None:  # type: ignore[type-arg]
        for node in body:
            uids.append(node["uid"])
            collect(node.get("body", []) if node["type"] == "ProcCall" else [])
            collect(node.get("then", []) + node.get("otherwise", []))
            for it in node.get("iterations", []):  # a for loop keeps every iteration
                collect(it["body"])

    collect(data["tasks"][0]["body"])
    assert uids == list(range(1, len(uids) + 1)) and len(uids) > 50
    assert data["cell"]["robots"][0]["source"] == {"type": "RobotSource", "kind": "library", "ref": "abb_irb1600",
                                                   "speed_share": 1.0, "accel_share": 1.0}


class TestIrCommand:
    def test_prints_the_dump_and_exits_0(self) -> None:
        """`rmot ir FILE` prints the golden dump."""
        result = CliRunner().invoke(cli, ["ir", str(EXAMPLE)])
        assert result.exit_code == 0
        assert result.output == GOLDEN.read_text(encoding="utf-8")

    def test_json_option(self) -> None:
        """`--json` prints a Program object."""
        result = CliRunner().invoke(cli, ["ir", str(EXAMPLE), "--json"])
        assert result.exit_code == 0 and json.loads(result.output)["type"] == "Program"

    def test_errors_go_to_stderr_with_exit_2(self, tmp_path: Path) -> None:
        """A bad file prints `file:line:col: error[...]`, the line and carets, and exits 2."""
        bad = tmp_path / "bad.rmot"
        bad.write_text("program p on r1 {\n  move joint hme\n}\n")
        result = CliRunner().invoke(cli, ["ir", str(bad)])
        assert result.exit_code == 2
        assert result.stderr.splitlines() == [f"{bad}:2:14: error[E101]: unknown name 'hme'",
                                              " 2 |   move joint hme", "   |              ^~~"]
        assert result.stdout == ""

    def test_cell_file_prints_the_cell(self) -> None:
        """A file holding only a cell dumps the cell."""
        result = CliRunner().invoke(cli, ["ir", str(ROOT / "examples" / "cells" / "demo.rmot")])
        assert result.exit_code == 0 and result.output.startswith("cell demo\n  robot r1 library:abb_irb1600")

    def test_cell_option(self, tmp_path: Path) -> None:
        """--cell makes the program run in another cell."""
        prog = tmp_path / "p.rmot"
        prog.write_text("program p on r1 { wait 1 s }\n")
        result = CliRunner().invoke(cli, ["ir", str(prog), "--cell", str(ROOT / "examples" / "cells" / "demo.rmot")])
        assert result.exit_code == 0 and "\ncell demo\n" in result.output

    def test_project_root_option(self, tmp_path: Path) -> None:
        """--project-root widens where named files may be; without it, ../ is refused (exit 2)."""
        (tmp_path / "sub").mkdir()
        (tmp_path / "lib.rmot").write_text("const h = 5 mm\n")
        prog = tmp_path / "sub" / "p.rmot"
        prog.write_text('import "../lib.rmot"\nprogram p on r1 { wait 1 s }\n')
        refused = CliRunner().invoke(cli, ["ir", str(prog)])
        assert refused.exit_code == 2 and "error[E504]" in refused.stderr
        allowed = CliRunner().invoke(cli, ["ir", str(prog), "--project-root", str(tmp_path)])
        assert allowed.exit_code == 0 and allowed.stdout.startswith("program p\ncell default_cell\n")

    def test_library_file_dumps_nothing(self) -> None:
        """A file of procs and consts has no program and no cell: exit 0, a note on stderr."""
        result = CliRunner().invoke(cli, ["ir", str(ROOT / "examples" / "lib" / "moves.rmot")])
        assert result.exit_code == 0 and result.stdout == "" and "no program and no cell" in result.stderr
