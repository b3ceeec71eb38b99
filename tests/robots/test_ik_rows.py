"""IkResult's solutions / branches views (sim/robots/ik_rows.py) behave as the tuples they
replace, and the lazy ones (many 2π-equivalents, robots/fastsolve.py) give what ik.solve_exact
gives, before and after their rows are made. Witnesses: Python's own tuple of the same rows,
ik.solve_exact (numpy + pinocchio), pinocchio's FK, and a plain expansion sorted by numpy."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.lang import ir
from rmot.sim.robots import fastsolve, ik, load_robot
from rmot.sim.robots.ik_rows import BranchRows, JointRows

_ROBOTS: dict[str, object] = {}


def robot_and_solver(name: str):  # type: ignore[no-untyped-def]
    if name not in _ROBOTS:
        robot = load_robot(name)
        _ROBOTS[name] = (robot, ik._fast_solver(robot))
    return _ROBOTS[name]


def _rows() -> np.ndarray:
    rows = np.arange(24.0).reshape(4, 6) / 7.0
    rows.setflags(write=False)
    return rows


def test_joint_rows_behave_as_a_tuple_of_rows() -> None:
    rows = _rows()
    view, plain = JointRows(rows), tuple(rows)
    assert len(view) == len(plain) == 4 and bool(view)
    for i in (0, 1, 3, -1, -4):
        assert np.array_equal(view[i], plain[i])
    for i in (4, -5):
        with pytest.raises(IndexError):
            view[i]
        with pytest.raises(IndexError):
            plain[i]
    assert isinstance(view[1:3], JointRows) and view[1:3] == plain[1:3]
    assert view[::-1] == plain[::-1]
    assert len(view[5:]) == 0 and not view[5:]
    assert [r.tolist() for r in view] == [r.tolist() for r in plain]
    assert [r.tolist() for r in reversed(view)] == [r.tolist() for r in reversed(plain)]
    assert view == plain and plain == view and view == JointRows(rows.copy())
    assert view != plain[:3] and view != list(plain)  # a tuple is never equal to a list either
    assert repr(view) == repr(plain)
    assert np.array_equal(np.asarray(view), rows)
    assert np.asarray(view, dtype=np.float32).dtype == np.float32
    a, b, *_ = view  # unpacking, zip, list: what the callers do
    assert np.array_equal(a, plain[0]) and np.array_equal(b, plain[1])


def test_joint_rows_cannot_be_changed() -> None:
    view = JointRows(_rows())
    with pytest.raises(ValueError):
        view[0][0] = 1.0  # read-only rows, as the tuple's were
    with pytest.raises(TypeError):
        view[0] = np.zeros(6)  # type: ignore[index]
    with pytest.raises(AttributeError):
        view.extra = 1  # type: ignore[attr-defined]
    with pytest.raises(TypeError):
        hash(view)  # a tuple of arrays is not hashable either


def test_branch_rows_behave_as_a_tuple_of_configs() -> None:
    table = tuple(ir.Config(s, e, w) for s in ir.Shoulder for e in ir.Elbow for w in ir.Wrist)
    codes = np.array([3, 0, 7, 3])
    plain = tuple(table[c] for c in codes)
    for view in (BranchRows(None, codes, table), BranchRows(plain)):
        assert len(view) == 4 and bool(view) and view == plain and plain == view
        assert view[0] is plain[0] and view[-1] is plain[-1] and view[1:3] == plain[1:3]
        assert list(view) == list(plain) and hash(view) == hash(plain) and repr(view) == repr(plain)
        assert view != list(plain)
        with pytest.raises(IndexError):
            view[4]
        with pytest.raises(TypeError):
            view[0] = plain[0]  # type: ignore[index]


def test_result_is_frozen_and_made_as_the_dataclass_makes_it() -> None:
    rows = JointRows(_rows())
    fast = ik.result(ik.IkStatus.OK, rows, (), "m")
    slow = ik.IkResult(ik.IkStatus.OK, rows, (), "m")
    for f in dataclasses.fields(ik.IkResult):
        a, b = getattr(fast, f.name), getattr(slow, f.name)
        assert a is b or a == b
    with pytest.raises(dataclasses.FrozenInstanceError):
        fast.solutions = ()  # type: ignore[misc]


@settings(max_examples=25, deadline=None)
@given(u=st.lists(st.floats(0.0, 1.0), min_size=6, max_size=6),
       offset=st.lists(st.floats(-4.0, 4.0), min_size=6, max_size=6), use_seed=st.booleans(),
       config=st.sampled_from((None, ir.Config(None, ir.Elbow.DOWN, None))))
def test_lazy_rows_give_the_exact_paths_answer_before_and_after_they_are_made(
        u, offset, use_seed, config) -> None:  # type: ignore[no-untyped-def]
    """ur5e: every joint spans ±360°, so a pose has up to 512 solutions, made only when asked."""
    robot, solver = robot_and_solver("ur5e")
    q = -3.0 + np.array(u) * 6.0
    pose = robot.fk(q).copy()
    seed = q + np.array(offset) if use_seed else None
    fast = solver.solve(robot, pose, seed, config)
    if fast is None:  # handed back (near a singularity, a tolerance or a branch boundary)
        return
    exact = ik.solve_exact(robot, pose, seed, config)
    assert fast.status is exact.status and len(fast.solutions) == len(exact.solutions)
    lazy = fast.solutions._rows is None  # type: ignore[attr-defined]
    assert lazy == (len(exact.solutions) > fastsolve._SORTED_ROWS)
    # the nearest row and its branch, before the others exist
    assert np.array_equal(fast.solutions[0], exact.solutions[0])
    assert np.array_equal(fast.solutions[-len(exact.solutions)], exact.solutions[0])
    assert fast.branches[0] == exact.branches[0] == robot.branch(exact.solutions[0])
    assert not fast.solutions[0].flags.writeable
    dp, dr = ik.pose_error(robot.fk(fast.solutions[0]), pose)  # pinocchio's FK
    assert dp <= ik.POS_TOL and dr <= ik.ROT_TOL
    # then all of them: the same rows in the same order, the same branches
    assert fast.branches[-1] == exact.branches[-1]
    assert fast.solutions == exact.solutions and fast.branches == exact.branches
    made = fast.solutions.array  # type: ignore[attr-defined]
    assert np.array_equal(made, np.array(list(exact.solutions))) and not made.flags.writeable


def _plain_order(groups: np.ndarray, seed: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every row of the groups (itertools.product per group, groups in order) and its distance
    from the seed (sum of squares in joint order, then sqrt), without fastsolve."""
    dof = len(seed)
    per = (groups.shape[1] - 2 - dof) // dof
    rows = []
    for g in groups:
        for digits in itertools.product(*(range(int(g[2 + j])) for j in range(dof))):
            rows.append([g[2 + dof + j * per + k] for j, k in enumerate(digits)])
    out = np.array(rows)
    seeds = seed.tolist()
    dist = np.array([np.sqrt(sum((v - s) * (v - s) for v, s in zip(r, seeds)))
                     for r in out.tolist()])
    return out, dist


