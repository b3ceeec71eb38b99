"""Runtime logic shared by the vendor backends: expressions, loops, unrolling.

A vendor describes its expression syntax with an `ExprDialect` (operators, literals, how a
variable, a digital input and an analog input read) and `expr_text` prints any `ir.RtExpr`
with it, every compound operand in parentheses: KRL compares with the LOWEST priority of all
its operators (KUKA System Software 8.x, Operating and Programming Instructions for System
Integrators, "Priority of operators": NOT, * /, + -, AND, EXOR, OR, then == <> < > <= >=),
so `$IN[1]==TRUE AND $IN[2]==FALSE` would read `$IN[1]==(TRUE AND $IN[2])==FALSE`; the
parentheses make every vendor read the expression as the IR means it.

`LoopState` is what a backend carries while it writes a vendor loop: the Cartesian targets
of the template with their offsets (backends/loops.py) and each loop's counter name.
`loop_template` decides (and warns W420 with the reason when a loop is unrolled);
`unrolled` writes the iterations one after another, each under a comment naming the values.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from rmot.backends import codes, loops
from rmot.lang import ir, ir_tree
from rmot.lang.record import record

__all__ = [
    "ExprDialect",
    "LoopPlan",
    "LoopState",
    "blocked_loop_lines",
    "expr_text",
    "is_int",
    "loop_plan",
    "loop_template",
    "offset_terms",
    "unrolled",
]


@record
class ExprDialect:
    """How one vendor writes runtime expressions."""

    true: str
    false: str
    and_: str
    or_: str
    not_: str  # prefix, e.g. "NOT " or "not "
    compare: dict[ir.CompareOp, str]
    var: Callable[[ir.VarRef], str]
    digital: Callable[[ir.InputCondition], str]  # the whole test `DInput(di1) = 1`
    analog: Callable[[ir.AnalogInput], str]  # the value in volts
    group: Callable[[ir.GroupInput], str]  # the group's unsigned integer (or a refusal, then "0")
    output: Callable[[ir.OutputRead], str]  # the whole test "the output is on" `DOutput(do1) = 1`
    real_division: Callable[[str, str], str] = lambda a, b: f"{a} / {b}"  # a/b of two INTs
    number: Callable[[float], str] = lambda v: repr(float(v))
    # comparisons bind tighter than and/or (RAPID, URScript): written bare inside and/or
    compare_binds_tighter: bool = False


def is_int(e: Any) -> bool:
    """True when `e` is an INT-valued expression (a group input reads an unsigned integer)."""
    return isinstance(e, ir.GroupInput) or getattr(e, "type", None) is ir.ValueType.INT


def expr_text(e: Any, d: ExprDialect) -> str:
    """`e` (an ir.RtExpr or Condition) in the dialect `d`."""
    if isinstance(e, ir.Const):
        if e.type is ir.ValueType.BOOL:
            return d.true if e.value else d.false
        if e.type is ir.ValueType.INT:
            return str(int(e.value))
        return d.number(float(e.value))
    if isinstance(e, ir.VarRef):
        return d.var(e)
    if isinstance(e, ir.InputCondition):
        return d.digital(e)
    if isinstance(e, ir.AnalogInput):
        return d.analog(e)
    if isinstance(e, ir.GroupInput):
        return d.group(e)
    if isinstance(e, ir.OutputRead):
        return d.output(e)
    if isinstance(e, ir.Arith):
        left, right = _arith_operand(e.left, d), _arith_operand(e.right, d)
        if e.op == "/" and is_int(e.left) and is_int(e.right):
            return d.real_division(left, right)
        return f"{left} {e.op} {right}"
    if isinstance(e, ir.Compare):
        return f"{_operand(e.left, d)} {d.compare[e.op]} {_operand(e.right, d)}"
    if isinstance(e, ir.Logic):
        word = d.and_ if e.op == "and" else d.or_
        bare = (ir.Compare, ir.InputCondition, ir.OutputRead) if d.compare_binds_tighter else ()
        return f" {word} ".join(
            expr_text(o, d) if isinstance(o, bare) else _operand(o, d) for o in e.operands
        )
    if isinstance(e, ir.Not):
        return f"{d.not_}{_operand(e.operand, d)}"
    raise TypeError(f"no runtime expression form for {type(e).__name__}")


def _operand(e: Any, d: ExprDialect) -> str:
    text = expr_text(e, d)
    compound = isinstance(e, (ir.Arith, ir.Compare, ir.Logic, ir.Not, ir.InputCondition, ir.OutputRead))
    if isinstance(e, ir.Const) and not isinstance(e.value, bool) and float(e.value) < 0:
        compound = True
    return f"({text})" if compound else text


def _arith_operand(e: Any, d: ExprDialect) -> str:
    """An operand of + - * /: an input read that a vendor writes as a computation (KRL's
    `$ANIN[n]*10`, volts from the -1..1 value) is parenthesised too, so `2 / ain[1]` stays
    2 divided by the volts and never `(2 / $ANIN[n])*10`."""
    text = _operand(e, d)
    if isinstance(e, (ir.AnalogInput, ir.GroupInput)) and any(ch in text for ch in " +-*/"):
        return f"({text})"
    return text


# --------------------------------------------------------------------------- loops


@dataclass
class LoopState:
    """While a vendor loop is written: (template uid, role) -> the target's offsets, and
    loop uid -> the vendor's counter name."""

    offsets: dict[tuple[int, str], loops.TargetOffset] = field(default_factory=dict)
    counters: dict[int, str] = field(default_factory=dict)
    templates: dict[int, loops.LoopTemplate] = field(default_factory=dict)  # nested loops
    pending: list[str] = field(default_factory=list)  # lines a target needs before its motion
    in_routine: int = 0  # > 0 while a proc's routine is printed
    extra: dict[str, object] = field(default_factory=dict)  # a vendor's own flags
    decls: list[str] = field(default_factory=list)  # declarations a vendor prints at the top
    choices: dict[int, frozenset[Any]] = field(default_factory=dict)  # LoopTemplate.choices
    loop_names: set[str] = field(default_factory=set)  # the `for` variables of the loops entered

    def enter(self, template: loops.LoopTemplate, counter: str) -> None:
        """`template` is being written with the counter `counter`: its targets take offsets,
        and its nested loops are written from their templates (not analysed again)."""
        self.counters[template.var.uid] = counter
        self.choices.update(template.choices)
        if template.var.name:
            self.loop_names.add(template.var.name)
        self.offsets.update(template.targets)
        self.templates.update(template.inner)


