"""`rmot render` says what it wrote, and its GIF progress bar (a line redrawn with carriage
returns) is drawn only on a terminal: in a CI log every redraw was a line of its own."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.compiler.cli import cli

PROGRAM = ("program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n  wait 3 s\n"
           "  move joint joints(30, -10, 10, 0, 90, 0) deg\n}\n")


def test_render_says_what_it_wrote_and_does_not_flood_a_log(tmp_path: Path) -> None:
    program = tmp_path / "p.rmot"
    program.write_text(PROGRAM, encoding="utf-8")
    for name, extra in (("a.gif", ["--size", "64x48", "--fps", "2"]), ("s.png", ["--size", "64x48"])):
        out = tmp_path / name
        result = CliRunner().invoke(cli, ["render", str(program), "-o", str(out), "--no-cache", *extra])
        assert result.exit_code == 0, result.output
        assert out.stat().st_size > 0
        assert result.output == f"wrote {out}\n", result.output  # one line; CliRunner's stderr is no terminal
        assert "\r" not in result.output and "rendering frames" not in result.output
