"""Damaged and hostile vendor files get a located error or a located warning from `rmot import`,
never a traceback or an internal error (E550): empty files, binary data, unterminated blocks,
absurd nesting of blocks, aggregates and offset expressions, numbers too big for a float."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli

DEEP = 3000
CASES = {
    "empty.mod": ("", "E510"),
    "nul.src": ("DEF x( )\x00\nEND\n", "E512"),
    "nested_if.mod": ("MODULE m\n PROC main()\n" + "IF DInput(a)=1 THEN\n" * 500 + "ENDIF\n" * 500
                      + " ENDPROC\nENDMODULE\n", "E510"),
    "nested_while.script": ("def x():\n" + "while get_standard_digital_in(1):\n" * 500 + "end\n" * 501, "E510"),
    "nested_if.ls": ("/PROG X\n/MN\n" + "".join(f" {k + 1}:  IF DI[1]<>ON,JMP LBL[{k + 1}] ;\n" for k in range(300))
                     + "".join(f" {301 + k}:  LBL[{300 - k}] ;\n" for k in range(300)) + "/POS\n/END\n", "E510"),
    "nested_for.src": ("DEF x( )\n" + "FOR i=1 TO 2\n" * 500 + "ENDFOR\n" * 500 + "END\n", "E510"),
    "deep_literal.mod": ("MODULE m\nCONST robtarget p:=" + "[" * DEEP + "]" * DEEP + ";\nENDMODULE\n", "W511"),
    "deep_offs.mod": ("MODULE m\n PROC main()\n  MoveL " + "Offs(" * DEEP + "p" + ",0,0,1)" * DEEP
                      + ", v100, fine, tool0;\n ENDPROC\nENDMODULE\n", "W510"),
    "deep_aggregate.src": ("DEF x( )\n PTP " + "{A1 " * DEEP + "}" * DEEP + "\nEND\n", "W510"),
    "deep_pose_add.script": ("def x():\n  movel(" + "pose_add(" * DEEP + "p[1,2,3,0,0,0]"
                             + ",p[0,0,0,0,0,0])" * DEEP + ")\nend\n", "W510"),
    "huge_number.mod": ("MODULE m\n PROC main()\n  MoveL [[1e400,0,0],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]],"
                        " v100, fine, tool0;\n ENDPROC\nENDMODULE\n", "W510"),
    "unterminated.src": ("DEF x( )\n FOR i=1 TO 3\n  WAIT SEC 1\nEND\n", "E510"),
    "garbage.ls": ("garbage\n", "E510"),
    # a condition cut short (an IndexError before), a module header without its name (one too)
    "cut_condition.src": ("DEF x( )\n WAIT FOR $IN[1] OR\n IF $IN[2] AND THEN\n  $OUT[1]=TRUE\n ENDIF\nEND\n", "W510"),
    "module_no_name.mod": ("MODULE\n PROC main()\n  WaitTime 1;\n ENDPROC\nENDMODULE\n", "E510"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_hostile_file_is_located(name: str, tmp_path: Path) -> None:
    text, code = CASES[name]
    path = tmp_path / name
    path.write_bytes(text.encode())
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(tmp_path / "out.rmot")])
    assert "Traceback" not in result.output and "E550" not in result.output, result.output[-400:]
    assert result.exit_code == (2 if code.startswith("E") else 0), result.output[-400:]
    severity = "error" if code.startswith("E") else "warning"
    assert f"{path}:" in result.output and f"{severity}[{code}]" in result.output, result.output[-400:]