def loop_template(
    backend: Any,
    node: ir.Loop,
    ctx: Any,
    *,
    config_key: loops.ConfigKey = loops.branch_and_turns,
    move_config: loops.MoveConfigKey | None = None,
    config_match: loops.ConfigMatch | None = None,
    extra_key: loops.ExtraKey | None = None,
    alternatives: tuple[dict[str, Any], ...] = (),
) -> tuple[loops.LoopTemplate | loops.Unrolled, int]:
    """The analysis of `node` for `backend` (its `unroll` option forces unrolling) and which
    set of keys found it (0: the keyword arguments; k: alternatives[k - 1], tried in turn
    when the ones before do not give one vendor loop); a loop not written as one vendor loop
    gets W420 with the first reason (not when --unroll asked for it)."""
    unroll = bool(getattr(backend, "unroll", False))
    first = {
        "config_key": config_key,
        "move_config": move_config,
        "config_match": config_match,
        "extra_key": extra_key,
    }
    result: loops.Unrolled | None = None
    best = 0
    for k, keys in enumerate((first, *({**first, **alt} for alt in alternatives))):
        found = loops.analyse(node, ctx.record, unroll=unroll, **keys)
        if isinstance(found, loops.LoopTemplate):
            return found, k
        if result is None or (found.peeled is not None and result.peeled is None):
            result, best = found, k
        if unroll:
            break
    assert result is not None
    if not unroll and node.iterations:
        how = "" if result.peeled is not None else "; written iteration by iteration"
        backend.warn(codes.LOOP_UNROLLED, result.message + how, result.span)
    return result, best


@record
class LoopPlan:
    """How one Loop is written, the one decision every vendor follows: `template`
    as one vendor loop (None: every iteration one after another), then `last`, the last
    iteration on its own when the loop holds all but it (a peeled loop); `why` is W420's text
    when the loop is not one whole vendor loop ("" when it is), at `span`."""

    template: loops.LoopTemplate | None
    last: ir.LoopIteration | None
    why: str
    span: Any


def loop_plan(
    node: ir.Loop,
    found: loops.LoopTemplate | loops.Unrolled,
    blocker: Callable[[loops.LoopTemplate], str | None] | None = None,
) -> LoopPlan:
    """The analysis `found` (loops.analyse) as a LoopPlan: its template, or the template of all
    iterations but the last, unless the vendor's `blocker` names a reason the vendor cannot
    write that loop (Fanuc registers, INFORM shifts): then every iteration, with the reason."""
    loop = found if isinstance(found, loops.LoopTemplate) else found.peeled
    reason = blocker(loop) if loop is not None and blocker is not None else None
    if isinstance(found, loops.LoopTemplate) and reason is None:
        return LoopPlan(found, None, "", None)
    if loop is None or reason is not None:
        if isinstance(found, loops.Unrolled) and reason is None:
            return LoopPlan(None, None, found.message, found.span)
        why = reason or (found.message if isinstance(found, loops.Unrolled) else "")
        return LoopPlan(None, None, why, node.span)
    assert isinstance(found, loops.Unrolled)
    return LoopPlan(loop, found.last, found.message, found.span)


