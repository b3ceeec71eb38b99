"""Each numba kernel (lang/jit.py) is one algorithm: the interpreted form and the compiled
form give the same floats on random inputs: bit for bit for the TOPP kernels (arithmetic only),
to within a few ulp where sin/cos/atan2/acos come from numba's or the interpreter's math
library; chain FK's numpy form repeats the compiled loop's arithmetic. (Which form runs is a
matter of speed only.)"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.lang.jit import Kernel
from rmot.compiler.plan import topp
from rmot.sim.robots import fastik, load_robot
from rmot.sim.robots.fastdls import DLS_CHAIN, JOINT_FRAMES
from rmot.sim.robots.opw import OpwJointMap, OpwParams

_SEEDS = st.integers(0, 2**32 - 1)


def _both(kernel: Kernel, *args: object) -> tuple[object, object]:
    plain = kernel.py(*(a.tolist() if kernel.lists and isinstance(a, np.ndarray) else a for a in args))
    return plain, kernel.jit()(*args)


def _same(a: object, b: object) -> bool:
    if isinstance(a, tuple):
        return all(_same(x, y) for x, y in zip(a, b))  # type: ignore[arg-type]
    return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True)


def _rows(rng: np.random.Generator, k: int, m: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(beta, lo, hi): symmetric rows (lo = -hi), rows without a u term (hi = inf) and
    one-sided rows shifted by a constant, as a joint torque with gravity gives (some of them
    empty, lo > hi: gravity alone beyond the limit)."""
    beta = rng.normal(size=(k, m)) * rng.choice([1e-3, 1.0, 1e3])
    hi = np.abs(rng.normal(size=(k, m))) + 1e-3
    hi[rng.random((k, m)) < 0.2] = np.inf  # rows without a u term
    lo = -hi
    shifted = rng.random((k, m)) < 0.3
    shift = rng.normal(size=(k, m)) * 2.0
    lo = np.where(shifted & np.isfinite(hi), lo + shift, lo)
    hi = np.where(shifted & np.isfinite(hi), hi + shift, hi)
    return beta, lo, hi


@settings(max_examples=25, deadline=None)
@given(_SEEDS, st.integers(2, 60), st.integers(1, 8))
def test_topp_kernels_interpreted_equal_compiled(seed: int, k: int, m: int) -> None:
    rng = np.random.default_rng(seed)
    beta, lo, hi = _rows(rng, k, m)
    ss = np.cumsum(rng.random(k) + 1e-3)
    xmax = np.where(rng.random(k) < 0.1, 1e18, rng.random(k) * 10)
    assert _same(*_both(topp.CEILING, beta, lo, hi))
    assert _same(*_both(topp.PASSES, ss, xmax, beta, lo, hi))
    n, t = m, 3
    args = (rng.random(k), rng.random(k - 1) + 1e-2, rng.normal(size=(k, n)), rng.normal(size=(k, n)),
            rng.normal(size=(t, k - 1, n)), rng.normal(size=(t, k - 1, n)), rng.random((t, k - 1)),
            np.array([0.25, 0.5, 0.75]), rng.random(n) + 0.5)
    assert _same(*_both(topp.CHECK, *args))
    t_args = (rng.random(k), rng.random(k - 1) + 1e-2, rng.normal(size=(t, k - 1, n)),
              rng.normal(size=(t, k - 1, n)), rng.normal(size=(t, k - 1, n)) * 3,
              np.array([0.25, 0.5, 0.75]), rng.random(n) * 3 + 0.5)
    assert _same(*_both(topp.CHECK_TORQUE, *t_args))


def _poses(rng: np.random.Generator, n: int, reach: float) -> np.ndarray:
    """n random orthonormal poses within `reach` of the origin (some of them out of reach)."""
    q, _ = np.linalg.qr(rng.normal(size=(n, 3, 3)))
    out = np.zeros((n, 4, 4))
    out[:, :3, :3] = q * np.sign(np.linalg.det(q))[:, None, None]
    out[:, :3, 3] = rng.uniform(-reach, reach, (n, 3))
    out[:, 3, 3] = 1.0
    return out


