"""FastSolver: Robot.ik's compiled single-pose pass (sim/robots/fastsolve.py) as an
object: one closed-form robot's arrays packed once in solve_packed's layout, and the call that
turns the kernel's answer into an IkResult (rows sorted by the kernel, or made and sorted when
first asked for), or None when ik.solve must decide the pose itself."""

from __future__ import annotations

from typing import Any

import numpy as np

from rmot.lang import ir
from rmot.sim.robots import fastsolve, ik_result
from rmot.sim.robots.branches import config_of
from rmot.sim.robots.ik_rows import BranchRows, JointRows, Lazy

__all__ = ["FastSolver"]


class FastSolver:
    """The arrays of one closed-form robot for SOLVE_ONE, and the call around it."""

    def __init__(self, robot, closed_form) -> None:  # type: ignore[no-untyped-def]
        chain = robot._chain
        dof = robot.dof
        self.kind = 0 if closed_form.kind == "opw" else 1
        # one signature for both kinds (numba types both calls): UR's unused arrays are dummies
        args = tuple(closed_form.args)
        args = args if len(args) == 4 else (args[0], np.zeros(6), np.zeros(6), np.eye(6))
        self.args = tuple(np.array(a, dtype=float) for a in args)
        self.closed_form = closed_form
        self.bpar, self.crows = (np.array(a, dtype=float) for a in closed_form.branch)
        self.lo = np.array(robot.joint_limits[:, 0], dtype=float)  # writable copies: one numba type
        self.hi = np.array(robot.joint_limits[:, 1], dtype=float)
        self.revolute = np.array(robot._revolute, dtype=np.bool_)
        self.placements = np.array(chain.placements, dtype=float)
        self.axes = np.array(chain.axes, dtype=float)
        self.prismatic = np.array(chain.prismatic, dtype=np.bool_)
        self.flange = np.array(robot._flange_in_joint, dtype=float)
        self.coupled = robot._coupling is not None
        self.coupling = np.array(robot._coupling, dtype=float) if self.coupled else np.eye(dof)
        self.reach = float(robot.reach)
        span = np.where(self.revolute, np.floor((self.hi - self.lo + 2e-12) / fastsolve._TWO_PI), 0.0)
        self.per_joint = int(span.max()) + 1
        self.max_rows = 8 * int(np.prod(span + 1))
        rows = min(self.max_rows, fastsolve._SORTED_ROWS)  # more rows are made only when asked for
        self.consts = np.concatenate([self.lo, self.hi, self.revolute.astype(float),
                                      [self.reach, *fastsolve._TOLS, float(self.coupled), float(self.kind)]])
        gcols = 2 + dof + dof * (self.per_joint + 1)
        self.gcols = gcols
        parts = (*self.args, self.bpar, self.crows, self.consts, self.placements, self.axes,
                 self.prismatic.astype(float), self.flange, self.coupling)
        self.fc = np.concatenate([np.ravel(a) for a in parts])  # solve_packed's layout
        self.ic = np.array([dof, len(self.args[0]), len(self.bpar), rows, gcols], dtype=np.int64)
        n_saved = 2 * dof + 8 * gcols
        self.fs = np.empty(n_saved + (35 + rows) * dof + rows + (dof + 16) * 8 + rows * dof)
        self.iscr = np.zeros(dof + 24 + 3 * rows, dtype=np.int64)
        self.saved = self.fs[:n_saved]  # seed, nearest row, groups (a lazy result's copy)
        self.out = self.fs[len(self.fs) - rows * dof:].reshape(rows, dof)  # the sorted rows
        self.codes = self.iscr[dof + 24 + 2 * rows:]
        self.zeros = np.zeros(dof)
        self.any = np.full(3, -1, dtype=np.int64)
        self.compiled: Any = None  # SOLVE_ONE's dispatcher, on first use
        self.configs = tuple(config_of(-1.0 if c & 4 else 1.0, -1.0 if c & 2 else 1.0, -1.0 if c & 1 else 1.0)
                             for c in range(8))  # the same objects as robot.branch gives
        self.usable = robot._flange_joint == dof and dof == 6
        self.kernel = fastsolve.SOLVE_ONE

    def want(self, config) -> np.ndarray:  # type: ignore[no-untyped-def]
        if config is None:
            return self.any
        return np.array([-1 if config.shoulder is None else int(config.shoulder is ir.Shoulder.BACK),
                         -1 if config.elbow is None else int(config.elbow is ir.Elbow.DOWN),
                         -1 if config.wrist is None else int(config.wrist is ir.Wrist.FLIP)], dtype=np.int64)

    def solve(self, robot, pose, seed, config):  # type: ignore[no-untyped-def]
        """IkResult, or None when ik.solve must decide (see the module docstring)."""
        target = np.asarray(pose, dtype=float)
        if target.shape != (4, 4):
            return None
        seed_q = self.zeros if seed is None else np.asarray(seed, dtype=float).reshape(robot.dof)
        cf = self.closed_form
        local = target if cf.pre is None and cf.post is None else np.ascontiguousarray(cf.local(target[None])[0])
        compiled = self.compiled
        if compiled is None:
            compiled = self.compiled = fastsolve.SOLVE_ONE.jit()
        m, flag, first, n_groups, code = compiled(
            self.fc, self.ic, local, target, seed_q,
            self.any if config is None else self.want(config), self.fs, self.iscr)
        if m < 0:
            return None
        if first < 0:  # all rows, sorted by the kernel
            rows = self.out[:m].copy()  # its own array of m rows: a result keeps no scratch alive
            rows.setflags(write=False)
            sols = JointRows(rows)
            brs = BranchRows(None, self.codes[:m].copy(), self.configs)
        else:  # many 2π-equivalents: made and sorted when asked for (ik_rows.Lazy)
            dof = robot.dof
            saved = self.saved[:2 * dof + n_groups * self.gcols].copy()  # private to the result
            nearest = saved[dof:2 * dof]
            nearest.setflags(write=False)
            lazy = Lazy(_make_rows, saved, dof, self.gcols, m)
            sols = JointRows(None, lazy, nearest, m)
            brs = BranchRows(None, None, self.configs, lazy, self.configs[code], m)
        if flag and ik_result.is_singular(robot, sols[0]):
            return ik_result.result(ik_result.IkStatus.SINGULAR, sols, brs,
                                    "the pose lies on a kinematic singularity")
        return ik_result.result(ik_result.IkStatus.OK, sols, brs)


def _make_rows(saved: np.ndarray, dof: int, gcols: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """(rows, codes) of a lazy result sorted as ik.solve sorts them (SOLVE_ONE's arithmetic);
    saved: the seed, the nearest row, the groups (solve_packed's layout)."""
    rows, codes = np.empty((m, dof)), np.empty(m, dtype=np.int64)
    fastsolve.EXPAND_SORTED.jit()(saved[2 * dof:].reshape(-1, gcols), saved[:dof], rows, codes)
    return rows, codes
