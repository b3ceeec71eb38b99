"""Atomic output files: the project's one writer (lang/atomic.py), plus the PNG encoder."""

from __future__ import annotations

import numpy as np
from PIL import Image

from rmot.lang.atomic import write_atomic, write_text

__all__ = ["write_atomic", "write_png", "write_text"]


def write_png(path: str, image: np.ndarray) -> None:
    """An (H, W, 3) uint8 image as PNG (no timestamps: the same pixels give the same bytes)."""
    write_atomic(path, lambda temp: Image.fromarray(np.ascontiguousarray(image)).save(temp, format="PNG", optimize=False))
