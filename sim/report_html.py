"""One self-contained HTML page per run of `rmot report`: what was checked and what was found.

For each program: the verdict and cycle times, the model assumptions, every finding with
its source line, a picture of its worst instant and a link into the 3D viewer at that
instant, the charts (sim.plots, embedded as data: URIs), the cycle-time breakdown, and the
robot and cell data used. The 3D viewer (sim.render.html) is embedded in an <iframe srcdoc>
so the page needs no other file and no network; the page's links call the viewer's
`rmotJump(t)`.

Same input, same bytes: no dates, fixed plot and picture sizes.
"""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rmot.lang import ir, ir_tree
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.sim.report import GUARANTEE
from rmot.sim.report_axes import axes_section
import io

__all__ = ["ProgramResult", "breakdown", "render_report"]

PICTURE = (480, 360)
PLOTS = ("tcp", "timeline", "joints", "speeds", "accels", "torque")


@dataclass(frozen=True, eq=False)
class ProgramResult:
    """One program's run: its file, the plan (None if the front end failed), every diagnostic
    (front end, planner, verification) and the cycle time per task."""

    path: str
    plan: Any | None
    diagnostics: tuple[Diagnostic, ...]
    cycle_times: dict[str, float] = field(default_factory=dict)
    robots: dict[str, Any] | None = None  # robot instance -> Robot, for tests (default: the library)
    machine_data: tuple[tuple[str, tuple[str, ...]], ...] = ()  # (heading, lines) per task and vendor (sim/report_axes.py)


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _data_uri(mime: str, data: bytes) -> str:
    return f"data:{mime};base64," + base64.b64encode(data).decode("ascii")


def breakdown(plan: Any) -> list[dict[str, Any]]:
    """Per task: seconds spent moving, waiting (time/input), at syncs, on I/O, and idle after
    the task ends while others still run; from the plan's instruction records (main timeline)."""
    rows = []
    cycle = float(plan.cycle_time)
    for tp in plan.tasks:
        instrs = {i.uid: i for i in ir_tree.walk(tp.task.body)}
        spent = {"move": 0.0, "wait": 0.0, "sync": 0.0, "io": 0.0}
        for r in tp.records:
            if r.variant != 0:
                continue
            i = instrs.get(r.uid)
            kind = ("move" if isinstance(i, ir.Move) else "sync" if isinstance(i, ir.Sync)
                    else "wait" if isinstance(i, (ir.WaitTime, ir.WaitInput))
                    else "io" if isinstance(i, (ir.SetDigital, ir.SetAnalog, ir.Pulse)) else None)
            if kind is not None:
                spent[kind] += max(float(r.t_end - r.t_start), 0.0)
        end = float(tp.trajectory.t[-1]) if tp.trajectory.t.size else 0.0
        rows.append({"task": tp.task.name, "robot": tp.robot, "total": end, **spent, "idle": max(cycle - end, 0.0)})
    return rows


def _source_block(d: Diagnostic) -> str:
    if d.span is None:
        return ""
    line = d.span.start.line
    text = d.span.file.line_text(line) if getattr(d.span, "file", None) is not None else ""
    where = f"{d.span.path}:{line}:{d.span.start.col}" if hasattr(d.span, "path") else f"line {line}"
    caret = ""
    if text:
        width = max(1, (d.span.end.col - d.span.start.col) if d.span.end.line == line else len(text) - d.span.start.col + 1)
        caret = "\n" + " " * (len(str(line)) + 3 + d.span.start.col - 1) + "^" + "~" * (width - 1)
    return f'<div class="where">{_e(where)}</div><pre class="src">{_e(f"{line} | {text}")}{_e(caret)}</pre>'


def _timing(d: Diagnostic) -> str:
    parts = []
    if d.time_s is not None:
        end = f"..{d.end_time_s:.3f}" if d.end_time_s is not None and d.end_time_s != d.time_s else ""
        parts.append(f"t = {d.time_s:.3f}{end} s")
    if d.peak_time_s is not None:
        parts.append(f"worst at {d.peak_time_s:.3f} s")
    if d.amount is not None:
        parts.append(f"{d.amount.value:g} {d.amount.unit}")
    if d.bodies:
        parts.append("bodies: " + ", ".join(d.bodies))
    return " · ".join(parts)


