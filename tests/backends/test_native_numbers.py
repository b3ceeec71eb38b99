"""A native Fanuc TP or INFORM line keeps the numbers of the program it came from; the backend
numbers labels, positions, registers and variables of its own. Labels a native line names are
kept (the backend's skip them); a program position it names, or a register or variable the
backend's own lines use, is refused with E411 at the statement.

Witness: the compiled files are read back here with plain regular expressions (every label
defined once, each jump landing on the label the test wrote), not with the backend's helpers;
the refusals are checked against a program whose registers the test knows (its one `var` is the
task's first register, R[1] in TP, D050 in INFORM: B-83284EN "Register instructions"; YRC1000
INSTRUCTIONS, "Variables", as the backend documents its ranges).
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

LOOP = """program l on r1 {{
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target a = joints(10, -10, 10, 0, 90, 0) deg
  var count: int = 0
  move joint home
  native {vendor} "{label}"
  while in[1] == on {{
    move joint a
    count = count + 1
  }}
  native {vendor} "{jump}"
{extra}}}
"""


def _compile(tmp_path: Path, vendor: str, label: str, jump: str, extra: str = "") -> tuple[int, str, Path]:
    src = tmp_path / "l.rmot"
    src.write_text(LOOP.format(vendor=vendor, label=label, jump=jump, extra=extra))
    result = CliRunner().invoke(cli, ["compile", str(src), "--target", vendor, "-o", str(tmp_path / "out")],
                                catch_exceptions=False)
    return result.exit_code, result.output, tmp_path / "out" / vendor


def test_a_tp_label_a_native_line_names_is_its_own(tmp_path: Path) -> None:
    code, out, folder = _compile(tmp_path, "fanuc", "LBL[1:top] ;", "JMP LBL[1] ;")
    assert code == 0, out
    mn = (folder / "L.ls").read_text().split("/MN")[1].split("/POS")[0]
    defined = Counter(re.findall(r"^\s*\d+:\s+LBL\[(\d+)", mn, re.M))
    assert defined and max(defined.values()) == 1, defined  # every label once (the loop's too)
    body = [re.sub(r"^\s*\d+:\s+|\s*;$", "", ln) for ln in mn.splitlines() if re.match(r"\s*\d+:", ln)]
    assert body.index("JMP LBL[1]") > body.index("LBL[1:top]")
    loop = [ln for ln in body if "JMP LBL[" in ln and ln != "JMP LBL[1]"]
    assert loop and all("LBL[1]" not in ln for ln in loop), loop  # the loop's own labels are others


def test_an_inform_label_a_native_line_names_is_its_own(tmp_path: Path) -> None:
    code, out, folder = _compile(tmp_path, "inform", "*L001", "JUMP *L001")
    assert code == 0, out
    inst = (folder / "L.JBI").read_text().split("NOP", 1)[1].splitlines()
    defined = Counter(ln for ln in inst if re.fullmatch(r"\*\w+", ln))
    assert defined["*L001"] == 1 and max(defined.values()) == 1, defined
    loop_jumps = [ln for ln in inst if ln.startswith("JUMP *L") and ln != "JUMP *L001"]
    assert loop_jumps and all("*L001" not in ln for ln in loop_jumps)


@pytest.mark.parametrize("vendor, line, name", [
    ("fanuc", "L P[2] 100mm/sec CNT50 RTCP ;", "P[2]"),
    ("fanuc", "R[1:other]=5 ;", "R[1]"),
    ("fanuc", "UTOOL[1]=PR[5] ;", "UTOOL[1]"),
    ("inform", "MOVL C00001 V=100.0", "C00001"),
    ("inform", "SET D050 3", "D050"),
])
def test_a_native_line_naming_the_backends_data_is_refused(tmp_path: Path, vendor: str, line: str, name: str) -> None:
    code, out, folder = _compile(tmp_path, vendor, "'x" if vendor == "inform" else "!x ;", "'y" if vendor == "inform"
                                 else "!y ;", f'  native {vendor} "{line}"\n')
    assert code == 1, out  # an error finding: no file written
    assert re.search(rf"l\.rmot:12:3: error\[E411\]: {vendor}: native line names {re.escape(name)},", out), out
    assert not folder.exists()


@pytest.mark.parametrize("vendor, line", [
    ("fanuc", "R[150]=5 ;"), ("fanuc", "!R[1] P[2] in a comment ;"), ("fanuc", "PR[40,2]=0 ;"),
    ("inform", "SET D099 3"), ("inform", "'C00005 and D050 in a comment"),
])
def test_a_native_line_naming_other_data_is_written(tmp_path: Path, vendor: str, line: str) -> None:
    code, out, folder = _compile(tmp_path, vendor, "'x" if vendor == "inform" else "!x ;", "'y" if vendor == "inform"
                                 else "!y ;", f'  native {vendor} "{line}"\n')
    assert code == 0, out
    text = next(folder.iterdir()).read_text()
    assert line.rstrip(" ;") in text
