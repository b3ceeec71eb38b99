"""`sync` as an I/O handshake, for vendors without a multi-robot barrier (KRL, Fanuc TP,
URScript, INFORM, VAL3; RAPID has WaitSyncTask and does not use this).

LANGUAGE.md §"Several robots": backends emit one program per robot with the vendor's
synchronisation, or an I/O handshake where the vendor has none. The convention:

Cell. Each robot whose task passes a barrier declares one digital output and one digital
input, both named "sync":

    io out[10] = "sync" on r1        io out[10] = "sync" on r2
    io in[10]  = "sync" on r1        io in[10]  = "sync" on r2

The integrator wires r1's sync output to r2's sync input and r2's output to r1's input.
With more than two robots each robot's sync input must be the *consensus* of its peers'
sync outputs, made by a PLC or wired logic: on when all peers are on, off when all peers are
off, unchanged otherwise (a Muller C-element). A plain AND is right for the rising barriers
only: on a falling barrier it would release a robot as soon as one peer is off.

Program. The k-th sync of a task (k = 1, 2, ..., in source order, proc bodies included)
becomes

    SetDigital(sync out, level)          level = on for odd k, off for even k
    WaitInput(sync in == level)

A level-toggling handshake: every barrier changes the level, so a robot can never pass a
barrier on the level its peer left at the previous one, and because the front end makes
every task pass its shared barriers in the same order (compiler.passes.check_syncs), the
k-th barrier of each task is the same barrier. Preconditions, documented to the user:
  * every sync output is off when the programs start (the level after an even number of
    barriers); a task with an odd number of barriers ends with its output on, so the cell's
    start-up must reset it before the next start (warning W410);
  * a sync inside an `if` arm is refused (E405): its k is not known before run time, so its
    level could not be fixed when compiling;
  * a single-task program's syncs are no-ops (LANGUAGE.md) and are not lowered.

The generated nodes are `HandshakeSet` / `HandshakeWait`: ordinary SetDigital / WaitInput
(backends print them with their SetDigital / WaitInput code) that also carry the barrier's
name and round, for the source-map comment "sync meet (handshake 1)". Both keep the sync's
span; the set keeps the sync's uid and the wait gets -uid - 1 (lowering.py's convention for
generated nodes: negative uids are never looked up in the plan's records — an I/O
instruction needs none).
"""

from __future__ import annotations

from collections.abc import Iterator
from itertools import count

from rmot.backends import codes
from rmot.lang import ir, ir_tree
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.record import record

__all__ = [
    "SYNC_SIGNAL", "HandshakePorts", "HandshakeSet", "HandshakeWait",
    "handshake_note", "handshake_ports", "check_handshake", "sync_as_handshake",
]

SYNC_SIGNAL = "sync"


@record(slots=True, kw_only=True)
class HandshakeSet(ir.SetDigital):
    """The set half of the `round`-th handshake of barrier `barrier`."""

    barrier: str
    round: int


@record(slots=True, kw_only=True)
class HandshakeWait(ir.WaitInput):
    """The wait half of the `round`-th handshake of barrier `barrier`."""

    barrier: str
    round: int


@record(slots=True)
class HandshakePorts:
    """One robot's handshake signals: its digital output and digital input named "sync"."""

    out: int
    inp: int


def handshake_ports(cell: ir.Cell, robot: str) -> HandshakePorts | None:
    """The robot's "sync" output and input ports, or None unless exactly one of each exists."""
    def ports(direction: ir.IoDirection) -> list[int]:
        return [s.port for s in cell.io
                if s.name == SYNC_SIGNAL and s.robot == robot and s.direction is direction]

    outs, ins = ports(ir.IoDirection.DIGITAL_OUT), ports(ir.IoDirection.DIGITAL_IN)
    if len(outs) != 1 or len(ins) != 1:
        return None
    return HandshakePorts(outs[0], ins[0])