def _pose_text(p: ir.Pose) -> str:
    x, y, z = (v * 1000.0 for v in p.position)
    w, qx, qy, qz = p.quaternion
    rx = math.degrees(math.atan2(2 * (w * qx + qy * qz), 1 - 2 * (qx * qx + qy * qy)))
    ry = math.degrees(math.asin(max(-1.0, min(1.0, 2 * (w * qy - qz * qx)))))
    rz = math.degrees(math.atan2(2 * (w * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz)))
    return f"x={x:.1f} y={y:.1f} z={z:.1f} mm, rx={rx:.1f} ry={ry:.1f} rz={rz:.1f} deg"


def _geometry_text(g: Any) -> str:
    if isinstance(g, ir.Box):
        return "box " + " x ".join(f"{v * 1000:.0f}" for v in g.size) + " mm"
    if isinstance(g, ir.Cylinder):
        return f"cylinder r={g.radius * 1000:.0f} h={g.height * 1000:.0f} mm"
    if isinstance(g, ir.Sphere):
        return f"sphere r={g.radius * 1000:.0f} mm"
    if isinstance(g, ir.Capsule):
        return f"capsule r={g.radius * 1000:.0f} length={g.length * 1000:.0f} mm"
    if isinstance(g, ir.Mesh):
        return f"mesh {g.path.rsplit('/', 1)[-1]} (scale {g.scale:g})"
    return "none"


def _cell_tables(plan: Any, robots: dict[str, Any]) -> str:
    cell = plan.program.cell
    out = ['<h3>Robots</h3><table><tr><th>instance</th><th>model</th><th>base in world</th><th>joint</th>'
           '<th>range [deg]</th><th>max speed [deg/s]</th><th>max accel. [deg/s²]</th><th>data source</th></tr>']
    for inst in cell.robots:
        robot = robots.get(inst.name)
        if robot is None:
            out.append(f"<tr><td>{_e(inst.name)}</td><td>{_e(inst.source.ref)}</td><td colspan=6>not loaded</td></tr>")
            continue
        dof = int(robot.dof)
        lim, vel, acc = np.degrees(robot.joint_limits), np.degrees(robot.velocity_limits), np.degrees(robot.accel_limits)
        model = f"{getattr(robot, 'vendor', '')} {getattr(robot, 'model_name', '') or inst.source.ref}".strip()
        source = getattr(getattr(robot, "spec", None), "source", None) or getattr(robot, "source", None) or inst.source.ref
        for j in range(dof):
            head = (f'<td rowspan="{dof}">{_e(inst.name)}</td><td rowspan="{dof}">{_e(model)}</td>'
                    f'<td rowspan="{dof}">{_e(_pose_text(inst.base))}</td>') if j == 0 else ""
            tail = f'<td rowspan="{dof}">{_e(source)}</td>' if j == 0 else ""
            out.append(f"<tr>{head}<td>J{j + 1}</td><td>{lim[j, 0]:.1f} .. {lim[j, 1]:.1f}</td><td>{vel[j]:.1f}</td>"
                       f"<td>{acc[j]:.1f}</td>{tail}</tr>")
    out.append("</table>")
    out.append("<h3>Fixtures</h3><table><tr><th>name</th><th>shape</th><th>pose in world</th></tr>")
    out += [f"<tr><td>{_e(f.name)}</td><td>{_e(_geometry_text(f.geometry))}</td><td>{_e(_pose_text(f.pose))}</td></tr>"
            for f in cell.fixtures]
    out.append("</table><h3>Tools</h3><table><tr><th>name</th><th>on</th><th>shape</th><th>TCP in flange</th><th>mass</th></tr>")
    out += [f"<tr><td>{_e(t.name)}</td><td>{_e(t.robot)}</td><td>{_e(_geometry_text(t.geometry))}</td>"
            f"<td>{_e(_pose_text(t.tcp))}</td><td>{t.mass:g} kg</td></tr>" for t in cell.tools]
    out.append("</table>")
    return "".join(out)


ASSUMPTIONS = (
    "Joint positions, speeds and accelerations are checked against the robot library's data (sources in the robot table); "
    "vendors publish no accelerations, so those are estimates (rmot.sim.robots.library).",
    "Torques come from inverse dynamics (RNEA) where the robot model has inertias, with the heaviest tool of the task as "
    "a point mass half way along the flange-to-TCP vector.",
    "The motion is the planner's time-optimal trajectory sampled every {step:g} ms; a real controller's own planner "
    "will differ in timing (cycle times are estimates).",
    "Runtime `if` branches are all planned and verified; waits for inputs are taken as satisfied at once.",
)


