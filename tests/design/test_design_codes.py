"""Bad input to the design commands (`rmot reach`, `rmot place`, `rmot compare`) is a diagnostic
with its registered code, rendered `rmot: error[E80x]: ...` (no span: the value came from a
command-line option, which the message names), exit 2 — never a bare `error:` line or a
traceback. Every code of rmot.compiler.design.codes is triggered here through the CLI."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

DATA = Path(__file__).resolve().parent / "data"
PROGRAM = str(DATA / "draw.rmot")
CELL = str(DATA / "cell_inside.rmot")
DEMO = str(Path(__file__).resolve().parents[2] / "examples" / "cells" / "demo.rmot")
PLACE = ["place", PROGRAM, "--cell", CELL, "--samples", "8"]
COMPARE = ["compare", PROGRAM, "--cell", CELL]

# (code, command line with OUT for the output file, text the message must contain)
CASES = [
    ("E800", [*PLACE, "--region", "x=0m..1m", "-o", "OUT.rmot"], "--region must give y=LO..HI"),
    ("E800", [*PLACE, "--region", "x=0m..1m, y=0m..1m, q=3m", "-o", "OUT.rmot"], "(got 'q=3m')"),
    ("E800", [*PLACE, "--region", "x=0m..1m, x=0m..1m, y=0m..1m", "-o", "OUT.rmot"], "each once"),
    ("E800", [*PLACE, "--region", "", "-o", "OUT.rmot"], "--region must give x=LO..HI"),
    ("E800", [*COMPARE, "--place", "--region", "y=0m..1m"], "--region must give x=LO..HI"),
    ("E801", [*PLACE, "--region", "x=1m..0m, y=0m..1m", "-o", "OUT.rmot"], "--region x must go from low to high"),
    ("E801", [*PLACE, "--region", "x=0m..1m, y=0m..1m, rz=90deg..-90deg", "-o", "OUT.rmot"], "--region rz"),
    ("E802", [*PLACE, "--region", "x=0..1m, y=0m..1m", "-o", "OUT.rmot"], "--region x must be a number with a unit"),
    ("E802", [*PLACE, "--region", "x=..1m, y=0m..1m", "-o", "OUT.rmot"], "--region x must be a number with a unit"),
    ("E802", [*PLACE, "--region", "x=1e999m..2m, y=0m..1m", "-o", "OUT.rmot"], "--region x must be a finite number"),
    ("E802", ["reach", "--robot", "ur5e", "--orientation", "rx=180", "-o", "OUT.png"], "--orientation rx must be a number"),
    ("E802", ["reach", "--robot", "ur5e", "--orientation", "rx=1e999deg", "-o", "OUT.png"], "rx must be a finite number"),
    ("E802", ["reach", "--robot", "ur5e", "--z", "1e999mm", "-o", "OUT.png"], "--z must be a length of at most 10 m"),
    ("E802", ["reach", "--robot", "ur5e", "--step", "5", "-o", "OUT.png"], "--step must be a length with a unit"),
    ("E803", ["reach", "--robot", "ur5e", "--orientation", "rq=180deg", "-o", "OUT.png"], "--orientation must be 'any'"),
    ("E803", ["reach", "--robot", "ur5e", "--orientation", "rx=1deg, rx=2deg", "-o", "OUT.png"], "each given once"),
    ("E804", ["reach", DEMO, "--robot", "zz", "-o", "OUT.png"], "--robot must name a robot of cell 'demo' (r1, r2) (got 'zz')"),
    ("E804", [*PLACE, "--robot", "zz", "--region", "x=0m..1m, y=0m..1m", "-o", "OUT.rmot"], "--robot must name a robot of cell"),
    ("E804", [*COMPARE, "--as", "zz"], "--as must name a robot of cell 'place_inside' (r1) (got 'zz')"),
    # an unknown bare library name is E804 too, not the loader's E111
    ("E804", ["reach", "--robot", "no_such_arm", "-o", "OUT.png"],
     "--robot: unknown robot 'no_such_arm'"),
    ("E804", [*COMPARE, "--robot", "no_such_arm"],
     "--robot must name a library robot or a URDF file"),
    ("E805", ["reach", DEMO, "--robot", "r1", "--tool", "zz", "-o", "OUT.png"], "--tool must name a tool of cell 'demo'"),
    ("E806", ["reach", "--robot", "ur5e", "-o", "OUT.jpg"], "-o must end in one of .png, .svg, .html"),
    ("E807", ["reach", "-o", "OUT.png"], "--robot must name a library robot or a URDF file"),
    ("E807", ["reach", "--robot", "ur5e", "--tool", "gripper", "-o", "OUT.png"], "--tool needs a cell"),
    ("E807", ["reach", DEMO, "-o", "OUT.png"], "--robot must name one of the cell's robots (r1, r2)"),
    ("E807", [*COMPARE, "--place"], "--place needs --region"),
    ("E808", ["reach", "--robot", "ur5e", "--step", "0mm", "-o", "OUT.png"], "--step must be positive"),
    ("E808", ["reach", "--robot", "ur5e", "--step", "0.01mm", "-o", "OUT.html"], "--step must be at least"),
]


def _args(args: list[str], tmp_path: Path) -> list[str]:
    return [str(tmp_path / a.replace("OUT", "out")) if a.startswith("OUT") else a for a in args]


@pytest.mark.parametrize(("code", "args", "message"), CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_bad_option_is_a_coded_diagnostic(tmp_path: Path, code: str, args: list[str], message: str) -> None:
    """The first line is `rmot: error[CODE]: <message naming the option>`, exit 2, nothing written."""
    result = CliRunner().invoke(cli, _args(args, tmp_path))
    assert result.exit_code == 2, result.output
    first = result.output.strip().splitlines()[0]
    assert re.fullmatch(rf"rmot: error\[{code}\]: .+", first), result.output
    assert message in first
    assert "Traceback" not in result.output and not re.search(r"^error:", result.output, re.M)
    assert not any(p.is_file() for p in tmp_path.iterdir())


def test_every_design_error_code_is_triggered() -> None:
    """The cases above reach every E-code the design commands register (none is dead)."""
    from rmot.lang.diagnostics import Code
    from rmot.compiler.design import codes

    registered = {v.id for v in vars(codes).values() if isinstance(v, Code) and v.id.startswith("E")}
    assert registered == {c[0] for c in CASES}


def test_region_without_place_warns(tmp_path: Path) -> None:
    """`compare --region` without `--place` runs, and says the region is ignored (W800)."""
    result = CliRunner().invoke(cli, [*COMPARE, "--region", "x=0m..1m, y=0m..1m"])
    assert result.exit_code in (0, 1), result.output
    assert "rmot: warning[W800]: --region is ignored without --place" in result.output
    assert "robot 'r1' replaced by each arm" in result.output


@pytest.mark.parametrize("args", [
    [*PLACE, "--region", "x=0m..1m, y=0m..1m", "-o", "OUT/missing/x.rmot"],     # checked before the search
    ["reach", "--robot", "ur5e", "-o", "OUT/missing/map.svg"],                    # ... before the map
    ["reach", "--robot", "ur5e", "--orientation", "rx=180deg", "--step", "200mm", "-o", "OUT/dir.svg"],  # a folder
])
def test_unwritable_output_is_e520(tmp_path: Path, args: list[str]) -> None:
    """An -o file that cannot be written is the project's output-failed diagnostic E520, exit 2."""
    (tmp_path / "out" / "dir.svg").mkdir(parents=True)
    result = CliRunner().invoke(cli, _args(args, tmp_path))
    assert result.exit_code == 2, result.output
    assert re.match(r"rmot: error\[E520\]: (cell|map) file '.*' must be writable", result.output.strip()), result.output
    assert "Traceback" not in result.output
