"""Kinematics speed: FK, closed-form IK (batched and single), numeric IK cold and warm,
each next to a plain pinocchio damped-least-squares loop run in the same process.

    pytest tests/benchmarks/bench_kinematics.py          # pytest-benchmark tables
    python tests/benchmarks/bench_kinematics.py          # one summary of medians (µs)

Targets: batched closed form <= 1 µs per pose (all 8 branches), single call
<= 10 µs, numeric median <= 100 µs cold with 100 % success at 1e-9, FK <= 1.5 µs.
Closed-form arms (`_closed_form_arm`, CPU-time medians): Robot.ik on abb_irb120, kuka_kr6_r900
and ur5e <= 20 µs per call with all its checks, ik_batch with limits and seed selection
<= 2 µs per pose, each next to the raw closed form in the same run. ur5e's joints span ±360°: a pose has 512
2π-equivalents (`solutions_per_call`); Robot.ik finds, checks and returns the nearest and makes
the others (rows of one array, sorted) only when asked for (`robot_ik_all_rows_us`: Robot.ik
plus a list of every solution, what a caller that reads all of them pays).
"""

from __future__ import annotations

import importlib.metadata
import itertools
import time

import numpy as np
import pinocchio as pin
import pytest

from rmot.sim.robots import load_robot

N_TARGETS = 200


def ur5_urdf() -> str:
    files = importlib.metadata.files("example-robot-data") or []
    return str(next(f for f in files if f.name == "ur5_robot.urdf").locate())


def targets(robot, n: int = N_TARGETS, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """(q, poses): reachable targets from random joints inside ±π and the limits."""
    lo, hi = np.maximum(robot.joint_limits[:, 0], -np.pi), np.minimum(robot.joint_limits[:, 1], np.pi)
    q = np.random.default_rng(seed).uniform(lo, hi, (n, robot.dof))
    return q, robot.fk_batch(q)


def pinocchio_dls(model, data, fid: int, target: np.ndarray, q0: np.ndarray, iters: int = 200):  # type: ignore[no-untyped-def]
    """pinocchio's examples/inverse-kinematics.py loop with full Newton steps (DT = 1)."""
    goal = pin.SE3(target[:3, :3].copy(), target[:3, 3].copy())
    q = q0.copy()
    damp = 1e-12 * np.eye(6)
    for _ in range(iters):
        pin.forwardKinematics(model, data, q)
        i_m_d = pin.updateFramePlacement(model, data, fid).actInv(goal)
        err = pin.log6(i_m_d).vector
        if np.linalg.norm(err) < 1e-10:
            return q, True
        jac = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL)
        jac = -pin.Jlog6(i_m_d.inverse()) @ jac
        q = pin.integrate(model, q, -jac.T @ np.linalg.solve(jac @ jac.T + damp, err))
    return q, False


def verified(robot, q: np.ndarray, target: np.ndarray) -> bool:
    t = robot.fk(q)
    return bool(np.abs(t[:3, 3] - target[:3, 3]).max() <= 1e-9 and np.linalg.norm(t[:3, :3] - target[:3, :3]) / np.sqrt(2) <= 1e-9)


def cycle(items):  # type: ignore[no-untyped-def]
    it = itertools.cycle(items)
    return lambda: next(it)


# ----------------------------------------------------------------------------- pytest-benchmark


@pytest.fixture(scope="module")
def irb():
    r = load_robot("abb_irb1600")
    return (r, *targets(r))


@pytest.fixture(scope="module")
def ur5():
    r = load_robot(ur5_urdf())
    return (r, *targets(r))


def test_fk_single_call(benchmark, irb):
    """FK through Robot.fk (target <= 1.5 µs)."""
    r, q, _ = irb
    benchmark(r.fk, q[0])


def test_fk_pinocchio_plain(benchmark, irb):
    """Reference: framesForwardKinematics on the same model."""
    r, q, _ = irb
    data = r.model.createData()
    benchmark(pin.framesForwardKinematics, r.model, data, q[0])


def test_closed_form_batched_1000_poses(benchmark, irb):
    """All 8 branches of 1000 poses in one call (divide by 1000: target <= 1 µs per pose)."""
    r, _, poses = irb
    many = np.concatenate([poses] * 5)
    benchmark(r.ik_closed_form, many)