def _section(k: int, result: ProgramResult, parts: dict[str, Callable[[], Any]], problems: list[Diagnostic]) -> str:
    """The HTML of one program; `parts` makes the pictures lazily so a failure becomes a W600."""
    out = _summary(k, result)
    out += _findings(k, result, parts, problems)
    if result.plan is None:
        return "".join(out) + "</section>"
    out += _planned(k, result, parts, problems)
    return "".join(out) + "</section>"


def _summary(k: int, result: ProgramResult) -> list[str]:
    """The program's heading, verdict, cycle time and (when planned) the model's assumptions."""
    errors = [d for d in result.diagnostics if d.severity is Severity.ERROR]
    warnings = [d for d in result.diagnostics if d.severity is Severity.WARNING]
    ok = result.plan is not None and not errors
    verdict = "verifies" if ok else ("not checked" if result.plan is None else "FAILS")
    cls = "ok" if ok else "bad"
    out = [f'<section class="program" id="p{k}"><h2>{_e(result.path)} <span class="verdict {cls}">{verdict}</span></h2>']
    if result.cycle_times:
        cyc = ", ".join(f"{_e(name)} {t:.3f} s" for name, t in result.cycle_times.items())
        out.append(f'<p class="summary">cycle time <b>{max(result.cycle_times.values()):.3f} s</b> ({cyc}); '
                   f"{len(errors)} error{'s' * (len(errors) != 1)}, {len(warnings)} warning{'s' * (len(warnings) != 1)}</p>")
    else:
        out.append(f"<p class=\"summary\">not planned; {len(errors)} error{'s' * (len(errors) != 1)}</p>")
    if result.plan is not None:
        step = float(getattr(result.plan, "step", 0.004)) * 1000.0
        items = [a.format(step=step) for a in ASSUMPTIONS] + [GUARANTEE[0].upper() + GUARANTEE[1:] + "."]
        out.append("<details><summary>Model assumptions</summary><ul>" + "".join(f"<li>{_e(a)}</li>" for a in items)
                   + "</ul></details>")
    return out


def _findings(k: int, result: ProgramResult, parts: dict[str, Callable[[], Any]],
              problems: list[Diagnostic]) -> list[str]:
    """Every finding with its source lines, its timing and (once per event) its picture."""
    out: list[str] = []
    marks = _safe(parts, "marks", problems) or ()
    by_diag = {id(m.diagnostic): m for m in marks}
    events = {m.diagnostic.code.id + str(m.diagnostic.span and m.diagnostic.span.start) + ",".join(sorted(m.bodies)): m
              for m in marks}
    out.append(f"<h3>Findings ({len(result.diagnostics)})</h3>")
    if not result.diagnostics:
        out.append("<p>none: no collision, no limit exceeded.</p>")
    shown: set[int] = set()
    for n, d in enumerate(result.diagnostics):
        m = by_diag.get(id(d)) or events.get(d.code.id + str(d.span and d.span.start) + ",".join(sorted(d.bodies)))
        sev = d.severity.name.lower()
        out.append(f'<div class="finding {sev}" id="p{k}-f{n}"><div class="head"><span class="code">{sev}[{_e(d.code.id)}]</span> '
                   f"{_e(d.message)}</div>{_source_block(d)}")
        timing = _timing(d)
        if timing:
            out.append(f'<div class="timing">{_e(timing)}</div>')
        if m is not None and id(m) not in shown:
            shown.add(id(m))
            png = _safe(parts, ("picture", m), problems)
            if png:
                out.append(f'<img class="shot" alt="{_e(m.caption)}" width="{PICTURE[0]}" height="{PICTURE[1]}" '
                           f'src="{_data_uri("image/png", png)}">')
            out.append(f'<div><a href="#viewer{k}" class="jump" data-viewer="viewer{k}" data-t="{m.worst:.4f}">'
                       f"show in the 3D viewer at t = {m.worst:.3f} s</a></div>")
        out.append("</div>")
    return out


