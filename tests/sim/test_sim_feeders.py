"""Feeders and parts resting on parts: a palletiser in nested `for` loops (2 layers x 2 rows x
2 columns of 190 x 90 x 100 mm cartons, touching side by side and stacked) in the cell of
examples/palletizing.rmot, whose `feeder` presents the cartons at the infeed stop.

Independent witnesses: the depth of a carton set 5 mm into its neighbour is the smallest
per-axis overlap of the two axis-aligned boxes at their slots (worked out from the box sizes
and the slot pitches here, not by the collision code); the iteration and the attach's line come
from the program text.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program
from rmot.sim.verification import verify

ROOT = Path(__file__).resolve().parents[2]
CELL = (ROOT / "examples" / "cells" / "palletizer_loops.rmot").read_text(encoding="utf-8")
FEEDER = "feeder carton = box(190mm, 90mm, 100mm) at pose(x=700mm, z=800mm) mass 2 kg count "
assert FEEDER + "36" in CELL  # the example's feeder, with the count each test gives

PROGRAM = """use cell "cell.rmot"
const lift = 250 mm
const slow = 150 mm/s
program palletizing on r1 {{
  tool suction
  speed 800 mm/s
  zone 50 mm
  target home  = joints(-45, -10, 10, 0, 90, 0) deg
  target pick  = pose(x=700mm, y=0mm, z=850mm, rx=180deg)
  target slot0 = pose(x=95mm, y=45mm, z=100mm, rx=180deg)
  move joint home
  for layer in 0 .. 2 {{
    for row in 0 .. 2 {{
      for col in 0 .. 2 {{
        frame world
        move joint shift(pick, z=lift) zone 50 mm
        move linear pick speed slow zone fine
        attach carton
        move linear shift(pick, z=lift) speed 2 * slow
        frame pallet
        move joint shift(slot0, x=col * 190mm - {offset} * layer * row * col, y=row * 90mm, z=layer * 100mm + lift) zone 50 mm
        move linear shift(slot0, x=col * 190mm - {offset} * layer * row * col, y=row * 90mm, z=layer * 100mm) speed slow zone fine
        detach carton
        move linear shift(slot0, x=col * 190mm, y=row * 90mm, z=layer * 100mm + lift) speed 2 * slow
      }}
    }}
  }}
  move joint home zone fine
}}
"""
ATTACH_LINE = 18  # `attach carton` in PROGRAM


def _verify(tmp_path: Path, offset_mm: float = 0.0, count: int = 8, program: str = PROGRAM):  # type: ignore[no-untyped-def]
    (tmp_path / "cell.rmot").write_text(CELL.replace(FEEDER + "36", FEEDER + str(count)), encoding="utf-8")
    path = tmp_path / "pallet.rmot"
    path.write_text(program.format(offset=f"{offset_mm}mm"), encoding="utf-8")
    result = load_program(str(path), require_program=True)
    assert not result.has_errors, [str(d) for d in result.diagnostics]
    plan = plan_program(result.program)
    return plan, [d for d in verify(plan).diagnostics if d.is_error]


def test_touching_cartons_side_by_side_and_stacked_check_clean(tmp_path: Path) -> None:
    plan, errors = _verify(tmp_path)
    assert errors == []
    assert any(isinstance(i, __import__("rmot.lang.ir", fromlist=["Loop"]).Loop) for i in plan.tasks[0].task.body)


def test_a_slot_5_mm_into_its_neighbour_is_one_collision_naming_both_cartons_depth_and_iteration(tmp_path: Path) -> None:
    """Only layer = 1, row = 1, col = 1 (the 8th carton) moves: x = 190 - 5 mm, into the 7th
    (col = 0 of the same row and layer). Per-axis overlaps of the two boxes: x 190 - 185 = 5 mm,
    y 90 mm, z 100 mm; the penetration depth of two aligned boxes is the smallest, 5 mm."""
    size = (190.0, 90.0, 100.0)
    centre_7, centre_8 = (0.0, 90.0, 100.0), (190.0 - 5.0, 90.0, 100.0)
    witness = min(s - abs(a - b) for s, a, b in zip(size, centre_7, centre_8))
    _, errors = _verify(tmp_path, offset_mm=5.0)
    (d,) = errors
    assert d.code.id == "E300" and set(d.bodies) == {"carton#7", "carton#8"}
    assert d.amount is not None and d.amount.value == pytest.approx(witness, abs=0.05)
    assert "(in iteration layer = 1, row = 1, col = 1)" in d.message


def test_attach_after_the_feeders_count_is_a_finding_at_its_line_naming_the_iteration(tmp_path: Path) -> None:
    _, errors = _verify(tmp_path, count=7)
    empty = [d for d in errors if d.code.id == "E334"]
    assert len(empty) == 1 and empty[0].span is not None and empty[0].span.start.line == ATTACH_LINE
    assert "(in iteration layer = 1, row = 1, col = 1)" in empty[0].message


def test_parts_findings_in_a_loop_name_their_iteration(tmp_path: Path) -> None:
    """The attach moved after the lift: the carton is 250 mm below the TCP in every iteration
    (E330 names the carton by ordinal and the iteration)."""
    late = PROGRAM.replace("        attach carton\n        move linear shift(pick, z=lift) speed 2 * slow\n",
                              "        move linear shift(pick, z=lift) speed 2 * slow\n        attach carton\n")
    _, errors = _verify(tmp_path, program=late)
    far = [d for d in errors if d.code.id == "E330"]
    assert far and all("(in iteration layer = " in d.message for d in far)
    assert "'carton#1'" in far[0].message and "(in iteration layer = 0, row = 0, col = 0)" in far[0].message


def test_payload_finding_names_the_feeder_part_by_its_ordinal(tmp_path: Path) -> None:
    """5 kg cartons on the 1.2 kg suction tool: 6.2 kg over the IRB 1600-6/1.45's rated 6 kg
    (ABB 3HAC023604-001, the model name) from each pick on; E332 names the carton carried then."""
    heavy = CELL.replace(FEEDER, FEEDER.replace("mass 2 kg", "mass 5 kg"))
    (tmp_path / "cell.rmot").write_text(heavy.replace(FEEDER.replace("mass 2 kg", "mass 5 kg") + "36",
                                                      FEEDER.replace("mass 2 kg", "mass 5 kg") + "8"), encoding="utf-8")
    path = tmp_path / "pallet.rmot"
    path.write_text(PROGRAM.format(offset="0mm"), encoding="utf-8")
    result = load_program(str(path), require_program=True)
    assert not result.has_errors
    over = [d for d in verify(plan_program(result.program)).diagnostics if d.code.id == "E332"]
    assert len(over) == 8  # one per carried carton
    for k, d in enumerate(over, 1):
        assert f"part 'carton#{k}' 5 kg" in d.message and "6.2 kg" in d.message, d.message
    assert "(in iteration layer = 1, row = 1, col = 1)" in over[-1].message


def test_a_feeder_declared_in_the_program_works_as_one_in_the_cell(tmp_path: Path) -> None:
    """The cell's feeder line moved to the program's top level: the same stack checks clean
    with 8 cartons; with 7 the 8th attach (one line lower: the feeder line above it) is E334."""
    line = FEEDER + "{count}"
    program = PROGRAM.replace("  tool suction\n", "  tool suction\n  " + line.replace("{", "{{").replace("}", "}}") + "\n")
    (tmp_path / "cell.rmot").write_text(CELL.replace(FEEDER + "36\n", ""), encoding="utf-8")
    for count, expected in ((8, []), (7, [("E334", ATTACH_LINE + 1)])):
        path = tmp_path / "pallet.rmot"
        path.write_text(program.format(offset="0mm").replace("{count}", str(count)), encoding="utf-8")
        result = load_program(str(path), require_program=True)
        assert not result.has_errors, [str(d) for d in result.diagnostics]
        assert [p.name for p in result.program.cell.parts if p.feeder] == ["carton"]
        errors = [d for d in verify(plan_program(result.program)).diagnostics if d.is_error]
        assert [(d.code.id, d.span.start.line) for d in errors] == expected


def test_a_feeder_inside_a_loop_or_named_like_a_cell_part_is_refused(tmp_path: Path) -> None:
    (tmp_path / "cell.rmot").write_text(CELL, encoding="utf-8")
    nested = PROGRAM.replace("      for col in 0 .. 2 {{\n", "      for col in 0 .. 2 {{\n        " + FEEDER + "3\n")
    twice = PROGRAM.replace("  tool suction\n", "  tool suction\n  " + FEEDER + "3\n")
    for text, code in ((nested, "E115"), (twice, "E102")):
        path = tmp_path / "pallet.rmot"
        path.write_text(text.format(offset="0mm"), encoding="utf-8")
        found = [d.code.id for d in load_program(str(path), require_program=True).diagnostics if d.is_error]
        assert code in found, found
