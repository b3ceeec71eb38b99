"""Session-wide test settings: the plan cache lives in a fresh temporary folder for the run
(never the user's ~/.cache/rmot), shared by every test and by the subprocesses they start."""

from __future__ import annotations

import os
import shutil
import tempfile

_CREATED: list[str] = []


def pytest_configure(config: object) -> None:
    folder = tempfile.mkdtemp(prefix="rmot-test-cache-")
    _CREATED.append(folder)
    os.environ["RMOT_CACHE_DIR"] = folder


def pytest_unconfigure(config: object) -> None:
    for folder in _CREATED:
        shutil.rmtree(folder, ignore_errors=True)
