"""`rmot compile`: exit codes, no files on findings, atomic all-or-nothing writes, the
--allow-findings header, and where each file went."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.compiler.cli.compile_cmd import write_all

CLEAN = """
program roundtrip on r1 {
  tool gripper
  frame table_top
  speed 250 mm/s
  zone fine
  move joint joints(0, -20, 30, 0, 50, 0) deg
  move linear pose(x=100mm, y=-50mm, z=150mm, rx=180deg)
  set out[1] = on
}
"""
COLLIDES = """
program crash on r1 {
  tool gripper
  move joint joints(0, -20, 30, 0, 50, 0) deg
  move linear pose(x=850mm, y=0mm, z=-50mm, rx=180deg)
}
"""
TARGETS = ["--target", "rapid", "--target", "krl", "--target", "fanuc"]


def run(*args: str) -> object:
    return CliRunner().invoke(cli, ["compile", *args])


@pytest.fixture
def programs(tmp_path: Path) -> Path:
    (tmp_path / "clean.rmot").write_text(CLEAN, encoding="utf-8")
    (tmp_path / "crash.rmot").write_text(COLLIDES, encoding="utf-8")
    (tmp_path / "broken.rmot").write_text("program x on r1 {\n  move joint\n}\n", encoding="utf-8")
    return tmp_path


def files_under(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != ".rmot.output"}  # rmot's list of the vendor folders it wrote


class TestCompile:
    def test_clean_program_writes_every_target(self, programs: Path) -> None:
        """Exit 0; OUTDIR/<vendor>/<file> for each target; stdout names each file written."""
        out = programs / "out"
        result = run(str(programs / "clean.rmot"), *TARGETS, "-o", str(out))
        assert result.exit_code == 0, result.output
        assert sorted(files_under(out)) == ["fanuc/ROUNDTRIP.ls", "krl/roundtrip.dat", "krl/roundtrip.src",
                                            "rapid/roundtrip.mod"]
        assert result.stdout.splitlines() == [
            f"wrote {out / 'rapid' / 'roundtrip.mod'}", f"wrote {out / 'krl' / 'roundtrip.src'}",
            f"wrote {out / 'krl' / 'roundtrip.dat'}", f"wrote {out / 'fanuc' / 'ROUNDTRIP.ls'}"]
        assert not any(name.startswith(".rmot-") for name in os.listdir(out / "krl"))

    def test_same_input_byte_identical(self, programs: Path) -> None:
        """Two compiles into two directories give byte-identical files."""
        for name in ("a", "b"):
            assert run(str(programs / "clean.rmot"), *TARGETS, "-o", str(programs / name)).exit_code == 0
        assert files_under(programs / "a") == files_under(programs / "b")

    def test_findings_exit_1_and_write_nothing(self, programs: Path) -> None:
        """A verification error: exit 1, the finding on stderr, no file written."""
        out = programs / "out"
        result = run(str(programs / "crash.rmot"), "--target", "rapid", "-o", str(out))
        assert result.exit_code == 1
        errors = result.stderr.count(": error[")  # how many depends on the default cell's layout
        assert "error[E300]" in result.stderr
        assert f"rmot: no files written ({errors} error{'s' if errors != 1 else ''})" in result.stderr
        assert not out.exists()

    def test_failed_compile_leaves_previous_output(self, programs: Path) -> None:
        """A compile that fails does not touch what an earlier compile wrote."""
        out = programs / "out"
        assert run(str(programs / "clean.rmot"), "--target", "rapid", "-o", str(out)).exit_code == 0
        before = files_under(out)
        (programs / "clean.rmot").write_text(COLLIDES.replace("crash", "roundtrip"), encoding="utf-8")
        assert run(str(programs / "clean.rmot"), "--target", "rapid", "-o", str(out)).exit_code == 1
        assert files_under(out) == before

    def test_allow_findings_writes_with_a_warning_header(self, programs: Path) -> None:
        """--allow-findings: exit 0, and every file says that verification reported errors."""
        out = programs / "out"
        result = run(str(programs / "crash.rmot"), *TARGETS, "-o", str(out), "--allow-findings")
        assert result.exit_code == 0, result.output
        written = files_under(out)
        assert len(written) == 4
        for name, data in written.items():
            joined = re.sub(rb" ;\n\s*\d+:  !", b" ", data)  # TP comments wrap at 32 characters
            assert b"WARNING: verification reported errors" in joined, name

    def test_front_end_error_exit_2(self, programs: Path) -> None:
        """A syntax error is an input error: exit 2 and no files."""
        out = programs / "out"
        result = run(str(programs / "broken.rmot"), "--target", "rapid", "-o", str(out))
        assert result.exit_code == 2 and "error[E0" in result.stderr
        assert not out.exists()

    def test_missing_file_exit_2(self, programs: Path) -> None:
        """A program that does not exist: exit 2 with a message, no traceback."""
        result = run(str(programs / "nope.rmot"), "--target", "rapid", "-o", str(programs / "out"))
        assert result.exit_code == 2
        assert "error[E501]: file" in result.stderr and "must be readable" in result.stderr  # the front end's code

    def test_unknown_target_is_a_usage_error(self, programs: Path) -> None:
        """--target outside the list: click usage error, exit 2."""
        result = run(str(programs / "clean.rmot"), "--target", "abb", "-o", str(programs / "out"))
        assert result.exit_code == 2 and "Invalid value for '--target'" in result.stderr


class TestWriteAll:
    def test_all_or_nothing(self, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
        """If swapping a vendor directory in fails, it keeps its old files and no staging
        directory is left behind (per-vendor atomic writes: compiler/cli/output_tree.py)."""
        from rmot.compiler.cli import output_tree

        (tmp_path / "rapid").mkdir()
        (tmp_path / "rapid" / "a.mod").write_text("old a\n")

        def broken(a: str, b: str) -> bool:
            raise OSError(28, "No space left on device", b)

        monkeypatch.setattr(output_tree, "exchange", broken)
        with pytest.raises(OSError):
            write_all(str(tmp_path), {"rapid/a.mod": "new a\n", "rapid/b.mod": "new b\n"})
        assert files_under(tmp_path) == {"rapid/a.mod": b"old a\n"}
        assert sorted(os.listdir(tmp_path)) == ["rapid"]

    def test_writes_nested_paths(self, tmp_path: Path) -> None:
        """Vendor sub-directories are created; texts are written with \\n line ends."""
        paths = write_all(str(tmp_path), {"krl/x.src": "a\nb\n"})
        assert paths == [str(tmp_path / "krl" / "x.src")]
        assert (tmp_path / "krl" / "x.src").read_bytes() == b"a\nb\n"
