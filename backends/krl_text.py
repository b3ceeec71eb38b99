"""KUKA KRL words apart from the KrlBackend class: reserved words and name rules, the
Status/Turn of a point, frame and load texts, and the helpers of its runtime logic
(types, operators, timed waits, loop keys)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rmot.backends import codes
from rmot.backends import runtime as _rt
from rmot.backends.base import euler_zyx_deg, fmt, position_mm, tool_cog, turn_bits
from rmot.backends.names import NameRules
from rmot.lang import ir
from rmot.backends.part_load import held_load, state_at_moves

if TYPE_CHECKING:
    from rmot.backends.krl import KrlBackend, KrlContext


__all__ = [
    "RESERVED", "KRL_RULES", "E_AXES", "PTP_HELPER", "status_of", "frame_text", "load_text",
    "ANALOG_IN_PORTS", "krl_config", "SHORTEST",
]


RESERVED = frozenset({
    "AND", "ANIN", "ANOUT", "B_AND", "B_EXOR", "B_NOT", "B_OR", "BOOL", "BRAKE", "C_DIS",
    "C_ORI", "C_PTP", "C_VEL", "CASE", "CAST_FROM", "CAST_TO", "CHAR", "CIRC", "CIRC_REL",
    "CONST", "CONTINUE", "DEF", "DEFAULT", "DEFDAT", "DEFFCT", "DELAY", "DECL", "DIV", "DO",
    "ELSE", "END", "ENDDAT", "ENDFCT", "ENDFOR", "ENDIF", "ENDLOOP", "ENDSWITCH", "ENDWHILE",
    "ENUM", "EXIT", "EXT", "EXTFCT", "FALSE", "FOR", "GLOBAL", "GOTO", "HALT", "IF", "IMPORT",
    "INTERRUPT", "INT", "IS", "LIN", "LIN_REL", "LOOP", "MAXIMUM", "MINIMUM", "NOT", "OR",
    "PRIO", "PTP", "PTP_REL", "PUBLIC", "REAL", "REPEAT", "RESUME", "RETURN", "SEC", "SIGNAL",
    "STRUC", "SWITCH", "THEN", "TO", "TRIGGER", "TRUE", "UNTIL", "WAIT", "WHEN", "WHILE", "EXOR",
    "POS", "E6POS", "AXIS", "E6AXIS", "FRAME", "LOAD", "RMOT_PTP",
    # further KRL keywords (KSS 8.x Operating and Programming Instructions for System
    # Integrators, "KRL syntax": signal and interrupt declarations, spline blocks, time
    # blocks; the keyword list krllint checks the case of): a datum named `start` or `path`
    # is read as the keyword
    "IN", "OUT", "ON", "OFF", "ENABLE", "DISABLE", "DISTANCE", "PATH", "ONSTART", "SPLINE",
    "ENDSPLINE", "SPL", "SPTP", "SLIN", "SCIRC", "TIME_BLOCK", "START", "PART", "STEP",
    "PULSE",
})


KRL_RULES = NameRules(max_len=24, first="A-Za-z_", reserved=RESERVED, prefix="P")


E_AXES = ",E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0"


PTP_HELPER = [
    "DEF RMOT_PTP(VEL_PCT:IN, ACC_PCT:IN)",
    "  ; PTP speed and acceleration in % of each axis's maximum",
    "  REAL VEL_PCT, ACC_PCT",
    "  INT I",
    "  FOR I=1 TO 6",
    "    $VEL_AXIS[I]=VEL_PCT",
    "    $ACC_AXIS[I]=ACC_PCT",
    "  ENDFOR",
    "END",
]


def status_of(branch: ir.Config) -> int:
    """KRL Status for a 6-axis arm (see the module docstring).

    Checked against RoboDK's KUKA KRC4 post (KUKA_KRC4_Config.py, conf_2_str: 'B' + flip +
    (elbow up) + rear, default 'B010') and KUKA's basic/overhead area definition (wrist root
    point x < 0 in the A1 frame = overhead = bit 0).
    """
    return ((1 if branch.shoulder is ir.Shoulder.BACK else 0)
            | (2 if branch.elbow is ir.Elbow.UP else 0)
            | (4 if branch.wrist is ir.Wrist.FLIP else 0))


def frame_text(pose: ir.Pose) -> str:
    """{X .., Y .., Z .., A .., B .., C ..} in mm and degrees."""
    x, y, z = position_mm(pose)
    a, b, c = euler_zyx_deg(pose)
    return f"X {fmt(x, 3)},Y {fmt(y, 3)},Z {fmt(z, 3)},A {fmt(a, 4)},B {fmt(b, 4)},C {fmt(c, 4)}"


def load_text(tool: ir.ToolRef) -> str:
    """{M kg,CM {..},J {..}}: the tool's mass, centre of gravity half way flange->TCP (base.tool_cog)."""
    cx, cy, cz = (fmt(c * 1000.0, 3) for c in tool_cog(tool))
    cog = f"X {cx},Y {cy},Z {cz},A 0.0,B 0.0,C 0.0"
    return f"{{M {fmt(tool.mass, 3)},CM {{{cog}}},J {{X 0.0,Y 0.0,Z 0.0}}}}"


