"""Further cases: if-variants, mesh fixtures (hull then triangles), static contacts, solids
that always touch by construction, and the plan's own diagnostics in the report."""

from __future__ import annotations

import numpy as np
import trimesh
from simkit import arm3, box, cell, line_span, make_plan, source, task_plan

from rmot.lang import ir, plan_types
from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.sim import codes
from rmot.sim.scene import build_scene
from rmot.sim.verification import verify_with

POST = ((0.05, 0.05, 0.05), (0.0, 0.0, 1.2))  # in link3's way when the arm swings upright


def _codes(report, code):
    return [d for d in report.diagnostics if d.code.id == code.id]


def test_if_variant_is_verified() -> None:
    """A collision only in the `otherwise` arm is found, at that arm's move (line 20)."""
    file = source()
    c = cell([("r1", (0, 0, 0))], fixtures=[box("post", *POST)])
    main = task_plan("main", "r1", [(0, -1, 0), (0, -1.2, 0)], [1.0], file)  # the `then` arm: clear
    arm = task_plan("arm", "r1", [(0, -1, 0), (0, 1, 0.2)], [1.0], file, first_line=20, first_uid=20)
    records = main.records + tuple(plan_types.InstructionRecord(r.uid, r.span, r.t_start, r.t_end, variant=1) for r in arm.records)
    variant = plan_types.Variant(1, if_uid=99, arm="otherwise", trajectory=arm.trajectory)
    task = ir.Task("main", "r1", main.task.body + arm.task.body)
    tp = plan_types.TaskPlan(task, "r1", main.trajectory, records, (variant,))
    report = verify_with(make_plan(c, [tp], file), robots={"r1": arm3("r1")})
    hits = _codes(report, codes.COLLISION)
    assert len(hits) == 1
    assert hits[0].span.start.line == 20
    assert hits[0].message.endswith("(on the path through the 'otherwise' arm of the if)")


def _l_shape_mesh(path) -> ir.Mesh:
    """An L in the x-z plane: a floor slab x 0..0.3, z 0..0.05 and a wall x 0.25..0.3, z 0..0.3
    (0.05 m thick in y). Its convex hull fills the notch between them; the mesh does not."""
    a = trimesh.creation.box((0.3, 0.05, 0.05), trimesh.transformations.translation_matrix((0.15, 0, 0.025)))
    b = trimesh.creation.box((0.05, 0.05, 0.3), trimesh.transformations.translation_matrix((0.275, 0, 0.15)))
    trimesh.util.concatenate([a, b]).export(path)
    return ir.Mesh(str(path), 1.0)


def test_mesh_fixture_confirmed_on_triangles(tmp_path) -> None:
    """A ball moving through the L's notch touches its hull but not its triangles: no finding;
    moved onto a slab it is a collision."""
    mesh = _l_shape_mesh(tmp_path / "ell.stl")
    robot = arm3("r1")
    half = np.pi / 2

    def report(height: float):
        file = source()
        # the arm lies along +x at z = 0.4 and turns about J1; the ball hangs 0.1 m below the
        # flange (x = 0.9, z = 0.3 at J1 = 0), over the floor slab and 3 cm short of the wall
        fixture = ir.Fixture("ell", mesh, ir.Pose((0.7, 0.0, height)))
        tool = ir.Tool("ball", "r1", ir.Sphere(0.02), ir.Pose(), geometry_pose=ir.Pose((0.1, 0.0, 0.0)))
        c = cell([("r1", (0, 0, 0))], fixtures=[fixture], tools=[tool])
        tp = task_plan("main", "r1", [(-0.3, half, 0), (0.3, half, 0)], [1.0], file, tool=ir.ToolRef("ball"))
        return verify_with(make_plan(c, [tp], file), robots={"r1": robot})

    assert _codes(report(0.1), codes.COLLISION) == []  # ball in the notch: hull only
    hits = _codes(report(0.24), codes.COLLISION)  # floor slab top at 0.29: 1 cm into the ball
    assert [h.bodies for h in hits] == [("ball", "ell")]


def test_static_overlap_is_one_warning() -> None:
    """A fixture 1 cm into the robot's fixed base (clear of the moving links): one W300, no error."""
    file = source()
    c = cell([("r1", (0, 0, 0))], fixtures=[box("plinth", (0.04, 0.04, 0.04), (0.09, 0.0, 0.02))])
    tp = task_plan("main", "r1", [(0, 0.5, 0), (0.5, 0.5, 0)], [1.0], file)
    report = verify_with(make_plan(c, [tp], file), robots={"r1": arm3("r1")})
    hits = _codes(report, codes.STATIC_CONTACT)
    assert [h.bodies for h in hits] == [("r1/base", "plinth")] and hits[0].severity is Severity.WARNING
    assert not report.has_errors


def test_always_touching_solids_are_not_findings() -> None:
    """Solids that touch at every configuration by construction (link2 and link3 meet at J3)
    but are missing from the robot's adjacent pairs are excluded, as MoveIt's "always in
    collision" pairs; pairs that touch only sometimes are still checked."""
    robot = arm3("r1")
    robot.adjacent_pairs = ((0, 1), (1, 2), (0, 2))  # (2, 3) left out
    scene = build_scene(cell([("r1", (0, 0, 0))]), {}, {"r1": robot})
    assert scene.always_touching == frozenset({frozenset({"r1/link2", "r1/link3"})})
    file = source()
    tp = task_plan("main", "r1", [(0, 0, 0), (0.5, 0.5, 0.5)], [1.0], file)
    report = verify_with(make_plan(scene.cell, [tp], file), robots={"r1": robot})
    assert report.diagnostics == ()


def test_plan_diagnostics_are_reported_first() -> None:
    """The Plan's own diagnostics come first in the report, unchanged."""
    file = source()
    c = cell([("r1", (0, 0, 0))])
    tp = task_plan("main", "r1", [(0, 0, 0), (0.2, 0, 0)], [1.0], file)
    own = Diagnostic(Code("E299", "test-plan-finding", "a planner finding for this test"), Severity.ERROR,
                     "target must be reachable (got 1.2 m away)", line_span(file, 2))
    plan = plan_types.Plan(make_plan(c, [tp], file).program, (tp,), diagnostics=(own,))
    report = verify_with(plan, robots={"r1": arm3("r1")})
    assert report.diagnostics == (own,) and report.has_errors