@settings(max_examples=40, deadline=None)
@given(data=st.data(), n_groups=st.integers(1, 4), dof=st.integers(1, 6))
def test_nearest_row_is_the_first_row_of_the_stable_sort(  # type: ignore[no-untyped-def]
        data, n_groups, dof) -> None:
    """fastsolve's pruned walk finds the first row of a stable sort by distance, ties included:
    values drawn from a small set symmetric about the seed make many distances exactly equal."""
    per = 3
    values = st.sampled_from([-2.0, -1.0, -0.5, 0.5, 1.0, 2.0, 1.0 + 2 ** -40, 3.0])
    seed = np.zeros(dof)
    groups = np.zeros((n_groups, 2 + dof + dof * per))
    for g in groups:
        counts = data.draw(st.lists(st.integers(1, per), min_size=dof, max_size=dof))
        g[0], g[1] = data.draw(st.integers(0, 7)), float(np.prod(counts))
        g[2:2 + dof] = counts
        for j, c in enumerate(counts):
            at = 2 + dof + j * per
            g[at:at + c] = data.draw(st.lists(values, min_size=c, max_size=c))
    rows, dist = _plain_order(groups, seed)
    want = int(np.argsort(dist, kind="stable")[0])
    for fn in (fastsolve._nearest_row, fastsolve.Kernel(fastsolve._nearest_row).jit()):
        row = np.empty(dof)
        first = fn(groups, n_groups, seed, row, np.zeros(dof, dtype=np.int64), np.zeros(dof))
        assert first == want and np.array_equal(row, rows[want])
    m = len(rows)
    out, codes, d = np.empty((m, dof)), np.empty(m, dtype=np.int64), np.empty(m)
    fastsolve.EXPAND.jit()(groups, n_groups, seed, out, codes, d, np.zeros(dof, dtype=np.int64))
    assert np.array_equal(out, rows) and np.array_equal(d, dist)


def test_a_ur5e_pose_has_512_lazy_solutions_that_reach_it() -> None:
    robot, solver = robot_and_solver("ur5e")
    pose = robot.fk(np.array([0.3, -1.2, 1.0, -0.5, 0.8, 0.2])).copy()
    res = solver.solve(robot, pose, None, None)
    assert res is not None and res.status is ik.IkStatus.OK
    assert len(res.solutions) == len(res.branches) == 512
    assert res.solutions._rows is None  # type: ignore[attr-defined]
    for s in res.solutions[::37]:  # pinocchio's FK of a sample of them
        dp, dr = ik.pose_error(robot.fk(s), pose)
        assert dp <= ik.POS_TOL and dr <= ik.ROT_TOL
    assert robot.ik(pose).solutions == res.solutions  # Robot.ik serves it the same way