# --------------------------------------------------------------------------- held parts: the load data


def _load_data(node: ir.Attach | ir.Detach, ctx: KrlContext) -> str:
    """The LOAD data (tool + parts held after `node`) in the .dat file: its name."""

    _, _, total, cog = held_load(node, ctx)
    cx, cy, cz = (fmt(c * 1000.0, 3) for c in cog)
    hint = f"{node.tool.name}_load" + "".join(f"_{p}" for p in node.held)
    value = f"LOAD:{{M {fmt(total, 3)},CM {{X {cx},Y {cy},Z {cz},A 0.0,B 0.0,C 0.0}},J {{X 0.0,Y 0.0,Z 0.0}}}}"
    return ctx.module.data.add(hint, value)


def _held_load_name(node: ir.Move, ctx: KrlContext) -> str | None:
    """The load a motion writes while parts are held (None: the tool's own): the state after
    the last attach/detach before it on its path (backends/part_load.state_at_moves)."""

    event = state_at_moves(ctx).get(node.uid)
    if event is None or not event.held or event.tool.name != node.tool.name:
        return None
    return _load_data(event, ctx)


# ----------------------------------------------------------------- runtime logic
#
# Sources: KUKA System Software 8.x "Operating and Programming Instructions for System
# Integrators" (KSS 8.x), chapter "Programming for user group Expert: KRL syntax":
#   * DECL INT / REAL / BOOL: data declared in the module's data list (.dat) is known in every
#     routine of the module (.src DEF and its local DEFs); its value in the .dat persists
#     between runs, so the `var` statement assigns the initial value where the program runs it.
#   * FOR counter = a TO b ... ENDFOR (counter: a declared INT, step 1); WHILE cond ...
#     ENDWHILE; IF cond THEN ... ELSE ... ENDIF; operators AND OR NOT, == <> < <= > >=; every
#     compound operand is parenthesised (runtime.py: comparisons have the lowest priority).
#   * INT / INT is an integer division in KRL ("Arithmetic operators": the result of two INT
#     operands is INT), so rmot's `/` (always a num) multiplies the left INT by 1.0 first.
#   * frame arithmetic: the components of an E6POS (or FRAME) are assigned one by one
#     (`P.X=BASE.X+...`, "Structures": access to a component with the point separator); the
#     target is in $BASE, which is the move's frame, so adding the in-frame step to X, Y, Z
#     offsets it exactly. S and T are copied from the template point: LIN/CIRC keep the Status
#     they start with and ignore the programmed S/T; a PTP in a loop is written to a FRAME
#     (Status kept, Turn the shortest path: _ptp_key) when that reaches every iteration's
#     planned joints, else to an E6POS whose S and T every iteration shares.
#   * $ANIN[n]: analog inputs as -1.0 .. +1.0 for -10 V .. +10 V (KSS 8.x System Variables,
#     $ANIN[1] .. $ANIN[32]; the same scaling as $ANOUT above), so a value in volts is
#     $ANIN[n]*10.
#   * WAIT FOR has no timeout: the timed wait waits on the condition OR the timer
#     $TIMER[TIMER_INDEX] (ms) as KrlBackend.wait_input does, then runs the timeout branch
#     when the condition still does not hold.
#   * stop: KRL has no instruction that ends the program from anywhere: HALT only pauses (the
#     Start key resumes at the next line) and an interpreter cannot cancel itself (CWRITE
#     "CANCEL 1" works from the Submit interpreter only; summarised in "KUKA robot program
#     abort: stopping execution like Fanuc ABORT", industrialmonitordirect.com knowledge base).
#     RETURN leaves the current DEF: in the main program it ends the program (its END is
#     reached: $PRO_STATE1 #P_END). A stop inside a routine sets RMOT_STOP and returns; every
#     call of such a routine is followed by `IF RMOT_STOP THEN RETURN ENDIF` (warning W421).

