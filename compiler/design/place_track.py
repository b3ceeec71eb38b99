"""Placing a track that carries the robot: `rmot place` of a robot on a track searches the
track's pose (its `at`, in world) in the region, the arm staying on its carriage.

With the track moved by D (world; D = B' B^-1 for the track's pose B -> B'), every body the
track carries moves by D at every axis value: the arm's base at a move's rail value v is
D * base(v). A target in a frame fixed in the world stays put, so in the arm's base frame it
becomes base(v)^-1 * D^-1 * base(v) * (its old pose there); a target in the robot's own frame
(or in a frame riding on the track) moves with the arm and keeps its pose. Each move keeps
its rail value: the search moves the track under the program, not the program along it.
The output cell changes the track's `at` only.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from rmot.compiler.design.place import Mover, Targets, screen
from rmot.lang import ir, ir_tree
from rmot.lang.ir_axes import ExternalAxes, Mechanism
from rmot.lang.ir_tree import children, rebuilt

__all__ = ["TrackMover", "track_of"]


def track_of(cell: ir.Cell, slot: str) -> Mechanism | None:
    """The track robot `slot` rides on, or None."""
    external = cell.external
    mount = None if external is None else external.mount(slot)
    if external is None or mount is None:
        return None
    mech = external.mechanism(mount.mechanism)
    return mech if mech is not None and mech.kind == "track" else None


def _fixed(frame: ir.FrameRef, slot: str, external: ExternalAxes, track: str) -> bool:
    """Whether a move's frame stays in the world when the track moves."""
    if frame.name is None or frame.name == slot:
        return False
    mount = external.mount(frame.name)
    return mount is None or mount.mechanism != track


class TrackMover(Mover):
    """The `place.Mover` of the track under robot `slot` (module docstring): its own targets
    (the arm's base differs per move), screening and rebasing."""

    def __init__(self, programs: list[ir.Program], slot: str, robot: Any) -> None:  # not Mover.__init__: its targets assume a fixed base
        cell = programs[0].cell
        track = track_of(cell, slot)
        assert track is not None and cell.external is not None
        self.slot, self.robot, self.track = slot, robot, track
        self.old = track.base.matrix()
        self.rows: list[tuple[np.ndarray, np.ndarray, bool, ir.Config, Any]] = []  # base(v), flange in base, fixed, config, span
        for program in programs:
            external = program.cell.external
            assert external is not None
            for task in (t for t in program.tasks if t.robot == slot):
                for m in ir_tree.walk(task.body):
                    if not isinstance(m, ir.Move) or not isinstance(m.target, ir.CartesianTarget):
                        continue
                    base = (external.world(slot, dict(m.ext)) or cell.robot(slot).base).matrix()
                    for t in (m.target,) + ((m.via,) if m.via is not None else ()):
                        flange = (t.pose * m.tool.tcp.inverse()).matrix()
                        self.rows.append((base, flange, _fixed(m.frame, slot, external, track.name), m.config, m.span))
        self.spans = tuple(r[4] for r in self.rows)

    def _shift(self, pose: np.ndarray) -> np.ndarray:
        """D^-1 for the track at `pose` (world)."""
        out: np.ndarray = self.old @ np.linalg.inv(pose)
        return out

    def screen(self, pose: np.ndarray) -> tuple[np.ndarray, float]:
        if not self.rows:
            return np.zeros(0, bool), 0.0
        d_inv = self._shift(pose)
        rel = np.array([np.linalg.inv(b) @ d_inv @ b @ f if fixed else f for b, f, fixed, _, _ in self.rows])
        targets = Targets(np.zeros((0, 4, 4)), rel, tuple(r[3] for r in self.rows), self.spans)
        return screen(self.robot, targets, np.eye(4))

    def rebase(self, program: ir.Program, pose: np.ndarray) -> ir.Program:
        """The program with the track at `pose`: the cell's track, what it carries (at home) and
        the slot's world-fixed targets re-expressed in the moved base frames."""
        external = program.cell.external
        assert external is not None
        move = ir.Pose.from_matrix(np.asarray(pose) @ np.linalg.inv(self.old))
        carried = {m.body for m in external.mounts if m.mechanism == self.track.name}
        mechanisms = tuple(replace(m, base=move * m.base) if m.name == self.track.name else m for m in external.mechanisms)
        cell = replace(program.cell, external=replace(external, mechanisms=mechanisms),
                       robots=tuple(replace(r, base=move * r.base) if r.name in carried else r for r in program.cell.robots),
                       fixtures=tuple(replace(f, pose=move * f.pose) if f.name in carried else f for f in program.cell.fixtures),
                       frames=tuple(replace(f, pose=move * f.pose) if f.name in carried else f for f in program.cell.frames))
        inv = move.inverse()
        tasks = tuple(replace(t, body=self._body(t.body, external, inv)) if t.robot == self.slot else t for t in program.tasks)
        return replace(program, cell=cell, tasks=tasks)

    def _body(self, body: tuple[Any, ...], external: ExternalAxes, inv: ir.Pose) -> tuple[Any, ...]:
        out = []
        for instr in body:
            if isinstance(instr, ir.Move):
                instr = self._move(instr, external, inv)
            else:
                instr = rebuilt(instr, tuple(self._body(b, external, inv) for b in children(instr)))
            out.append(instr)
        return tuple(out)

    def _move(self, m: ir.Move, external: ExternalAxes, inv: ir.Pose) -> ir.Move:
        if not _fixed(m.frame, self.slot, external, self.track.name):
            return m
        base = external.world(self.slot, dict(m.ext))
        assert base is not None
        frame = replace(m.frame, pose=base.inverse() * inv * m.frame.world)

        def moved(t: ir.CartesianTarget | None) -> ir.CartesianTarget | None:
            if t is None:
                return None
            if m.axes_only:  # the arm holds its joints: its pose in the base frame stays
                return replace(t, in_frame=frame.pose.inverse() * t.pose)
            return replace(t, pose=base.inverse() * inv * base * t.pose)

        target = m.target if isinstance(m.target, ir.JointTarget) else moved(m.target)
        return replace(m, frame=frame, target=target, via=moved(m.via))  # type: ignore[arg-type]
