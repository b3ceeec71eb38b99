"""`rmot robots`: list the library, show a robot, forward and inverse kinematics by hand.

Angles on the command line are degrees, lengths millimetres; orientation rx ry rz with
R = Rz(rz)·Ry(ry)·Rx(rx) (LANGUAGE.md). Bad input exits 2 with a message, never a traceback;
`ik` exits 1 when the pose has no solution (unreachable or out of limits).
"""

from __future__ import annotations

import json
import math
import sys

import click
import numpy as np

__all__ = ["robots"]

_ARGS = {"ignore_unknown_options": True}  # so "-90" is a value, not an option


def _load(name: str):  # type: ignore[no-untyped-def]
    from rmot.sim.robots import RobotError, load_robot  # late: loads coal only when this runs

    try:
        return load_robot(name)
    except RobotError as exc:
        raise click.UsageError(exc.message) from None


def _numbers(values: tuple[str, ...], what: str) -> list[float]:
    out = []
    for i, text in enumerate(values, 1):
        try:
            v = float(text)
        except ValueError:
            raise click.UsageError(f"{what} {i} must be a number (got '{text}')") from None
        if not math.isfinite(v):
            raise click.UsageError(f"{what} {i} must be a finite number (got '{text}')")
        out.append(v)
    return out


def _emit(data: object) -> None:
    click.echo(json.dumps(data, indent=2, sort_keys=True))


def _fmt(values: list[float] | np.ndarray, digits: int = 3) -> str:
    return " ".join(f"{v:.{digits}f}" for v in values) if len(values) else ""


def _branch_dict(cfg) -> dict[str, str | None]:  # type: ignore[no-untyped-def]
    return {k: (v.value if v is not None else None) for k, v in (("shoulder", cfg.shoulder), ("elbow", cfg.elbow), ("wrist", cfg.wrist))}


def _display(robot, q: np.ndarray) -> list[float]:  # type: ignore[no-untyped-def]
    """Joint values as users read them: deg for revolute, mm for prismatic."""
    return [float(math.degrees(v)) if t == "R" else float(v * 1000) for v, t in zip(q, robot.joint_types)]


def _rpy_deg(pose) -> list[float]:  # type: ignore[no-untyped-def]
    """rx ry rz in degrees; at ry = ±90° (gimbal lock) only rz ∓ rx is defined: rx is set to 0."""
    rx, ry, rz = pose.rpy()
    if abs(abs(ry) - math.pi / 2) < 1e-7:
        rz = rz - rx if ry > 0 else rz + rx
        rx = 0.0
        rz = math.atan2(math.sin(rz), math.cos(rz))
    return [round(math.degrees(a), 9) + 0.0 for a in (rx, ry, rz)]


@click.group(name="robots")
def robots() -> None:
    """The robot library: list, show, fk, ik."""


@robots.command(name="list")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
def list_cmd(as_json: bool) -> None:
    """List the library robots."""
    from rmot.sim.robots import list_robots, load_robot  # late: loads coal only when this runs

    rows = [load_robot(n) for n in list_robots()]
    if as_json:
        _emit([{"name": r.name, "vendor": r.vendor, "model": r.model_name, "dof": r.dof, "reach_mm": round(r.reach * 1000, 1)} for r in rows])
        return
    for r in rows:
        click.echo(f"{r.name:<20} {r.vendor:<17} {r.model_name:<20} {r.dof} axes  reach {r.reach * 1000:.0f} mm")


def _coupled_terms(robot) -> list[str]:  # type: ignore[no-untyped-def]
    """Rows of a joint coupling as text, e.g. Fanuc's "q3 = J2 + J3" (empty when uncoupled)."""
    c = robot._coupling
    if c is None:
        return []
    out = []
    for i, row in enumerate(c):
        terms = [f"J{j + 1}" if w == 1 else f"{w:g}*J{j + 1}" for j, w in enumerate(row) if w != 0]
        if terms != [f"J{i + 1}"]:
            out.append(f"q{i + 1} = " + " + ".join(terms))
    return out