_KRL_TYPES = {ir.ValueType.INT: ("INT", "0"), ir.ValueType.NUM: ("REAL", "0.0"),
              ir.ValueType.BOOL: ("BOOL", "FALSE")}


_KRL_COMPARE = {ir.CompareOp.EQ: "==", ir.CompareOp.NE: "<>", ir.CompareOp.LT: "<",
                ir.CompareOp.LE: "<=", ir.CompareOp.GT: ">", ir.CompareOp.GE: ">="}


ANALOG_IN_PORTS = (1, 32)  # $ANIN[1..32], KSS 8.x System Variables


_STOP_FLAG = "RMOT_STOP"


def _declare_var(ctx: KrlContext, name: str, krl_type: str, value: str) -> None:
    """`DECL type name=value` in the module's .dat (once per module)."""
    if all(n != name for n, _ in ctx.module.data.items):
        ctx.module.data.items.append((name, f"{krl_type}:{value}"))


def _krl_dialect(self: KrlBackend, ctx: KrlContext, span: object) -> _rt.ExprDialect:
    def analog(a: ir.AnalogInput) -> str:
        low, high = ANALOG_IN_PORTS
        if not low <= a.port <= high:
            self.unsupported(codes.ANALOG_IN_PORT,
                             f"analog input port must be in {low}..{high} "
                             f"for $ANIN (got {a.port})", span)  # type: ignore[arg-type]
        return f"$ANIN[{a.port}]*10"

    def digital(c: ir.InputCondition) -> str:
        self.port_ok(c.port, "digital input", span)  # type: ignore[arg-type]
        return f"$IN[{c.port}]=={self._level(c.value)}"

    def output(o: ir.OutputRead) -> str:
        # $OUT[n] is readable as a BOOL in any expression (KSS 8.x Programming for System
        # Integrators, "System variables": $OUT, "digital outputs ... read and written").
        self.port_ok(o.port, "digital output", span)  # type: ignore[arg-type]
        return f"$OUT[{o.port}]"

    def group(g: ir.GroupInput) -> str:
        # KRL reads a group of inputs by the name of a SIGNAL declaration (`SIGNAL PGNO_IN
        # $IN[33] TO $IN[40]`, read as an INT: KSS 8.x Programming for System Integrators,
        # "SIGNAL") or of an INT global the cell program fills from it (PGNO): either way a
        # name the controller's $CONFIG.DAT declares, which only the cell's io line gives.
        if g.signal is None:
            self.unsupported(codes.LOGIC_UNSUPPORTED, f"gin[{g.port}] must be named by the cell "
                             f"(io gin[{g.port}] = \"NAME\"): KRL reads a group of inputs by its "
                             "SIGNAL name declared in $CONFIG.DAT", span)  # type: ignore[arg-type]
            return "0"
        return ctx.names.name(g.signal)

    return _rt.ExprDialect(
        true="TRUE", false="FALSE", and_="AND", or_="OR", not_="NOT ", compare=_KRL_COMPARE,
        var=lambda v: ctx.names.name(v.name), digital=digital, analog=analog, group=group,
        output=output, real_division=lambda a, b: f"({a}*1.0)/{b}", number=lambda v: _rt.trimmed(fmt(v, 6)),
    )


