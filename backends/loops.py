"""Can a `for` loop be written as ONE vendor loop? The vendor-neutral analysis.

The front end lowers `for i in a .. b { ... }` to an `ir.Loop` whose every iteration is
lowered with `i` bound (what the planner plans and the verifier checks). A controller's loop
runs one body for every value of its counter, so the iterations can be written as one
vendor loop only when

  * they have the same structure: the same instructions in the same order with the same
    settings (motion, zone as printed, tool, frame, IK branch request, signal ports, values,
    nested loops with the same bounds), everything equal except Cartesian target poses;
  * every Cartesian target's `in_frame` pose (what the backends write, in the move's frame)
    is affine in the loop variables: the same orientation in every iteration, and
    position = base + sum over loop variables (value - first) * step, checked numerically
    for every iteration (POSITION_TOL, ORIENTATION_TOL);
  * every iteration's planned configuration (the vendor's configuration data computed from
    the planner's records: IK branch and turns) is the same, so the one target the vendor
    loop writes is reached with the joints the planner verified in each iteration.

`analyse(loop, record, ...)` returns a `LoopTemplate` (the first iteration's body, every
Cartesian target's base pose and step per loop variable, nested loops analysed with it) or
an `Unrolled` reason naming the iteration, the instruction and what differs. The backends
write the template as a loop and the reason as a warning (W420) above the unrolled
iterations. Nothing here imports the planner: the records come in through `record`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field, fields, is_dataclass, replace
from enum import Enum
from typing import Any

import numpy as np

from rmot.lang import ir, ir_tree, plan_types
from rmot.lang.record import record
from rmot.lang.ir_tree import bind_loop_variable
from rmot.backends.loop_words import field_words as _field_words, kind_words as _kind, show as _show
from rmot.backends.loop_words import show_difference as _show_difference, show_key as _show_key

__all__ = [
    "ConfigKey",
    "ConfigMatch",
    "MoveConfigKey",
    "ExtraKey",
    "LoopTemplate",
    "LoopVar",
    "level_moves",
    "ORIENTATION_TOL",
    "POSITION_TOL",
    "TargetOffset",
    "Unrolled",
    "analyse",
    "bind_loop_var",
    "branch_and_turns",
    "iteration_label",
    "offset_at",
    "uses_loop_var",
]

# A target is affine when every iteration's position lies within POSITION_TOL (m) of
# base + sum (value - first) * step: 1 um, far below what any vendor prints (0.001 mm is
# RAPID's and KRL's last printed digit here) and far above float rounding of the front
# end's sums. Orientation: |<q_k, q_0>| >= 1 - ORIENTATION_TOL, i.e. the two rotations
# differ by less than 2*acos(1 - 1e-12) ~ 3e-6 rad.
POSITION_TOL = 1e-6
ORIENTATION_TOL = 1e-12

ConfigKey = Callable[[np.ndarray, "ir.Config | None"], Hashable]
"""The vendor's configuration data of one joint solution (q, branch): what its program writes
for a Cartesian target (RAPID confdata, KRL Status/Turn, ...). Equal keys = one target fits."""

MoveConfigKey = Callable[[ir.Move, np.ndarray, "ir.Config | None"], Hashable]
"""A vendor whose configuration data depends on the motion (KRL: PTP reads Status and Turn,
LIN and CIRC only follow the current joints) gives this instead of a ConfigKey."""

ConfigMatch = Callable[[Hashable, Hashable], bool]
"""(the first iteration's configuration key, another iteration's) -> True when the one target
the vendor loop writes (with the first iteration's configuration data) reaches the other's."""

ExtraKey = Callable[[ir.Instr, "plan_types.InstructionRecord | None"], Hashable]
"""Anything else a vendor prints from the record of an instruction (RAPID: a joint move's
planned duration): the iterations must agree on it too."""


def branch_and_turns(q: np.ndarray, branch: ir.Config | None) -> Hashable:
    """The default configuration key: the IK branch and each joint's turn (the whole number
    of revolutions, round(q / 2 pi)): what every vendor's configuration data distinguishes
    at the least."""
    turns = tuple(math.floor(float(v) / (2 * math.pi) + 0.5) for v in q)
    return (branch, turns)


@record
class LoopVar:
    """One loop of the analysed nest: `name` is the `for` variable (None for `repeat n`);
    the vendor loop counts from `first` to `last`, both run (`last` is the Loop's exclusive
    end minus one: `for i in 0 .. 3` runs 0, 1, 2, so first 0 and last 2)."""

    uid: int
    name: str | None
    first: int
    last: int


@record
class TargetOffset:
    """A Cartesian target of the template: `base` is its `in_frame` pose at the first value
    of every loop in `loops` (outer first); `steps[k]` the position change (m, in the move's
    frame) per unit of loop k's variable. The pose at values v is
    base translated by sum (v[k] - loops[k].first) * steps[k]."""

    base: ir.Pose
    loops: tuple[LoopVar, ...]
    steps: tuple[tuple[float, float, float], ...]

    def step_of(self, loop_uid: int) -> tuple[float, float, float]:
        for var, step in zip(self.loops, self.steps):
            if var.uid == loop_uid:
                return step
        raise KeyError(loop_uid)


@record
class LoopTemplate:
    """A loop that can be written as one vendor loop.

    `loop` is the template loop node; `body` is its first iteration's body (nested loops in
    it are the first iteration's nested loops, written with `inner[uid]`); `targets` maps
    (template instruction uid, "target" | "via") to the target's offsets, for every
    Cartesian target in the body at any depth."""

    loop: ir.Loop
    var: LoopVar
    body: tuple[ir.Instr, ...]
    targets: dict[tuple[int, str], TargetOffset]
    inner: dict[int, LoopTemplate]
    # template uid -> the forms every iteration accepts, where the vendor's extra_key gave a
    # frozenset of acceptable forms (their intersection over the iterations, never empty)
    choices: dict[int, frozenset[Hashable]] = field(default_factory=dict)


@record
class Unrolled:
    """Why the loop must be written iteration by iteration: `iteration` names the values of
    the loop variables where it first differs (`layer = 2, row = 1`), `uid` the instruction,
    `what` the difference in words; `span` the instruction's source (or the loop's)."""

    loop: ir.Loop
    iteration: str
    uid: int | None
    what: str
    span: Any = None
    # every iteration but the last fits one vendor loop (typically: the last iteration's final
    # move blends into what follows the loop where the others stop): the vendor may write
    # this template and then the last iteration on its own (`Unrolled.last`)
    peeled: LoopTemplate | None = None

    @property
    def last(self) -> ir.LoopIteration:
        return self.loop.iterations[-1]

    @property
    def message(self) -> str:
        at = f" at {self.iteration}" if self.iteration else ""
        if self.peeled is not None:
            value = f"{self.loop.var or 'iteration'} = {self.last.value}"
            return (
                f"{_loop_label(self.loop)}: the last iteration ({value}) is written after the "
                f"loop{at}: {self.what}"
            )
        return f"{_loop_label(self.loop)} unrolled{at}: {self.what}"


def _loop_label(loop: ir.Loop) -> str:
    if loop.var is None:
        return f"repeat {loop.last - loop.first} loop"
    return f"loop 'for {loop.var} in {loop.first} .. {loop.last}'"


def iteration_label(values: tuple[tuple[LoopVar, int], ...]) -> str:
    """`layer = 2, row = 1` (a `repeat` counter reads `iteration = k`)."""
    return ", ".join(f"{v.name or 'iteration'} = {val}" for v, val in values)


def offset_at(offset: TargetOffset, values: dict[int, int]) -> ir.Pose:
    """The target's pose when loop uid -> value (missing loops at their first value)."""
    pos = list(offset.base.position)
    for var, step in zip(offset.loops, offset.steps):
        d = values.get(var.uid, var.first) - var.first
        pos = [p + d * s for p, s in zip(pos, step)]
    return ir.Pose((pos[0], pos[1], pos[2]), offset.base.quaternion)


