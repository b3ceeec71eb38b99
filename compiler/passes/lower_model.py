"""A cell's `model NAME { ... }` block -> a ModelSpec (plain SI data), or diagnostics.

Each joint line is `joint revolute|prismatic dh(a=, alpha=, d=, theta=) | mdh(...)
range(lo, hi) speed V accel A`, every field once (the calls before speed/accel), plus any
number of `solid(GEOMETRY, at=POSE)` fields placing a link solid in DH frame i. Revolute joints take
angles for range, angular speeds and accelerations (deg/s, deg/s^2); prismatic joints take
lengths (mm, mm/s, mm/s^2). `flange POSE` (default identity) and `payload MASS` (rated
payload, default none) may appear once each. Every number must be finite; speeds and
accelerations > 0; range lo < hi; payload >= 0; 1 to MAX_JOINTS joints; dh and mdh rows
are not mixed. See sim/robots/model.py for the conventions.
Optional per joint: `mass M` (the link's mass, >= 0, on every joint line or on
none: E809) and `torque T` (the motor's rated torque, N*m, > 0; a force in N on a prismatic
joint); ratings without masses cannot be checked (W801).
"""

from __future__ import annotations

import math

from collections.abc import Callable

from rmot.lang import check_codes as codes, ir
from rmot.compiler.passes.context import Reporter, Scope
from rmot.compiler.passes.lower_controller import declared_controller, record_pendant, urdf_controller
from rmot.compiler.passes.load_files import resolve_folder
from rmot.compiler.passes.evaluate import eval_expr, expect_pose, expect_quantity, match_args
from rmot.compiler.passes.limits import MAX_POSITION_M
from rmot.compiler.passes.values import (ACCEL, ANGLE, ANGULAR_ACCEL, ANGULAR_SPEED, FORCE, LENGTH,
                                         MASS, SPEED, TORQUE, Dim, Quantity, example_unit,
                                         fmt_quantity)
from rmot.lang.model_spec import MAX_JOINTS, ModelJointSpec, ModelSolid, ModelSpec
from rmot.lang import ast
from rmot.lang.source import SourceFile, Span

__all__ = ["lower_model", "solid_shape"]

_DH_ARGS = ("a", "alpha", "d", "theta")
_KINDS = {"revolute": "R", "prismatic": "P"}
_FIELDS = ("dh", "range", "speed", "accel")  # dh stands for dh or mdh
_OPTIONAL = ("mass", "torque")  # link mass, motor's rated torque (N for prismatic)


GeometryFn = Callable[[ast.Geometry], "ir.Geometry | None"]


def lower_model(decl: ast.ModelDecl, scope: Scope, rep: Reporter, geometry: GeometryFn | None = None) -> ModelSpec | None:
    """geometry: the cell's evaluator of `box(...)` etc. (for `solid(...)` fields)."""
    name = decl.name.name
    joints: list[ModelJointSpec] = []
    solids: list[ModelSolid] = []
    conventions: dict[str, Span] = {}
    flange: ast.Setting | None = None
    payload: ast.Setting | None = None
    controller: ast.Setting | None = None
    pendant: dict[int, tuple[float, float, int]] = {}
    ok = True
    for item in decl.items:
        if isinstance(item, ast.ModelJoint):
            index = sum(1 for x in decl.items[:decl.items.index(item) + 1] if isinstance(x, ast.ModelJoint))
            j = _joint(item, scope, rep, conventions)
            ok &= j is not None
            if j is not None:
                joints.append(j)
            for part in item.parts:
                if isinstance(part, ast.Call) and part.func.name == "pendant" and j is not None:
                    ok &= record_pendant(part, index, j.kind, pendant, scope, rep)
                if isinstance(part, ast.Call) and part.func.name == "solid":
                    given = _solid(part, index, scope, rep, geometry)
                    ok &= given is not None
                    if given is not None:
                        solids.append(given)
        elif item.kind == "flange":
            ok &= _once(item, flange, name, rep)
            flange = flange or item
        elif item.kind == "controller":
            ok &= _once(item, controller, name, rep)
            controller = controller or item
        else:
            ok &= _once(item, payload, name, rep)
            payload = payload or item
    if len(conventions) > 1:
        rep.error(codes.MODEL_MIXED_DH, f"model '{name}' must use one DH convention, dh(...) or mdh(...) "
                  "(got both)", conventions["mdh"], (("a dh(...) row is here", conventions["dh"]),))
        ok = False
    n = sum(1 for i in decl.items if isinstance(i, ast.ModelJoint))
    if n == 0 or n > MAX_JOINTS:
        rep.error(codes.MODEL_CHAIN_LENGTH, f"model '{name}' must have 1 to {MAX_JOINTS} joint lines (got {n})", decl.name.span)
        ok = False
    flange_m = _flange_matrix(flange, name, scope, rep)
    ok &= flange_m is not None
    payload_kg = None
    if payload is not None:
        payload_kg = _number(payload.value, MASS, f"payload of model '{name}'", rep, scope, minimum=0.0)  # type: ignore[arg-type]
        ok &= payload_kg is not None
    if ok and joints:
        ok &= _dynamics_complete(decl, joints, rep)
    declared = declared_controller(controller, pendant, len(joints), rep)
    if not ok or declared is None or flange_m is None:
        return None
    return ModelSpec(name, "mdh" in conventions, tuple(joints), flange_m, payload_kg, tuple(solids), *declared)


