"""A model's controller conventions: `controller MAKER` and per joint `pendant(...)`.

`controller kuka` names the maker whose pendant values the model's joint values are
(sim/robots/controller.py states what that declares); `pendant(sign=-1, zero=-90deg,
coupled_to=2)` on a joint line gives how the joint's pendant value p drives its DH variable:
θ = theta + sign·(p + p_coupled − zero) (a prismatic joint: d = d + sign·(p − zero)).
"""

from __future__ import annotations

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Reporter, Scope
from rmot.compiler.passes.evaluate import eval_expr, expect_quantity, match_args
from rmot.compiler.passes.values import ANGLE, DIMENSIONLESS, LENGTH, Quantity
from rmot.lang import ast

__all__ = ["controller_word", "declared_controller", "pendant_of", "record_pendant", "urdf_controller"]


def controller_word(item: ast.Setting, rep: Reporter) -> str | None:
    """The maker of `controller NAME` (a key of controller.MAKERS), None after E186."""
    from rmot.sim.robots.controller import MAKERS  # late: loads coal only when this runs

    assert isinstance(item.value, ast.Ident)
    word = item.value.name.lower()
    if word not in MAKERS:
        rep.unknown(item.value.name, "robot maker", item.value.span, sorted(MAKERS), codes.UNKNOWN_CONTROLLER)
        return None
    return word


def declared_controller(item: ast.Setting | None, pendant: dict[int, tuple[float, float, int]], n_joints: int,
                        rep: Reporter) -> tuple[str | None, tuple[tuple[float, float, int], ...]] | None:
    """(maker or None, per joint (sign, zero, coupled_to) or ()) of a model; None after E186."""
    maker = None if item is None else controller_word(item, rep)
    if item is not None and maker is None:
        return None
    return maker, tuple(pendant.get(k, (1.0, 0.0, 0)) for k in range(1, n_joints + 1)) if pendant else ()


def record_pendant(call: ast.Call, index: int, kind: str, pendant: dict[int, tuple[float, float, int]],
                   scope: Scope, rep: Reporter) -> bool:
    """Lower joint `index`'s `pendant(...)` into `pendant`; False after a diagnostic."""
    if index in pendant:
        rep.error(codes.MODEL_JOINT_FIELD, "a joint must have one pendant(...) field (got two)", call.span)
        return False
    mapping = pendant_of(call, index, kind, scope, rep)
    if mapping is None:
        return False
    pendant[index] = mapping
    return True


def urdf_controller(value: ast.Expr, rep: Reporter) -> str | None:
    """The maker of `urdf(..., controller="abb")` (a key of controller.MAKERS), None after E186."""
    from rmot.sim.robots.controller import MAKERS  # late: loads coal only when this runs

    if not isinstance(value, ast.String) or value.value.lower() not in MAKERS:
        shown = value.value if isinstance(value, ast.String) else "an expression"
        rep.unknown(shown, "robot maker (in quotes)", value.span, sorted(MAKERS), codes.UNKNOWN_CONTROLLER)
        return None
    return value.value.lower()


def pendant_of(call: ast.Call, index: int, kind: str, scope: Scope, rep: Reporter) -> tuple[float, float, int] | None:
    """(sign, zero, coupled_to) of joint `index` (1-based) from `pendant(sign=, zero=, coupled_to=)`."""
    bound = match_args(call.args, ("sign", "zero", "coupled_to"), "pendant", call.span, rep, required=0)
    if bound is None:
        return None
    sign, zero, coupled = 1.0, 0.0, 0
    if "sign" in bound:
        value = eval_expr(bound["sign"].value, scope, rep)
        number = value.value if isinstance(value, Quantity) and value.dim == DIMENSIONLESS else None
        if number not in (1.0, -1.0):
            rep.error(codes.MODEL_PENDANT, "pendant sign must be 1 or -1 (the pendant turns with or against "
                      "the DH joint)", bound["sign"].value.span)
            return None
        sign = float(number)
    if "zero" in bound:
        dim = ANGLE if kind == "R" else LENGTH
        z = expect_quantity(eval_expr(bound["zero"].value, scope, rep), dim, "pendant zero", bound["zero"].value.span, rep)
        if z is None or not abs(z) < 1e6:
            return None
        zero = z
    if "coupled_to" in bound:
        value = eval_expr(bound["coupled_to"].value, scope, rep)
        number = value.value if isinstance(value, Quantity) and value.dim == DIMENSIONLESS else None
        if number is None or number != int(number) or not 0 <= number < index or kind != "R":
            rep.error(codes.MODEL_PENDANT, f"pendant coupled_to must name an earlier revolute joint "
                      f"({'1' if index == 2 else f'1..{index - 1}'}) or be 0 for none (Fanuc's J2/J3 interaction: coupled_to=2 on joint 3)",
                      bound["coupled_to"].value.span)
            return None
        coupled = int(number)
    return sign, zero, coupled
