"""User text (file names, signal names, names) made safe for the comment it lands in.

A program's *file name* or a cell's signal name reaches every vendor file inside comments;
a line break in it (LF, CR, form feed, U+2028, ...) would end the comment and turn the rest
into controller code. Every character that is not printable by Python's definition (all
line breaks and controls among them) is shown as '?'.
"""

from __future__ import annotations

import re

__all__ = ["comment_safe", "tp_io_comment"]


def comment_safe(text: str) -> str:
    """`text` with every non-printable character (line breaks, controls) replaced by '?'."""
    return text if text.isprintable() else "".join(c if c.isprintable() else "?" for c in text)


# A Fanuc TP I/O comment sits between ':' and ']' in DO[1:comment]; ']' or ':' inside it
# would end or split the reference. Letters, digits, '_', '-', '.' and spaces only.
_TP_UNSAFE = re.compile(r"[^A-Za-z0-9_ .\-]")


def tp_io_comment(text: str) -> str:
    return _TP_UNSAFE.sub("_", text)
