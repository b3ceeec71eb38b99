"""Comments and docstrings say what the code does and why, never which tracker issue asked for
it: no "issue 27", "issues 29/30" or "#34" in a comment or docstring of the package. An issue
of another project cited as a source names its repository ("ros-industrial/motoman issue 167",
a github.com/.../issues/N address) and is allowed.

The witness is the source read with `tokenize` (comments) and `ast` (docstrings)."""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("lang", "compiler", "backends", "sim")
OWN_ISSUE = re.compile(r"(?<![\w/-])(?:issues?\s*#?\s*\d+|#\d{1,3}\b)", re.IGNORECASE)
CITED = re.compile(r"[\w.-]+/[\w.-]+\s+issues?\s*#?\s*\d+|/issues/\d+|/pull/\d+", re.IGNORECASE)


def _texts(source: str) -> list[tuple[int, str]]:
    """(line, text) of every comment and docstring."""
    out = [(tok.start[0], tok.string) for tok in tokenize.generate_tokens(io.StringIO(source).readline)
           if tok.type == tokenize.COMMENT]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc:
                out.append((node.body[0].lineno, doc))
    return out


def issue_numbers(paths: list[Path]) -> list[str]:
    """`path:line: text` for each comment or docstring naming an issue of this project."""
    found = []
    for path in paths:
        for line, text in _texts(path.read_text(encoding="utf-8")):
            if OWN_ISSUE.search(CITED.sub("", text)):
                found.append(f"{path.relative_to(ROOT)}:{line}: {text.strip()[:80]}")
    return found


def test_no_comment_or_docstring_names_an_issue_number() -> None:
    paths = sorted(p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py"))
    assert issue_numbers(paths) == []


def test_the_check_sees_an_issue_number_and_allows_a_cited_one(tmp_path: Path) -> None:
    global ROOT
    saved, ROOT = ROOT, tmp_path
    try:
        bad = tmp_path / "bad.py"
        bad.write_text('"""Coordinated moves (issue 29)."""\nx = 1  # see #34\n', encoding="utf-8")
        assert [f.split(":")[1] for f in issue_numbers([bad])] == ["2", "1"]
        good = tmp_path / "good.py"
        good.write_text('"""From ros-industrial/motoman issue 167."""\n'
                        'x = 1  # https://github.com/a/b/issues/3; infeed#2 sorts first\n', encoding="utf-8")
        assert issue_numbers([good]) == []
    finally:
        ROOT = saved