@settings(max_examples=15, deadline=None)
@given(_SEEDS)
def test_closed_forms_interpreted_equal_compiled(seed: int) -> None:
    """OPW and UR closed forms (arbitrary arm lengths: only the two forms are compared), on
    poses in and out of reach (NaN branches)."""
    rng = np.random.default_rng(seed)
    lengths = rng.uniform(0.05, 0.8, 7) * rng.choice([-1.0, 1.0], 7)
    opw = fastik.opw_kernel_args(OpwParams(*map(float, lengths)), OpwJointMap(sign=(1, -1, 1, 1, -1, 1),
                                                                              offset=(0, 0.5, 0, 0, 0, 3.1)))
    ur = np.array([0.16, -0.42, -0.39, 0.13, 0.1, 0.1]) * rng.uniform(0.5, 2.0, 6)
    poses = _poses(rng, 12, 1.5)
    for kernel, args in ((fastik.OPW_MANY, opw), (fastik.UR_MANY, (ur,))):
        out_py, out_jit = np.empty((12, 8, 6)), np.empty((12, 8, 6))
        kernel.py(*args, poses, out_py)
        kernel.jit()(*args, poses, out_jit)
        assert np.array_equal(np.isnan(out_py), np.isnan(out_jit))
        np.testing.assert_allclose(out_py, out_jit, rtol=4 * np.finfo(float).eps, atol=1e-15)


@settings(max_examples=10, deadline=None)
@given(_SEEDS, st.sampled_from(["abb_irb1600", "ur5e", "kuka_kr6_r900"]))
def test_chain_fk_numpy_and_both_kernel_forms_agree_bit_for_bit(seed: int, name: str) -> None:
    robot = load_robot(name)
    chain = robot._chain
    q = np.random.default_rng(seed).uniform(-7, 7, (9, robot.dof))
    out_py, out_jit = np.empty((9, robot.dof, 4, 4)), np.empty((9, robot.dof, 4, 4))
    JOINT_FRAMES.py(chain.placements, chain.axes, chain.prismatic, q, out_py)
    JOINT_FRAMES.jit()(chain.placements, chain.axes, chain.prismatic, q, out_jit)
    assert np.array_equal(chain.joint_frames_vectorised(q), out_py)  # numpy = the loop, interpreted
    np.testing.assert_allclose(out_py, out_jit, rtol=0, atol=4e-16)  # compiled: libm's last bit
    np.testing.assert_allclose(chain.joint_frames_numpy(q), out_jit, atol=1e-13)  # the plain reference


def test_dls_interpreted_equals_compiled() -> None:
    robot = load_robot("ur5e")
    chain = robot._chain
    rng = np.random.default_rng(3)
    target = robot.fk(rng.uniform(-2, 2, 6))
    args = (chain.placements, chain.axes, chain.prismatic, np.array(robot._flange_in_joint), np.eye(6),
            target, rng.uniform(-2, 2, 6), 1e-11, 60, 1e-12, 0.5)
    (q1, e1), (q2, e2) = DLS_CHAIN.py(*args), DLS_CHAIN.jit()(*args)
    np.testing.assert_allclose(q1, q2, rtol=0, atol=1e-12)
    assert e1 < 1e-11 and e2 < 1e-11


def test_a_kernel_compiles_once_its_work_passes_the_threshold() -> None:
    calls: list[str] = []

    def twice(x: float) -> float:
        calls.append("py")
        return 2 * x

    k = Kernel(twice, threshold=10)
    assert k(4, 1.0) == 2.0 and k(5, 1.0) == 2.0 and not k.compiled and calls == ["py", "py"]
    k.jit = lambda: (lambda x: 3 * x)  # type: ignore[method-assign]  # stands for the compiled form
    assert k(1, 1.0) == 3.0 and calls == ["py", "py"]  # the 10th unit of work: compiled from now on
