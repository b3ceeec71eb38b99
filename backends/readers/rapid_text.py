"""RAPID source as located statements and data literals.

RAPID (ABB Technical reference manual, RAPID overview, "Basic elements"): `!` starts a comment
to the end of the line, statements end with `;`, and the block words (MODULE, PROC, IF ..
THEN, FOR .. DO, ...) stand on their own without one. Old S4 `.prg` files start with a
`%%%` ... `%%%` header. Keywords and names are case-insensitive.
"""

from __future__ import annotations

import re

from rmot.backends.readers.common import number, split_top
from rmot.backends.readers.model import Where
from rmot.lang.record import record

__all__ = ["Statement", "statements", "literal", "Literal", "native_line"]

_BLOCK = re.compile(
    r"(?i)^\s*(?:(?:LOCAL|SYSMODULE)\s+)?(?:MODULE\b|ENDMODULE\b|PROC\b|ENDPROC\b|FUNC\b|ENDFUNC\b|TRAP\b|ENDTRAP\b"
    r"|ENDIF\b|ELSE\b\s*$|ENDFOR\b|ENDWHILE\b|TEST\b|CASE\b.*:\s*$|DEFAULT\s*:|ENDTEST\b|ERROR\b\s*(?:\(.*\))?\s*$"
    r"|UNDO\b\s*$|BACKWARD\b\s*$|(?:IF|ELSEIF)\b.*\bTHEN\s*$|(?:FOR|WHILE)\b.*\bDO\s*$)")


# a label (RAPID Technical reference manual, "GOTO" and labels: `name:` before a statement or on
# a line of its own), not an assignment `x := ..`; a TEST's `DEFAULT:` is split off the same way
_LABEL = re.compile(r"(\s*[A-Za-z_]\w*\s*:)(?!=)")


@record(slots=True)
class Statement:
    text: str
    where: Where

    @property
    def word(self) -> str:
        """The first word, upper case (RAPID is case-insensitive)."""
        m = re.match(r"\s*([A-Za-z_]\w*)", self.text)
        return m.group(1).upper() if m else ""


def _strip_comment(line: str) -> str:
    quote = False
    for i, ch in enumerate(line):
        if ch == '"':
            quote = not quote
        elif ch == "!" and not quote:
            return line[:i]
    return line


def statements(path: str, text: str) -> list[Statement]:
    """The module's statements in order, each at the line and column where it starts."""
    out: list[Statement] = []
    buf, start = "", None
    header = False
    for n, raw in enumerate(text.split("\n"), 1):
        if raw.strip() == "%%%":
            header = not header
            continue
        if header:
            continue
        line = _strip_comment(raw)
        pos = 0
        while pos < len(line):
            if not buf.strip():
                stripped = line[pos:].lstrip()
                if not stripped:
                    break
                start = Where(path, n, len(line) - len(stripped) + 1)
                buf = ""
                label = _LABEL.match(line, pos)
                if label is not None:  # `skip:` is a statement of its own, the one after it another
                    out.append(Statement(label.group(1).strip(), start))
                    pos = label.end()
                    continue
            semi = _find_semicolon(line, pos)
            if semi < 0:
                buf += line[pos:] + " "
                break
            buf += line[pos:semi]
            out.append(Statement(buf.strip(), start))  # type: ignore[arg-type]
            buf, pos = "", semi + 1
        if buf.strip() and _BLOCK.match(buf):
            out.append(Statement(buf.strip(), start))  # type: ignore[arg-type]
            buf = ""
    if buf.strip():
        out.append(Statement(buf.strip(), start))  # type: ignore[arg-type]
    return out


def _find_semicolon(line: str, pos: int) -> int:
    quote = False
    for i in range(pos, len(line)):
        if line[i] == '"':
            quote = not quote
        elif line[i] == ";" and not quote:
            return i
    return -1


Literal = float | str | list["Literal"]


MAX_DEPTH = 8  # robtarget nests 3 deep; deeper aggregates are no data rmot reads


def literal(text: str, depth: int = 0) -> Literal | None:
    """A RAPID aggregate `[[..],[..]]` as nested lists of numbers and names, or None."""
    text = text.strip()
    if text.startswith("[") and text.endswith("]"):
        if depth >= MAX_DEPTH:
            return None
        items = [literal(p, depth + 1) for p in split_top(text[1:-1])]
        if any(i is None for i in items):
            return None
        return items  # type: ignore[return-value]
    value = number(text)
    if value is not None:
        return value
    if re.fullmatch(r"[A-Za-z_]\w*|\"[^\"]*\"", text):
        return text
    return None


# the lines RAPID writes without `;`: a block's own lines, a label, a routine's handler keywords
_NO_SEMICOLON = re.compile(r"(?i)^(IF\b.*\bTHEN|ELSEIF|ELSE|ENDIF|FOR|ENDFOR|WHILE|ENDWHILE|TEST|CASE|DEFAULT|ENDTEST"
                           r"|ERROR|UNDO|BACKWARD)\b|^\w+\s*:$")


def native_line(text: str) -> str:
    """A statement (as `statements` gives it, without its `;`) as the RAPID line a native
    statement keeps: with its `;`, except a block's own line, a label and a handler keyword."""
    text = text.strip()
    return text if _NO_SEMICOLON.match(text) else text + ";"