def test_closed_form_single_call(benchmark, irb):
    """All 8 branches of one pose (target <= 10 µs)."""
    r, _, poses = irb
    benchmark(r.ik_closed_form, poses[0])


def test_full_ik_single_call(benchmark, irb):
    """Robot.ik: closed form + FK verification + equivalents + branches + sorting."""
    r, q, poses = irb
    nxt = cycle(range(len(poses)))
    benchmark(lambda: r.ik(poses[nxt()]))


def test_numeric_ik_cold(benchmark, ur5):
    """Robot.ik on a URDF arm (numeric), seed zeros, restarts when needed (target <= 100 µs)."""
    r, _, poses = ur5
    nxt = cycle(range(len(poses)))
    benchmark(lambda: r.ik(poses[nxt()]))


def test_numeric_ik_warm(benchmark, ur5):
    """Robot.ik seeded 0.05 rad from the answer."""
    r, q, poses = ur5
    nxt = cycle(range(len(poses)))

    def call():  # type: ignore[no-untyped-def]
        i = nxt()
        return r.ik(poses[i], seed=q[i] + 0.05)

    benchmark(call)


def test_pinocchio_dls_cold(benchmark, ur5):
    """Reference: the plain pinocchio DLS loop from zeros."""
    r, _, poses = ur5
    data = r.model.createData()
    fid = r._fid
    nxt = cycle(range(len(poses)))
    benchmark(lambda: pinocchio_dls(r.model, data, fid, poses[nxt()], np.zeros(6)))


def test_pinocchio_dls_warm(benchmark, ur5):
    """Reference: the plain pinocchio DLS loop seeded 0.05 rad from the answer."""
    r, q, poses = ur5
    data = r.model.createData()
    nxt = cycle(range(len(poses)))

    def call():  # type: ignore[no-untyped-def]
        i = nxt()
        return pinocchio_dls(r.model, data, r._fid, poses[i], q[i] + 0.05)

    benchmark(call)


# ----------------------------------------------------------------------------- summary


def _median_us(fn, calls: int) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(calls):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times) * 1e6)


def _cpu_median_us(fn, calls: int = 200, repeats: int = 25) -> float:  # type: ignore[no-untyped-def]
    """Median over `repeats` of the CPU time (time.process_time: a loaded machine's waits do
    not count) per call of `calls` calls."""
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        for _ in range(calls):
            fn()
        times.append((time.process_time() - t0) / calls)
    return float(np.median(times) * 1e6)


def _closed_form_arm(name: str) -> dict[str, float]:
    """Robot.ik per call and ik_batch per pose, each next to the raw closed form (same run)."""
    arm = load_robot(name)
    aq, aposes = targets(arm)
    amany = np.concatenate([aposes] * 5)
    for i in range(400):  # past the compiled single-pose pass's threshold (fastsolve)
        arm.ik(aposes[i % N_TARGETS])
    for _ in range(3):  # past the closed form's threshold (fastik), as in a planner's process
        arm.ik_batch(amany, seed=aq[0])
    nxt = cycle(range(N_TARGETS))

    def ik_all_rows() -> None:  # Robot.ik, then every solution made (and sorted) as a row array
        list(arm.ik(aposes[nxt()]).solutions)

    return {
        f"{name}_closed_form_single_us": _cpu_median_us(lambda: arm.ik_closed_form(aposes[nxt()])),
        f"{name}_robot_ik_us": _cpu_median_us(lambda: arm.ik(aposes[nxt()])),
        f"{name}_robot_ik_all_rows_us": _cpu_median_us(ik_all_rows, calls=50),
        f"{name}_closed_form_batched_us_per_pose": _cpu_median_us(
            lambda: arm.ik_closed_form(amany), calls=3) / len(amany),
        f"{name}_ik_batch_us_per_pose": _cpu_median_us(
            lambda: arm.ik_batch(amany, seed=aq[0]), calls=3) / len(amany),
        f"{name}_solutions_per_call": float(np.median([len(arm.ik(t).solutions) for t in aposes])),
    }


ISSUE_18_ARMS = ("abb_irb120", "kuka_kr6_r900", "ur5e")


