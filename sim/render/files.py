"""Atomic output files: write to a temporary file in the target's folder, then rename."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable

import numpy as np
from PIL import Image

__all__ = ["write_atomic", "write_png", "write_text"]


def write_atomic(path: str, write: Callable[[str], None]) -> None:
    """Call write(temp_path) with a temporary path that keeps the extension, then os.replace it onto path."""
    folder = os.path.dirname(os.path.abspath(path))
    suffix = os.path.splitext(path)[1]
    fd, temp = tempfile.mkstemp(prefix=".rmot-", suffix=suffix, dir=folder)
    os.close(fd)
    try:
        write(temp)
        os.chmod(temp, 0o666 & ~_umask())  # mkstemp makes 0600; give the usual permissions
        os.replace(temp, path)
    except BaseException:
        if os.path.exists(temp):
            os.unlink(temp)
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_png(path: str, image: np.ndarray) -> None:
    """An (H, W, 3) uint8 image as PNG (no timestamps: the same pixels give the same bytes)."""
    write_atomic(path, lambda temp: Image.fromarray(np.ascontiguousarray(image)).save(temp, format="PNG", optimize=False))


def write_text(path: str, text: str) -> None:
    def _write(temp: str) -> None:
        with open(temp, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)

    write_atomic(path, _write)
