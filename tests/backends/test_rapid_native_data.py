"""A RAPID line `rmot import` keeps native compiles back with the data it names: the module-level
declarations of the data a native line uses (and the data those use) are kept beside it and
declared at module level under their own names (readers/position_records.py, backends/rapid.py,
lang/REFERENCE.md §5 `native`, §14). Data rmot declares itself under the same name (a tool its own
moves use too) is the same datum, declared once.

Witness: the source module itself. Every name a native line of the compiled module uses that the
source declares at module level must be declared in the compiled module by the source's own
declaration text, so the line means the data it was written with; the compiled module must pass
rapidchecker, an independent RAPID syntax checker.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

SOURCE = """MODULE Cell
  CONST robtarget pHome:=[[600,0,600],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pAbove:=[[550,50,500],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pPick:=[[550,50,420],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST speeddata vSlow:=[50,500,5000,1000];
  CONST num nLift:=5;
  CONST num nDown:=nLift*2;
  PERS tooldata tGrip:=[TRUE,[[0,0,100],[1,0,0,0]],[1,[0,0,50],[1,0,0,0],0,0,0]];
  PROC main()
    MoveJ pHome, v1000, z50, tGrip;
    MoveL \\Conc, pAbove, v200, z10, tGrip;
    MoveL \\Conc, Offs(pPick, 0, 0, nDown), vSlow, fine, tGrip;
    MoveJ pHome, v1000, fine, tGrip;
  ENDPROC
ENDMODULE
"""


def _declarations(text: str) -> dict[str, str]:
    """Module-level data declarations by name (upper case), whitespace collapsed."""
    out = {}
    for m in re.finditer(r"(?im)^\s*((?:(?:LOCAL|TASK)\s+)*(?:CONST|PERS|VAR)\s+\w+\s+(\w+)\s*:=[^;]*;)", text):
        out[m.group(2).upper()] = " ".join(m.group(1).split())
    return out


def _compile(tmp_path: Path, source: str) -> tuple[str, str, str]:
    (tmp_path / "Cell.mod").write_text(source)
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "Cell.mod"), "-o", str(tmp_path / "p.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "rapid", "-o", str(tmp_path / "out"),
                                      "--allow-findings", "--no-cache"], catch_exceptions=False)
    folder = tmp_path / "out" / "rapid"
    compiled = "".join(p.read_text() for p in folder.glob("*.mod")) if folder.exists() else ""
    return (tmp_path / "p.rmot").read_text(), compiled, result.output


def test_native_lines_name_the_data_they_were_written_with(tmp_path: Path) -> None:
    program, compiled, output = _compile(tmp_path, SOURCE)
    assert program.count('native rapid "MoveL \\\\Conc') == 2 and "error[" not in output, output
    source, written = _declarations(SOURCE), _declarations(compiled)
    natives = [ln.strip() for ln in compiled.splitlines() if ln.strip().startswith("MoveL \\Conc")]
    assert len(natives) == 2
    used = {w.upper() for line in natives for w in re.findall(r"\b[A-Za-z]\w*\b", line)} & set(source)
    assert used == {"PABOVE", "PPICK", "VSLOW", "TGRIP", "NDOWN"}
    for name in used - {"TGRIP"} | {"NLIFT"}:  # and the constant nDown's value names
        assert written[name] == source[name], name
    # the tool rmot's moves use too is rmot's tGrip, the same datum: declared once, at the same numbers
    assert len(re.findall(r"(?m)^\s*PERS tooldata tGrip\b", compiled)) == 1
    numbers = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", written["TGRIP"].split(":=")[1])]
    assert numbers == [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", source["TGRIP"].split(":=")[1])]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from rapidchecker.cli import check_file
    assert list(check_file(compiled)) == []


def test_two_native_declarations_of_one_name_that_differ_are_refused(tmp_path: Path) -> None:
    _, _, _ = _compile(tmp_path, SOURCE)
    text = (tmp_path / "p.rmot").read_text()
    record = next(line for line in text.splitlines() if 'native rapid "CONST robtarget pAbove' in line)
    (tmp_path / "p.rmot").write_text(text.replace(record, record + "\n" + record.replace("[550,50,500]", "[551,50,500]")))
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "rapid", "-o", str(tmp_path / "o2")])
    assert re.search(r"p\.rmot:\d+:\d+: error\[E411\]: rapid: native declaration of pAbove must be the only one of that "
                     r"name in the task", result.output), result.output
    assert not (tmp_path / "o2" / "rapid").exists()
