"""The public API of rmot.sim.render: the names and signatures other stages call."""

from __future__ import annotations

import inspect

import rmot.sim.render as render


def test_exported_names() -> None:
    """__all__ lists exactly the public entry points, and each exists."""
    assert sorted(render.__all__) == ["Camera", "Light", "Material", "Shading", "render_animation", "render_finding",
                                      "render_still", "render_triangles"]
    assert all(hasattr(render, name) for name in render.__all__)


def test_signatures_that_other_stages_rely_on() -> None:
    """`rmot check --images` and the CLI call these with these parameters and defaults."""
    still = inspect.signature(render.render_still)
    assert [(p.name, p.default) for p in still.parameters.values()][1:] == [
        ("time", 0.0), ("size", (640, 480)), ("aa", 2), ("camera", None), ("highlight", ()), ("caption", None),
        ("findings", ())]
    finding = inspect.signature(render.render_finding)
    assert list(finding.parameters) == ["plan", "diagnostic", "path", "size", "camera"]
    assert finding.parameters["size"].default == (640, 480)
    anim = inspect.signature(render.render_animation)
    assert {k: p.default for k, p in anim.parameters.items() if k in ("fps", "size", "aa", "camera")} == {
        "fps": 25, "size": (480, 360), "aa": 1, "camera": None}