# --------------------------------------------------------------------------- analysis

Record = Callable[[ir.Instr], "plan_types.InstructionRecord | None"]
_NESTED = ("body", "then", "otherwise", "on_timeout")


@dataclass
class _Run:
    """What one analysis carries: the vendor's keys and every target's samples."""

    record: Record
    config_key: ConfigKey
    extra_key: ExtraKey | None
    move_config: MoveConfigKey | None
    # (template uid, role) -> [(loop uid -> value, in_frame pose, instruction, role)]
    slots: dict[tuple[int, str], list[tuple[dict[int, int], ir.Pose, ir.Instr, str]]]
    loop_vars: dict[int, LoopVar]
    config_match: ConfigMatch | None = None
    options: dict[int, frozenset[Hashable]] = field(default_factory=dict)


class _Differs(Exception):
    def __init__(self, uid: int | None, what: str, span: Any, iteration: str = "") -> None:
        super().__init__(what)
        self.uid, self.what, self.span, self.iteration = uid, what, span, iteration


def analyse(
    loop: ir.Loop,
    record: Record,
    *,
    config_key: ConfigKey = branch_and_turns,
    extra_key: ExtraKey | None = None,
    unroll: bool = False,
    move_config: MoveConfigKey | None = None,
    config_match: ConfigMatch | None = None,
    peel: bool = True,
) -> LoopTemplate | Unrolled:
    """A template when `loop` (with every loop nested in it) can be one vendor loop, else
    why not. `unroll` (`rmot compile --unroll`) always answers Unrolled ("--unroll").
    `move_config`, when given, replaces `config_key` (it also sees the move); `config_match`
    (first iteration's key, this iteration's key) -> bool replaces key equality. With `peel`,
    an Unrolled whose iterations but the last fit one loop carries that loop (`peeled`)."""
    if unroll:
        return Unrolled(loop, "", None, "--unroll writes every iteration", loop.span)
    if not loop.iterations:
        return Unrolled(loop, "", None, "the range is empty (no iteration to write)", loop.span)
    run = _Run(record, config_key, extra_key, move_config, {}, {}, config_match)
    holder: dict[int, LoopTemplate] = {}
    try:
        _nested(loop, loop, (), {}, run, holder)
        targets = {key: _fit(samples, run) for key, samples in run.slots.items()}
        holder[loop.uid] = replace(holder[loop.uid], choices=dict(run.options))
    except _Differs as d:
        peeled = None
        if peel and len(loop.iterations) > 2:
            rest = replace(loop, iterations=loop.iterations[:-1], last=loop.last - 1)
            found = analyse(
                rest,
                record,
                config_key=config_key,
                extra_key=extra_key,
                move_config=move_config,
                config_match=config_match,
                peel=False,
            )
            peeled = found if isinstance(found, LoopTemplate) else None
        return Unrolled(loop, d.iteration, d.uid, d.what, d.span or loop.span, peeled)
    return _with_targets(holder[loop.uid], targets)


