"""`rmot check --dynamics`: the per-joint torque figures of rmot.compiler.design.metrics as text lines
(text format) and as the per-task `dynamics` block of the JSON report (rmot.sim.report)."""

from __future__ import annotations

from typing import Any

from rmot.lang import plan_types
from rmot.compiler.design.metrics import TaskMetrics, program_metrics

__all__ = ["dynamics_json", "dynamics_text"]


def dynamics_text(plan: plan_types.Plan, metrics: dict[str, TaskMetrics] | None = None) -> str:
    """One block per task: peak / RMS torque, peak power and use of the rated torque per joint,
    or the reason there are none (no inertia data). `metrics`: program_metrics(plan) if known."""
    lines = []
    for task, m in (program_metrics(plan) if metrics is None else metrics).items():
        if m.dynamics is None:
            lines.append(f"dynamics: task '{task}' ({m.model}): {m.dynamics_note}")
            continue
        lines.append(f"dynamics: task '{task}' ({m.model}), peak / RMS torque, peak power, peak / rated torque:")
        for j in m.dynamics:
            unit = "N" if j.prismatic else "N·m"
            use = "rated torque unknown"
            if j.utilisation is not None and j.rms_utilisation is not None:
                verdict = "the motor suffices" if j.suffices else "EXCEEDS the motor's rating"
                use = (f"{j.utilisation * 100:.0f}% of {j.rated_torque:g} {unit} "
                       f"(RMS {j.rms_utilisation * 100:.0f}%): {verdict}")
            lines.append(f"  J{j.joint}: {j.peak_torque:.2f} / {j.rms_torque:.2f} {unit}, {j.peak_power:.1f} W, {use}")
        if m.dynamics_note:
            lines.append(f"  note: {m.dynamics_note}")
    return "\n".join(lines) + ("\n" if lines else "")


def _r(x: float | None) -> float | None:
    return None if x is None else round(float(x), 6)


def dynamics_json(metrics: dict[str, TaskMetrics]) -> dict[str, dict[str, Any]]:
    """task name -> the `dynamics` block of its JSON report entry (schema: rmot.sim.report._DYNAMICS):
    model, per joint peak / RMS torque (N·m; N for a prismatic joint, `unit` says), peak power (W),
    rated torque, peak / rated, RMS / rated and whether the motor suffices (peak within the
    rating; null when the model gives no rating); `joints` null and `note`
    saying why when the model has no inertia data."""
    out = {}
    for task, m in metrics.items():
        joints = None
        if m.dynamics is not None:
            joints = [{"joint": j.joint, "unit": "N" if j.prismatic else "N·m",
                       "peak_torque": _r(j.peak_torque), "rms_torque": _r(j.rms_torque),
                       "peak_power_w": _r(j.peak_power), "rated_torque": _r(j.rated_torque),
                       "utilisation": _r(j.utilisation), "rms_utilisation": _r(j.rms_utilisation),
                       "suffices": j.suffices} for j in m.dynamics]
        out[task] = {"model": m.model, "joints": joints, "note": m.dynamics_note}
    return out
