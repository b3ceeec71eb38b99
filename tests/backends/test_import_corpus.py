"""`rmot import` on real programs by other people (tests/data/vendor_programs/*/SOURCE names
each file's repository, path, commit and licence): no traceback, exit 0 (or a located E510 for
a file that is not the vendor language, such as a template), and every line rmot cannot
express kept at its place with a warning located at the vendor file's line.

Witness: the files themselves, written for real controllers by other people; each W510 must
point at a line whose text is the native statement's text (read from the file, not from the
reader).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.backends.fanuc_records import number_of
from rmot.backends.inform_records import number_of as inform_number_of
from rmot.compiler.cli import cli

CORPUS = Path(__file__).resolve().parents[1] / "data" / "vendor_programs"
FILES = sorted(p for p in CORPUS.glob("*/*") if p.suffix.lower() in (".mod", ".prg", ".src", ".urscript", ".script", ".ls", ".jbi"))
NOT_THE_LANGUAGE = {"external_control.urscript"}  # a driver template: `{{...}}` placeholders


def test_corpus_has_every_vendor_and_its_sources() -> None:
    assert {p.parent.name for p in FILES} == {"rapid", "krl", "urscript", "fanuc", "inform"}
    for vendor in ("rapid", "krl", "urscript", "fanuc", "inform"):
        source = (CORPUS / vendor / "SOURCE").read_text()
        for f in (p for p in FILES if p.parent.name == vendor):
            assert f.name in source, f"{f.name} has no entry in {vendor}/SOURCE"
        assert "commit:" in source and "licence:" in source


@pytest.mark.parametrize("path", FILES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_imports_without_traceback(path: Path, tmp_path: Path) -> None:
    out = tmp_path / "imported.rmot"
    result = CliRunner().invoke(cli, ["import", str(path), "-o", str(out)])
    assert "Traceback" not in result.output and "E550" not in result.output
    if path.name in NOT_THE_LANGUAGE:
        assert result.exit_code == 2 and re.search(rf"{re.escape(str(path))}:\d+:\d+: error\[E510\]", result.output)
        return
    assert result.exit_code == 0, result.output
    lines = path.read_text(errors="replace").splitlines()
    text = out.read_text()
    natives = re.findall(r'native \w+ "((?:[^"\\]|\\.)*)"\s+# (.+):(\d+):(\d+)', text)
    warned = set(re.findall(rf"{re.escape(str(path))}:(\d+):\d+: warning\[W51[01]\]", result.output))
    for body, file, line, _col in natives:
        unescaped = body.replace('\\"', '"').replace("\\\\", "\\")
        record = number_of(unescaped) is not None or inform_number_of(unescaped) is not None or (
            path.parent.name == "rapid" and re.match(r"(?i)((LOCAL|TASK)\s+)*(CONST|PERS|VAR)\s", unescaped) is not None)
        if path.suffix.lower() == ".src" and file.lower().endswith(".dat") and re.match(r"(?i)\s*(DECL\s|\w+\s+\w+\s*=)", unescaped):
            continue  # a .dat declaration a native line names, located in the .dat (the companion)
        assert file == str(path)
        source_line = lines[int(line) - 1]
        position = re.match(r"P\[\d+|C\d+", unescaped)  # a TP or INFORM record starts with its position's name
        first = position.group() if record and position else unescaped.split()[0].rstrip(";")
        assert first in source_line, (line, unescaped, source_line)  # its `;` added
        if not record:  # a position record is the data of the native lines that move to it
            assert line in warned, f"native line {line} has no located warning"
