"""Bounds on the numbers a program may give and on the work it may cause.

A hostile or clumsy program must get a diagnostic at the span of the number, never a hang, a
memory blow-up or a crash deep in the planner, the verifier or a backend. Each bound below
is either a vendor's own limit (cited) or a *policy* bound, stated as such: far beyond any
real cell or cycle, small enough that the work it allows stays bounded (the planner samples
every 4 ms, so the 900 s the planner accepts are 225,000 samples).
"""

from __future__ import annotations

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Reporter
from rmot.lang.source import Span

__all__ = [
    "MAX_DURATION_S", "MAX_ITERATIONS", "MAX_POSITION_M", "MIN_SIZE_M", "MAX_PORT", "MAX_SIZE_M", "MAX_TCP_SPEED",
    "MAX_WORK_STEPS", "MAX_ZONE_M", "MIN_RATIO", "MIN_TCP_ACCEL", "MIN_TCP_SPEED", "MAX_MESH_SCALE", "MIN_MESH_SCALE", "within",
]

# Policy: one wait, pulse, timeout or fixed move time of at most 5 minutes; the planner also
# refuses programs whose timelines take more than 900 s in all (compiler/plan/planner.py, E124).
MAX_DURATION_S = 300.0
# Fanuc TP linear speeds are 1..2000 mm/sec (FANUC R-30iB Operator's Manual, "Motion
# instruction: feed rate"); slower is a typo, and a slow move is a long one to sample.
MIN_TCP_SPEED = 0.001
# ABB's largest predefined speeddata is v7000, 7000 mm/s (RAPID Technical reference,
# "speeddata"); 10 m/s is above every arm's TCP speed.
MAX_TCP_SPEED = 10.0
# Fanuc TP joint speeds are 1..100 % (Operator's Manual, feed rate) and KUKA's PTP velocity
# $VEL_AXIS / BAS(#VEL_PTP) is 1..100 % (KSS 8 system variables): one percent is the floor.
MIN_RATIO = 0.01
# Policy: 1 mm/s^2 (a move of a metre would take a minute just to accelerate).
MIN_TCP_ACCEL = 0.001
# Policy: blend radii up to a metre; RAPID's largest predefined zonedata is z200 (200 mm).
MAX_ZONE_M = 1.0
# Policy: targets within 100 m of their robot's base. The longest reach of a catalogue arm is
# under 5 m (FANUC M-2000iA/2300: 4683 mm); a circular move through a far via point would
# otherwise be sampled along an arc of kilometres.
MAX_POSITION_M = 100.0
# Policy: fixture and tool solids up to a kilometre across; a mesh scale up to 1000.
MAX_SIZE_M = 1000.0
# Policy: solid dimensions of at least 0.1 mm: a capsule of 1 nm radius made the collision
# bounds split without end (2 GB, found by `make fuzz`, seed 13338).
MIN_SIZE_M = 1e-4
MAX_MESH_SCALE = 1000.0
# Policy: a mesh scale of at least 1e-6 (a file in micrometres, the finest unit a CAD export
# uses): a scale of 1e-300 squares to zero inside the collision library's bounding volumes and
# crashed the process with SIGSEGV (found by `make fuzz`, seed 25011).
MIN_MESH_SCALE = 1e-6
# Policy: I/O port numbers fit 16 bits (KUKA $OUT has 1..4096, Fanuc DO[] up to 512 by default).
MAX_PORT = 65535
# Loop iterations (all loops of a task together) and statements visited while unrolling
# (inlined proc bodies count once per level they are re-spanned at): bounded before the work
# is done, so an empty or settings-only loop of 10^9 rounds or a fan-out of empty procs is a
# diagnostic, not a hang. A round costs 25..100 us: as many rounds as instructions allowed
# (MAX_INSTRUCTIONS, E121, is 200,000) and twice as many statements keep the front end to
# seconds.
MAX_ITERATIONS = 200_000
MAX_WORK_STEPS = 400_000


def within(x: float | None, lo: float, hi: float, what: str, unit: str, factor: float, span: Span,
           rep: Reporter) -> float | None:
    """x (SI) if lo <= x <= hi; else E125 at `span`, shown in `unit` (1 unit = factor SI)."""
    if x is None:
        return None
    if lo <= x <= hi:
        return x
    u = f" {unit}" if unit else ""
    rep.error(codes.PHYSICAL_RANGE, f"{what} must be between {lo / factor:g}{u} and {hi / factor:g}{u} "
              f"(got {x / factor:.6g}{u})", span)
    return None
