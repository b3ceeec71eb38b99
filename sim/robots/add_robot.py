"""`rmot robots add`: a data sheet's DH table turned into a library-style arm definition.

The input is a small YAML (or JSON) file (lang/REFERENCE.md, "Adding a robot to the
library"): the maker whose pendant values the table's joint values are, the DH convention,
six revolute rows (a, alpha, d, theta in mm and degrees, range in degrees, speed in deg/s)
and where the numbers come from. The table is built as a cell model would be
(robots/model.py), its OPW parameters are derived and proved by FK (robots/model_opw.py),
and the definition `opw_spec(...)` of library_rosi.py is written from them. The definition is
then built as the library builds its arms (robots/build.py) and its FK compared with the
table's at random joint values within the ranges: the report says the largest difference.

Refused, with the file position: an unreadable or malformed file (E547), a missing or bad
field (E548), a table the library's OPW form cannot hold (E549: not six revolute joints with
a spherical wrist, or a frame 0 / flange the definition cannot express). A table without a
`source` is W547; accelerations are always the library's estimate (W548 says so once).
"""

from __future__ import annotations

import math
import re

import numpy as np

from rmot.lang.model_spec import ModelJointSpec, ModelSpec
from rmot.sim.robots.opw import OpwJointMap, OpwParams
from rmot.sim.robots.spec import RobotSpec
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span
from rmot.lang.record import record
from rmot.lang.check_codes import (
    ADD_BAD_FIELD,
    ADD_UNREADABLE,
    ADD_NOT_OPW,
    ADD_ACCEL_ESTIMATED,
    ADD_NO_SOURCE,
)

__all__ = ["Added", "add_from_dh", "add_from_urdf"]

_MAKERS = ("abb", "kuka", "fanuc", "yaskawa", "staubli", "any")
_FIELDS = ("a", "alpha", "d", "theta", "range", "speed", "sign")
_CHECKS = 64  # random joint values at which the definition's FK is compared with the table's


@record(slots=True)
class Added:
    """The definition text, the FK check's largest differences and the diagnostics."""

    text: str
    max_mm: float
    max_rad: float
    diagnostics: tuple[Diagnostic, ...]


class _Refused(Exception):
    def __init__(self, diagnostic: Diagnostic) -> None:
        super().__init__(diagnostic.message)
        self.diagnostic = diagnostic


def _span(file: SourceFile, mark: object | None) -> Span:
    line = int(getattr(mark, "line", 0)) + 1
    col = int(getattr(mark, "column", 0)) + 1
    pos = Pos(line, col, int(getattr(mark, "index", 0)))
    return Span(file, pos, pos)


def _fail(code: Code, message: str, file: SourceFile, mark: object | None) -> _Refused:
    return _Refused(Diagnostic(code, Severity.ERROR, message, _span(file, mark)))


def _node_map(node: object, file: SourceFile, what: str) -> dict[str, object]:
    import yaml  # type: ignore[import-untyped]  # PyYAML, no stubs installed  # late: yaml is heavy or optional, loaded only where used


    if not isinstance(node, yaml.MappingNode):
        raise _fail(ADD_BAD_FIELD, f"{what} must be a mapping of names to values", file, getattr(node, "start_mark", None))
    out: dict[str, object] = {}
    for key, value in node.value:
        out[str(key.value)] = value
    return out


def _number(node: object, file: SourceFile, what: str) -> float:

    text = str(getattr(node, "value", ""))
    try:
        v = float(text)
    except ValueError:
        raise _fail(ADD_BAD_FIELD, f"{what} must be a number (got '{text}')", file, getattr(node, "start_mark", None)) from None
    if not math.isfinite(v) or abs(v) > 1e5:
        raise _fail(ADD_BAD_FIELD, f"{what} must be finite and within 100 m / 1e5 deg (got {text})", file,
                    getattr(node, "start_mark", None))
    return v


