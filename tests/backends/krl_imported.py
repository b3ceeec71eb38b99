"""The KRL import tests' one way of running `rmot import` on a .src and its .dat."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli


def imported_krl(tmp_path: Path, name: str, src: str, dat: str) -> tuple[str, str]:
    """`rmot import` of name.src with its .dat for a KR 16: (what it prints, the .rmot written)."""
    (tmp_path / f"{name}.src").write_text(src)
    (tmp_path / f"{name}.dat").write_text(dat)
    out = tmp_path / f"{name}.rmot"
    result = CliRunner().invoke(cli, ["import", str(tmp_path / f"{name}.src"), "-o", str(out), "--robot", "kuka_kr16"])
    assert result.exit_code == 0, result.output
    return result.output, out.read_text()