IDENTITY_FLANGE = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0)


def _flange_matrix(flange: ast.Setting | None, name: str, scope: Scope, rep: Reporter) -> tuple[float, ...] | None:
    """The flange's 4x4 matrix, row by row (identity when the model gives none); None after an
    error: a pose that is not finite, or a flange farther than MAX_POSITION_M from the last DH
    frame (a flange km away would make GiB of samples)."""
    if flange is None:
        return IDENTITY_FLANGE
    pose = expect_pose(eval_expr(flange.value, scope, rep), f"flange of model '{name}'", flange.value.span, rep)  # type: ignore[arg-type, union-attr]
    if pose is None:
        return None
    m = pose.matrix()
    finite = all(math.isfinite(x) for x in m.flat)
    if not finite or max(abs(float(x)) for x in m[:3, 3]) > MAX_POSITION_M:
        rep.error(codes.MODEL_BAD_VALUE if not finite else codes.PHYSICAL_RANGE, f"flange of model '{name}' must be "
                  + (f"within {MAX_POSITION_M:g} m of the last DH frame" if finite else "finite"), flange.value.span)  # type: ignore[union-attr]
        return None
    return tuple(float(x) for x in m.flat)


def _dynamics_complete(decl: ast.ModelDecl, joints: list[ModelJointSpec], rep: Reporter) -> bool:
    """Link masses on every joint line or on none (E809); torque ratings without masses can be
    neither checked nor used by the timing (W801)."""
    name = decl.name.name
    lines = [i for i in decl.items if isinstance(i, ast.ModelJoint)]
    massless = [k for k, j in enumerate(joints, 1) if j.mass is None]
    if massless and len(massless) < len(joints):
        verb = "has" if len(massless) == 1 else "have"
        rep.error(codes.MODEL_MASS_INCOMPLETE,
                  f"model '{name}' must give a link mass on every joint line or on none "
                  f"(joint {', '.join(map(str, massless))} {verb} none; write "
                  "mass 0 kg for a link without mass)", lines[massless[0] - 1].span)
        return False
    rated = [k for k, j in enumerate(joints, 1) if j.torque is not None]
    if rated and massless:
        rep.warning(codes.MODEL_TORQUE_UNCHECKED,
                    f"model '{name}' gives torque ratings but no link masses: the joint torques "
                    "cannot be computed, so the ratings are neither checked nor slow the motion "
                    "(give every joint line a mass, e.g. mass 4 kg)", lines[rated[0] - 1].span)
    return True


def _once(item: ast.Setting, first: ast.Setting | None, name: str, rep: Reporter) -> bool:
    if first is None:
        return True
    rep.error(codes.MODEL_JOINT_FIELD, f"'{item.kind}' must appear once in model '{name}' (got it twice)", item.span,
              (("first given here", first.span),))
    return False


