"""The one way rmot writes an output file: atomically, with the umask's mode.

Every output — vendor programs (compiler/cli/output_tree.py), `check -o` and `merge -o`
reports, `plan --csv`, renders, plots, reach maps, `place -o` — goes through `write_atomic`
(or `write_new` for a file inside a staging directory that is itself swapped in whole):

  * atomic: the data goes to a temporary file beside the target, flushed to disk, then
    renamed onto it, so a reader (or a killed run) sees the old file or the new one, never a
    part; the temporary file is removed when anything fails;
  * mode 0666 & ~umask, as `open(path, "w")` gives any other tool's output (mkstemp alone
    would give 0600, which hid vendor files from the cell's file server).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable

__all__ = ["file_mode", "write_atomic", "write_bytes", "write_new", "write_text"]


def file_mode() -> int:
    """The mode a new file gets under the process's umask (0o644 under the usual 022)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def write_atomic(path: str, write: Callable[[str], None]) -> None:
    """Call write(temp_path) with a temporary path beside `path` that keeps its extension,
    give it the umask's mode, flush it to disk, then rename it onto `path`."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, temp = tempfile.mkstemp(prefix=".rmot-", suffix=os.path.splitext(path)[1], dir=folder)
    os.close(fd)
    try:
        write(temp)
        os.chmod(temp, file_mode())
        _fsync_file(temp)
        os.replace(temp, path)
    except BaseException:
        if os.path.exists(temp):
            os.unlink(temp)
        raise


def write_text(path: str, text: str) -> None:
    """`text` as UTF-8 with "\\n" line ends, atomically."""
    write_atomic(path, lambda temp: write_new(temp, text))


def write_bytes(path: str, data: bytes) -> None:
    write_atomic(path, lambda temp: write_new(temp, data))


def write_new(path: str, data: str | bytes) -> None:
    """Write `data` (text as UTF-8, "\\n" line ends) to `path` and flush it to disk; for a
    temporary file, or a file in a staging directory that is renamed into place whole."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o666)  # the umask applies
    with os.fdopen(fd, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())


def _fsync_file(path: str) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
