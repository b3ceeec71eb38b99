"""A tool or frame a vendor program selects by the controller's number without setting it
(KRL `BAS(#TOOL, 2)` without `TOOL_DATA[2]`, INFORM `///TOOL 5`, `///USER 3`) is the controller's:
the stub cell declares it with that number (`number 2`), so compiled back the program selects
the same slot and writes none (lang/REFERENCE.md §8 "Numbered tools and frames", §14). The Fanuc
case is in test_fanuc_position_records.py. Witness: the source file's own numbers, read here
with regular expressions.
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

KRL = """DEF pick()
  BAS(#INITMOV, 0)
  BAS(#TOOL, 2)
  BAS(#BASE, 3)
  PTP {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}
  LIN {X 500, Y 0, Z 300, A 0, B 90, C 0}
END
"""

JOB = """/JOB
//NAME PICK
//POS
///NPOS 2,0,0,0,0,0
///TOOL 5
///POSTYPE ROBOT
///RECTAN
///RCONF 0,0,0,0,0,0,0,0
C00000=450.000,0.000,300.000,180.00,0.00,0.00
///USER 3
///POSTYPE USER
C00001=400.000,50.000,250.000,180.00,0.00,0.00
//INST
///DATE 2020/01/01 00:00
///ATTR SC,RW
///GROUP1 RB1
NOP
MOVJ C00000 VJ=10.00
MOVL C00001 V=50.0
END
"""


def _round_trip(tmp_path: Path, name: str, text: str, vendor: str) -> tuple[str, str]:
    (tmp_path / name).write_text(text)
    result = CliRunner().invoke(cli, ["import", str(tmp_path / name), "-o", str(tmp_path / "p.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", vendor, "-o", str(tmp_path / "out"),
                                      "--allow-findings", "--no-cache"], catch_exceptions=False)
    assert "error[" not in result.output, result.output
    compiled = "".join(p.read_text() for p in sorted((tmp_path / "out" / vendor).iterdir()))
    return (tmp_path / "p_cell.rmot").read_text(), compiled


def test_krl_selects_the_controllers_tool_and_base_data(tmp_path: Path) -> None:
    stub, compiled = _round_trip(tmp_path, "pick.src", KRL, "krl")
    assert " number 2 on r1  # the controller's TOOL_DATA[2]" in stub and " number 3  # the controller's BASE_DATA[3]" in stub
    code = [line.split(";")[0] for line in compiled.splitlines()]
    assert {m for line in code for m in re.findall(r"\$(TOOL|BASE)\s*=\s*(\w+\[\d+\])", line)} == {
        ("TOOL", "TOOL_DATA[2]"), ("BASE", "BASE_DATA[3]")}
    assert not [line for line in code if re.search(r"\b(TOOL|BASE|LOAD)_DATA\[\d+\]\s*=", line)]  # nothing stored written


def test_inform_selects_the_controllers_tool_file_and_user_frame(tmp_path: Path) -> None:
    stub, compiled = _round_trip(tmp_path, "PICK.JBI", JOB, "inform")
    assert " number 5 on r1  # the controller's tool file entry 5" in stub and " number 3  # the controller's user frame 3" in stub
    assert set(re.findall(r"///(TOOL|USER) (\d+)", compiled)) == set(re.findall(r"///(TOOL|USER) (\d+)", JOB))
