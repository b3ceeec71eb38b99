"""`rmot render` end to end: front end, planner, picture; bad input is a diagnostic and exit code 2."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from rmot.compiler.cli import cli

PROGRAM = str(Path(__file__).parent / "data" / "swing.rmot")


def _run(*args: str) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["render", *args])
    return result.exit_code, result.output


def test_png_still_of_the_program(tmp_path: Path) -> None:
    """A PNG of the requested size is written atomically (no temporary file left), exit code 0."""
    out = tmp_path / "swing.png"
    code, output = _run(PROGRAM, "-o", str(out), "--size", "200x150", "--at", "0.3", "--aa", "1")
    assert (code, output) == (0, f"wrote {out}\n")
    assert Image.open(out).size == (200, 150)
    assert [p.name for p in tmp_path.iterdir()] == ["swing.png"]


def test_svg_and_html_outputs(tmp_path: Path) -> None:
    """-o .svg writes a parseable drawing with a path per body; -o .html a page with the scene inlined."""
    svg, page = tmp_path / "a.svg", tmp_path / "a.html"
    assert _run(PROGRAM, "-o", str(svg), "--size", "200x150")[0] == 0
    ids = {p.get("id") for p in ET.parse(svg).getroot().iter("{http://www.w3.org/2000/svg}path")}
    assert {"table", "lines"} <= ids and any(i.startswith("r1/") for i in ids)
    assert _run(PROGRAM, "-o", str(page), "--fps", "5")[0] == 0
    assert '"name":"table"' in page.read_text(encoding="utf-8")


@pytest.mark.parametrize(("args", "message"), [
    (["-o", "x.bmp"], "Invalid value for '-o' / '--output': must end in one of .png, .gif, .mp4, .svg, .html (got 'x.bmp')"),
    (["-o", "x.png", "--size", "640by480"], "Invalid value for '--size': must be WIDTHxHEIGHT in pixels, each 16..8192 (got '640by480')"),
    (["-o", "x.png", "--camera", "eye=1,2"], "Invalid value for '--camera': camera eye must be three numbers x,y,z (got '1,2')"),
])
def test_bad_options_are_usage_errors(args: list[str], message: str) -> None:
    """Option values are checked before any work: a one-line message, exit code 2."""
    code, output = _run(PROGRAM, *args)
    assert code == 2
    assert message in output


def test_instant_outside_the_program_is_an_input_error(tmp_path: Path) -> None:
    """--at beyond the cycle time: error E582 naming the duration, exit 2, nothing written."""
    out = tmp_path / "late.png"
    code, output = _run(PROGRAM, "-o", str(out), "--at", "99")
    assert code == 2
    assert "error[E582]: --at must be within 0..0." in output and "(got 99 s)" in output
    assert not out.exists()


def test_program_errors_are_rendered_diagnostics(tmp_path: Path) -> None:
    """A broken program prints file:line:col: error[...] with the source line; exit 2, no picture."""
    bad = tmp_path / "bad.rmot"
    bad.write_text(Path(PROGRAM).read_text(encoding="utf-8").replace("move joint joints(40", "move joint jionts(40"))
    out = tmp_path / "bad.png"
    code, output = _run(str(bad), "-o", str(out))
    assert code == 2
    assert f"{bad}:10:" in output and "error[E" in output and "jionts" in output
    assert not out.exists()


def test_unwritable_output_is_an_error_not_a_traceback(tmp_path: Path) -> None:
    """Writing into a missing folder reports E580, exit 2."""
    code, output = _run(PROGRAM, "-o", str(tmp_path / "missing" / "x.png"), "--size", "64x48", "--aa", "1")
    assert code == 2
    assert "error[E580]: output file must be writable" in output


def test_partial_camera_keeps_the_default_view_for_keys_left_out(tmp_path: Path) -> None:
    """--camera "fov=20" narrows the default three-quarter view (same eye and centre), so the picture zooms in."""
    wide, narrow = tmp_path / "wide.png", tmp_path / "narrow.png"
    common = ["--size", "120x90", "--aa", "1"]
    assert _run(PROGRAM, "-o", str(wide), *common)[0] == 0
    assert _run(PROGRAM, "-o", str(narrow), "--camera", "fov=20", *common)[0] == 0
    background = np.array([235, 237, 242])
    sky = lambda p: int(np.all(np.asarray(Image.open(p)) == background, axis=2).sum())  # noqa: E731
    assert sky(narrow) < 0.7 * sky(wide)  # zoomed in: the cell and floor cover more of the picture


def test_camera_that_cannot_be_built_is_a_usage_error(tmp_path: Path) -> None:
    """Eye on the centre of interest: message names the problem, exit 2."""
    code, output = _run(PROGRAM, "-o", str(tmp_path / "x.png"), "--camera", "eye=0,0,1;center=0,0,1")
    assert code == 2
    assert "Invalid value for '--camera': camera eye and center must differ (both (0.0, 0.0, 1.0))" in output


def test_planning_errors_are_reported_and_the_motion_still_drawn(tmp_path: Path) -> None:
    """An unreachable target: E220 at its line, exit 1 (a finding, as in check), and the picture of what was planned is written."""
    far = tmp_path / "far.rmot"
    far.write_text(Path(PROGRAM).read_text(encoding="utf-8").replace(
        "move joint joints(40, -70, 80, -100, -90, 0) deg", "move linear pose(x=3000mm, z=300mm, rx=180deg)"))
    out = tmp_path / "far.png"
    code, output = _run(str(far), "-o", str(out), "--size", "64x48", "--aa", "1")
    assert code == 1
    assert f"{far}:10:3: error[E220]: target must be within the robot's reach" in output
    assert Image.open(out).size == (64, 48)
