"""`rmot import` reads each vendor's test of its own digital output back as an `out[n]` read,
and compile -> import -> compile gives the same vendor file.

Witnesses: the vendor files the backend writes for the original and for the imported program,
compared byte for byte (without source maps); and the imported .rmot's conditions, compared with
what the vendor line means (RAPID "DOutput", KRL $OUT, FANUC B-83284EN §4.15 IF .. JMP: the arm
runs when the jump is not taken; INFORM JUMP .. IF OT#: likewise), written here by hand.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

ROOT = Path(__file__).resolve().parents[2]
CELL = ROOT / "examples" / "cells" / "demo.rmot"
MAIN_FILE = {"rapid": "*.mod", "krl": "*.src", "urscript": "*.script", "fanuc": "*.ls", "inform": "*.JBI"}
# what every vendor reads back as a whole: one output tested in if / while / wait
SIMPLE = """program p on r1 {
  set out[3] = on
  if out[3] == on {
    set out[1] = off
  } else {
    set out[1] = on
  }
  if out[2] == off {
    set out[4] = on
  }
  wait until out[4] == on
}
"""
# and/or/not over outputs and inputs and a while: RAPID, KRL and URScript
LOGIC = SIMPLE.replace("  wait until out[4] == on\n", """  wait until out[4] == on
  if out[2] == off and in[1] == on {
    set out[5] = on
  }
  while out[2] == off {
    wait 0.1 s
    set out[2] = on
  }
""")


def _compile(source: Path, vendor: str, out: Path) -> str:
    result = CliRunner().invoke(cli, ["compile", str(source), "--cell", str(CELL), "--project-root", "/",
                                      "--target", vendor, "-o", str(out), "--no-source-map", "--no-cache"],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    text = next((out / vendor).glob(MAIN_FILE[vendor])).read_text()
    return re.sub(r".*\.rmot:\d+\).*", "", text)  # the header line names the source file


def _imported(vendor_file: Path, out: Path) -> str:
    result = CliRunner().invoke(cli, ["import", str(vendor_file), "-o", str(out)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert "W510" not in result.output, result.output  # nothing kept native
    return out.read_text()


@pytest.mark.parametrize(("vendor", "program"), [("rapid", LOGIC), ("krl", LOGIC), ("urscript", SIMPLE),
                                                 ("fanuc", SIMPLE), ("inform", SIMPLE)])
def test_compile_import_compile_gives_the_same_file(vendor: str, program: str, tmp_path: Path) -> None:
    source = tmp_path / "p.rmot"
    source.write_text(program)
    first = _compile(source, vendor, tmp_path / "one")
    vendor_file = next((tmp_path / "one" / vendor).glob(MAIN_FILE[vendor]))
    imported = _imported(vendor_file, tmp_path / "back.rmot")
    assert "if out[3] == on {" in imported and "if out[2] == off {" in imported, imported
    second = _compile(tmp_path / "back.rmot", vendor, tmp_path / "two")
    assert second == first


@pytest.mark.parametrize(
    ("vendor", "name", "line", "expected"),
    [("krl", "job.src", "DEF job()\n  IF $OUT[7]==FALSE THEN\n    $OUT[1]=TRUE\n  ENDIF\n  WAIT FOR $OUT[2]\nEND\n",
      ["if out[7] == off {", "wait until out[2] == on"]),
     ("fanuc", "JOB.ls", "/PROG JOB\n/MN\n 1: IF DO[7]<>OFF,JMP LBL[1] ;\n 2: DO[1]=ON ;\n 3: LBL[1] ;\n"
      " 4: WAIT DO[2]=OFF ;\n/END\n", ["if out[7] == off {", "wait until out[2] == off"]),
     ("inform", "JOB.JBI", "/JOB\n//NAME JOB\n//POS\n///NPOS 0,0,0,0,0,0\n//INST\n///DATE 2026/01/01 00:00\n"
      "///ATTR SC,RW\n///GROUP1 RB1\nNOP\nJUMP *L1 IF OT#(7)=ON\nDOUT OT#(1) ON\n*L1\nWAIT OT#(2)=ON\nEND\n",
      ["if out[7] == off {", "wait until out[2] == on"])],
)
def test_a_vendor_output_test_reads_as_its_meaning(vendor: str, name: str, line: str, expected: list[str],
                                                   tmp_path: Path) -> None:
    """`IF DO[7]<>OFF,JMP` and `JUMP *L1 IF OT#(7)=ON` skip the arm when the output is on: the
    arm runs when out[7] is off."""
    source = tmp_path / name
    source.write_text(line)
    text = _imported(source, tmp_path / "back.rmot")
    for want in expected:
        assert re.search(re.escape(want), text), (want, text)
