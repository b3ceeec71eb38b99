"""Pictures of a planned program: bodies posed by FK, named as in the simulator, highlights, captions."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image
from render_fixtures import arm3, plan

from rmot.lang.diagnostics import Code, Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span
from rmot.sim.render.scene import HIGHLIGHT, body_poses, prepare
from rmot.sim.render.still import default_camera, finding_caption, frame, render_finding, still_image

SIZE = (160, 120)
FINDING = Code("E300", "collision", "a robot link or tool touches a fixture")


@pytest.fixture(scope="module")
def scene():  # type: ignore[no-untyped-def]
    return prepare(plan(), robots={"r1": arm3()})


def test_bodies_are_named_as_in_the_simulator(scene) -> None:  # type: ignore[no-untyped-def]
    """Fixtures and tools by name, link solids as robot/solid, in the verification scene's order."""
    assert scene.names == ("table", "post", "r1/base", "r1/link1", "r1/link2", "r1/link3", "gripper")


def test_bodies_are_posed_by_forward_kinematics(scene) -> None:  # type: ignore[no-untyped-def]
    """At t, each link sits at solid_poses(q(t)) and the tool at fk(q(t)) times its geometry pose."""
    robot = arm3()
    poses = body_poses(scene, np.array([0.5, 2.0]))
    for k, t in enumerate((0.5, 2.0)):
        q = np.array([-0.6, 0.3, 0.6]) + (t / 2.0) * np.array([1.2, 0.6, 0.3])
        np.testing.assert_allclose(poses[k, 2:6], robot.solid_poses(q), atol=1e-9)
        tool = robot.fk(q) @ np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.06], [0, 0, 0, 1.0]])
        np.testing.assert_allclose(poses[k, 6], tool, atol=1e-9)
        np.testing.assert_allclose(poses[k, 0, :3, 3], [0.8, 0.0, 0.2])


def test_camera_frames_every_body_over_the_whole_program(scene) -> None:  # type: ignore[no-untyped-def]
    """The default camera sees every vertex of every body at every sampled instant."""
    cam = default_camera(scene, SIZE)
    m = cam.matrix(SIZE[0] / SIZE[1])
    for poses in body_poses(scene, np.linspace(0, 2, 9)):
        for mesh, pose in zip(scene.meshes, poses):
            p = mesh.vertices.reshape(-1, 3) @ pose[:3, :3].T + pose[:3, 3]
            clip = np.c_[p, np.ones(len(p))] @ m.T
            assert np.all(np.abs(clip[:, :2]) <= clip[:, 3:4])


def test_highlighted_bodies_turn_red_and_nothing_else_changes(scene) -> None:  # type: ignore[no-untyped-def]
    """Highlighting the table recolours only table pixels, to shades of the highlight red."""
    poses = body_poses(scene, np.array([1.0]))[0]
    cam = default_camera(scene, SIZE)
    plain = frame(scene, poses, cam, SIZE, 1).astype(int)
    red = frame(scene, poses, cam, SIZE, 1, highlight=("table",)).astype(int)
    changed = np.any(plain != red, axis=2)
    assert changed.sum() > 200
    r, g, b = red[changed].T
    assert np.all(r > 2 * g) and np.all(r > 2 * b)
    assert HIGHLIGHT[0] > 3 * HIGHLIGHT[1]


def test_tcp_path_is_drawn_over_the_picture(scene) -> None:  # type: ignore[no-untyped-def]
    """The TCP path overlay adds blue pixels along the projected path, and only there."""
    poses = body_poses(scene, np.array([0.0]))[0]
    cam = default_camera(scene, SIZE)
    without = frame(scene, poses, cam, SIZE, 1, paths=False).astype(int)
    with_path = frame(scene, poses, cam, SIZE, 1).astype(int)
    changed = np.any(without != with_path, axis=2)
    assert changed.sum() > 40
    r, g, b = with_path[changed].T
    assert np.all(b > r)


