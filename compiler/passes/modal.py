"""Modal settings (tool, frame, speed, joint_speed, accel, zone) resolved to values per move.

Choices (LANGUAGE.md is silent; what RAPID/KRL/TP programmers expect):
  * Defaults when never set: speed 250 mm/s, joint_speed 100 %, accel 2 m/s^2 (TCP),
    joint acceleration 100 % of each axis' limit, zone fine, tool = the robot flange,
    frame = the robot base.
  * `accel` takes an acceleration (TCP, m/s^2) or a ratio (share of each joint's maximum
    acceleration, used by joint moves): `accel 50 %`.
  * `speed` takes a TCP speed (mm/s, m/s), used by linear and circular moves, or a ratio
    (share of each joint's maximum speed, used by joint moves): `speed 20 %` is exactly
    `joint_speed 20 %`, as a setting or a move's modifier. A modifier that the move
    it is on does not use warns: a TCP speed on a joint move W170, a ratio on a linear or
    circular move W171 (speed_modifier_warnings).
  * Settings are scoped to their block: a setting inside a proc body, a loop body or an if
    arm does not leak out of it (an if arm is a runtime branch, so it could not).
  * Built-in names: `tool flange` is the bare flange, `frame base` the robot base and
    `frame world` the cell's world frame (each unless the cell defines that name).
  * A frame can be a cell/program frame, a fixture (its pose) or a robot (its base).
  * A tool must be mounted (`on ROBOT`) on the robot whose task uses it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import replace

from rmot.lang import check_codes as codes, ir
from rmot.compiler.passes.context import Reporter, Scope
from rmot.compiler.passes.evaluate import eval_expr, expect_quantity
from rmot.compiler.passes.limits import MAX_TCP_SPEED, MAX_ZONE_M, MIN_RATIO, MIN_TCP_ACCEL, MIN_TCP_SPEED, within
from rmot.compiler.passes.values import article, ACCEL, LENGTH, RATIO, SPEED, PoseV, Quantity, fmt_quantity
from rmot.lang import ast
from rmot.lang.record import record

__all__ = [
    "DEFAULT_MODAL", "SETTING_HANDLERS", "Modal", "apply_setting", "require_setting_handlers",
    "speed_modifier_warnings",
]


@record(slots=True)
class Modal:
    tool: ir.ToolRef
    frame: ir.FrameRef
    tcp_speed: float = ir.DEFAULT_TCP_SPEED  # m/s
    tcp_accel: float = ir.DEFAULT_TCP_ACCEL  # m/s^2
    joint_speed: float = ir.DEFAULT_JOINT_SPEED  # fraction
    joint_accel: float = ir.DEFAULT_JOINT_ACCEL  # fraction
    zone: ir.Zone = ir.Zone(0.0)


DEFAULT_MODAL = Modal(ir.ToolRef(None), ir.FrameRef(None))


def apply_setting(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose, rep: Reporter) -> Modal:
    """The modal state after setting `s` (unchanged, with a diagnostic, when `s` is wrong)."""
    return SETTING_HANDLERS[s.kind](modal, s, scope, robot, base, rep)


def _set_tool(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose, rep: Reporter) -> Modal:
    tool = _tool(s.value, scope, robot, rep)  # type: ignore[arg-type]
    return modal if tool is None else replace(modal, tool=tool)


def _set_frame(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose, rep: Reporter) -> Modal:
    frame = _frame(s.value, scope, base, rep)  # type: ignore[arg-type]
    return modal if frame is None else replace(modal, frame=frame)


def _set_zone(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose, rep: Reporter) -> Modal:
    if s.value is None:
        return replace(modal, zone=ir.Zone(0.0))
    r = _positive(s, scope, LENGTH, "zone", rep, allow_zero=True)
    r = None if r is None else within(r, 0.0, MAX_ZONE_M, "zone", "mm", 1e-3, s.value.span, rep)  # type: ignore[union-attr]
    return modal if r is None else replace(modal, zone=ir.Zone(r))


def _set_speed(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose, rep: Reporter) -> Modal:
    """A ratio is the joint speed share (`speed 20 %` = `joint_speed 20 %`), else a TCP speed."""
    if _is_ratio(s.value, scope, rep):  # type: ignore[arg-type]
        return _set_joint_speed(modal, s, scope, robot, base, rep, "speed")
    v = _positive(s, scope, SPEED, "speed", rep)
    v = None if v is None else within(v, MIN_TCP_SPEED, MAX_TCP_SPEED, "speed", "mm/s", 1e-3, s.value.span, rep)  # type: ignore[union-attr]
    return modal if v is None else replace(modal, tcp_speed=v)


def _set_joint_speed(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose,
                     rep: Reporter, word: str = "joint_speed") -> Modal:
    v = _ratio(s, scope, word, rep)
    return modal if v is None else replace(modal, joint_speed=v)


def _set_accel(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose, rep: Reporter) -> Modal:
    return _accel(modal, s, scope, rep)


def _misplaced(modal: Modal, s: ast.Setting, scope: Scope, robot: str, base: ir.Pose, rep: Reporter) -> Modal:
    """E115: a move modifier (config, time) or a model line written as a setting."""
    rep.error(codes.MISPLACED, f"'{s.kind}' must be a modifier of a move (got it as a setting)", s.span)
    return modal


SettingHandler = Callable[[Modal, ast.Setting, Scope, str, ir.Pose, Reporter], Modal]

# Every setting kind -> how a setting of that kind changes the modal state; checked below when
# this module is imported, so a kind added to ast.SettingKind without an entry fails at once.
SETTING_HANDLERS: dict[ast.SettingKind, SettingHandler] = {
    ast.SettingKind.TOOL: _set_tool,
    ast.SettingKind.FRAME: _set_frame,
    ast.SettingKind.ZONE: _set_zone,
    ast.SettingKind.SPEED: _set_speed,
    ast.SettingKind.JOINT_SPEED: _set_joint_speed,
    ast.SettingKind.ACCEL: _set_accel,
    ast.SettingKind.CONFIG: _misplaced,
    ast.SettingKind.TIME: _misplaced,
    ast.SettingKind.TORQUE: _misplaced,
    ast.SettingKind.MASS: _misplaced,
    ast.SettingKind.FLANGE: _misplaced,
    ast.SettingKind.PAYLOAD: _misplaced,
    ast.SettingKind.CONTROLLER: _misplaced,
    ast.SettingKind.CLEARANCE: _misplaced,
    ast.SettingKind.SAMPLES: _misplaced,
    ast.SettingKind.BUDGET: _misplaced,
    ast.SettingKind.EXT: _misplaced,
}


def require_setting_handlers(table: Iterable[str], kinds: Iterable[str] = ast.SettingKind) -> None:
    """TypeError unless `table` (its keys) has an entry for every member of `kinds`, no other."""
    missing, unknown = sorted(set(kinds) - set(table)), sorted(set(table) - set(kinds))
    if missing or unknown:
        raise TypeError(f"compiler/passes/modal.SETTING_HANDLERS: no handler for setting kind "
                        f"{', '.join(missing) or '-'}; unknown kind {', '.join(unknown) or '-'}")


require_setting_handlers(SETTING_HANDLERS)


def _tool(name: ast.Ident, scope: Scope, robot: str, rep: Reporter) -> ir.ToolRef | None:
    entry = scope.lookup(name.name)
    if entry is None:
        if name.name == "flange":
            return ir.ToolRef(None)
        tools = [n for n in scope.visible() if (e := scope.lookup(n)) is not None and e.kind == "tool"]
        rep.unknown(name.name, "tool", name.span, [*tools, "flange"])
        return None
    if entry.kind != "tool":
        rep.error(codes.WRONG_TYPE, f"'{name.name}' must be a tool (got {article(entry.kind)})", name.span,
                  ((f"'{name.name}' is defined here", entry.span),))
        return None
    tool: ir.Tool = entry.value
    if tool.robot != robot:
        rep.error(codes.TOOL_NOT_ON_ROBOT, f"tool '{tool.name}' must be mounted on robot '{robot}' to be used in its task "
                  f"(got a tool on '{tool.robot}')", name.span, ((f"'{tool.name}' is declared here", entry.span),))
        return None
    return ir.ToolRef(tool.name, tool.tcp, tool.mass)


def _frame(name: ast.Ident, scope: Scope, base: ir.Pose, rep: Reporter) -> ir.FrameRef | None:
    entry = scope.lookup(name.name)
    if entry is None:
        if name.name == "base":
            return ir.FrameRef(None)
        if name.name == "world":
            return ir.FrameRef("world", base.inverse(), ir.Pose())
        frames = [n for n in scope.visible() if (e := scope.lookup(n)) is not None and e.kind in ("frame", "fixture")]
        rep.unknown(name.name, "frame", name.span, [*frames, "base", "world"])
        return None
    if entry.kind not in ("frame", "fixture", "robot") or not isinstance(entry.value, PoseV):
        rep.error(codes.WRONG_TYPE, f"'{name.name}' must be a frame, a fixture or a robot (got {article(entry.kind)})", name.span,
                  ((f"'{name.name}' is defined here", entry.span),))
        return None
    world = entry.value.pose
    return ir.FrameRef(name.name, base.inverse() * world, world)


def _positive(s: ast.Setting, scope: Scope, dim: tuple[int, ...], what: str, rep: Reporter, allow_zero: bool = False) -> float | None:
    e: ast.Expr = s.value  # type: ignore[assignment]
    value = eval_expr(e, scope, rep)
    v = expect_quantity(value, dim, what, e.span, rep)  # type: ignore[arg-type]
    if v is None:
        return None
    if v < 0 or (v == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        shown = fmt_quantity(value) if isinstance(value, Quantity) else f"{v:g}"  # as the user wrote it
        rep.error(codes.OUT_OF_RANGE, f"{what} must be {bound} (got {shown})", e.span)
        return None
    return v


def _ratio(s: ast.Setting, scope: Scope, what: str, rep: Reporter) -> float | None:
    e: ast.Expr = s.value  # type: ignore[assignment]
    v = eval_expr(e, scope, rep)
    x = expect_quantity(v, RATIO, what, e.span, rep)
    if x is None:
        return None
    if not 0 < x <= 1:
        shown = fmt_quantity(v) if isinstance(v, Quantity) else f"{x:g}"
        rep.error(codes.OUT_OF_RANGE, f"{what} must be more than 0 % and at most 100 % (got {shown})", e.span)
        return None
    return within(x, MIN_RATIO, 1.0, what, "%", 0.01, e.span, rep)


def _accel(modal: Modal, s: ast.Setting, scope: Scope, rep: Reporter) -> Modal:
    e: ast.Expr = s.value  # type: ignore[assignment]
    v = eval_expr(e, scope, rep)
    if isinstance(v, Quantity) and v.dim == RATIO:
        x = _ratio(s, scope, "accel", rep)
        return modal if x is None else replace(modal, joint_accel=x)
    x = _positive(s, scope, ACCEL, "accel", rep) if v is not None else None
    x = None if x is None else within(x, MIN_TCP_ACCEL, float("inf"), "accel", "mm/s^2", 1e-3, e.span, rep)
    return modal if x is None else replace(modal, tcp_accel=x)


def _is_ratio(e: ast.Expr, scope: Scope, rep: Reporter) -> bool:
    """Whether a speed value is a ratio (%). Evaluating again is harmless: the Reporter drops
    the exact repeat of an error the setting itself reports."""
    v = eval_expr(e, scope, rep)
    return isinstance(v, Quantity) and v.dim == RATIO


def speed_modifier_warnings(mods: tuple[ast.Setting, ...], joint_move: bool, scope: Scope,
                            rep: Reporter) -> None:
    """W170 for a TCP speed on a joint move, W171 for a joint speed share on a linear or
    circular move: a move's own modifier it does not use is never silently dropped. (Modal
    settings do not warn: `speed 400 mm/s` before joint moves is for the Cartesian ones.)"""
    for m in mods:
        if m.kind not in ("speed", "joint_speed") or m.value is None:
            continue
        ratio = m.kind == "joint_speed" or _is_ratio(m.value, scope, rep)  # type: ignore[arg-type]
        if joint_move and not ratio:
            v = eval_expr(m.value, scope, rep)  # type: ignore[arg-type]
            if isinstance(v, Quantity) and v.dim == SPEED:
                rep.warning(codes.TCP_SPEED_ON_JOINT_MOVE,
                            "a joint move is timed by its joint speed share, not a TCP speed "
                            f"(got {fmt_quantity(v)}, which it does not use); write a share of "
                            "each joint's maximum speed such as `speed 20 %`", m.span)
        elif ratio and not joint_move:
            rep.warning(codes.JOINT_SPEED_ON_CARTESIAN_MOVE,
                        "a linear or circular move is timed by its TCP speed, not a share of "
                        f"the joint speeds ('{m.kind}' with a ratio, which it does not use); "
                        "write a TCP speed such as `speed 100 mm/s`", m.span)