@robots.command(name="show")
@click.argument("name")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
def show_cmd(name: str, as_json: bool) -> None:
    """Show a robot's DH table, limits, speeds, accelerations, masses, torque limits, rated
    payload, conventions, and the source of every number."""
    r = _load(name)
    limits = [[round(v, 3) for v in _display(r, row)] for row in r.joint_limits]
    speeds = [round(v, 3) for v in _display(r, r.velocity_limits)]
    dh = [
        {"joint": i + 1, "type": row.kind, "sign": int(row.sign), "theta_offset_deg": round(math.degrees(row.offset), 4),
         "d_mm": round(row.d * 1000, 4), "a_mm": round(row.a * 1000, 4), "alpha_deg": round(math.degrees(row.alpha), 4)}
        for i, row in enumerate(r.dh_rows)
    ]
    coupled = _coupled_terms(r)
    accels = [round(v, 3) for v in _display(r, r.accel_limits)]
    dyn = _dynamics(r)
    if as_json:
        _emit({"name": r.name, "vendor": r.vendor, "model": r.model_name, "dof": r.dof, "reach_mm": round(r.reach * 1000, 1),
               "closed_form": r.has_closed_form, "dh_convention": "modified" if r.dh_modified else "standard",
               "dh": dh, "coupling": coupled, "limits_deg": limits, "speed_deg_s": speeds, "accel_deg_s2": accels,
               "source": r.source, "rated_payload_kg": getattr(r, "rated_payload_kg", None), **dyn,
               "sources": dict(getattr(r, "sources", ())), "conventions": dict(getattr(r, "conventions", ()))})
        return
    click.echo(f"{r.name}: {r.vendor} {r.model_name}, {r.dof} axes, reach {r.reach * 1000:.1f} mm")
    click.echo(f"source: {r.source}")
    click.echo(f"ik: {'closed form (8 branches)' if r.has_closed_form else 'numeric'}")
    if dh:
        click.echo(f"DH ({'modified' if r.dh_modified else 'standard'}): theta = sign*q + offset")
        for text in coupled:
            click.echo(f"  where {text}")
        click.echo(" joint  type  sign  offset(deg)      d(mm)      a(mm)  alpha(deg)")
        for row in dh:
            click.echo(f" {row['joint']:>5}  {row['type']:>4}  {row['sign']:>4}  {row['theta_offset_deg']:>11.3f}  "
                       f"{row['d_mm']:>9.3f}  {row['a_mm']:>9.3f}  {row['alpha_deg']:>10.3f}")
    click.echo(" joint        min        max   speed(/s)   accel(/s²)   mass(kg)  torque(N·m)")
    none: list[float | None] = [None] * r.dof
    masses, torques = dyn.get("link_mass_kg") or none, dyn.get("torque_limit_nm") or none
    for i, ((lo, hi), sp, ac, m, t) in enumerate(zip(limits, speeds, accels, masses, torques), 1):
        extra = f"  {m:>9.2f}  {t:>11.1f}" if m is not None and t is not None else ""
        click.echo(f" {i:>5}  {lo:>9.2f}  {hi:>9.2f}  {sp:>10.1f}  {ac:>11.1f}{extra}")
    payload = getattr(r, "rated_payload_kg", None)
    if payload is not None:
        click.echo(f"rated payload: {payload:g} kg")
    conventions = getattr(r, "conventions", ())
    if conventions:
        click.echo("conventions:")
        for topic, text in conventions:
            click.echo(f"  {topic}: {text}")
    sources = getattr(r, "sources", ())
    if sources:
        click.echo("sources:")
        for quantity, text in sources:
            click.echo(f"  {quantity}: {text}")


def _dynamics(robot) -> dict[str, list[float] | None]:  # type: ignore[no-untyped-def]
    """Link masses and torque limits of a robot with inertias (None without)."""
    if not getattr(robot, "has_inertia", False):
        return {"link_mass_kg": None, "torque_limit_nm": None}
    model = robot.model
    return {"link_mass_kg": [round(float(model.inertias[j].mass), 4) for j in range(1, robot.dof + 1)],
            "torque_limit_nm": [round(float(v), 2) for v in model.effortLimit[: robot.dof]]}


@robots.command(name="fk", context_settings=_ARGS)
@click.argument("name")
@click.argument("joints", nargs=-1, type=click.UNPROCESSED)
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
def fk_cmd(name: str, joints: tuple[str, ...], as_json: bool) -> None:
    """Flange pose for joint values J1..Jn (degrees; mm for prismatic joints)."""
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    r = _load(name)
    values = _numbers(joints, "joint value")
    if len(values) != r.dof:
        raise click.UsageError(f"{r.name} needs {r.dof} joint values (got {len(values)})")
    q = np.array([math.radians(v) if t == "R" else v / 1000 for v, t in zip(values, r.joint_types)])
    pose = ir.Pose.from_matrix(r.fk(q))
    xyz = [c * 1000 + 0.0 for c in pose.position]
    rpy = _rpy_deg(pose)
    branch = r.branch(q)
    if as_json:
        _emit({"robot": r.name, "joints": values, "position_mm": [round(v, 6) for v in xyz],
               "rpy_deg": [round(v, 6) for v in rpy], "branch": _branch_dict(branch)})
        return
    click.echo(f"x y z (mm):    {_fmt(xyz)}")
    click.echo(f"rx ry rz (deg): {_fmt(rpy)}")
    click.echo(f"branch: {branch}")


@robots.command(name="ik", context_settings=_ARGS)
@click.argument("name")
@click.argument("pose", nargs=-1, type=click.UNPROCESSED)
@click.option("--all", "show_all", is_flag=True, help="Every solution (all equivalent angles), not one per branch.")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
def ik_cmd(name: str, pose: tuple[str, ...], show_all: bool, as_json: bool) -> None:
    """Every IK solution of the flange pose X Y Z (mm) RX RY RZ (deg)."""
    from rmot.lang import ir  # late: tests replace it (monkeypatch): read at call time

    r = _load(name)
    values = _numbers(pose, "pose value")
    if len(values) != 6:
        raise click.UsageError(f"a pose needs 6 values X Y Z RX RY RZ (got {len(values)})")
    x, y, z, rx, ry, rz = values
    target = ir.Pose.from_xyz_rpy(x / 1000, y / 1000, z / 1000, math.radians(rx), math.radians(ry), math.radians(rz))
    result = r.ik(target.matrix())
    rows = list(zip(result.solutions, result.branches))
    if not show_all:
        seen: set[str] = set()
        rows = [(q, b) for q, b in rows if not (str(b) in seen or seen.add(str(b)))]  # type: ignore[func-returns-value]
    if as_json:
        _emit({"robot": r.name, "status": result.status.value, "message": result.message,
               "solutions": [{"branch": _branch_dict(b), "joints": [round(v, 6) for v in _display(r, q)]} for q, b in rows]})
        if not result.solutions:
            sys.exit(1)
        return
    click.echo(f"status: {result.status.value}" + (f" ({result.message})" if result.message else ""))
    for i, (q, b) in enumerate(rows, 1):
        click.echo(f"{i:>3}  {str(b):<40} {_fmt(_display(r, q))}")
    if not result.solutions:
        sys.exit(1)  # a finding about the input pose, not a usage error


from rmot.compiler.cli.robots_add_cmd import add_cmd  # noqa: E402  (`rmot robots add`)

robots.add_command(add_cmd)
