"""A feeder's parts in the vendor programs: every carton is taken at the feeder's pose, so every
attach carries the same payload, the carton's own mass with its centre where the cell puts it.

Witness: the cell file's numbers (examples/cells/palletizer_loops.rmot): the carton is a
100 mm tall box of 2 kg and the suction TCP sits on its top face, so the centre of gravity is
50 mm along the tool's z from the TCP. A declaration name that appears twice with different
values would not load on the controller (RAPID: a name is declared once per module).
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "palletizing.rmot"


def test_every_carton_of_the_feeder_is_the_same_rapid_load(tmp_path: Path) -> None:
    result = CliRunner().invoke(cli, ["compile", str(EXAMPLE), "--target", "rapid", "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    text = next((tmp_path / "rapid").glob("*.mod")).read_text(encoding="utf-8")
    loads = re.findall(r"PERS loaddata (\w+):=\[([-\d.]+),\[([-\d.]+),([-\d.]+),([-\d.]+)\]", text)
    names = [name for name, *_ in loads]
    assert len(names) == len(set(names)) == 1, loads
    _, mass, x, y, z = loads[0]
    assert float(mass) == 2.0
    assert (float(x), float(y), float(z)) == (0.0, 0.0, 50.0)
    assert text.count(f"GripLoad {names[0]};") >= 2  # taken in the loop body and after it
