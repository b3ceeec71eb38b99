"""config(...) on a joint target warns (W123); range errors show the value in the user's unit."""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.compiler.frontend import load_text

PATH = str(Path(__file__).resolve().parents[1] / "data" / "probe.rmot")
HOME = "joints(0, -20, 30, 0, 50, 0) deg"


def _diags(body: str):  # type: ignore[no-untyped-def]
    return load_text(f"program p {{\n{body}}}\n", PATH).diagnostics


def test_config_on_joint_target_warns_at_the_config() -> None:
    """`move joint joints(...) config(...)`: a W123 warning at the config modifier, still a program."""
    result = load_text(f"program p {{\n  move joint {HOME} config(wrist=flip)\n}}\n", PATH)
    (w,) = result.diagnostics
    assert w.code.id == "W123" and not w.is_error
    assert "no IK branch to choose" in w.message
    assert (w.span.start.line, w.span.start.col) == (2, 47)
    assert w.span.end.col - w.span.start.col == len("config(wrist=flip)")
    assert result.program is not None


def test_config_on_named_joint_target_warns_too() -> None:
    """A target constant holding joints is a joint target as well."""
    codes = [d.code.id for d in _diags(f"  target home = {HOME}\n  move joint home config(elbow=up)\n")]
    assert codes == ["W123"]


def test_config_on_pose_target_does_not_warn() -> None:
    """config(...) on a pose is what it is for: no diagnostic."""
    assert _diags("  move joint pose(x=400mm, z=400mm, rx=180deg) config(wrist=flip)\n") == ()


@pytest.mark.parametrize(("setting", "shown"), [("speed 0 mm/s", "got 0 mm/s"), ("speed -5 m/s", "got -5 m/s"),
                                                ("accel -2 cm/s^2", "got -2 cm/s^2")])
def test_range_error_shows_the_value_in_the_written_unit(setting: str, shown: str) -> None:
    """A non-positive speed reads 'got 0 mm/s', not 'got 0 in SI units'."""
    (d,) = [d for d in _diags(f"  {setting}\n  move joint {HOME}\n") if d.is_error]
    assert d.code.id == "E118"
    assert f"({shown})" in d.message and "SI units" not in d.message
