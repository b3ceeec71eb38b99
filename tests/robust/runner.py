"""Materialise a reproducer case in a directory and run `rmot` on it in this process."""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

from click.testing import CliRunner

from tests.robust.cases import Case

__all__ = ["Outcome", "materialise", "run_case"]

ROOT = Path(__file__).resolve().parents[2]
ARM6 = ROOT / "examples" / "urdf_cell" / "arm6.urdf"
STL = ("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.01 0 0\nvertex 0 0.01 0\nendloop\nendfacet\n"
       "endsolid t\n")


class Outcome:
    def __init__(self, exit_code: int, output: str, exception: BaseException | None, files: dict[str, bytes]) -> None:
        self.exit_code, self.output, self.exception, self.files = exit_code, output, exception, files


def _expand(text: str | bytes, d: str) -> str | bytes:
    if isinstance(text, bytes):
        return text
    if text == "@STL@":
        return STL
    if text == "@URDF0@":
        urdf = ARM6.read_text(encoding="utf-8")
        return urdf.replace('<origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>', '<origin xyz="0 0 0.2"/><axis xyz="0 0 0"/>', 1)
    sub = re.fullmatch(r"@URDFSUB:(.*?)=>(.*)@", text, re.S)
    if sub:  # arm6.urdf with its first `old` replaced by `new`
        urdf = ARM6.read_text(encoding="utf-8")
        assert sub.group(1) in urdf, sub.group(1)
        return urdf.replace(sub.group(1), sub.group(2), 1)
    m = re.fullmatch(r"@URDF:(.*)@", text)
    if m:
        urdf = ARM6.read_text(encoding="utf-8")
        mesh = f'<mesh filename="{m.group(1).format(d=d)}"/>'
        return re.sub(r'<geometry><cylinder radius="0.09" length="0.2"/></geometry>', f"<geometry>{mesh}</geometry>", urdf, count=1)
    return text


def materialise(case: Case, d: str) -> list[str]:
    for rel, text in case.files.items():
        path = Path(d) / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        body = _expand(text, d)
        path.write_bytes(body if isinstance(body, bytes) else body.encode("utf-8"))
    for link, target in case.extra.items():  # symbolic links: name -> target
        (Path(d) / link).symlink_to(target)
    if case.setup == "lock":
        os.chmod(Path(d) / "locked", 0)
    if case.setup == "lock_stl":
        os.chmod(Path(d) / "part.stl", 0)
    return [a.format(d=d) for a in case.argv]


def unlock(d: str) -> None:
    for p in (Path(d) / "locked", Path(d) / "part.stl"):
        if p.exists():
            os.chmod(p, stat.S_IRWXU)


def run_case(case: Case, d: str) -> Outcome:
    from rmot.compiler.cli import cli

    argv = materialise(case, d)
    try:
        result = CliRunner().invoke(cli, argv, catch_exceptions=True)
    finally:
        unlock(d)
    exc = result.exception if not isinstance(result.exception, SystemExit) else None
    files = {}
    out = Path(d) / "out"
    if out.is_dir():
        files = {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}
    output = result.output + (result.stderr if result.stderr_bytes is not None and result.stderr not in result.output else "")
    return Outcome(result.exit_code, output, exc, files)
