"""A finding's caption leaves the picture to the finding: four robot/box contacts at one
instant covered 42 % of a 640x480 still with their caption band; the band is now bounded to a
fifth of the height. The witness is the written PNG itself, read back with Pillow: the rows
mostly of the band's colour are counted."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from click.testing import CliRunner
from PIL import Image

from rmot.compiler.cli import cli

BOXES = "".join(f"  fixture {name} = box(300mm, 300mm, 300mm) at pose(x={dx}mm, y={dy}mm, z=150mm)\n"
                for name, dx, dy in (("a", 0, 0), ("b", 0, 10), ("d", 10, 0), ("e", 20, 0)))
PROGRAM = (f"cell c {{\n  robot r1 = abb_irb1600\n{BOXES}}}\n"
           "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n  move joint joints(30, -10, 10, 0, 90, 0) deg\n}\n")
BAND_RGB = np.array([24, 26, 30])


def test_captions_of_many_findings_cover_at_most_a_fifth_of_the_picture(tmp_path: Path) -> None:
    program = tmp_path / "p.rmot"
    program.write_text(PROGRAM, encoding="utf-8")
    still = tmp_path / "s.png"
    result = CliRunner().invoke(cli, ["render", str(program), "-o", str(still), "--at", "0.2", "--no-cache"])
    assert result.exit_code == 0, result.output
    pixels = np.asarray(Image.open(still).convert("RGB")).astype(int)
    assert pixels.shape == (480, 640, 3)
    band_rows = (np.abs(pixels - BAND_RGB).sum(axis=-1) < 6).mean(axis=1) > 0.5
    assert 0.05 < band_rows.mean() <= 0.2, f"caption rows: {band_rows.mean():.0%} of the picture"
    assert band_rows[-1] and not band_rows[: int(0.75 * 480)].any()  # one band, at the bottom