def test_same_input_gives_the_same_pixels(scene) -> None:  # type: ignore[no-untyped-def]
    """Rendering is deterministic."""
    a = still_image(scene, time=1.3, size=SIZE, aa=2)
    b = still_image(scene, time=1.3, size=SIZE, aa=2)
    np.testing.assert_array_equal(a, b)


def _span(line: int) -> Span:
    f = SourceFile("cell.rmot", "\n" * 20)
    return Span(f, Pos(line, 3), Pos(line, 9))


def test_finding_caption_names_code_line_time_and_message() -> None:
    """The caption reads 'E300 line 12 t=3.21 s: message'."""
    d = Diagnostic(FINDING, Severity.ERROR, "r1/link3 touches table", _span(12), time_s=3.2149)
    assert finding_caption(d) == "E300 line 12 t=3.21 s: r1/link3 touches table"
    assert finding_caption(Diagnostic(FINDING, Severity.ERROR, "x", None)) == "E300: x"


def test_render_finding_writes_a_png_with_the_bodies_in_red_and_a_caption(scene, tmp_path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """The finding's picture: its instant, its bodies in red, a dark caption band at the bottom."""
    import rmot.sim.render.still as still

    monkeypatch.setattr(still, "prepare", lambda p: scene)  # the fake arm is not in the robot library
    d = Diagnostic(FINDING, Severity.ERROR, "r1/link3 touches post", _span(7), time_s=1.0, bodies=("r1/link3", "post"))
    out = tmp_path / "finding.png"
    render_finding(scene.plan, d, str(out), size=(320, 240))
    img = np.asarray(Image.open(out).convert("RGB")).astype(int)
    assert img.shape == (240, 320, 3)
    assert img[-3:, :, :].max() < 60  # the caption band
    top = img[:180]
    assert np.sum((top[..., 0] > 150) & (top[..., 1] < 60) & (top[..., 2] < 60)) > 100  # red bodies
    assert sorted(p.name for p in tmp_path.iterdir()) == ["finding.png"]  # no temporary file left


def _cell_with_mesh(path: str) -> object:
    import dataclasses

    from rmot.lang import ir

    p = plan()
    mesh = ir.Fixture("wedge", ir.Mesh(path, scale=0.001), ir.Pose((0.6, -0.5, 0.0)))
    cell = dataclasses.replace(p.program.cell, fixtures=p.program.cell.fixtures + (mesh,))
    program = dataclasses.replace(p.program, cell=cell)
    return dataclasses.replace(p, program=program)


def test_mesh_fixture_from_a_file_is_drawn(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """A fixture given as a mesh file (points then polygons, in mm) is loaded, scaled and drawn."""
    path = tmp_path / "wedge.txt"
    path.write_text("4 4\n0 0 0\n400 0 0\n0 400 0\n0 0 400\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    rs = prepare(_cell_with_mesh(str(path)), robots={"r1": arm3()})
    assert rs.names[2] == "wedge" and rs.diagnostics == ()
    np.testing.assert_allclose(rs.meshes[2].vertices.reshape(-1, 3).max(axis=0), [0.4, 0.4, 0.4])
    poses = body_poses(rs, np.array([0.0]))[0]
    cam = default_camera(rs, SIZE)
    plain, red = (frame(rs, poses, cam, SIZE, 1, highlight=h).astype(int) for h in ((), ("wedge",)))
    assert np.any(plain != red, axis=2).sum() > 50


def test_missing_mesh_file_is_a_diagnostic_not_a_crash(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """A mesh that does not exist is reported (E560 from the mesh loader) and the rest is still drawn."""
    rs = prepare(_cell_with_mesh(str(tmp_path / "nowhere.stl")), robots={"r1": arm3()})
    assert [d.code.id for d in rs.diagnostics] == ["E560"]
    assert "wedge" not in rs.names
    assert still_image(rs, size=SIZE, aa=1).shape == (120, 160, 3)