def _kexpr(self: KrlBackend, e: object, ctx: KrlContext, span: object) -> str:
    return _rt.expr_text(e, _krl_dialect(self, ctx, span))


def _k_timed(self: KrlBackend, cond: str, timeout: float, on_timeout: tuple[ir.Instr, ...],
             ctx: KrlContext, span: object) -> list[str]:
    """A wait on `cond` for at most `timeout` s, then the timeout branch (or HALT without one)."""
    self.warn(codes.TIMEOUT_LOWERED, f"KRL WAIT FOR has no timeout; lowered to a wait on $TIMER"
              f"[{self.TIMER_INDEX}] for {fmt(timeout, 3)} s", span)  # type: ignore[arg-type]
    t, n = f"$TIMER[{self.TIMER_INDEX}]", self.TIMER_INDEX
    branch = self.body(on_timeout, ctx) if on_timeout else ["HALT ; timeout"]
    return [f"$TIMER_STOP[{n}]=TRUE", f"{t}=0", f"$TIMER_STOP[{n}]=FALSE",
            f"WAIT FOR ({cond}) OR ({t}>={int(round(timeout * 1000))})", f"$TIMER_STOP[{n}]=TRUE",
            f"IF NOT ({cond}) THEN"] + self.indent(branch, "  ") + ["ENDIF"]


def krl_config(node: ir.Move, q: np.ndarray, branch: ir.Config | None) -> object:
    """What KRL reads of a target's configuration in a loop: the Status (the branch) for every
    motion (a LIN or CIRC keeps the Status it starts with; a PTP to a FRAME keeps the previous
    one; a PTP to an E6POS takes the programmed one); the Turn of a PTP is _ptp_key's."""
    if branch is None or None in (branch.shoulder, branch.elbow, branch.wrist):
        return None
    return status_of(branch)


SHORTEST = "shortest"


def _ptp_key(ctx: KrlContext, node: ir.Move, rec: object) -> object:
    """SHORTEST when a PTP to a FRAME (no Status, no Turn) reaches the planned joints: the
    controller keeps the previous Status and takes the Turn with the shortest path (KSS 8.x
    "Status and Turn": "The robot controller retains the previous Status value ... In the case
    of PTP motions, the robot controller selects the Turn value that results in the shortest
    possible path", quoted in robot-forum.com thread 42877): true when the branch equals the
    previous move's and every axis moves by less than 179 degrees. Else ("T", Turn) (an
    E6POS with that Turn)."""
    q = getattr(rec, "q_target", None)
    if q is None:
        return None
    bits = ("T", turn_bits(q))
    if getattr(rec, "variant", 0) != 0:
        return bits
    t0 = float(getattr(rec, "t_start", 0.0))
    before = [r for r in ctx.task_plan.records
              if r.variant == 0 and r.q_target is not None and r.t_end <= t0 + 1e-9
              and r.uid != node.uid]
    if not before:
        return bits
    prev = max(before, key=lambda r: r.t_end)
    start = ctx.task_plan.trajectory.at(t0)
    if prev.branch != getattr(rec, "branch", None):
        return bits
    if np.all(np.abs(np.asarray(q, float) - start) < np.radians(179.0)):
        return SHORTEST
    return bits


def _krl_extra(self: KrlBackend, node: ir.Instr, rec: object, ctx: KrlContext) -> object:
    """A PTP to a Cartesian target in a loop accepts an E6POS with its own Turn, and a FRAME
    when that reaches its planned joints (_ptp_key): the loop analysis keeps the forms every
    iteration accepts (LoopTemplate.choices)."""
    key = self.context_key(node, ctx)
    if (isinstance(node, ir.Move) and node.kind is ir.MotionKind.JOINT
            and isinstance(node.target, ir.CartesianTarget)):
        q = getattr(rec, "q_target", None)
        forms: set[tuple[object, object]] = {(key, ("T", None if q is None else turn_bits(q)))}
        if _ptp_key(ctx, node, rec) == SHORTEST:
            forms.add((key, SHORTEST))
        return frozenset(forms)
    return key