def _nested(
    t: ir.Loop,
    b: ir.Loop,
    loops: tuple[LoopVar, ...],
    values: dict[int, int],
    run: _Run,
    inner: dict[int, LoopTemplate] | None,
) -> None:
    """Compare loop `b` (in some iteration of the enclosing loops) with its template `t`, every
    iteration of `b` with the first iteration of `t`; file the template in `inner`."""
    expected = list(range(t.first, t.last))  # Loop.last is the exclusive end
    got = [it.value for it in b.iterations]
    if (b.var, b.first, b.last) != (t.var, t.first, t.last) or got != expected:
        raise _Differs(
            b.uid,
            f"the nested loop runs {got} where the first iteration's runs {expected}",
            b.span,
            _values_label(values, run),
        )
    if not t.iterations:
        raise _Differs(b.uid, "a nested range is empty", b.span, _values_label(values, run))
    var = run.loop_vars.setdefault(t.uid, LoopVar(t.uid, t.var, t.first, t.last - 1))
    sub: dict[int, LoopTemplate] = {}
    for k, b_it in enumerate(b.iterations):
        at = {**values, var.uid: b_it.value}
        try:
            _compare(
                t.iterations[0].body,
                b_it.body,
                loops + (var,),
                at,
                run,
                sub if inner is not None and k == 0 else None,
            )
        except _Differs as d:
            if not d.iteration:
                d.iteration = _values_label(at, run)
            raise
    if inner is not None:
        inner[t.uid] = LoopTemplate(t, var, t.iterations[0].body, {}, sub)


def _compare(
    template: tuple[ir.Instr, ...],
    body: tuple[ir.Instr, ...],
    loops: tuple[LoopVar, ...],
    values: dict[int, int],
    run: _Run,
    inner: dict[int, LoopTemplate] | None,
) -> None:
    if len(template) != len(body):
        raise _Differs(
            None,
            f"its body has {len(body)} instructions where the first iteration has {len(template)}",
            None,
        )
    for t, b in zip(template, body):
        if type(t) is not type(b):
            raise _Differs(b.uid, f"{_kind(b)} where the first iteration has {_kind(t)}", b.span)
        if isinstance(t, ir.Loop):
            assert isinstance(b, ir.Loop)
            _nested(t, b, loops, values, run, inner)
        else:
            _compare_node(t, b, loops, values, run, inner)


