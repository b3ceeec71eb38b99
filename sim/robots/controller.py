"""The controller a robot's joint values and frames belong to: its maker and conventions.

A library arm carries its vendor's conventions (library.py's docstring and each spec's
`conventions`). A robot the cell brings — a `model` block or a URDF file — carries them only
when the cell declares them:

* `model NAME { ... controller kuka }` and, per joint line, `pendant(sign=, zero=,
  coupled_to=)`: the model's joint values are then the pendant's. The DH angle of joint i is
  θᵢ = theta + signᵢ·(pᵢ + p_c − zeroᵢ) (p_c the pendant value of joint `coupled_to`, Fanuc's
  J2/J3 interaction; 0 when not coupled); DH frame 0 is the controller's base frame and the
  model's `flange` its flange frame.
* `urdf("f.urdf", controller="abb")`: the URDF's joint values are the pendant's, as
  ROS-Industrial's drivers pass them (one to one; Fanuc: the driver's J23_factor = 1, URDF
  joint_3 = J2 + J3), and its `base` and `tool0` links are the controller's base and flange
  frames (ROS-Industrial's convention, REP 199).

`controller any` declares that the model's own joint values and frames are written to every
controller as they are (an arm made up for an example, or one the user vouches for).
A vendor target refuses a robot without declared conventions (E480) and one declared for
another maker (E481) before anything is emitted (compiler/cli/compile_cmd.py).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from rmot.lang import ir

__all__ = ["ANY", "MAKERS", "coupling_matrix", "fanuc_urdf_coupling", "in_joint_values", "maker_of"]

ANY = "any"
# the word a cell writes -> the maker's name as backends/controller_data.TARGET_BRANDS prints it
MAKERS: dict[str, str] = {
    "abb": "ABB", "kuka": "KUKA", "fanuc": "FANUC", "yaskawa": "Yaskawa", "motoman": "Yaskawa",
    "staubli": "Stäubli", "ur": "Universal Robots", ANY: ANY,
}


def maker_of(word: str) -> str | None:
    """The maker named by a cell's word (case-insensitive), None when unknown."""
    return MAKERS.get(word.strip().lower())


def coupling_matrix(signs: tuple[float, ...], coupled_to: tuple[int, ...]) -> np.ndarray | None:
    """Pendant values p -> model variables u = C p, uᵢ = signᵢ·(pᵢ + p_{coupled_to[i]}) (1-based
    joint numbers, 0 = not coupled); None when C is the identity."""
    n = len(signs)
    c = np.diag(np.asarray(signs, dtype=float))
    for i, j in enumerate(coupled_to):
        if j:
            c[i, j - 1] = signs[i]
    return None if np.array_equal(c, np.eye(n)) else c


def fanuc_urdf_coupling(dof: int) -> np.ndarray:
    """ROS-Industrial fanuc_driver passes J3 to ROS as J3 + J2 (J23_factor = 1, the default of
    its `fanuc_driver` launch files): URDF joint_3 = J2 + J3, the other joints one to one."""
    return coupling_matrix((1.0,) * dof, (0, 0, 2) + (0,) * (dof - 3)) if dof >= 3 else np.eye(dof)  # type: ignore[return-value]


def in_joint_values(closed_form: Callable[[np.ndarray], np.ndarray] | None,
                     branch_fn: Callable[[np.ndarray], ir.Config], coupling: np.ndarray,
                     ) -> tuple[Callable[[np.ndarray], np.ndarray] | None, Callable[[np.ndarray], ir.Config]]:
    """A closed form and branch function of the model variables u, as functions of the joint
    values p = C⁻¹ u (a row the closed form leaves NaN stays NaN)."""
    inverse_t = np.linalg.inv(coupling).T

    def branch(q: np.ndarray) -> ir.Config:
        return branch_fn(coupling @ q)

    if closed_form is None:
        return None, branch
    solve = closed_form

    def in_joints(poses: np.ndarray) -> np.ndarray:
        return solve(poses) @ inverse_t

    return in_joints, branch