def summary() -> dict[str, float]:
    out: dict[str, float] = {}
    r = load_robot("abb_irb1600")
    q, poses = targets(r)
    r.ik_closed_form(poses)
    r.ik(poses[0])
    nxt = cycle(range(N_TARGETS))
    data = r.model.createData()
    out["fk_api_us"] = _median_us(lambda: r.fk(q[nxt()]), 5000)
    out["fk_pinocchio_us"] = _median_us(lambda: pin.framesForwardKinematics(r.model, data, q[nxt()]), 5000)
    many = np.concatenate([poses] * 5)
    out["closed_form_batched_us_per_pose"] = _median_us(lambda: r.ik_closed_form(many), 50) / len(many)
    out["closed_form_single_us"] = _median_us(lambda: r.ik_closed_form(poses[nxt()]), 5000)
    out["full_ik_single_us"] = _median_us(lambda: r.ik(poses[nxt()]), 1000)
    r.ik_batch(many, seed=q[0])
    batch_us = _median_us(lambda: r.ik_batch(many, seed=q[0]), 50)
    out["ik_batch_limits_seed_us_per_pose"] = batch_us / len(many)
    ur = load_robot("ur5e")
    _, ur_poses = targets(ur)
    ur_many = np.concatenate([ur_poses] * 5)
    ur.ik_closed_form(ur_many)
    out["ur5e_closed_form_batched_us_per_pose"] = _median_us(lambda: ur.ik_closed_form(ur_many), 50) / len(ur_many)
    out["ur5e_closed_form_single_us"] = _median_us(lambda: ur.ik_closed_form(ur_poses[nxt()]), 5000)
    for name in ISSUE_18_ARMS:  # Robot.ik <= 20 us, ik_batch <= 2 us/pose
        out.update(_closed_form_arm(name))
    u = load_robot(ur5_urdf())
    uq, uposes = targets(u)
    u.ik(uposes[0])
    udata = u.model.createData()
    for label, seed in (("cold", lambda i: np.zeros(6)), ("warm", lambda i: uq[i] + 0.05)):
        times, ok, ptimes, pok = [], 0, [], 0
        for i in range(N_TARGETS):
            t0 = time.perf_counter()
            res = u.ik(uposes[i], seed=seed(i))
            times.append(time.perf_counter() - t0)
            ok += bool(res.solutions) and verified(u, res.solutions[0], uposes[i])
            t0 = time.perf_counter()
            qp, _ = pinocchio_dls(u.model, udata, u._fid, uposes[i], seed(i))
            ptimes.append(time.perf_counter() - t0)
            pok += verified(u, qp, uposes[i])
        out[f"numeric_{label}_us"] = float(np.median(times) * 1e6)
        out[f"numeric_{label}_success"] = ok / N_TARGETS
        out[f"pinocchio_dls_{label}_us"] = float(np.median(ptimes) * 1e6)
        out[f"pinocchio_dls_{label}_success"] = pok / N_TARGETS
    return out


if __name__ == "__main__":
    import os

    results = summary()
    for key, value in results.items():
        print(f"{key:<34} {value:10.3f}")
    raw = results["closed_form_batched_us_per_pose"]
    print(f"Robot.ik: {results['full_ik_single_us']:.1f} us per call (target <= 20), "
          f"{results['full_ik_single_us'] / results['closed_form_single_us']:.0f}x the raw closed form")
    batch = results["ik_batch_limits_seed_us_per_pose"]
    print(f"ik_batch with limits and seed: {batch:.2f} us per pose (target <= 2), "
          f"{batch / raw:.1f}x the raw closed form")
    for name in ISSUE_18_ARMS:
        one, raw1 = results[f"{name}_robot_ik_us"], results[f"{name}_closed_form_single_us"]
        per, rawb = results[f"{name}_ik_batch_us_per_pose"], results[f"{name}_closed_form_batched_us_per_pose"]
        print(f"{name}: Robot.ik {one:.1f} us per call (target <= 20; raw closed form {raw1:.1f} us, "
              f"{results[f'{name}_solutions_per_call']:.0f} solutions per call; "
              f"{results[f'{name}_robot_ik_all_rows_us']:.1f} us with every solution made), "
              f"ik_batch {per:.2f} us per pose (target <= 2; raw closed form {rawb:.2f} us "
              f"per pose, {per - rawb:.2f} us above it)")
    print(f"(load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)")