def _planned(k: int, result: ProgramResult, parts: dict[str, Callable[[], Any]],
             problems: list[Diagnostic]) -> list[str]:
    """What only a planned program has: the cycle-time breakdown, the plots, the 3D viewer and
    the robot and cell data used."""
    assert result.plan is not None
    out = ["<h3>Cycle-time breakdown</h3><table><tr><th>task</th><th>robot</th><th>ends at [s]</th><th>moving</th>"
           "<th>waiting (time / input)</th><th>at syncs</th><th>I/O</th><th>idle after its end</th></tr>"]
    for row in breakdown(result.plan):
        out.append(f"<tr><td>{_e(row['task'])}</td><td>{_e(row['robot'])}</td><td>{row['total']:.3f}</td>"
                   + "".join(f"<td>{row[c]:.3f}</td>" for c in ("move", "wait", "sync", "io", "idle")) + "</tr>")
    out.append("</table>")
    out.append("<h3>Plots</h3>")
    for what in PLOTS:
        svg = _safe(parts, ("plot", what), problems)
        if svg:
            out.append(f'<figure><img class="plot" alt="{what}" src="{_data_uri("image/svg+xml", svg)}"></figure>')
    free_paths = _safe(parts, "free_paths", problems) or ()
    if free_paths:
        out.append("<h3>Paths found by 'move free'</h3>")
    for caption, svg in free_paths:
        out.append(f'<figure><img class="plot" alt="{_e(caption)}" src="{_data_uri("image/svg+xml", svg.encode())}">'
                   f"<figcaption>{_e(caption)}</figcaption></figure>")
    page = _safe(parts, "viewer", problems)
    if page:
        out.append(f'<h3>3D viewer</h3><iframe class="viewer" id="viewer{k}" title="3D viewer of {_e(result.path)}" '
                   f'srcdoc="{_e(page)}"></iframe>')
    robots = _safe(parts, "robots", problems) or {}
    out.append("<h3>Robot and cell data used</h3>" + _cell_tables(result.plan, robots))
    out += axes_section(result.plan, result.machine_data)
    out += _placed_table(_safe(parts, "placements", problems) or ())
    return out


def _placed_table(placed: Sequence[Any]) -> list[str]:
    """The parts put down (a feeder's by ordinal), where they stay, when, and by which `detach`."""
    if not placed:
        return []
    out = [f"<h3>Parts placed ({len(placed)})</h3><table><tr><th>part</th><th>pose in world</th><th>placed at [s]</th>"
           "<th>by the detach at</th><th>in iteration</th></tr>"]
    for p in placed:
        line = f"{p.span.file.path}:{p.span.start.line}" if p.span is not None else "?"
        out.append(f"<tr><td>{_e(p.name)}</td><td>{_e(_pose_text(ir.Pose.from_matrix(p.pose)))}</td>"
                   f"<td>{p.t:.3f}</td><td>{_e(line)}</td><td>{_e(p.iteration)}</td></tr>")
    out.append("</table>")
    return out


def _safe(parts: dict[Any, Callable[[], Any]], key: Any, problems: list[Diagnostic]) -> Any:
    from rmot.sim.render.codes import REPORT_PART_MISSING as PART_MISSING  # late: loads PIL only when this runs

    make = parts.get(key if not isinstance(key, tuple) else key[0])
    if make is None:
        return None
    try:
        return make(*key[1:]) if isinstance(key, tuple) else make()
    except Exception as exc:
        what = key if isinstance(key, str) else f"{key[0]} {getattr(key[1], 'caption', key[1])}"
        problems.append(Diagnostic(PART_MISSING, Severity.WARNING, f"the report's {what} was not made ({exc.__class__.__name__}: {exc})", None))
        return None


