"""The solids and mass of external axes: `solid(GEOMETRY, at=POSE)` and `mass M` after an axis'
speed and accel, as a `model` joint takes them (compiler/passes/lower_model.py, solid_shape).

Each solid becomes a cell fixture named `AXIS.solidN` (`rail.solid1`, `pos.1.solid2`: a dot no
user name has) placed in the frame the axis carries (its pose at the axes' home values in the
cell's listing) and a Mount riding through that axis only (Mount.through; the last axis' solids
ride on the flange). So a carriage, a tilt frame or a turntable plate is drawn in pictures and
moves in the collision check (sim/axes_collide.py) with exactly the axes that carry it: a tilt
frame on axis 1 of a two-axis positioner tilts but does not turn with axis 2.
`mass M`: the kg the axis moves (finite, >= 0), printed in each vendor's machine-data checklist.
"""

from __future__ import annotations

import math

from rmot.compiler.passes.context import Reporter, Scope
from rmot.compiler.passes.evaluate import eval_expr, expect_quantity
from rmot.compiler.passes.lower_model import GeometryFn, solid_shape
from rmot.compiler.passes.values import MASS
from rmot.lang import ast, codes_axes, ir
from rmot.lang.ir_axes import Mechanism, Mount

__all__ = ["axis_mass", "axis_solids"]

MAX_AXIS_MASS_KG = 1.0e5  # policy: a positioner or carriage of at most 100 t


def axis_mass(e: ast.Expr | None, name: str, scope: Scope, rep: Reporter) -> float | None:
    """`mass M` of axis `name`: kg, finite, 0..MAX_AXIS_MASS_KG (E601 else); 0 when not given."""
    if e is None:
        return 0.0
    kg = expect_quantity(eval_expr(e, scope, rep), MASS, f"mass of axis '{name}'", e.span, rep)
    if kg is not None and not (math.isfinite(kg) and 0.0 <= kg <= MAX_AXIS_MASS_KG):
        rep.error(codes_axes.EXT_AXIS_DEFINITION, f"mass of axis '{name}' must be a finite number in "
                  f"0..{MAX_AXIS_MASS_KG:g} kg (got {kg:g} kg)", e.span)
        return None
    return kg


def axis_solids(decl: ast.MechanismDecl, mech: Mechanism, scope: Scope, rep: Reporter,
                geometry: GeometryFn) -> tuple[list[ir.Fixture], list[Mount]]:
    """The fixtures and mounts of every solid the mechanism's axes carry."""
    fixtures: list[ir.Fixture] = []
    mounts: list[Mount] = []
    for k, (axis, a) in enumerate(zip(mech.axes, decl.axes, strict=True), start=1):
        through = None if k == len(mech.axes) else k
        carrier = mech.flange(mech.home(), through)
        for n, call in enumerate(a.solids, start=1):
            found = solid_shape(call, scope, rep, geometry)
            if found is None:
                continue
            shape, local = found
            name = f"{axis.name}.solid{n}"
            fixtures.append(ir.Fixture(name, shape, carrier * local, span=call.span))
            mounts.append(Mount(name, "fixture", mech.name, local, call.span, through))
    return fixtures, mounts
