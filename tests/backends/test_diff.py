"""`rmot diff A B` names what a pendant touch-up changed: a target moved (by how much), a zone,
an added instruction; identical programs give no difference and exit 0.

Witness: the touch-up is made by hand in the test (a robtarget's y moved by exactly 2.5 mm, one
`fine` turned into `z10`, one SetDO inserted), so the expected lines come from the edit, not
from the reader under test.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def module(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("diff")
    result = CliRunner().invoke(cli, ["compile", str(ROOT / "examples" / "pick_place.rmot"), "--target", "rapid",
                                      "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return out / "rapid" / "pick_place.mod"


def _diff(a: Path, b: Path) -> tuple[int, list[str]]:
    result = CliRunner().invoke(cli, ["diff", str(a), str(b)], catch_exceptions=False)
    return result.exit_code, result.output.splitlines()


def test_same_program_has_no_difference(module: Path) -> None:
    code, lines = _diff(module, module)
    assert code == 0 and lines == ["0 differences"]


def test_touch_up(module: Path, tmp_path: Path) -> None:
    text = module.read_text()
    lines = text.splitlines()
    target = next(i for i, ln in enumerate(lines) if "robtarget p_3:=" in ln)
    assert "[[100.000,100.000,30.000]" in lines[target]
    lines[target] = lines[target].replace("[[100.000,100.000,30.000]", "[[100.000,102.500,30.000]")
    zone = next(i for i, ln in enumerate(lines) if "MoveL nest, v100, fine" in ln)
    lines[zone] = lines[zone].replace("fine", "z10")
    wait = next(i for i, ln in enumerate(lines) if "WaitTime 0.300;" in ln)
    lines.insert(wait + 1, "      SetDO gripper_close, 1;")
    touched = tmp_path / "touched.mod"
    touched.write_text("\n".join(lines) + "\n")
    code, out = _diff(module, touched)
    assert code == 1
    assert f"{module}:{target + 1}:3 -> {touched}:{target + 1}:3: target p_3 moved 2.500 mm, turned 0.000 deg" in out
    assert f"{module}:{zone + 1}:5 -> {touched}:{zone + 2}:5: move linear nest: zone fine -> 10 mm" in out
    assert f"{touched}:{wait + 2}:7: added set out gripper_close" in out
    assert out[-1] == f"{len(out) - 1} differences"


def test_not_a_program_is_located(tmp_path: Path, module: Path) -> None:
    bad = tmp_path / "bad.mod"
    bad.write_text("hello\n")
    result = CliRunner().invoke(cli, ["diff", str(module), str(bad)])
    assert result.exit_code == 2 and f"{bad}:1:1: error[E510]" in result.output


def test_vendor_program_against_its_rmot_source(tmp_path: Path) -> None:
    """A TP program touched on the pendant (one L speed 50 -> 40 mm/sec, by hand here) against
    the .rmot it was compiled from: the .rmot side is compiled in memory and compared."""
    source = ROOT / "examples" / "weld_seam.rmot"
    result = CliRunner().invoke(cli, ["compile", str(source), "--target", "fanuc", "-o", str(tmp_path)],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    ls = tmp_path / "fanuc" / "WELD_SEAM.ls"
    code, out = _diff(source, ls)
    assert (code, out) == (0, ["0 differences"])
    lines = ls.read_text().splitlines()
    n = next(i for i, ln in enumerate(lines) if "50mm/sec FINE" in ln)
    lines[n] = lines[n].replace("50mm/sec", "40mm/sec")
    ls.write_text("\n".join(lines) + "\n")
    code, out = _diff(source, ls)
    assert code == 1
    assert out[0].endswith(f"-> {ls}:{n + 1}:3: move linear start: speed 50 mm/s -> 40 mm/s"), out
    assert out[0].startswith(f"{source}[fanuc/WELD_SEAM.ls]:{n + 1}:3")


def test_touch_up_of_a_real_tp_program(tmp_path: Path) -> None:
    """A real generated TP toolpath (tests/data/vendor_programs/fanuc/crs_surface.ls, whose
    moves stay native: `Tool_Offset,PR[15]`): P[5] touched up 1.5 mm in X in /POS and one
    move's CNT60 turned into CNT20 are both named, each at its line in both files."""
    a = ROOT / "tests" / "data" / "vendor_programs" / "fanuc" / "crs_surface.ls"
    text = a.read_text()
    start = text.index("P[5]{")
    x_at = text.index("X =", start)
    x_end = text.index("mm", x_at)
    x = float(text[x_at:x_end].split("=")[1])
    touched = text[:x_at] + f"X =\t{x + 1.5:.6f}\t" + text[x_end:]
    move = "\t7:L P[3] 200mm/sec CNT60"
    assert touched.count(move) == 1
    touched = touched.replace(move, "\t7:L P[3] 200mm/sec CNT20")
    b = tmp_path / "crs_surface.ls"
    b.write_text(touched)
    code, lines = _diff(a, b)
    assert code == 1 and lines[-1] == "2 differences", lines
    p5 = text[:start].count("\n") + 1
    cnt = text[:text.index(move)].count("\n") + 1  # the line the match starts
    assert f":{p5}:1 -> {b}:{p5}:1: target surface_p5 moved 1.500 mm, turned 0.000 deg" in lines[0]
    assert f":{cnt}:2 -> {b}:{cnt}:2: native line changed (CNT60 -> CNT20)" in lines[1]