def _syncs_in_if_arms(body: tuple[ir.Instr, ...], inside: bool = False) -> Iterator[ir.Sync]:
    """The syncs in bodies that may not run: if arms (and whiles, timeout branches, which the
    front end refuses already); a barrier's level is fixed when compiling, so it must run."""
    for node in body:
        if isinstance(node, ir.Sync) and inside:
            yield node
        runs, bodies = ir_tree.flow(node)
        for sub in bodies:
            yield from _syncs_in_if_arms(sub, inside or not runs.sure)


def check_handshake(body: tuple[ir.Instr, ...], cell: ir.Cell, robot: str,
                    vendor: str) -> tuple[Diagnostic, ...]:
    """What stops (errors) or qualifies (warnings) lowering the syncs of one task's `body`.

    Errors: the robot lacks its "sync" signals (E409, at every sync), a sync inside an `if`
    arm (E405). Warning: an odd number of barriers leaves the output on (W410, at the last).
    """
    syncs = [n for n in ir_tree.walk(body) if isinstance(n, ir.Sync)]
    if not syncs:
        return ()
    out: list[Diagnostic] = []
    ports = handshake_ports(cell, robot)
    if ports is None:
        out += [Diagnostic(codes.SYNC_HANDSHAKE_MISSING, Severity.ERROR,
                           f"{vendor}: sync '{s.name}' needs an I/O handshake on {vendor}: declare "
                           f"io out[n] = \"{SYNC_SIGNAL}\" on {robot} and io in[m] = \"{SYNC_SIGNAL}\" "
                           f"on {robot} in the cell (exactly one of each)", s.span) for s in syncs]
    out += [Diagnostic(codes.SYNC_UNSUPPORTED, Severity.ERROR,
                       f"{vendor}: sync '{s.name}' must not be inside an if arm on {vendor} (the I/O "
                       "handshake's level is fixed per barrier when compiling; got it in an arm)", s.span)
            for s in _syncs_in_if_arms(body)]
    if ports is not None and len(syncs) % 2 == 1:
        out.append(Diagnostic(codes.SYNC_OUTPUT_LEFT_ON, Severity.WARNING,
                              f"{vendor}: task on {robot} passes {len(syncs)} barriers, an odd number: "
                              f"its sync output out[{ports.out}] stays on after the program; reset it "
                              "to off before the programs start again", syncs[-1].span))
    return tuple(out)


def sync_as_handshake(body: tuple[ir.Instr, ...], ports: HandshakePorts) -> tuple[ir.Instr, ...]:
    """Every Sync -> HandshakeSet(out, level), HandshakeWait(in == level); level on for the
    1st, 3rd, ... sync in source order (into ProcCall bodies and If arms), off for the 2nd, 4th, ...

    Pure IR -> IR; run `check_handshake` first (it refuses syncs in If arms).
    """
    return _lower(body, ports, count(1))


def _lower(body: tuple[ir.Instr, ...], ports: HandshakePorts, rounds: Iterator[int]) -> tuple[ir.Instr, ...]:
    out: list[ir.Instr] = []
    for node in body:
        if isinstance(node, ir.Sync):
            k = next(rounds)
            level = k % 2 == 1
            out += [
                HandshakeSet(uid=node.uid, port=ports.out, value=level, signal=SYNC_SIGNAL,
                             span=node.span, barrier=node.name, round=k),
                HandshakeWait(uid=-node.uid - 1, span=node.span, barrier=node.name, round=k,
                              condition=ir.InputCondition(port=ports.inp, value=level, signal=SYNC_SIGNAL)),
            ]
        else:  # into every body, in source order (proc bodies, if arms, loop iterations)
            bodies = tuple(_lower(sub, ports, rounds) for sub in ir_tree.children(node))
            out.append(ir_tree.rebuilt(node, bodies) if bodies else node)
    return tuple(out)


def handshake_note(node: ir.Instr) -> str | None:
    """'sync meet (handshake 1)' above the set half of a handshake; None for any other node."""
    if isinstance(node, HandshakeSet):
        return f"sync {node.barrier} (handshake {node.round})"
    return None