def _compare_node(
    t: ir.Instr,
    b: ir.Instr,
    loops: tuple[LoopVar, ...],
    values: dict[int, int],
    run: _Run,
    inner: dict[int, LoopTemplate] | None,
) -> None:
    for f in fields(t):
        name = f.name
        if name in ("uid", "span"):
            continue
        tv, bv = getattr(t, name), getattr(b, name)
        if name in _NESTED and isinstance(tv, tuple):
            _compare(tv, bv, loops, values, run, inner)
            continue
        if (
            isinstance(t, ir.Move)
            and name in ("target", "via")
            and isinstance(tv, ir.CartesianTarget)
        ):
            if not isinstance(bv, ir.CartesianTarget):
                raise _Differs(b.uid, f"the {name} is not a Cartesian target here", b.span)
            samples = run.slots.setdefault((t.uid, name), [])
            samples.append(({lv.uid: values[lv.uid] for lv in loops}, bv.in_frame, b, name))
            continue
        if _key(tv) != _key(bv):
            raise _Differs(
                b.uid,
                f"the {_kind(b)}'s {_field_words(name)} differs from the first "
                f"iteration's ({_show_difference(bv, tv)})",
                b.span,
            )
    _compare_record(t, b, run)


def _matches(run: _Run, first: Hashable, other: Hashable) -> bool:
    return run.config_match(first, other) if run.config_match is not None else first == other


def _config(run: _Run, node: ir.Move, q: np.ndarray, branch: ir.Config | None) -> Hashable:
    if run.move_config is not None:
        return run.move_config(node, q, branch)
    return run.config_key(q, branch)


def _compare_record(t: ir.Instr, b: ir.Instr, run: _Run) -> None:
    rt, rb = run.record(t), run.record(b)
    if isinstance(t, ir.Move):
        if rt is None or rb is None or rt.q_target is None or rb.q_target is None:
            raise _Differs(b.uid, "a move has no planned joint solution", b.span)
        if (rt.blend_radius > 0.0) != (rb.blend_radius > 0.0):
            stop = "stops exactly" if rb.blend_radius <= 0.0 else "blends"
            raise _Differs(b.uid, f"the move {stop} here, unlike in the first iteration", b.span)
        assert isinstance(t, ir.Move) and isinstance(b, ir.Move)  # checked as moves above
        if isinstance(t.target, ir.CartesianTarget):
            kt, kb = (
                _config(run, t, rt.q_target, rt.branch),
                _config(run, b, rb.q_target, rb.branch),
            )
            if not _matches(run, kt, kb):
                raise _Differs(
                    b.uid,
                    f"the move needs configuration {_show_key(kb)} where the first "
                    f"iteration has {_show_key(kt)} (one vendor target cannot reach both)",
                    b.span,
                )
            if t.via is not None and rt.q_via is not None and rb.q_via is not None:
                vt, vb = _config(run, t, rt.q_via, rt.branch), _config(run, b, rb.q_via, rb.branch)
                if not _matches(run, vt, vb):
                    raise _Differs(
                        b.uid,
                        f"the via point needs configuration {_show_key(vb)} where "
                        f"the first iteration has {_show_key(vt)}",
                        b.span,
                    )
    if run.extra_key is not None:
        xt, xb = run.extra_key(t, rt), run.extra_key(b, rb)
        if isinstance(xb, frozenset):  # forms this iteration accepts: one must suit them all
            left = run.options.get(t.uid, xt if isinstance(xt, frozenset) else frozenset()) & xb
            if not left:
                raise _Differs(
                    b.uid,
                    f"the {_kind(b)} has no written form that suits every "
                    f"iteration ({_show(sorted(map(repr, xb)))})",
                    b.span,
                )
            run.options[t.uid] = left
            return
        et, eb = _key(xt), _key(xb)
        if et != eb:
            raise _Differs(b.uid, f"the {_kind(b)} is written differently ({eb} vs {et})", b.span)


