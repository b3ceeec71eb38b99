"""The controller machine data a program with external axes assumes, per vendor, for the report's
checklist: the lines each backend prints in its program header (backends/ext_axes.machine_data:
ABB MOC mechanical units, KUKA MACHINE_DEF / $ETn kinematics, Fanuc group pairing;
backends/inform_axes: Yaskawa R1/B1/S1 groups and pulse scales). rmot cannot read a controller,
so a person compares these with its configuration. Built here (above both layers) because the
report (sim/) may not import the backends.
"""

from __future__ import annotations

from rmot.backends.ext_axes import driven_axes, machine_data
from rmot.backends.inform_axes import inform_axes
from rmot.lang import plan_types

__all__ = ["VENDORS", "checklists"]

VENDORS = (("rapid", "ABB RAPID (MOC mechanical units)"), ("krl", "KUKA KRL (MACHINE_DEF, $ETn kinematics)"),
           ("fanuc", "Fanuc TP (motion groups, extended axes)"))


def checklists(plan: plan_types.Plan) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """(heading, lines) per task and vendor for every task that drives external axes; () without."""
    cell = plan.program.cell
    out: list[tuple[str, tuple[str, ...]]] = []
    for tp in plan.tasks:
        axes = driven_axes(tp.task, cell)
        if not axes:
            continue
        robot = cell.robot(tp.robot)
        for vendor, title in VENDORS:
            out.append((f"{tp.task.name}: {title}", tuple(machine_data(cell, robot, axes, vendor))))
        found = inform_axes(tp.task, cell, axes)
        lines = (f"not writable: {found}",) if isinstance(found, str) else tuple(found.checklist())
        out.append((f"{tp.task.name}: Yaskawa INFORM (R1/B1/S1 control groups, pulse scales)", lines))
    return tuple(out)
