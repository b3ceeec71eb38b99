"""The server's features in process, on examples/pick_place.rmot (which imports
examples/lib/moves.rmot and runs in the default cell).

Witnesses: a half-typed program is every prefix of a real one (nothing may raise); a unit's
SI value is hand arithmetic; references are a word search of the files' text; the pose a
hover shows in world is the forward kinematics of the joints the same hover shows (the
pose comes from the written target, the joints from the planner's IK: two paths).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from lsprotocol import types as lsp

from rmot.compiler.lsp import features
from rmot.compiler.lsp.analysis import Analysis, analyze
from rmot.compiler.lsp.planning import PlanJob, PlanResult, plan_document

ROOT = Path(__file__).resolve().parents[2]
PICK = ROOT / "examples" / "pick_place.rmot"
MOVES = ROOT / "examples" / "lib" / "moves.rmot"
TEXT = PICK.read_text(encoding="utf-8")
LINES = TEXT.split("\n")


def _pos(needle: str, offset: int = 0, occurrence: int = 0) -> lsp.Position:
    """The 0-based position of the `occurrence`-th `needle` in pick_place (+ offset chars)."""
    hits = [(i, m.start()) for i, line in enumerate(LINES) for m in re.finditer(re.escape(needle), line)]
    line, col = hits[occurrence]
    return lsp.Position(line, col + offset)


@pytest.fixture(scope="module")
def analysis() -> Analysis:
    return analyze(str(PICK), TEXT)


@pytest.fixture(scope="module")
def plan() -> PlanResult:
    return plan_document(str(PICK), TEXT)


def test_every_prefix_answers_without_raising() -> None:
    """A program typed from the top: each prefix (cut inside lines too) gets diagnostics and
    every feature answers (a value or nothing), never an exception."""
    cuts = sorted({*range(0, len(TEXT), 97), *(i for i, c in enumerate(TEXT) if c == "\n")})
    for cut in cuts[::3]:
        text = TEXT[:cut]
        a = analyze(str(PICK), text)
        lines = text.split("\n")
        end = lsp.Position(len(lines) - 1, len(lines[-1]))
        features.hover(a, None, end)
        features.definition(a, end)
        features.completion(a, text, end)
        features.document_symbols(a)
        features.inlay_hints(a, None, lsp.Range(lsp.Position(0, 0), end))


def test_unit_literal_hover_gives_si(analysis: Analysis) -> None:
    hover = features.hover(analysis, None, _pos("400 mm/s", 5))
    assert hover is not None and "0.4 m/s" in hover.contents.value  # type: ignore[union-attr]
    hover = features.hover(analysis, None, _pos("90, 0) deg", 8))
    # joints(...) deg: the unit of the whole vector; 1 deg = pi/180 rad
    assert hover is not None and f"{math.pi / 180:.6g} rad" in hover.contents.value  # type: ignore[union-attr]


def test_references_of_an_imported_const_match_a_word_search(analysis: Analysis) -> None:
    found = features.references(analysis, lsp.Position(0, 0), True)
    assert found == []
    # `approach_height` is used in moves.rmot only; ask from its declaration there
    decl = next(s for s in analysis.index.declarations if s.name == "approach_height")
    refs = analysis.index.references(decl)
    words = [(i + 1, m.start() + 1) for i, line in enumerate(MOVES.read_text().split("\n"))
             for m in re.finditer(r"\bapproach_height\b", line.split("#")[0])]
    assert sorted((r.span.start.line, r.span.start.col) for r in refs) == words


def test_io_port_goes_to_the_cells_declaration(analysis: Analysis) -> None:
    (location,) = features.definition(analysis, _pos("in[2]", 1))
    assert location.uri.endswith("compiler/default_cell.rmot")
    cell_line = (ROOT / "compiler" / "default_cell.rmot").read_text().split("\n")[location.range.start.line]
    assert re.match(r"\s*io in\[2\]\s*=", cell_line)


def test_local_target_and_frame_definitions(analysis: Analysis) -> None:
    (home,) = features.definition(analysis, _pos("move joint home", 12))
    assert home.range.start.line == _pos("target home").line
    (frame,) = features.definition(analysis, _pos("      frame pallet", 13))
    assert frame.uri.endswith("default_cell.rmot")


def test_outline_lists_the_program_and_its_targets(analysis: Analysis) -> None:
    (program,) = features.document_symbols(analysis)
    assert program.name == "pick_place" and program.kind == lsp.SymbolKind.Module
    assert [c.name for c in program.children or []] == ["home", "nest", "slot0", "pitch"]


def test_completion_kinds(analysis: Analysis) -> None:
    line = _pos("move joint home zone fine").line
    labels = {i.label for i in features.completion(analysis, TEXT, lsp.Position(line, 2))}
    assert {"move", "wait", "for", "set"} <= labels and "grasp" in labels  # statement start + procs
    text = TEXT.replace("speed 400 mm/s", "speed 400 ")
    units = {i.label for i in features.completion(analysis, text, _pos("speed 400 mm/s", 10))}
    assert {"mm/s", "m/s", "deg"} <= units and "home" not in units
    # a space typed elsewhere (the trigger character) offers nothing: no popup after every word
    assert features.completion(analysis, TEXT, _pos("tool gripper", 5), typed_space=True) == []
    assert features.completion(analysis, TEXT, _pos("tool gripper", 5)) != []


def test_hover_on_a_target_shows_joints_that_reach_its_world_pose(analysis: Analysis, plan: PlanResult) -> None:
    from rmot.sim.robots import load_robot

    hover = features.hover(analysis, plan, _pos("grasp(nest)", 7))
    assert hover is not None
    text = hover.contents.value  # type: ignore[union-attr]
    block = text[text.index("in world"):]
    world = [float(v) for v in re.search(r"x=(\S+) y=(\S+) z=(\S+) mm", block).groups()]  # type: ignore[union-attr]
    joints = [math.radians(float(v)) for v in re.findall(r"J\d (-?[0-9.]+)°", block.split("\n**move")[0])]
    assert len(joints) == 6
    cell = analysis.cell
    assert cell is not None
    robot = cell.robots[0]
    flange = load_robot(robot.source.ref).fk(np.array(joints))
    tcp = next(t for t in cell.tools if t.name == "gripper").tcp.matrix()
    tip = robot.base.matrix() @ flange @ tcp
    assert np.allclose(tip[:3, 3] * 1000, world, atol=0.5)
    assert "time:" in text and "configuration:" in text


def test_inlay_hints_give_each_moves_duration(analysis: Analysis, plan: PlanResult) -> None:
    window = lsp.Range(lsp.Position(0, 0), lsp.Position(len(LINES), 0))
    hints = features.inlay_hints(analysis, plan, window)
    lines = {h.position.line for h in hints}
    assert _pos("move joint home").line in lines and _pos("grasp(nest)").line in lines
    durations = {m.uid: m.t_end - m.t_start for m in plan.moves}
    last = next(h for h in hints if h.position.line == _pos("move joint home zone fine").line)
    moves = [m for t in analysis.program.tasks for m in t.body if getattr(m, "span", None)  # type: ignore[union-attr]
             and m.span.start.line == last.position.line + 1]
    assert f"{durations[moves[0].uid]:.2f} s" in str(last.label)


def test_hover_on_a_proc_call_lists_the_moves_of_its_body(analysis: Analysis, plan: PlanResult) -> None:
    hover = features.hover(analysis, plan, _pos("grasp(nest)", 2))
    assert hover is not None
    text = hover.contents.value  # type: ignore[union-attr]
    assert text.startswith("**proc** `grasp`") and "lib/moves.rmot" in text
    # grasp = approach (joint + linear) then retract (linear), inlined once per loop iteration
    assert "**move joint**" in text and "**move linear**" in text and "more instances" in text


def test_a_cancelled_plan_job_answers_none() -> None:
    job = PlanJob(str(PICK), TEXT)
    job.cancel()
    assert job.result() is None


def test_an_error_in_an_imported_file_is_shown_at_the_import(tmp_path: Path) -> None:
    (tmp_path / "lib.rmot").write_text("const slow = 100 mm/s\nconst fast = 3 * slwo\n", encoding="utf-8")
    text = 'import "lib.rmot"\n\nprogram p on r1 {\n  move joint joints(0, 0, 0, 0, 90, 0) deg\n}\n'
    a = analyze(str(tmp_path / "main.rmot"), text)
    (typo,) = [a.to_lsp(d) for d in a.diagnostics if d.code.id == "E101"]
    assert (typo.range.start.line, typo.range.start.character) == (0, 0)  # the `import` line
    (inside,) = typo.related_information or []
    assert inside.location.uri == (tmp_path / "lib.rmot").as_uri()
    assert (inside.location.range.start.line, inside.location.range.start.character) == (1, 17)


def test_hover_gives_the_joint_limit_margin_at_the_target(analysis: Analysis, plan: PlanResult) -> None:
    """The margin shown for `home` = joints(0, -10, 10, 0, 90, 0) deg, against the IRB 1600's
    ranges as the robot library gives them (the worst joint recomputed here)."""
    from rmot.sim.robots import load_robot

    hover = features.hover(analysis, plan, _pos("move joint home", 12))
    assert hover is not None
    shown = re.search(r"margin: J(\d) is ([0-9.]+)°", hover.contents.value)  # type: ignore[union-attr]
    assert shown is not None
    limits = load_robot("abb_irb1600").joint_limits
    home = np.radians([0, -10, 10, 0, 90, 0])
    margins = np.minimum(home - limits[:, 0], limits[:, 1] - home)
    assert int(shown.group(1)) == int(np.argmin(margins)) + 1
    assert float(shown.group(2)) == pytest.approx(math.degrees(margins.min()), abs=0.06)


@pytest.mark.parametrize("needle, offset, declared", [
    ("program pick_place on r1", 22, r"\s*robot r1 = "),        # a robot, in the cell
    ("  tool gripper", 8, r"\s*tool gripper = "),               # a tool, in the cell
    ("grasp(nest)", 1, r"proc grasp\("),                         # a proc, in the import
])
def test_definitions_across_use_cell_and_import(analysis: Analysis, needle: str, offset: int, declared: str) -> None:
    (location,) = features.definition(analysis, _pos(needle, offset))
    path = location.uri[len("file://"):]
    line = Path(path).read_text(encoding="utf-8").split("\n")[location.range.start.line]
    assert re.match(declared, line), line