def _number(e: ast.Expr, dim: Dim, what: str, rep: Reporter, scope: Scope | None = None, minimum: float | None = None,
            positive: bool = False) -> float | None:
    v = eval_expr(e, scope or Scope(), rep)
    x = expect_quantity(v, dim, what, e.span, rep)
    if x is None:
        return None
    shown = fmt_quantity(v) if isinstance(v, Quantity) else f"{x:g}"
    if not math.isfinite(x):
        rep.error(codes.MODEL_BAD_VALUE, f"{what} must be a finite number (got {shown})", e.span)
        return None
    if dim == LENGTH and abs(x) > MAX_POSITION_M:  # a DH length of 10^9 m made verification allocate 90 GiB
        rep.error(codes.PHYSICAL_RANGE, f"{what} must be within {MAX_POSITION_M:g} m (got {shown})", e.span)
        return None
    if positive and x <= 0:
        rep.error(codes.MODEL_BAD_VALUE, f"{what} must be > 0 (got {shown})", e.span)
        return None
    if minimum is not None and x < minimum:
        rep.error(codes.MODEL_BAD_VALUE, f"{what} must be >= {minimum:g} (got {shown})", e.span)
        return None
    return x


def _joint(j: ast.ModelJoint, scope: Scope, rep: Reporter, conventions: dict[str, Span]) -> ModelJointSpec | None:
    kind = _KINDS.get(j.kind.name)
    if kind is None:
        rep.unknown(j.kind.name, "joint kind (revolute or prismatic)", j.kind.span, list(_KINDS), codes.MODEL_JOINT_FIELD)
        return None
    fields: dict[str, ast.Call | ast.Setting] = {}
    ok = True
    for part in j.parts:
        key = part.kind if isinstance(part, ast.Setting) else part.func.name
        if key in ("solid", "pendant"):  # solids: any number, lowered by _solid; pendant: lower_controller
            continue
        slot = "dh" if key in ("dh", "mdh") else key
        if slot not in _FIELDS + _OPTIONAL:
            rep.unknown(key, "joint field", part.func.span if isinstance(part, ast.Call) else part.span,
                        ["dh", "mdh", "range", "solid", "pendant"], codes.MODEL_JOINT_FIELD)
            ok = False
            continue
        if slot in fields:
            rep.error(codes.MODEL_JOINT_FIELD, f"a joint must have one {'dh/mdh' if slot == 'dh' else slot} field (got two)",
                      part.span, (("first given here", fields[slot].span),))
            ok = False
            continue
        fields[slot] = part
        if slot == "dh":
            conventions.setdefault(key, part.span)
    if not ok:  # an unknown or repeated field, reported: do not also call the line incomplete
        return None
    missing = [f for f in _FIELDS if f not in fields]
    if missing:
        shown = {"dh": "dh(...) or mdh(...)", "range": "range(lo, hi)", "speed": "speed", "accel": "accel"}
        rep.error(codes.MODEL_JOINT_FIELD, f"a model joint must have {', '.join(shown[m] for m in missing)} "
                  f"(got {', '.join(fields) or 'no field'})", j.span)
        return None
    joint_dim = ANGLE if kind == "R" else LENGTH
    dh = _dh(fields["dh"], scope, rep)  # type: ignore[arg-type]
    rng = _range(fields["range"], joint_dim, scope, rep)  # type: ignore[arg-type]
    speed_e, accel_e = fields["speed"].value, fields["accel"].value  # type: ignore[union-attr]
    speed = _number(speed_e, ANGULAR_SPEED if kind == "R" else SPEED, "joint speed", rep, scope, positive=True)  # type: ignore[arg-type]
    accel = _number(accel_e, ANGULAR_ACCEL if kind == "R" else ACCEL, "joint accel", rep, scope, positive=True)  # type: ignore[arg-type]
    mass = torque = None
    if "mass" in fields:
        mass_s = fields["mass"]
        assert isinstance(mass_s, ast.Setting)
        assert mass_s.value is not None and not isinstance(mass_s.value, (ast.Ident, tuple))
        mass = _number(mass_s.value, MASS, "link mass", rep, scope, minimum=0.0)
        ok &= mass is not None
    if "torque" in fields:
        what = "joint torque rating" if kind == "R" else "joint force rating (prismatic)"
        torque_s = fields["torque"]
        assert isinstance(torque_s, ast.Setting)
        assert torque_s.value is not None and not isinstance(torque_s.value, (ast.Ident, tuple))
        dim = TORQUE if kind == "R" else FORCE
        torque = _number(torque_s.value, dim, what, rep, scope, positive=True)
        ok &= torque is not None
    if dh is None or rng is None or speed is None or accel is None or not ok:
        return None
    a, alpha, d, theta = dh
    return ModelJointSpec(kind, a, alpha, d, theta, rng[0], rng[1], speed, accel, mass, torque)


