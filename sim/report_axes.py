"""The report's external-axes part: a table of the axes each task drives (name, mechanism, kind,
range, speed, acceleration, what rides on it, in mm or deg) and the machine-data checklist per
vendor (given by the caller: compiler/design/machine_data.py), so a person can compare the
numbers rmot planned with against the controller's configuration before running a program."""

from __future__ import annotations

import html
from collections.abc import Sequence
from typing import Any

from rmot.lang.axis_motion import task_axes
from rmot.lang.axis_series import display_factor, mechanism_of

__all__ = ["axes_section"]


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _rows(plan: Any) -> list[str]:
    external = plan.program.cell.external
    rows = []
    for tp in plan.tasks:
        for axis in task_axes(tp.task, external):
            f, unit = display_factor(axis), axis.unit()
            mech = mechanism_of(axis, external)
            riding = ", ".join(f"{m.kind} {m.body}" for m in external.mounts if m.mechanism == mech) or "-"
            rows.append(f"<tr><td>{_e(tp.task.name)}</td><td>{_e(axis.name)}</td><td>{_e(mech)}</td>"
                        f"<td>{'linear' if axis.linear else 'revolute'} {'xyz'[axis.direction.index(1.0)]}</td>"
                        f"<td>{axis.low * f:g} .. {axis.high * f:g} {unit}</td><td>{axis.speed * f:g} {unit}/s</td>"
                        f"<td>{axis.accel * f:g} {unit}/s²</td><td>{_e(riding)}</td></tr>")
    return rows


def axes_section(plan: Any, checklists: Sequence[tuple[str, Sequence[str]]]) -> list[str]:
    """The HTML of the axes table and the checklists; [] for a program without external axes."""
    rows = _rows(plan) if plan.program.cell.external is not None else []
    if not rows:
        return []
    out = ['<h3 id="external-axes">External axes</h3><table><tr><th>task</th><th>axis</th><th>mechanism</th><th>kind</th>'
           "<th>range</th><th>max speed</th><th>max accel.</th><th>carries</th></tr>", *rows, "</table>"]
    if checklists:
        out.append('<h3 id="machine-data">Machine data to check on the controller</h3>')
    for heading, lines in checklists:
        out.append(f'<details class="machine-data" open><summary>{_e(heading)}</summary><ul>'
                   + "".join(f"<li>{_e(line)}</li>" for line in lines) + "</ul></details>")
    return out