def _parts(result: ProgramResult) -> dict[str, Callable[..., Any]]:
    """The expensive pieces of a program's section, made on demand (each may fail alone)."""
    from rmot.sim.free.drawing import free_path_pictures  # late: loads coal only when this runs
    from rmot.sim.parts import placements  # late: loads coal only when this runs
    from rmot.sim.plots import figure_bytes, plot_data  # late: tests replace it (monkeypatch): read at call time
    from rmot.sim.render.files import write_png  # noqa: F401 - the PNG encoder lives with it  # late: loads PIL only when this runs
    from rmot.sim.render.findings import markings  # late: loads PIL only when this runs
    from rmot.sim.render.html import render_html  # late: loads PIL only when this runs
    from rmot.sim.render.scene import prepare  # late: loads PIL only when this runs
    from rmot.sim.render.still import finding_camera, still_image  # late: loads PIL only when this runs

    cache: dict[str, Any] = {}

    def scene() -> Any:
        if "rs" not in cache:
            assert result.plan is not None  # a report with pictures has a plan
            cache["rs"] = prepare(result.plan, robots=result.robots)
        return cache["rs"]

    def marks() -> Any:
        if "marks" not in cache:
            cache["marks"] = markings(scene(), result.diagnostics)
        return cache["marks"]

    def picture(m: Any) -> bytes:

        from PIL import Image  # late: PIL is heavy or optional, loaded only where used

        camera = finding_camera(scene(), m, PICTURE)
        image = still_image(scene(), time=m.worst, size=PICTURE, aa=2, marks=(m,), camera=camera)
        buffer = io.BytesIO()
        Image.fromarray(image).save(buffer, format="PNG", optimize=False)
        return buffer.getvalue()

    def plot(what: str) -> bytes:
        if "plots" not in cache:
            assert result.plan is not None
            cache["plots"] = plot_data(result.plan)
        return figure_bytes(cache["plots"], what, "svg")

    return {"marks": marks, "picture": picture, "plot": plot,
            "viewer": lambda: render_html(scene(), fps=10, marks=marks()),
            "robots": lambda: {name: e.robot for name, e in scene().scene.robots.items()},
            "placements": lambda: placements(scene().scene, scene().plan),
            "free_paths": lambda: free_path_pictures(result.plan)}


STYLE = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 0 auto; max-width: 1100px; padding: 16px 24px; color: #1c1e22; }
h1 { font-size: 22px; } h2 { font-size: 18px; border-bottom: 2px solid #ddd; padding-bottom: 4px; } h3 { font-size: 15px; margin-top: 22px; }
.verdict { font-size: 13px; padding: 2px 8px; border-radius: 10px; color: #fff; vertical-align: middle; }
.verdict.ok { background: #2e7d32; } .verdict.bad { background: #c62828; }
.finding { border-left: 4px solid #999; background: #fafafa; margin: 10px 0; padding: 6px 10px; }
.finding.error { border-color: #c62828; } .finding.warning { border-color: #ef6c00; }
.finding .code { font-weight: bold; } .finding.error .code { color: #c62828; } .finding.warning .code { color: #ef6c00; }
pre.src { background: #f0f1f4; padding: 4px 8px; margin: 4px 0; overflow-x: auto; }
.where, .timing { color: #555; font-size: 12px; }
img.shot { display: block; margin: 6px 0; border: 1px solid #ccc; max-width: 100%; height: auto; }
img.plot { max-width: 100%; height: auto; }
table { border-collapse: collapse; font-size: 12px; } td, th { border: 1px solid #ddd; padding: 2px 6px; text-align: left; }
iframe.viewer { width: 100%; height: 520px; border: 1px solid #ccc; }
nav a { margin-right: 12px; }
"""

SCRIPT = """
document.querySelectorAll("a.jump").forEach(function (a) {
  a.addEventListener("click", function (e) {
    var frame = document.getElementById(a.getAttribute("data-viewer"));
    var t = parseFloat(a.getAttribute("data-t"));
    if (frame && frame.contentWindow && frame.contentWindow.rmotJump) { e.preventDefault(); frame.contentWindow.rmotJump(t); frame.scrollIntoView(); }
  });
});
"""


def render_report(results: Sequence[ProgramResult], title: str = "rmot report") -> tuple[str, tuple[Diagnostic, ...]]:
    """The page, and W600 warnings for the pieces that could not be made."""
    problems: list[Diagnostic] = []
    sections = [_section(k, r, _parts(r) if r.plan is not None else {}, problems) for k, r in enumerate(results)]
    ok = sum(1 for r in results if r.plan is not None and not any(d.is_error for d in r.diagnostics))
    nav = "".join(f'<a href="#p{k}">{_e(r.path)}</a>' for k, r in enumerate(results))
    notes = "".join(f'<div class="finding warning"><span class="code">warning[{_e(p.code.id)}]</span> {_e(p.message)}</div>'
                    for p in problems)
    page = (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>{_e(title)}</title>'
            f"<style>{STYLE}</style></head><body><h1>{_e(title)}</h1>"
            f'<p class="overall">{ok} of {len(results)} program{"s" * (len(results) != 1)} verif{"y" if len(results) != 1 else "ies"}.</p>'
            f"<nav>{nav}</nav>{notes}{''.join(sections)}<script>{SCRIPT}</script></body></html>\n")
    return page, tuple(problems)