def solid_shape(call: ast.Call, scope: Scope, rep: Reporter, geometry: GeometryFn | None) -> tuple[ir.Geometry, ir.Pose] | None:
    """`solid(box(...), at=POSE)`: its geometry and placement (a model joint's or an external
    axis' solid), or None after an error."""
    bound = match_args(call.args, ("shape", "at"), "solid", call.span, rep, required=1)
    if bound is None:
        return None
    shape = bound["shape"].value
    if not isinstance(shape, ast.Call) or geometry is None:
        rep.error(codes.MODEL_JOINT_FIELD, "solid() must hold a geometry such as capsule(r=40mm, length=300mm)", shape.span)
        return None
    g = geometry(ast.Geometry(shape.func, shape.args, shape.span))
    pose = ir.Pose()
    if "at" in bound:
        pose = expect_pose(eval_expr(bound["at"].value, scope, rep), "solid placement", bound["at"].value.span, rep)  # type: ignore[assignment]
    return None if g is None or pose is None else (g, pose)


def _solid(call: ast.Call, joint: int, scope: Scope, rep: Reporter, geometry: GeometryFn | None) -> ModelSolid | None:
    """`solid(box(...), at=POSE)`: a solid of link `joint`, placed in DH frame `joint`."""
    found = solid_shape(call, scope, rep, geometry)
    if found is None:
        return None
    g, pose = found
    m = tuple(float(x) for x in pose.matrix().flat)
    if isinstance(g, ir.Box):
        return ModelSolid(joint, "box", tuple(g.size), m)
    if isinstance(g, ir.Cylinder):
        return ModelSolid(joint, "cylinder", (g.radius, g.height), m)
    if isinstance(g, ir.Sphere):
        return ModelSolid(joint, "sphere", (g.radius,), m)
    if isinstance(g, ir.Capsule):
        return ModelSolid(joint, "capsule", (g.radius, g.length), m)
    assert isinstance(g, ir.Mesh)
    return ModelSolid(joint, "mesh", (g.scale,), m, g.path)


def _dh(call: ast.Call, scope: Scope, rep: Reporter) -> tuple[float, float, float, float] | None:
    func = call.func.name
    bound = match_args(call.args, _DH_ARGS, func, call.span, rep)
    if bound is None:
        return None
    missing = [n for n in _DH_ARGS if n not in bound]
    if missing:
        rep.error(codes.MODEL_JOINT_FIELD, f"{func}() must give {', '.join(missing)} (write 0mm or 0deg for a zero)", call.span)
        return None
    dims = {"a": LENGTH, "alpha": ANGLE, "d": LENGTH, "theta": ANGLE}
    values = [_number(bound[n].value, dims[n], f"{func} '{n}'", rep, scope) for n in _DH_ARGS]
    if any(v is None for v in values):
        return None
    return values[0], values[1], values[2], values[3]  # type: ignore[return-value]


def _range(call: ast.Call, dim: Dim, scope: Scope, rep: Reporter) -> tuple[float, float] | None:
    bound = match_args(call.args, ("lo", "hi"), "range", call.span, rep, required=2)
    if bound is None:
        return None
    lo = _number(bound["lo"].value, dim, f"range lower limit ({example_unit(dim)})", rep, scope)
    hi = _number(bound["hi"].value, dim, f"range upper limit ({example_unit(dim)})", rep, scope)
    if lo is None or hi is None:
        return None
    if lo >= hi:
        scale, unit = (180 / math.pi, "deg") if dim == ANGLE else (1000.0, "mm")
        rep.error(codes.MODEL_BAD_VALUE, f"range must have lo < hi (got lo {lo * scale:g} {unit} >= hi {hi * scale:g} {unit})", call.span)
        return None
    return lo, hi


def check_model_name(decl: ast.ModelDecl, rep: Reporter) -> None:
    """W135 when the model is named like a library robot: the cell's model is used (it shadows
    the library entry within this cell), as a local name shadows an outer one."""
    try:
        from rmot.sim.robots import list_robots  # late: optional, tried where used
    except ImportError:  # the robot library is not available: nothing to shadow
        return
    name = decl.name.name
    if name in list_robots():
        rep.warning(codes.MODEL_SHADOWS_LIBRARY, f"model '{name}' shadows the library robot '{name}': robots of this "
                    "cell declared with it use the model (rename the model to use the library arm)", decl.name.span)


