"""`rmot check --dynamics`: the per-joint torque figures of rmot.sim.design.metrics as text lines."""

from __future__ import annotations

from rmot.compiler import planned
from rmot.sim.design.metrics import program_metrics

__all__ = ["dynamics_text"]


def dynamics_text(plan: planned.Plan) -> str:
    """One block per task: peak / RMS torque, peak power and use of the rated torque per joint,
    or the reason there are none (no inertia data)."""
    lines = []
    for task, m in program_metrics(plan).items():
        if m.dynamics is None:
            lines.append(f"dynamics: task '{task}' ({m.model}): {m.dynamics_note}")
            continue
        lines.append(f"dynamics: task '{task}' ({m.model}), peak / RMS torque, peak power, peak / rated torque:")
        for j in m.dynamics:
            unit = "N" if j.prismatic else "N·m"
            use = f"{j.utilisation * 100:.0f}% of {j.rated_torque:g} {unit}" if j.utilisation is not None else "rated torque unknown"
            lines.append(f"  J{j.joint}: {j.peak_torque:.2f} / {j.rms_torque:.2f} {unit}, {j.peak_power:.1f} W, {use}")
        if m.dynamics_note:
            lines.append(f"  note: {m.dynamics_note}")
    return "\n".join(lines) + ("\n" if lines else "")
