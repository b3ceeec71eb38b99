"""Parts in the cell language: declarations, attach/detach and what the front end
can tell before anything moves (the bad inputs are fixtures in tests/data/bad/part_*.rmot)."""

from __future__ import annotations

from pathlib import Path

from rmot.lang import ir
from rmot.compiler.frontend import load_text

SUPPORT = Path(__file__).resolve().parents[1] / "data" / "bad" / "support"
CELL = 'use cell "support/parts_cell.rmot"\n'


def _load(body: str):  # type: ignore[no-untyped-def]
    return load_text(CELL + body, str(SUPPORT.parent / "prog.rmot"))


def test_part_declaration_in_si_units() -> None:
    """`part b1 = box(100mm, ...) at pose(x=650mm, z=50mm) mass 2 kg` -> metres and kilograms."""
    r = _load("program p on r1 { wait 1 s }")
    assert not r.has_errors
    b1, b2 = r.cell.parts  # type: ignore[union-attr]
    assert (b1.name, b1.geometry, b1.mass) == ("b1", ir.Box((0.1, 0.1, 0.1)), 2.0)
    assert b1.pose.position == (0.65, 0.0, 0.05)
    assert b2.pose.position == (0.65, 0.15, 0.05)


def test_mass_defaults_to_zero() -> None:
    r = load_text("cell c { robot r1 = ur10e\n part p = sphere(10mm) }\nprogram q on r1 { wait 1 s }", "x.rmot")
    assert [p.mass for p in r.cell.parts] == [0.0]  # type: ignore[union-attr]


def test_attach_and_detach_carry_what_is_held_and_the_load() -> None:
    """The tool is 1 kg, each cube 2 kg: holding b1 and b2 is 5 kg on the flange, then 3 kg."""
    r = _load("program p on r1 {\n tool gripper\n attach b1\n attach b2\n detach b1\n detach b2\n}")
    assert not r.has_errors, r.diagnostics
    body = r.program.tasks[0].body  # type: ignore[union-attr]
    assert [(type(i).__name__, i.part, i.held, i.load) for i in body] == [
        ("Attach", "b1", ("b1",), 3.0), ("Attach", "b2", ("b1", "b2"), 5.0),
        ("Detach", "b1", ("b2",), 3.0), ("Detach", "b2", (), 1.0)]
    assert body[0].tool.name == "gripper"


def test_part_still_held_at_the_end_is_a_warning_at_its_attach() -> None:
    r = _load("program p on r1 {\n tool gripper\n attach b1\n}")
    assert not r.has_errors
    (d,) = r.diagnostics
    assert d.code.id == "W140" and d.span.start.line == 4 and "'b1'" in d.message  # type: ignore[union-attr]


def test_a_part_name_is_its_starting_pose() -> None:
    """`b1 * pose(z=50mm)` is 50 mm above where b1 starts (world), like a fixture's name."""
    r = _load("program p on r1 {\n move joint b1 * pose(z=50mm, rx=180deg)\n}")
    assert not r.has_errors
    (move,) = r.program.tasks[0].body  # type: ignore[union-attr]
    assert move.target.pose.position == (0.65, 0.0, 0.1)  # robot at the world origin


def test_both_arms_holding_the_same_part_is_fine() -> None:
    r = _load("program p on r1 {\n tool gripper\n if in[1] == on { attach b1 } else { attach b1 }\n detach b1\n}")
    assert not r.has_errors and r.diagnostics == ()


def test_handover_tasks_each_hold_their_own_state() -> None:
    """Two tasks: r1 attaches and detaches, r2 then attaches and detaches the same part."""
    cell = ('cell c {\n robot r1 = ur10e\n robot r2 = ur5e at pose(x=1.2m)\n'
            ' part b = box(50mm, 50mm, 50mm) at pose(x=600mm) mass 1 kg\n}\n')
    r = load_text(cell + "program p {\n task r1 { attach b; detach b; sync s }\n task r2 { sync s; attach b; detach b }\n}", "h.rmot")
    assert not r.has_errors and r.diagnostics == ()
