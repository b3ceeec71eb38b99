"""One registry per concept: the backend registry is the only list of vendors, and
every table keyed by ir.MotionKind (each backend's MOVES, the planner's segment builders) has
a handler for each kind, checked at import.

* A toy backend (one small class below, one `register` line) compiles a program end to end
  through the real `rmot compile` command, and the front end accepts `native toy { }`.
* vendor x kind: every registered backend prints each motion kind with that kind's handler.
* A motion kind without a handler fails loudly in every backend and in the planner.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from enum import Enum
from pathlib import Path

import numpy as np
import pytest
from backend_fixtures import FRONT_UP_NOFLIP, hand_plan, motion
from click.testing import CliRunner, Result

from rmot import backends
from rmot.backends import BACKENDS, controllers, targets
from rmot.backends.base import Backend, TaskContext
from rmot.lang import ir, plan_types
from rmot.compiler.cli import cli
from rmot.lang.motion_kinds import MissingMotionHandler, require_handlers


def _line(letter: str, rec: plan_types.InstructionRecord) -> str:
    assert rec.tcp_pose is not None
    return letter + " " + " ".join(f"{v * 1000.0:.1f}" for v in rec.tcp_pose.position)


class ToyBackend(Backend):
    """A controller language of one line per move: `J|L|C x y z` in mm."""

    name = "toy"
    file_ext = ".toy"

    def emit_task(self, ctx: TaskContext) -> dict[str, str]:
        _, program, body = self.open_task(ctx)
        return {program + self.file_ext: "\n".join(self.body(body, ctx)) + "\n"}

    def move(self, node: ir.Move, ctx: TaskContext) -> list[str]:
        rec = self.move_record(node, ctx)
        return rec if isinstance(rec, list) else self.by_kind(node)(rec)

    def move_joint(self, rec: plan_types.InstructionRecord) -> list[str]:
        return [_line("J", rec)]

    def move_linear(self, rec: plan_types.InstructionRecord) -> list[str]:
        return [_line("L", rec)]

    def move_circular(self, rec: plan_types.InstructionRecord) -> list[str]:
        return [_line("C", rec)]

    def set_digital(self, node: ir.SetDigital, ctx: TaskContext) -> list[str]:
        return [f"OUT {node.port} {int(node.value)}"]


PROGRAM = """
program toy_demo on r1 {
  tool gripper
  frame table_top
  speed 250 mm/s
  move joint joints(0, -20, 30, 0, 50, 0) deg
  move linear pose(x=100mm, y=-50mm, z=150mm, rx=180deg)
  move circular via pose(x=150mm, y=0mm, z=150mm, rx=180deg)
    to pose(x=100mm, y=50mm, z=150mm, rx=180deg)
  set out[1] = on
  native toy "BEEP"
}
"""


def _compile(src: Path, out: Path) -> Result:
    return CliRunner().invoke(cli, ["compile", str(src), "--target", "toy", "-o", str(out)])


@pytest.fixture
def toy() -> Iterator[None]:
    backends.register("toy", ToyBackend)  # the one registration line a new backend needs
    yield
    backends.unregister("toy")


class TestToyBackend:
    def test_compiles_end_to_end(self, toy: None, tmp_path: Path) -> None:
        """`rmot compile --target toy` accepts the new target, the front end accepts its native
        block, and the file holds one line per move, its kind's letter first."""
        src = tmp_path / "toy_demo.rmot"
        src.write_text(PROGRAM, encoding="utf-8")
        result = _compile(src, tmp_path / "out")
        assert result.exit_code == 0, result.output
        lines = (tmp_path / "out" / "toy" / "toy_demo.toy").read_text().splitlines()
        words = [ln.split()[0] for ln in lines if not ln.startswith("#")]
        assert words == ["J", "L", "C", "OUT", "BEEP"]
        # the linear move ends at the programmed pose (the table_top frame puts it elsewhere in
        # the base frame, so only the arc's and the line's common height is compared)
        z = {ln.split()[0]: float(ln.split()[3]) for ln in lines if ln[:1] in "LC"}
        assert z["L"] == pytest.approx(z["C"], abs=0.05)

    def test_registry_lists_it_everywhere(self, toy: None) -> None:
        assert "toy" in targets() and "toy" in controllers() and BACKENDS["toy"] is ToyBackend

    def test_without_registration_it_is_unknown(self, tmp_path: Path) -> None:
        """Unregistered, the same program is refused by the front end (E116) and the CLI."""
        src = tmp_path / "toy_demo.rmot"
        src.write_text(PROGRAM, encoding="utf-8")
        result = _compile(src, tmp_path / "out")
        assert result.exit_code == 2 and "toy" in result.output
        result = CliRunner().invoke(cli, ["check", str(src)])
        assert "E116" in result.output


class TestRegistry:
    def test_every_target_loads_its_named_class(self) -> None:
        assert targets() and set(controllers()) < set(targets())
        for name in targets():
            assert BACKENDS[name].name == name

    def test_registering_twice_is_refused(self) -> None:
        with pytest.raises(ValueError, match="registered twice"):
            backends.register(targets()[0], ToyBackend)

    def test_wrong_class_is_refused(self, toy: None) -> None:
        backends.register("toy2", "rmot.backends.rapid:RapidBackend")
        try:
            with pytest.raises(TypeError, match="whose name is 'rapid'"):
                BACKENDS["toy2"]
        finally:
            backends.unregister("toy2")