def described_urdf(s: ast.RobotDecl, path: str, file: SourceFile, roots: tuple[str, ...], rep: Reporter) -> str | None:
    """The URDF a `urdf(...)` declaration describes: the file itself, or (a .xacro file, or
    packages= given) its expansion with the packages resolved (compiler/passes/xacro_files.py)."""
    arg = next((a for a in s.urdf_args if a.name is not None and a.name.name == "packages"), None)
    if arg is None and not path.lower().endswith(".xacro"):
        return path
    packages: dict[str, str] = {}
    if arg is not None:
        if not isinstance(arg.value, ast.Vector) or not all(i.name is not None for i in arg.value.items):
            rep.error(codes.BAD_ARGUMENT, 'urdf() packages must be {name: "folder", ...}', arg.value.span)
            return None
        for item in arg.value.items:
            assert item.name is not None and isinstance(item.value, ast.String)
            folder = resolve_folder(item.value.value, file, roots, item.value.span, rep)
            if folder is None:
                return None
            packages[item.name.name] = folder
    from rmot.compiler.passes.xacro_files import expand_description  # late: loads xml only when this runs

    return expand_description(path, packages, roots, s.urdf.span if s.urdf else s.span, rep)


def urdf_chain(s: ast.RobotDecl, path: str, rep: Reporter) -> tuple[str | None, str | None, str | None] | None:
    """(base, tip, controller) of `urdf("f.urdf", base="...", tip="...", controller="...")`,
    checked against the file. With controller= alone the chain runs from the URDF's `base`
    link to its `tool0` (ROS-Industrial's controller base and flange frames); with
    controller="any" alone, the whole file as without arguments."""
    bound = match_args(s.urdf_args, ("base", "tip", "controller", "packages"), "urdf", s.span, rep, required=0)
    if bound is None:
        return None
    maker = None
    if "controller" in bound:
        maker = urdf_controller(bound["controller"].value, rep)
        if maker is None:
            return None
    if maker == "any" and "base" not in bound and "tip" not in bound:
        return None, None, maker  # the whole file, its joint values vouched for as they are
    names: dict[str, str] = {}
    for key in ("base", "tip"):
        arg = bound.get(key)
        if arg is None and maker is not None and "base" not in bound and "tip" not in bound:
            names[key] = {"base": "base", "tip": "tool0"}[key]
            continue
        if arg is None:
            rep.error(codes.BAD_ARGUMENT, f"urdf() with a chain must give {key}=\"LINK\" (got no {key})", s.urdf.span if s.urdf else s.span)
            return None
        if not isinstance(arg.value, ast.String):
            rep.error(codes.URDF_UNKNOWN_LINK, f"urdf() {key} must be a link name in quotes such as \"base_link\"", arg.value.span)
            return None
        names[key] = arg.value.value
    try:
        from rmot.sim.robots import RobotError  # late: optional, tried where used
        from rmot.sim.robots.urdf import urdf_links  # late: optional, tried where used

        links = urdf_links(path)
    except (ImportError, RobotError):
        return names["base"], names["tip"], maker  # the load step says why the file is unusable
    ok = True
    for key in ("base", "tip"):
        if names[key] not in links and key not in bound:
            rep.error(codes.URDF_CONTROLLER_FRAMES, f"URDF '{path}' must have a link '{names[key]}' (ROS-Industrial's "
                      f"controller {'base' if key == 'base' else 'flange'} frame) for urdf(controller=), or the call "
                      "must name the links at the controller's base and flange frames: base=\"LINK\", tip=\"LINK\"",
                      s.urdf.span if s.urdf else s.span)
            ok = False
        elif names[key] not in links:
            rep.unknown(names[key], f"URDF link ({key}=)", bound[key].value.span, list(links), codes.URDF_UNKNOWN_LINK)
            ok = False
    if ok:
        from rmot.sim.robots.urdf import urdf_chain_error  # late: loads coal only when this runs

        problem = urdf_chain_error(path, names["base"], names["tip"])
        if problem is not None:
            rep.error(codes.URDF_BAD_CHAIN, f"urdf() base and tip must bound a chain of joints ({problem})", s.span)
            ok = False
    return (names["base"], names["tip"], maker) if ok else None
