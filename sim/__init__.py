"""rmot.sim: the physical world of a Plan: robots, verification (collisions, limits), rendering.

Public API: `verify(plan, *, clearance=None) -> Report`, `Report`, `load_mesh(mesh)`.
Imported lazily so `rmot.sim.meshio` and `rmot.sim.render` do not pull in pinocchio.

Where things are: verification.py runs the checks over the whole Plan: scene.py (every body
with its name, geometry and pose; parts.py for parts carried and placed), collide.py with
bounds.py (sampled collision and clearance with a no-miss guarantee between samples) and
exact.py (exact distances, coal), limits.py (joint position, speed, acceleration, torque);
report.py (the Report as text, JSON, JUnit, SARIF), report_html.py, timing_report.py (what a
cycle time assumes) and plots.py; meshio.py reads mesh files. render/ draws stills,
animations and findings; robots/ is the robot library and kinematics (FK, Jacobians,
closed-form and numeric IK, IK branches, dynamics with pinocchio); free/ finds the
collision-free paths of `move free`. sim imports only lang (the vocabulary), never the
planner, the command line or the backends (pyproject's layer contract).
"""

from __future__ import annotations

from typing import Any

__all__ = ["Report", "load_mesh", "verify"]


def __getattr__(name: str) -> Any:
    if name == "verify":
        from rmot.sim.verification import verify  # late: tests replace it (monkeypatch): read at call time

        return verify
    if name == "Report":
        from rmot.sim.report import Report  # late: loads numpy only when this runs

        return Report
    if name == "load_mesh":
        from rmot.sim.meshio import load_mesh  # late: loads numpy only when this runs

        return load_mesh
    raise AttributeError(f"module 'rmot.sim' has no attribute {name!r}")
