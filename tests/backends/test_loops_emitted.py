"""Vendor loops as emitted: the emitted RAPID / KRL / URScript loop, run by the
witness interpreters of loop_witness.py (written from the manuals, not from the backends),
moves to exactly the poses the planner verified for every iteration; loops that cannot be one
vendor loop are unrolled with W420 naming the iteration; `--unroll` writes every iteration;
golden files for a loop program and a tending program, each checked by the independent
validators of test_vendor_validators.py (rapidchecker, krllint + check_krl, check_urscript)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from backend_fixtures import FRONT_UP_NOFLIP, check_golden, example_plans
from click.testing import CliRunner
from loop_fixtures import Q0, palletiser, place
from loop_witness import krl_targets, rapid_targets, ur_targets
from test_vendor_validators import findings

from rmot.backends import BACKENDS
from rmot.lang import ir, ir_tree, plan_types

PROGRAMS = Path(__file__).parent / "programs"
LOOP_VENDORS = ("rapid", "krl", "urscript")


def verified_poses(
    plan: plan_types.Plan, *, cartesian_only: bool
) -> list[tuple[np.ndarray, np.ndarray] | None]:
    """The TCP pose (base frame) the planner verified at every move of the main timeline, in
    execution order (None for a joint-target move when not `cartesian_only`)."""
    tp = plan.tasks[0]
    moves = {n.uid: n for n in ir_tree.walk(tp.task.body) if isinstance(n, ir.Move)}
    recs = sorted(
        (r for r in tp.records if r.variant == 0 and r.uid in moves and r.q_target is not None),
        key=lambda r: r.t_start,
    )
    out: list[tuple[np.ndarray, np.ndarray] | None] = []
    for r in recs:
        cart = isinstance(moves[r.uid].target, ir.CartesianTarget)
        if cart:
            assert r.tcp_pose is not None
            out.append((np.array(r.tcp_pose.position), r.tcp_pose.matrix()[:3, :3]))
        elif not cartesian_only:
            out.append(None)
    return out


def witness(vendor: str, files: dict[str, str]) -> list[tuple[np.ndarray, np.ndarray] | None]:
    if vendor == "rapid":
        return list(rapid_targets(next(iter(files.values()))))
    if vendor == "krl":
        src = next(n for n in files if n.endswith(".src"))
        return list(krl_targets(files[src], files[src[:-4] + ".dat"]))
    return ur_targets(next(iter(files.values())))


def assert_same_poses(
    vendor: str, files: dict[str, str], plan: plan_types.Plan, tol: float = 2e-6
) -> None:
    got = witness(vendor, files)
    want = verified_poses(plan, cartesian_only=vendor != "urscript")
    assert len(got) == len(want), (len(got), len(want))
    for k, (g, w) in enumerate(zip(got, want, strict=True)):
        if g is None or w is None:
            assert g is None and vendor == "urscript", k  # a movej to the planned joints
            continue
        assert np.linalg.norm(g[0] - w[0]) < tol, (k, g[0], w[0])
        assert np.abs(g[1] - w[1]).max() < 1e-5, (k, g[1], w[1])


def emit(vendor: str, plan: plan_types.Plan, **kw: bool):  # type: ignore[no-untyped-def]
    return BACKENDS[vendor](**kw).emit(plan)


def w420(result) -> list[str]:  # type: ignore[no-untyped-def]
    return [d.message for d in result.diagnostics if d.code.id == "W420"]


# --------------------------------------------------------------------------- the shipped palletiser


@pytest.fixture(scope="module")
def pallet_plan() -> plan_types.Plan:
    return example_plans(("palletizing",))["palletizing"]


@pytest.mark.parametrize("vendor", LOOP_VENDORS)
def test_palletiser_loops_reach_every_verified_placement(
    pallet_plan: plan_types.Plan, vendor: str
) -> None:
    """The 3x4x3 palletiser: the emitted loops, run by the witness, give the 36 placements'
    verified poses in order (and every pick, approach and retreat between them)."""
    result = emit(vendor, pallet_plan)
    assert not result.has_errors
    assert_same_poses(vendor, result.files, pallet_plan)


def test_palletiser_rapid_is_a_few_dozen_moves(pallet_plan: plan_types.Plan) -> None:
    """The palletiser as one program: RAPID with no more than a few dozen moves (216
    unrolled), nested FOR loops with Offs on the slot targets."""
    text = next(iter(emit("rapid", pallet_plan).files.values()))
    moves = [ln for ln in text.splitlines() if ln.strip().startswith("Move")]
    assert len(moves) <= 36, len(moves)
    assert "FOR layer FROM 0 TO 1 DO" in text and "FOR row FROM 0 TO 3 DO" in text
    assert "FOR col FROM 0 TO 2 DO" in text
    assert "Offs(" in text and "col*190" in text and "row*90" in text and "layer*100" in text
    # the payload follows the carton in the gripper inside the loop: GripLoad at each attach and detach
    body = text[text.index("FOR col FROM 0 TO 2 DO"):]
    assert "GripLoad" in body.split("ENDFOR")[0], body[:2000]


@pytest.mark.parametrize("vendor", LOOP_VENDORS)
def test_palletiser_unroll_option(pallet_plan: plan_types.Plan, vendor: str) -> None:
    """--unroll writes every iteration: no vendor loop, no W420, the same verified poses."""
    result = emit(vendor, pallet_plan, unroll=True)
    text = "\n".join(result.files.values())
    assert not any(w in text for w in ("FOR layer", "FOR row", "FOR col", "FOR col=", "while col"))
    assert w420(result) == []
    assert_same_poses(vendor, result.files, pallet_plan)


def test_compile_unroll_flag(tmp_path: Path) -> None:
    """`rmot compile --unroll` reaches the backends (threaded through compile_program)."""
    src = PROGRAMS / "rows.rmot"
    looped, unrolled = tmp_path / "a", tmp_path / "b"
    r1 = CliRunner().invoke(
        _cli(), ["compile", str(src), "--target", "rapid", "--no-cache", "-o", str(looped)]
    )
    r2 = CliRunner().invoke(
        _cli(),
        ["compile", str(src), "--target", "rapid", "--unroll", "--no-cache", "-o", str(unrolled)],
    )
    assert r1.exit_code == 0 and r2.exit_code == 0, (r1.output, r2.output)
    a, b = (p / "rapid" / "rows.mod" for p in (looped, unrolled))
    assert "FOR layer FROM 1 TO 2 DO" in a.read_text() and "FOR " not in b.read_text()
    assert b.read_text().count("MoveL ") == 12 and a.read_text().count("MoveL ") == 2


def _cli():  # type: ignore[no-untyped-def]
    from rmot.compiler.cli import cli

    return cli


# --------------------------------------------------------------------------- hand-built nests


def rotated_frame() -> ir.FrameRef:
    """A pallet frame turned 30 deg about z and tilted 10 deg about x (offsets are in it)."""
    pose = ir.Pose.from_xyz_rpy(0.45, -0.1, 0.02, math.radians(10), 0, math.radians(30))
    return ir.FrameRef("pallet", pose, pose)


@pytest.mark.parametrize("vendor", LOOP_VENDORS)
def test_offsets_are_in_the_moves_frame(vendor: str) -> None:
    """In a rotated frame the step is along the frame's axes: RAPID Offs (work object), KRL
    component arithmetic (in $BASE), URScript pose_add (base frame, the step turned by the
    frame): the witness gives the hand-built poses of every iteration."""
    plan, _ = palletiser(3, 4, frame=rotated_frame())
    result = emit(vendor, plan)
    assert not result.has_errors and w420(result) == []
    assert_same_poses(vendor, result.files, plan)


def test_loop_not_starting_at_zero() -> None:
    """A loop from 1: the offset counts from the first value ((layer - 1)*step)."""
    plan = example_rows()
    text = next(iter(emit("rapid", plan).files.values()))
    assert "FOR layer FROM 1 TO 2 DO" in text and "(layer - 1)*30" in text
    assert_same_poses("rapid", emit("rapid", plan).files, plan)


def example_rows() -> plan_types.Plan:
    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan import plan_program

    front = load_program(str(PROGRAMS / "rows.rmot"))
    assert front.program is not None
    return plan_program(front.program)


@pytest.mark.parametrize("vendor", LOOP_VENDORS)
def test_other_orientation_is_unrolled_with_the_iteration_named(vendor: str) -> None:
    turned = ir.Pose.from_xyz_rpy(0, 0, 0, math.pi, 0, math.pi / 2).quaternion
    down = place(0, 0, 0).quaternion
    plan, _ = palletiser(
        2, 3, pose=lambda a, b: place(0.1, 0.06 * b, 0.05 * a, turned if (a, b) == (0, 1) else down)
    )
    result = emit(vendor, plan)
    messages = w420(result)
    assert any("layer = 0, row = 1" in m and "orientation" in m for m in messages), messages
    text = "\n".join(result.files.values())
    assert "FOR layer" not in text and "while layer" not in text
    assert_same_poses(vendor, result.files, plan)


@pytest.mark.parametrize("vendor", LOOP_VENDORS)
def test_other_ik_branch_is_unrolled_with_the_iteration_named(vendor: str) -> None:
    down = ir.Config(ir.Shoulder.FRONT, ir.Elbow.DOWN, ir.Wrist.NOFLIP)
    plan, _ = palletiser(2, 2, branch=lambda a, b: down if (a, b) == (1, 0) else FRONT_UP_NOFLIP)
    result = emit(vendor, plan)  # URScript: get_inverse_kin near the first iteration's joints
    messages = w420(result)
    assert any("layer = 1, row = 0" in m and "configuration" in m for m in messages), messages
    assert_same_poses(vendor, result.files, plan)


def test_rapid_other_turn_of_axis_6_is_unrolled() -> None:
    """A full turn of axis 6 in one iteration: cf6 four quadrants away (RAPID cannot write one
    robtarget for both)."""
    turned = Q0.copy()
    turned[5] -= 2 * math.pi
    plan, _ = palletiser(2, 2, q=lambda a, b: turned if (a, b) == (0, 1) else Q0)
    result = emit("rapid", plan)
    assert any("layer = 0, row = 1" in m for m in w420(result)), w420(result)


# --------------------------------------------------------------------------- golden files


@pytest.fixture(scope="module")
def program_plans() -> dict[str, plan_types.Plan]:
    from rmot.compiler.frontend import load_program
    from rmot.compiler.plan import plan_program

    out = {}
    for name in ("rows", "tending"):
        front = load_program(str(PROGRAMS / f"{name}.rmot"))
        assert front.program is not None, [d.message for d in front.diagnostics]
        out[name] = plan_program(front.program)
    return out


@pytest.mark.parametrize("vendor", LOOP_VENDORS)
@pytest.mark.parametrize("name", ["rows", "tending"])
def test_golden_runtime_programs(
    program_plans: dict[str, plan_types.Plan], name: str, vendor: str, tmp_path: Path
) -> None:
    """Hand-reviewed golden files (golden/<vendor>/runtime_<name>__*), each passing the
    vendor's independent validator."""
    result = emit(vendor, program_plans[name])
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    assert findings(vendor, result.files, tmp_path) == []
    check_golden(vendor, f"runtime_{name}", result.files)
