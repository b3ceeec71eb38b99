"""The `model` block and `urdf(..., base=, tip=)`: what the parser builds, with spans."""

from __future__ import annotations

from rmot.lang import ast, parse_text
from rmot.lang.diagnostics import render

TEXT = """cell c {
  model my_arm {
    joint revolute dh(a=0mm, alpha=-90deg, d=350mm, theta=0deg) range(-170deg, 170deg) speed 200 deg/s accel 800 deg/s^2
    joint prismatic mdh(a=0mm, alpha=0deg, d=0mm, theta=0deg) range(0mm, 300mm) solid(sphere(r=10mm)) speed 1 m/s accel 4 m/s^2

    flange pose(z=10mm)        # the flange in the last DH frame
    payload 5 kg
  }
  robot arm = my_arm at pose(x=1m)
  robot hand = urdf("f.urdf", base="base_link", tip="tool0")
}
"""


def test_model_block_builds_joint_lines_flange_and_payload() -> None:
    result = parse_text(TEXT, "t.rmot")
    assert result.diagnostics == (), [render(d) for d in result.diagnostics]
    cell = result.module.body[0]  # type: ignore[union-attr]
    model, arm, hand = cell.body
    assert isinstance(model, ast.ModelDecl) and model.name.name == "my_arm"
    j1, j2, flange, payload = model.items
    assert isinstance(j1, ast.ModelJoint) and j1.kind.name == "revolute"
    assert [p.func.name if isinstance(p, ast.Call) else p.kind for p in j1.parts] == ["dh", "range", "speed", "accel"]
    assert [p.func.name if isinstance(p, ast.Call) else p.kind for p in j2.parts] == ["mdh", "range", "solid", "speed", "accel"]
    assert j1.parts[2].value == ast.Number(200.0, "deg/s", None) and j1.parts[3].value == ast.Number(800.0, "deg/s^2", None)
    assert (flange.kind, payload.kind) == ("flange", "payload")
    assert payload.value == ast.Number(5.0, "kg", None)
    # spans: a joint line from `joint` to its last number; the model from `model` to `}`
    lines = TEXT.splitlines()
    assert (j1.span.start.line, j1.span.start.col) == (3, 5)
    assert j1.span.end.col == len(lines[2]) + 1
    assert (model.span.start.line, model.span.end.line) == (2, 8)
    assert arm.library.name == "my_arm" and arm.urdf_args == ()
    assert hand.urdf.value == "f.urdf"
    assert [(a.name.name, a.value.value) for a in hand.urdf_args] == [("base", "base_link"), ("tip", "tool0")]


def test_model_names_stay_usable_elsewhere_and_unit_errors_are_unchanged() -> None:
    """`model`, `flange`, `payload`, `range`, `solid` are keywords only where a model expects them."""
    result = parse_text("program p {\n  const payload = 2 kg\n  target flange = pose(z=1mm)\n  speed 100 mmm\n}\n", "t.rmot")
    assert [d.code.id for d in result.diagnostics] == ["E007"]