def _text(fields: dict[str, object], key: str, file: SourceFile, where: object, default: str | None = None) -> str:

    node = fields.get(key)
    if node is None:
        if default is not None:
            return default
        raise _fail(ADD_BAD_FIELD, f"the table needs `{key}`", file, where)
    return str(getattr(node, "value", ""))


def _joint(node: object, k: int, file: SourceFile) -> tuple[float, ModelJointSpec]:

    fields = _node_map(node, file, f"joint {k}")
    mark = getattr(node, "start_mark", None)
    for key in fields:
        if key not in _FIELDS:
            raise _fail(ADD_BAD_FIELD, f"joint {k}: unknown field `{key}` (fields: {', '.join(_FIELDS)})", file, mark)
    for key in _FIELDS[:-1]:
        if key not in fields:
            raise _fail(ADD_BAD_FIELD, f"joint {k} needs `{key}`", file, mark)
    a, alpha, d, theta = (_number(fields[f], file, f"joint {k} {f}") for f in ("a", "alpha", "d", "theta"))
    rng = fields["range"]
    items = getattr(rng, "value", None)
    if not isinstance(items, list) or len(items) != 2:
        raise _fail(ADD_BAD_FIELD, f"joint {k} range must be [low, high] in degrees", file, getattr(rng, "start_mark", mark))
    lo, hi = (_number(v, file, f"joint {k} range") for v in items)
    speed = _number(fields["speed"], file, f"joint {k} speed")
    if not lo < hi or speed <= 0:
        raise _fail(ADD_BAD_FIELD, f"joint {k}: range needs low < high and speed > 0", file, mark)
    sign = _number(fields["sign"], file, f"joint {k} sign") if "sign" in fields else 1.0
    if sign not in (1.0, -1.0):
        raise _fail(ADD_BAD_FIELD, f"joint {k} sign must be 1 or -1 (got {sign:g})", file, mark)
    return sign, ModelJointSpec("R", a / 1000, math.radians(alpha), d / 1000, math.radians(theta), math.radians(lo),
                          math.radians(hi), math.radians(speed), math.radians(4 * speed))


