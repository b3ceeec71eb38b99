"""compile -> import -> compile gives the same URScript file for the runtime forms the URScript
backend writes around I/O reads: a task variable declared from an output or an input (written
`global b = False` among the program's globals, then `b = get_standard_digital_out(1)` where the
declaration stands), and the timed waits on an output and on an input (the `get_steptime()`
counting loop, then popup + halt).

Witnesses: the two vendor files the backend writes, compared byte for byte (without source
maps), and the imported .rmot's lines, written here by hand from what the URScript lines mean.
"""

from __future__ import annotations

from pathlib import Path

from tests.backends.test_output_reads_import import MAIN_FILE, _compile, _imported

PROGRAM = """program p on r1 {
  var b: bool = out[1]
  var c: bool = in[2]
  set out[3] = on
  wait until out[4] == on timeout 2 s
  wait until in[2] == on timeout 3 s
  b = out[2]
  if b and c {
    set out[5] = on
  }
}
"""


def test_io_declarations_and_timed_waits_round_trip(tmp_path: Path) -> None:
    source = tmp_path / "p.rmot"
    source.write_text(PROGRAM)
    first = _compile(source, "urscript", tmp_path / "one")
    assert "global b = False" in first and "  b = get_standard_digital_out(1)" in first
    vendor_file = next((tmp_path / "one" / "urscript").glob(MAIN_FILE["urscript"]))
    imported = _imported(vendor_file, tmp_path / "back.rmot")
    for line in ("var b: bool = out[1] == on", "var c: bool = in[2] == on", "wait until out[4] == on timeout 2 s",
                 "wait until in[2] == on timeout 3 s", "b = out[2] == on"):
        assert f"  {line}\n" in imported, (line, imported)
    assert "var b: bool = off" not in imported
    second = _compile(tmp_path / "back.rmot", "urscript", tmp_path / "two")
    assert second == first
