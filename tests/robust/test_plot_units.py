"""A prismatic joint is plotted in mm (mm/s, mm/s², N), a revolute one in deg: the model block
below declares J3 prismatic, and its panel was labelled `[deg]` with values in mm."""

from __future__ import annotations

import pytest

from tests.robust.cases import _MODEL_PROG


@pytest.mark.parametrize("what, revolute, prismatic", [("joints", "deg", "mm"), ("speeds", "deg/s", "mm/s"),
                                                       ("accels", "deg/s²", "mm/s²")])
def test_prismatic_joint_panels_are_in_mm(what: str, revolute: str, prismatic: str) -> None:
    from rmot.compiler.frontend import load_text
    from rmot.compiler.plan import plan_program
    from rmot.sim.plots import make_figure, plot_data

    program = load_text(_MODEL_PROG, "p.rmot").program
    assert program is not None
    figure = make_figure(plot_data(plan_program(program)), what)
    labels = [ax.get_ylabel() for ax in figure.axes]
    assert labels == [f"J1 [{revolute}]", f"J2 [{revolute}]", f"J3 [{prismatic}]"]
    assert "joint prismatic" in _MODEL_PROG.splitlines()[4]  # the third joint line declares it
