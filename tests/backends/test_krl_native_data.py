"""A KRL line `rmot import` keeps native compiles back with the .dat data it names: the `.dat`
declarations of the data a native line uses (and the data those use) are kept beside it and
written into the compiled module's .dat (readers/position_records.py, backends/krl.py,
lang/REFERENCE.md §5 `native`, §14). Data rmot declares itself under the same name (a point its
own moves use too) is the same datum, declared once.

Witness: the source .dat itself. Each datum the compiled native lines use that the source .dat
declares is declared in the compiled .dat, by the source's own text where rmot does not declare
it; nothing else of the source's is added; the module passes the structural KRL validator of
tests/backends/vendor_validators.py.
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner
from vendor_validators import check_krl

from rmot.compiler.cli import cli

SRC = """DEF pick()
  PTP XHOME
  PTP XP1
  XTMP=XP1
  XTMP.Z=XTMP.Z+nLift
  LIN XTMP
  XSPARE=XTMP
  PTP XHOME
END
"""
DAT = """DEFDAT pick
  DECL E6AXIS XHOME={A1 0.0,A2 -90.0,A3 90.0,A4 0.0,A5 0.0,A6 0.0,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
  DECL E6POS XP1={X 500.0,Y 0.0,Z 300.0,A 0.0,B 90.0,C 0.0,S 2,T 2,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
  DECL E6POS XTMP={X 0.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0,S 2,T 2,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}
  DECL REAL nBase=20.0
  DECL REAL nLift=nBase+5.0
  DECL REAL nUnused=1.0
  E6POS XSPARE
ENDDAT
"""


def _declared(text: str) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for m in re.finditer(r"(?im)^\s*(DECL\s+\w+\s+(\w+)\s*=.*?)\s*$", text):
        out.setdefault(m.group(2).upper(), []).append(m.group(1))
    return out


def test_native_lines_name_the_data_they_were_written_with(tmp_path: Path) -> None:
    (tmp_path / "pick.src").write_text(SRC)
    (tmp_path / "pick.dat").write_text(DAT)
    result = CliRunner().invoke(cli, ["import", str(tmp_path / "pick.src"), "-o", str(tmp_path / "p.rmot")], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "krl", "-o", str(tmp_path / "out"),
                                      "--allow-findings", "--no-cache"], catch_exceptions=False)
    assert "error[" not in result.output, result.output
    files = {p.name: p.read_text() for p in (tmp_path / "out" / "krl").iterdir()}
    source, written = _declared(DAT), _declared(files["pick.dat"])
    natives = [ln.strip() for ln in files["pick.src"].splitlines()
               if ln.strip() in ("XTMP=XP1", "XTMP.Z=XTMP.Z+nLift", "LIN XTMP", "XSPARE=XTMP")]
    assert len(natives) == 4
    assert re.search(r"(?m)^\s*E6POS XSPARE\s*$", files["pick.dat"])  # declared without a value, as in the source
    for name in ("XTMP", "NLIFT", "NBASE"):  # named by the native lines, and nLift's value names nBase
        assert written[name] == source[name], name
    assert len(written["XP1"]) == 1  # rmot's own moves use it too: one declaration
    assert "NUNUSED" not in written  # no native line names it
    assert check_krl(files) == []


def test_two_native_declarations_of_one_name_that_differ_are_refused(tmp_path: Path) -> None:
    (tmp_path / "pick.src").write_text(SRC)
    (tmp_path / "pick.dat").write_text(DAT)
    CliRunner().invoke(cli, ["import", str(tmp_path / "pick.src"), "-o", str(tmp_path / "p.rmot")])
    text = (tmp_path / "p.rmot").read_text()
    record = next(line for line in text.splitlines() if 'native krl "DECL REAL nLift' in line)
    (tmp_path / "p.rmot").write_text(text.replace(record, record + "\n" + record.replace("+5.0", "+6.0")))
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "krl", "-o", str(tmp_path / "o2")])
    assert re.search(r"p\.rmot:\d+:\d+: error\[E411\]: krl: native declaration of nLift must be the only one of that name",
                     result.output), result.output
