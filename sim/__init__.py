"""rmot.sim: verification (collisions, limits) and rendering of a Plan.

Public API: `verify(plan, *, clearance=None) -> Report`, `Report`, `load_mesh(mesh)`.
Imported lazily so `rmot.sim.meshio` and `rmot.sim.render` do not pull in pinocchio.
"""

from __future__ import annotations

from typing import Any

__all__ = ["Report", "load_mesh", "verify"]


def __getattr__(name: str) -> Any:
    if name == "verify":
        from rmot.sim.verification import verify

        return verify
    if name == "Report":
        from rmot.sim.report import Report

        return Report
    if name == "load_mesh":
        from rmot.sim.meshio import load_mesh

        return load_mesh
    raise AttributeError(f"module 'rmot.sim' has no attribute {name!r}")