def _read(file: SourceFile) -> tuple[dict[str, object], tuple[ModelJointSpec, ...], tuple[float, ...], object]:
    """The top-level fields, the six joints and their pendant signs (file positions kept for the errors)."""
    import yaml  # late: yaml is heavy or optional, loaded only where used


    try:
        root = yaml.compose(file.text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as exc:
        raise _fail(ADD_UNREADABLE, f"not a YAML/JSON DH table: {getattr(exc, 'problem', None) or exc}", file,
                    getattr(exc, "problem_mark", None)) from None
    if root is None:
        raise _fail(ADD_UNREADABLE, "the file is empty", file, None)
    fields = _node_map(root, file, "the table")
    joints = fields.get("joints")
    if joints is None or not isinstance(getattr(joints, "value", None), list):
        raise _fail(ADD_BAD_FIELD, "the table needs `joints`: a list of six rows", file, root.start_mark)
    rows = joints.value  # type: ignore[attr-defined]
    if len(rows) != 6:

        raise _fail(ADD_NOT_OPW, f"the library's arms have six revolute joints (the table has {len(rows)})", file,
                    joints.start_mark)  # type: ignore[attr-defined]
    signed = [_joint(node, k, file) for k, node in enumerate(rows, 1)]
    return fields, tuple(j for _, j in signed), tuple(s for s, _ in signed), root.start_mark


def add_from_dh(path: str, text: str, seed: int = 7) -> Added:
    """The library definition of the DH table in `text` (read from `path`), or the refusal."""
    file = SourceFile(path, text)
    try:
        return _add(file, seed)
    except _Refused as exc:
        return Added("", math.nan, math.nan, (exc.diagnostic,))


def add_from_urdf(path: str, name: str, maker: str, source: str, base: str | None = None, tip: str | None = None,
                  seed: int = 7) -> Added:
    """The library definition of a URDF arm (from `base` to `tip`, else the loader's chain and
    flange), its joint values taken as the pendant's one to one (as ROS-I's Motoman and Stäubli
    drivers have them), or the refusal."""
    from rmot.sim.robots.errors import RobotError  # late: loads subprocess only when this runs
    from rmot.sim.robots.urdf import robot_from_urdf  # late: loads subprocess only when this runs

    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            file = SourceFile(path, f.read(200))  # the first line, for the error's caret
    except OSError:
        file = SourceFile(path, "")
    try:
        if not re.fullmatch(r"[a-z][a-z0-9_]{1,62}", name):
            raise _fail(ADD_BAD_FIELD, f"name '{name}' must be lower case letters, digits and _", file, None)
        if maker not in _MAKERS:
            raise _fail(ADD_BAD_FIELD, f"vendor '{maker}' is none of {', '.join(_MAKERS)}", file, None)
        try:
            robot = robot_from_urdf(path, base, tip)
        except RobotError as exc:
            raise _fail(ADD_UNREADABLE, f"the URDF does not load as a serial arm: {exc.message}", file, None) from None
        notes = [Diagnostic(ADD_ACCEL_ESTIMATED, Severity.WARNING, "accelerations are the library's estimate "
                            "(4 x the axis speed per second)", _span(file, None))]
        if not source:
            notes.insert(0, Diagnostic(ADD_NO_SOURCE, Severity.WARNING, "no --source: the URDF's numbers are cited as "
                                       "the file's path", _span(file, None)))
        arm = _Arm(name, name, maker, source or path, (1.0,) * 6)
        return _derived(arm, robot, robot, tuple(notes), seed, file, None)
    except _Refused as exc:
        return Added("", math.nan, math.nan, (exc.diagnostic,))


def _add(file: SourceFile, seed: int) -> Added:
    from rmot.sim.robots.model import robot_from_model  # late: loads subprocess only when this runs

    fields, joints, signs, top = _read(file)
    name = _text(fields, "name", file, top)
    if not re.fullmatch(r"[a-z][a-z0-9_]{1,62}", name):
        raise _fail(ADD_BAD_FIELD, f"name '{name}' must be lower case letters, digits and _", file, top)
    maker = _text(fields, "vendor", file, top).lower()
    if maker not in _MAKERS:
        raise _fail(ADD_BAD_FIELD, f"vendor '{maker}' is none of {', '.join(_MAKERS)}", file, top)
    dh = _text(fields, "dh", file, top, "standard")
    if dh not in ("standard", "modified"):
        raise _fail(ADD_BAD_FIELD, f"dh must be standard or modified (got '{dh}')", file, top)
    notes: list[Diagnostic] = []
    source = _text(fields, "source", file, top, "")
    if not source:
        notes.append(Diagnostic(ADD_NO_SOURCE, Severity.WARNING, "the table names no `source`: its numbers are cited "
                                "as 'unknown' in the definition", _span(file, top)))
    notes.append(Diagnostic(ADD_ACCEL_ESTIMATED, Severity.WARNING, "accelerations are the library's estimate "
                            "(4 x the axis speed per second)", _span(file, top)))
    # the OPW form is derived on the DH variables u; the pendant value p turns u = sign·p
    spec = ModelSpec(name, dh == "modified", joints, controller=None if maker == "any" else maker)
    pendant = tuple((sg, 0.0, 0) for sg in signs)
    table = robot_from_model(ModelSpec(name, dh == "modified", joints, pendant=pendant))
    arm = _Arm(name, _text(fields, "model", file, top, name), maker, source or "unknown", signs)
    return _derived(arm, robot_from_model(spec), table, tuple(notes), seed, file, top)


@record(slots=True)
class _Arm:
    """What the definition says besides the geometry: names, maker, source, pendant signs."""

    name: str
    model: str
    maker: str
    source: str
    signs: tuple[float, ...]


def _derived(arm: _Arm, in_dh: object, in_pendant: object, notes: tuple[Diagnostic, ...], seed: int,
             file: SourceFile, where: object) -> Added:
    """The definition of the arm whose FK in DH variables is `in_dh`'s, checked against
    `in_pendant` (the same arm in pendant values)."""
    from rmot.sim.robots.model_opw import derive_opw  # late: loads subprocess only when this runs

    found = derive_opw(in_dh)
    if found is None:
        raise _fail(ADD_NOT_OPW, "not an ortho-parallel arm with a spherical wrist (no OPW closed form reproduces "
                    "its FK)", file, where)
    params, jmap = _clean(found[0], OpwJointMap(sign=tuple(a * b for a, b in zip(found[1].sign, arm.signs)),
                                                offset=found[1].offset))
    limits = in_pendant.joint_limits  # type: ignore[attr-defined]
    speeds = in_pendant.velocity_limits  # type: ignore[attr-defined]
    flange_rz = _flange_turn(found[2], _spec(arm, params, jmap, limits, speeds, 0.0), in_pendant)
    if flange_rz is None:
        raise _fail(ADD_NOT_OPW, "frame 0 or the flange is turned against the OPW frames in a way a library "
                    "definition cannot state (frame 0 must have z up along J1 and x towards the arm at zero; the "
                    "flange only turned about its z)", file, where)
    lib = _spec(arm, params, jmap, limits, speeds, flange_rz)
    max_mm, max_rad = _fk_check(in_pendant, lib, seed)
    return Added(_definition(lib, arm.maker, params, jmap, flange_rz), max_mm, max_rad, notes)


def _tidy(v: float) -> float:
    """v to 12 significant digits, rounding noise of the derivation (below 1e-12) to 0."""
    return 0.0 if abs(v) < 1e-12 else float(f"{v:.12g}")


def _clean(p: OpwParams, jmap: OpwJointMap) -> tuple[OpwParams, OpwJointMap]:
    """The derived numbers without floating-point noise (the FK check runs on these)."""
    params = OpwParams(**{k: _tidy(getattr(p, k)) for k in ("a1", "a2", "b", "c1", "c2", "c3", "c4")})
    return params, OpwJointMap(sign=tuple(_tidy(v) for v in jmap.sign), offset=tuple(_tidy(v) for v in jmap.offset))


def _flange_turn(base: np.ndarray, unturned: RobotSpec, arm: object) -> float | None:
    """The flange's turn about its z (the library's `flange_rz`), where frame 0 is the OPW base
    and the arm's flange differs from the definition's unturned one by a turn about z only."""
    from rmot.sim.robots.build import build_robot  # late: loads subprocess only when this runs

    if not np.allclose(base, np.eye(4), atol=1e-9):
        return None
    zero = np.zeros(6)
    m = np.linalg.inv(build_robot(unturned).fk(zero)) @ arm.fk(zero)  # type: ignore[attr-defined]
    if not np.allclose(m[:3, 3], 0.0, atol=1e-9) or abs(m[2, 2] - 1.0) > 1e-9:
        return None
    return _tidy(math.atan2(m[1, 0], m[0, 0]))


def _spec(arm: _Arm, params: OpwParams, jmap: OpwJointMap, limits_rad: np.ndarray, speed_rad: np.ndarray,
          flange_rz: float) -> RobotSpec:
    from rmot.sim.robots.library_common import ACC_EST, acc_estimate, sources  # late: loads subprocess only when this runs
    from rmot.sim.robots.spec import opw_spec  # late: loads subprocess only when this runs

    limits = tuple((round(math.degrees(lo), 6), round(math.degrees(hi), 6)) for lo, hi in limits_rad)
    speed = tuple(round(math.degrees(v), 6) for v in speed_rad)
    name, model, maker, source = arm.name, arm.model, arm.maker, arm.source
    reach = params.a1 + params.c2 + math.hypot(params.a2, params.c3)
    scale = max(reach, 0.3) / 1.44  # the MH12's capsule radii (library_rosi.py) scaled by wrist reach
    radii = tuple(max(0.02, round(r * scale, 3)) for r in (0.13, 0.11, 0.08, 0.08, 0.065, 0.055, 0.04))
    return opw_spec(
        name=name, vendor=maker.capitalize(), model=model, source=source, params=params, jmap=jmap,
        limits_deg=limits, speed_deg_s=speed, accel_deg_s2=acc_estimate(speed), reach=reach, radii=radii,
        flange_rz=flange_rz, sources=sources(geometry=source, limits=source, speed=source, accel=ACC_EST,
                                            reach="estimate: a1 + c2 + hypot(a2, c3)"),
    )


def _fk_check(table_robot, lib: RobotSpec, seed: int) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """Largest position (mm) and orientation (rad) difference of the definition's FK from the table's."""
    from rmot.sim.robots.build import build_robot  # late: loads subprocess only when this runs

    built = build_robot(lib)
    qs = np.random.default_rng(seed).uniform(table_robot.joint_limits[:, 0], table_robot.joint_limits[:, 1], (_CHECKS, 6))
    worst_mm = worst_rad = 0.0
    for q in qs:
        a, b = built.fk(q), table_robot.fk(q)
        worst_mm = max(worst_mm, float(np.linalg.norm(a[:3, 3] - b[:3, 3])) * 1000)
        rel = a[:3, :3].T @ b[:3, :3]
        skew = np.array([rel[2, 1] - rel[1, 2], rel[0, 2] - rel[2, 0], rel[1, 0] - rel[0, 1]]) / 2
        worst_rad = max(worst_rad, math.atan2(float(np.linalg.norm(skew)), (np.trace(rel) - 1) / 2))
    return worst_mm, worst_rad


_CONV = {"abb": "ABB_CONV", "kuka": "KUKA_CONV", "fanuc": "FANUC_CONV", "yaskawa": "YASKAWA_CONV", "staubli": "STAUBLI_CONV"}


def _definition(lib: RobotSpec, maker: str, p: OpwParams, jmap: OpwJointMap, flange_rz: float) -> str:
    """The `opw_spec(...)` call of a library module, numbers as derived (repr: exact)."""
    def tup(values: tuple[float, ...]) -> str:
        return "(" + ", ".join(f"{v:.12g}" for v in values) + ")"

    conv = f"conventions={_CONV[maker]}, " if maker in _CONV else ""
    limits = "(" + ", ".join(f"({lo:.12g}, {hi:.12g})" for lo, hi in lib.limits_deg) + ")"
    return "\n".join((
        f"# {lib.model}: derived by `rmot robots add` from {lib.source}",
        "opw_spec(",
        f"    name={lib.name!r}, vendor={lib.vendor!r}, model={lib.model!r}, source={lib.source!r},",
        f"    params=OpwParams(a1={p.a1:.12g}, a2={p.a2:.12g}, b={p.b:.12g}, c1={p.c1:.12g}, c2={p.c2:.12g}, "
        f"c3={p.c3:.12g}, c4={p.c4:.12g}),",
        f"    jmap=OpwJointMap(sign={tup(jmap.sign)}, offset={tup(jmap.offset)}),",
        f"    limits_deg={limits},",
        f"    speed_deg_s={tup(lib.speed_deg_s)}, accel_deg_s2=acc_estimate({tup(lib.speed_deg_s)}),",
        f"    reach={lib.reach:.12g}, radii={tup(tuple(s.radius for s in lib.segments))}, flange_rz={flange_rz:.12g}, "
        f"{conv}",
        f"    sources=sources(geometry={lib.source!r}, limits={lib.source!r}, speed={lib.source!r}, accel=ACC_EST,",
        "                    reach=\"estimate: a1 + c2 + hypot(a2, c3)\"),",
        ")",
        "",
    ))
