"""The HTML report with external axes: the axes table and the machine-data checklist per vendor
(ABB MOC units, KUKA MACHINE_DEF/$ETn, Fanuc groups, INFORM R1/B1/S1), read back with the
standard library's HTML parser and compared with the numbers of the cell text."""

from __future__ import annotations

from html.parser import HTMLParser

import pytest
from click.testing import CliRunner
from ext_axes_witness import CELL_HEAD

from rmot.compiler.cli import cli
from rmot.compiler.design.machine_data import checklists
from rmot.compiler.frontend import load_text
from rmot.compiler.plan import plan_program
from rmot.lang.plan_types import Plan
from rmot.sim.report_axes import axes_section

SOURCE = CELL_HEAD + """  tool torch = none tcp pose(z=300mm) on r1
}
program p on r1 with rail, pos {
  tool torch
  move joint joints(0deg, -90deg, 90deg, 0deg, 45deg, 0deg) ext(rail=500mm, pos=(10deg, 30deg))
}
"""


class Reader(HTMLParser):
    """Table rows (lists of cell texts), and the <summary>/<li> texts of the checklists."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: list[list[str]] = []
        self.lists: dict[str, list[str]] = {}
        self._tag = ""
        self._summary = ""

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self._tag = tag
        if tag == "tr":
            self.rows.append([])
        if tag in ("td", "th"):
            self.rows[-1].append("")

    def handle_data(self, data: str) -> None:
        if self._tag in ("td", "th"):
            self.rows[-1][-1] += data
        elif self._tag == "summary":
            self._summary = data
            self.lists[data] = []
        elif self._tag == "li":
            self.lists[self._summary].append(data)


@pytest.fixture(scope="module")
def plan() -> Plan:
    front = load_text(SOURCE, "/tmp/ext_axes_report.rmot")
    assert front.program is not None, [d.message for d in front.diagnostics]
    return plan_program(front.program)


def test_axes_table_and_checklists(plan: Plan) -> None:
    reader = Reader()
    reader.feed("".join(axes_section(plan, checklists(plan))))
    assert reader.rows[1:] == [
        ["p", "rail", "rail", "linear x", "0 .. 4000 mm", "1500 mm/s", "2000 mm/s²", "robot r1"],
        ["p", "pos.1", "pos", "revolute y", "-90 .. 90 deg", "90 deg/s", "180 deg/s²", "fixture jig, frame work"],
        ["p", "pos.2", "pos", "revolute z", "-360 .. 360 deg", "180 deg/s", "360 deg/s²", "fixture jig, frame work"],
    ]
    heads = list(reader.lists)
    assert [h.split(": ", 1)[1].split(" ")[0:2] for h in heads] == [["ABB", "RAPID"], ["KUKA", "KRL"], ["Fanuc", "TP"], ["Yaskawa", "INFORM"]]
    rapid, krl, fanuc, inform = (reader.lists[h] for h in heads)
    assert any('unit "RAIL": MOC type TRACK' in x for x in rapid) and any(x.strip().startswith("eax_c = pos.2") for x in rapid)
    assert any("MACHINE_DEF[3]" in x and "$ETn" in x for x in krl) and any(x.strip().startswith("E1 = rail: linear along x") for x in krl)
    assert any(x.strip().startswith("GP1 E1 = rail") for x in fanuc) and any(x.strip().startswith("GP2 J2 = pos.2") for x in fanuc)
    # no scale declared: the track's BC in mm, each station axis at the assumed 100000 pulses per
    # turn, flagged for the operator to confirm (W610)
    assert any(x.startswith("R1+B1 base BS1 axis 1 = rail") and "BC in mm" in x for x in inform)
    per_deg = f"{100000 / 360:.3f} pulses/deg ASSUMED"
    assert [x.split(":")[0] for x in inform if per_deg in x] == ["S1 station ST1 axis 1 = pos.1", "S1 station ST1 axis 2 = pos.2"]


def test_no_axes_no_section() -> None:
    text = "cell c {\n  robot r1 = kuka_kr16\n}\nprogram p on r1 {\n  move joint joints(0, -90, 90, 0, 45, 0) deg\n}\n"
    front = load_text(text, "/tmp/no_axes.rmot")
    assert front.program is not None
    plan = plan_program(front.program)
    assert axes_section(plan, checklists(plan)) == [] and checklists(plan) == ()


def test_cli_report_of_the_track_example(tmp_path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "r.html"
    r = CliRunner().invoke(cli, ["report", "examples/track_tending.rmot", "-o", str(out)])
    assert r.exit_code == 0, r.output
    reader = Reader()
    reader.feed(out.read_text())
    assert ["track_tending", "rail", "rail", "linear x", "0 .. 4000 mm", "1500 mm/s", "2000 mm/s²", "robot r1"] in reader.rows
    inform = next(v for k, v in reader.lists.items() if "INFORM" in k)
    assert any("R1+B1 base BS1 axis 1 = rail" in x and "200 pulses/mm" in x for x in inform)