# --------------------------------------------------------------------------- vendor x kind

KIND_MOVES = {
    ir.MotionKind.JOINT: "move joint joints(10, -25, 35, 0, 45, 0) deg",
    ir.MotionKind.LINEAR: "move linear pose(x=100mm, y=-50mm, z=150mm, rx=180deg)",
    ir.MotionKind.CIRCULAR: ("move circular via pose(x=150mm, y=0mm, z=150mm, rx=180deg) "
                             "to pose(x=100mm, y=50mm, z=150mm, rx=180deg)"),
}


def _kind_program(kind: ir.MotionKind) -> str:
    return ("program kinds on r1 {\n  tool gripper\n  frame table_top\n  speed 250 mm/s\n"
            f"  move joint joints(0, -20, 30, 0, 50, 0) deg\n  {KIND_MOVES[kind]}\n}}\n")


def test_kind_moves_cover_every_kind() -> None:
    require_handlers("this test's KIND_MOVES", KIND_MOVES)


def _printing_targets() -> list[str]:
    return [t for t in targets() if "MOVES" in BACKENDS[t].kind_tables()]


@pytest.mark.parametrize("kind", list(ir.MotionKind), ids=lambda k: k.name.lower())
@pytest.mark.parametrize("target", _printing_targets())
def test_vendor_prints_each_kind_with_its_handler(
        target: str, kind: ir.MotionKind, plan_from_text: Callable[..., plan_types.Plan],
        monkeypatch: pytest.MonkeyPatch) -> None:
    """A program with a joint move then one move of `kind`: the backend calls its MOVES handler
    for `kind` exactly once (the joint handler once more for the first move), nothing else,
    and reports no error."""
    cls = BACKENDS[target]
    calls: list[ir.MotionKind] = []
    for k, method in cls.MOVES.items():
        real = getattr(cls, method)

        def spy(self: Backend, *args: object, _k: ir.MotionKind = k,
                _real: object = real) -> list[str]:
            calls.append(_k)
            return _real(self, *args)  # type: ignore[operator, no-any-return]

        monkeypatch.setattr(cls, method, spy)
    result = cls().emit(plan_from_text(_kind_program(kind), f"kinds_{kind.name.lower()}.rmot"))
    assert not result.has_errors, [d.message for d in result.diagnostics]
    by_name = sorted(calls, key=lambda k: k.name)
    assert by_name == sorted([ir.MotionKind.JOINT, kind], key=lambda k: k.name)


# ------------------------------------------------------------------ a kind without handlers

Extended = Enum("Extended", [*(k.name for k in ir.MotionKind), "SPLINE"])  # type: ignore[misc]


@pytest.mark.parametrize("target", targets())
def test_new_kind_without_handler_fails_in_every_backend(target: str) -> None:
    """Every registered backend with a kind table refuses a kind it has no handler for (the
    check `Backend.__init_subclass__` runs at import); the csv writer alone prints samples,
    whatever the kind, and declares no table."""
    cls = BACKENDS[target]
    cls.validate_kinds()  # complete for today's kinds
    if not cls.kind_tables():
        assert target not in controllers()
        return
    with pytest.raises(MissingMotionHandler, match="SPLINE"):
        cls.validate_kinds(Extended)


def test_new_kind_without_handler_fails_in_the_planner() -> None:
    from rmot.compiler.plan import segments

    require_handlers("planner", segments._TCP_PATHS)
    with pytest.raises(MissingMotionHandler, match="planner.*SPLINE"):
        require_handlers("planner", segments._TCP_PATHS, Extended)


def test_a_backend_missing_a_handler_fails_when_looked_up() -> None:
    """A backend outside rmot.backends (the package's own fail at import) is checked when the
    registry hands it out."""
    class Half(Backend):
        name = "half"

        def move_joint(self) -> list[str]:
            return []

        def move_linear(self) -> list[str]:
            return []

    backends.register("half", Half)
    try:
        with pytest.raises(MissingMotionHandler, match="move_circular"):
            BACKENDS["half"]
    finally:
        backends.unregister("half")


@pytest.mark.parametrize("target", _printing_targets())
def test_circular_without_via_is_e451_everywhere(target: str) -> None:
    """One meaning, one code: a circular move built without its via point (only an IR made by
    hand can be) is E451 circular-via-missing for every vendor, never printed."""
    q = np.array([0.0, -0.3, 0.5, 0.0, 0.9, 0.0])
    lead = ir.Move(uid=1, kind=ir.MotionKind.JOINT, target=ir.JointTarget(tuple(q)),
                   via=None, motion=motion(), tool=ir.ToolRef("t0", ir.Pose((0, 0, 0.1))),
                   frame=ir.FrameRef("world", ir.Pose()))
    pose = ir.Pose((0.4, 0.0, 0.3), (0.0, 1.0, 0.0, 0.0))
    arc = ir.Move(uid=2, kind=ir.MotionKind.CIRCULAR, target=ir.CartesianTarget(pose, pose, "p2"),
                  via=None, motion=motion(), tool=lead.tool, frame=lead.frame)
    plan = hand_plan((lead, arc), {1: (q, FRONT_UP_NOFLIP), 2: (q, FRONT_UP_NOFLIP)})
    result = BACKENDS[target]().emit(plan)
    assert "E451" in {d.code.id for d in result.diagnostics if d.is_error}