def _fit(samples: list[tuple[dict[int, int], ir.Pose, ir.Instr, str]], run: _Run) -> TargetOffset:
    """The affine fit of one target over every iteration (raises _Differs when none fits):
    the step of each loop variable from the sample one value past the first (the others at
    their first), then every sample checked against base + sum (value - first) * step."""
    first_values, base, _, _ = samples[0]
    order = list(first_values)
    loops = tuple(run.loop_vars[uid] for uid in order)
    p0 = np.array(base.position)
    steps: list[tuple[float, float, float]] = []
    for var in loops:
        probe = next(
            (
                s
                for s in samples
                if s[0][var.uid] == var.first + 1
                and all(s[0][o] == first_values[o] for o in order if o != var.uid)
            ),
            None,
        )
        if probe is None:  # a one-value loop: no step to take
            steps.append((0.0, 0.0, 0.0))
            continue
        d = np.array(probe[1].position) - p0
        steps.append((float(d[0]), float(d[1]), float(d[2])))
    for values, pose, node, role in samples:
        label = _values_label(values, run)
        if abs(float(np.dot(pose.quaternion, base.quaternion))) < 1.0 - ORIENTATION_TOL:
            raise _Differs(
                node.uid,
                f"the {role} has another orientation than in the first iteration "
                "(a vendor loop offsets positions only)",
                node.span,
                label,
            )
        expect = p0.copy()
        for var, step in zip(loops, steps):
            expect += (values[var.uid] - var.first) * np.array(step)
        miss = float(np.linalg.norm(np.array(pose.position) - expect))
        if miss > POSITION_TOL:
            raise _Differs(
                node.uid,
                f"the {role} lies {miss * 1000.0:.3f} mm off the constant step of "
                "the first iterations (its position is not affine in the loop variables)",
                node.span,
                label,
            )
    return TargetOffset(base, loops, tuple(steps))


def _values_label(values: dict[int, int], run: _Run) -> str:
    return iteration_label(tuple((run.loop_vars[uid], v) for uid, v in values.items()))


def _with_targets(
    template: LoopTemplate,
    targets: dict[tuple[int, str], TargetOffset],
    choices: dict[int, frozenset[Hashable]] | None = None,
) -> LoopTemplate:
    """The template and its nested ones with every target's offsets and every choice."""
    choices = template.choices if choices is None else choices
    inner = {uid: _with_targets(sub, targets, choices) for uid, sub in template.inner.items()}
    return replace(template, targets=targets, inner=inner, choices=choices)


def _key(v: Any) -> Hashable:
    """`v` as a comparable value: floats rounded to 1e-9, spans and uids left out."""
    if v is None or isinstance(v, (str, bool, int, Enum)):
        return v
    if isinstance(v, float):
        return round(v, 9)
    if isinstance(v, np.ndarray):
        return tuple(round(float(x), 9) for x in v.ravel())
    if is_dataclass(v) and not isinstance(v, type):
        return (
            type(v).__name__,
            tuple(_key(getattr(v, f.name)) for f in fields(v) if f.name not in ("uid", "span")),
        )
    if isinstance(v, (tuple, list)):
        return tuple(_key(x) for x in v)
    return repr(v)


# --------------------------------------------------------------------------- unrolled bodies


def uses_loop_var(body: tuple[ir.Instr, ...], name: str) -> bool:
    """True when an expression in `body` reads the loop variable `name` (a VarRef)."""
    return any(_reads(node, name) for node in body)


def _reads(v: Any, name: str) -> bool:
    if isinstance(v, ir.VarRef):
        return v.name == name
    if isinstance(v, ir.Loop):
        return any(_reads(it.body, name) for it in v.iterations) and v.var != name
    if isinstance(v, tuple):
        return any(_reads(x, name) for x in v)
    if is_dataclass(v) and not isinstance(v, (ir.Pose, type)):
        return any(_reads(getattr(v, f.name), name) for f in fields(v) if f.name not in ("span",))
    return False


def bind_loop_var(body: tuple[ir.Instr, ...], name: str, value: int) -> tuple[ir.Instr, ...]:
    """`body` with every read of the loop variable `name` replaced by Const(value) (what an
    unrolled iteration writes: the vendor has no loop counter there); the front end's
    lang/ir_tree.bind_loop_variable, the one walker of the IR's nesting."""

    return bind_loop_variable(body, name, value)


def level_moves(body: tuple[ir.Instr, ...]) -> list[int]:
    """Uids of the moves of `body` outside nested loops (in If arms, whiles, procs too)."""
    out: list[int] = []
    for node in body:
        if isinstance(node, ir.Move):
            out.append(node.uid)
            continue
        runs, bodies = ir_tree.flow(node)
        if runs is not ir_tree.Runs.ITERATIONS:
            for sub in bodies:
                out += level_moves(sub)
    return out
