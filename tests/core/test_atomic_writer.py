"""One atomic writer honouring the umask: every output file — vendor programs,
`check -o` reports, `plan --csv`, renders, plots — gets mode 0666 & ~umask, under any umask
(before, vendor files and reports were 0600 while renders were 0644)."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.lang.atomic import write_atomic, write_bytes, write_text
from rmot.compiler.cli import cli

PROGRAM = """
program modes on r1 {
  tool gripper
  move joint joints(0, -20, 30, 0, 50, 0) deg
  move joint joints(10, -20, 30, 0, 50, 0) deg
}
"""
UMASKS = (0o022, 0o077)


@pytest.fixture(params=UMASKS, ids=lambda m: f"umask{m:03o}")
def umask(request: pytest.FixtureRequest) -> Iterator[int]:
    old = os.umask(request.param)
    try:
        yield request.param
    finally:
        os.umask(old)


def mode(path: Path) -> int:
    return stat.S_IMODE(path.stat().st_mode)


def expected(umask: int) -> int:
    return 0o666 & ~umask  # what `open(path, "w")` or `touch` gives under this umask


def test_expected_mode_is_what_the_os_gives(umask: int, tmp_path: Path) -> None:
    """The reference: a file made by plain open() under the same umask."""
    ref = tmp_path / "ref.txt"
    ref.write_text("x")
    assert mode(ref) == expected(umask)


def test_writer_modes(umask: int, tmp_path: Path) -> None:
    write_text(str(tmp_path / "a.txt"), "a\n")
    write_bytes(str(tmp_path / "b.bin"), b"b")
    write_atomic(str(tmp_path / "c.dat"), lambda temp: Path(temp).write_bytes(b"c"))
    modes = {p.name: mode(p) for p in tmp_path.iterdir()}
    assert modes == dict.fromkeys(["a.txt", "b.bin", "c.dat"], expected(umask))
    assert (tmp_path / "a.txt").read_text() == "a\n"


def test_failed_write_leaves_nothing(tmp_path: Path) -> None:
    """A writer that fails leaves the old file and no temporary file behind."""
    target = tmp_path / "keep.txt"
    target.write_text("old")

    def boom(temp: str) -> None:
        Path(temp).write_text("half")
        raise RuntimeError("disk full")

    with pytest.raises(RuntimeError):
        write_atomic(str(target), boom)
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"] and target.read_text() == "old"


def test_every_command_output_has_the_umask_mode(umask: int, tmp_path: Path) -> None:
    """compile (vendor files), check -o, plan --csv, render and plot, through the CLI."""
    src = tmp_path / "modes.rmot"
    src.write_text(PROGRAM, encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    runs = [
        ["compile", str(src), "--target", "rapid", "--target", "csv", "-o", str(out / "vendor")],
        ["check", str(src), "--format", "json", "-o", str(out / "report.json")],
        ["plan", str(src), "--csv", str(out / "traj.csv")],
        ["render", str(src), "-o", str(out / "still.svg"), "--size", "64x48"],
        ["plot", str(src), "-o", str(out / "plot.svg")],
    ]
    for args in runs:
        result = CliRunner().invoke(cli, [*args, "--no-cache"] if args[0] != "check" else args)
        assert result.exit_code == 0, (args, result.output)
    files = sorted(p for p in out.rglob("*") if p.is_file())
    assert {p.relative_to(out).parts[0] for p in files} == {
        "vendor", "report.json", "traj.csv", "still.svg", "plot.svg"}
    assert {str(p.relative_to(out)): mode(p) for p in files} == {
        str(p.relative_to(out)): expected(umask) for p in files}