def loop_lines(
    backend: Any,
    node: ir.Loop,
    ctx: Any,
    write: Callable[[loops.LoopTemplate], list[str]],
    body: Callable[[tuple[ir.Instr, ...]], list[str]],
    found: Callable[[loops.LoopTemplate, int], None] | None = None,
    **keys: Any,
) -> list[str]:
    """A Loop as the vendor writes it: `write(template)` for a vendor loop (a nested loop of a
    template being written uses its own template), else, when all iterations but the last
    fit, that loop and then the last iteration, else every iteration (`unrolled`).
    `found(template, k)` hears which keys (loop_template) gave a template before it is written."""
    template = ctx.loops.templates.get(node.uid)
    if template is not None:
        return write(template)
    result, k = loop_template(backend, node, ctx, **keys)  # k: which keys found a template
    plan = loop_plan(node, result)  # (loop_template warned W420 already)
    if plan.template is None:
        return unrolled(backend, node, ctx, body)
    if found is not None:
        found(plan.template, k)
    lines = write(plan.template)
    if plan.last is None:
        return lines
    last = plan.last
    nodes = last.body if node.var is None else loops.bind_loop_var(last.body, node.var, last.value)
    note = f"{node.var or 'iteration'} = {last.value}: the last iteration, on its own"
    return lines + [backend.comment(note)] + body(nodes)


def blocked_loop_lines(
    backend: Any,
    node: ir.Loop,
    found: loops.LoopTemplate | loops.Unrolled,
    blocker: Callable[[loops.LoopTemplate], str | None],
    write: Callable[[loops.LoopTemplate], list[str]],
    unroll: Callable[[ir.Loop], list[str]],
) -> list[str]:
    """A Loop for a vendor whose loops have limits of their own (Fanuc registers, INFORM
    shifts): the analysed template (or, when only the last iteration differs, all but it)
    written by `write` unless `blocker` names a reason it cannot be; otherwise every iteration
    by `unroll`, with W420 giving the reason; a peeled last iteration follows the loop."""
    plan = loop_plan(node, found, blocker)
    if plan.template is None:
        backend.warn(codes.LOOP_UNROLLED, plan.why, plan.span)
        return unroll(node)
    lines = write(plan.template)
    if plan.last is not None:  # the last iteration on its own, after the loop
        backend.warn(codes.LOOP_UNROLLED, plan.why, plan.span)
        lines += unroll(replace(node, iterations=(plan.last,)))
    return lines


def unrolled(
    backend: Any, node: ir.Loop, ctx: Any, body: Callable[[tuple[ir.Instr, ...]], list[str]]
) -> list[str]:
    """Every iteration of `node` in order, each under a comment `layer = 2`, with reads of
    the loop variable bound to the iteration's value (bind_loop_var)."""
    out: list[str] = []
    for it in node.iterations:
        nodes = it.body if node.var is None else loops.bind_loop_var(it.body, node.var, it.value)
        out.append(backend.comment(f"{node.var or 'iteration'} = {it.value}"))
        out.extend(body(nodes))
    return out


def moving_offset(state: LoopState, uid: int, role: str) -> loops.TargetOffset | None:
    """The offsets of a target the vendor loop being written moves (None: it stays put)."""
    offset = state.offsets.get((uid, role))
    if offset is None or not any(any(step) for step in offset.steps):
        return None
    return offset


def inline_call(node: ir.ProcCall, state: LoopState) -> bool:
    """True when a call inside a vendor loop must be written inline (its body, not a call to
    its routine): its body has a target the loop offsets or reads a loop counter, and a
    vendor's loop counter is not known inside another routine (RAPID: the FOR counter is
    local to the loop; URScript: a local of the program's def)."""
    uids = {n.uid for n in ir_tree.walk(node.body)}
    moving = {uid for (uid, _), off in state.offsets.items() if any(any(s) for s in off.steps)}
    if uids & moving:
        return True
    names = {v.name for t in state.templates.values() for v in (t.var,) if v.name}
    names |= {name for name in state.loop_names}
    return any(loops.uses_loop_var(node.body, name) for name in names)


def offset_terms(
    offset: loops.TargetOffset,
    counters: dict[int, str],
    scale: float,
    fmt_num: Callable[[float], str],
    frame: np.ndarray | None = None,
) -> tuple[str, str, str]:
    """The x, y, z offsets as text: sum over loops of `(counter - first)*step` (`counter*step`
    when first is 0), steps times `scale` (1000 for mm), rotated by `frame` (3x3) first when
    given (a vendor that writes targets in another frame than `in_frame`); "0" when none."""
    out: list[str] = []
    steps = [np.asarray(s, float) for s in offset.steps]
    if frame is not None:
        steps = [frame @ s for s in steps]
    for axis in range(3):
        text = ""
        for var, step in zip(offset.loops, steps, strict=True):
            value = float(step[axis]) * scale
            if abs(value) < 1e-9:
                continue
            name = counters[var.uid]
            count = name if var.first == 0 else f"({name} - {var.first})"
            term = f"{count}*{fmt_num(abs(value))}"
            if not text:
                text = term if value > 0 else f"-{term}"
            else:
                text += f" + {term}" if value > 0 else f" - {term}"
        out.append(text or "0")
    return out[0], out[1], out[2]


def trimmed(text: str) -> str:
    """A fixed-point number without trailing zeros: '60.000' -> '60', '4.500' -> '4.5'."""
    if "." not in text:
        return text
    return text.rstrip("0").rstrip(".") or "0"
