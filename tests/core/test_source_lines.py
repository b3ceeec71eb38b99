"""`SourceFile.line_text` quotes the same line the lexer counts (LF only, a CRLF's CR dropped),
checked against `str.split("\\n")` on arbitrary texts; and quoting every line of a large file is
linear: the line starts are computed once per text, not rescanned per diagnostic."""

from __future__ import annotations

from hypothesis import given, strategies as st

from rmot.lang import source
from rmot.lang.source import SourceFile


def _by_split(text: str, line: int) -> str:
    lines = text.split("\n")
    if not 1 <= line <= len(lines):
        return ""
    return lines[line - 1].removesuffix("\r")


@given(st.text(alphabet="ab\n\r\x0c\u2028 ", max_size=40), st.integers(-2, 14))
def test_line_text_is_the_lf_split_line(text: str, line: int) -> None:
    assert SourceFile("f.rmot", text).line_text(line) == _by_split(text, line)


def test_quoting_every_line_scans_the_text_once() -> None:
    text = "".join(f"move joint p{i}\n" for i in range(20_000))
    file = SourceFile("big.rmot", text)
    source._line_starts.cache_clear()
    quoted = [file.line_text(n) for n in range(1, 20_001)]
    assert quoted[0] == "move joint p0" and quoted[-1] == "move joint p19999"
    info = source._line_starts.cache_info()
    assert (info.misses, info.hits) == (1, 19_999)
