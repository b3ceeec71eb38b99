"""Parts in the pictures: a held part is drawn where the gripper holds it, a
placed one where it was put, in every picture kind.

The pixel test projects a world point with its own pinhole camera (look-at with +z up, the
vertical view angle, the image centre at the principal point), not with sim/render's code.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rmot.compiler.frontend import load_program
from rmot.compiler.plan import plan_program
from rmot.sim.robots import load_robot
from rmot.sim.render.camera import Camera
from rmot.sim.render.still import render_still

STACK = Path(__file__).resolve().parents[1] / "data" / "parts" / "stack.rmot"
EYE, CENTER, FOV = np.array([1.6, 0.9, 1.1]), np.array([0.55, -0.15, 0.3]), 35.0
SIZE = (320, 240)


@pytest.fixture(scope="module")
def plan():  # type: ignore[no-untyped-def]
    front = load_program(str(STACK))
    assert front.program is not None
    return plan_program(front.program)


def _project(point: np.ndarray) -> tuple[int, int]:
    """Pixel (column, row) of a world point for a camera at EYE looking at CENTER."""
    f = (CENTER - EYE) / np.linalg.norm(CENTER - EYE)
    s = np.cross(f, [0.0, 0.0, 1.0])
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    d = point - EYE
    x, y, z = d @ s, d @ u, d @ f
    w, h = SIZE
    focal = (h / 2) / math.tan(math.radians(FOV) / 2)
    return int(round(w / 2 + focal * x / z - 0.5)), int(round(h / 2 - focal * y / z - 0.5))


def _tcp(plan, t: float) -> np.ndarray:  # type: ignore[no-untyped-def]
    """The TCP in world at t, by the robot library's forward kinematics and the cell's numbers
    (UR10e at z = 400 mm turned 180 deg about z; TCP 100 mm along the flange z axis)."""
    base = np.eye(4)
    base[:3, :3] = [[-1, 0, 0], [0, -1, 0], [0, 0, 1]]
    base[2, 3] = 0.4
    q = plan.tasks[0].trajectory.at(t)
    return (base @ np.asarray(load_robot("ur10e").fk(q)) @ np.array([0, 0, 0.1, 1.0]))[:3]


def _is_cardboard(rgb: np.ndarray) -> bool:
    r, g, b = (int(c) for c in rgb)
    return r > b + 40 and g > b + 10 and r >= g


def _time_between(plan, first: str, second: str) -> float:  # type: ignore[no-untyped-def]
    """Half way between the records of two source lines (text of the lines)."""
    lines = STACK.read_text(encoding="utf-8").splitlines()
    at = {text: lines.index("  " + text) + 1 for text in (first, second)}
    recs = {r.span.start.line: r for r in plan.tasks[0].records if r.span is not None}
    return (recs[at[first]].t_end + recs[at[second]].t_start) / 2


def test_held_part_is_drawn_below_the_tcp(plan) -> None:  # type: ignore[no-untyped-def]
    """While b1 is carried (between its attach and detach), the pixel of the point 50 mm below
    the TCP (the cube's centre: the TCP is on its top face, tool pointing down) is cardboard;
    at the start, with no part there, it is not."""
    camera = Camera(tuple(EYE), tuple(CENTER), fov_deg=FOV)
    t_held = _time_between(plan, "attach b1", "detach b1")
    centre = _tcp(plan, t_held) - np.array([0.0, 0.0, 0.05])
    col, row = _project(centre)
    assert 0 <= col < SIZE[0] and 0 <= row < SIZE[1]
    image = render_still(plan, time=t_held, size=SIZE, aa=1, camera=camera)
    assert _is_cardboard(image[row, col]), image[row, col]
    start = render_still(plan, time=0.0, size=SIZE, aa=1, camera=camera)  # nothing there yet
    assert not _is_cardboard(start[row, col]), start[row, col]


def test_placed_part_stays_where_it_was_put(plan) -> None:  # type: ignore[no-untyped-def]
    """After the detach b1 sits on the outfeed at the place point (TCP there, cube 50 mm below)
    for the rest of the program, wherever the robot goes."""
    camera = Camera(tuple(EYE), tuple(CENTER), fov_deg=FOV)
    col, row = _project(np.array([0.0, -0.65, 0.25]))
    end = float(plan.tasks[0].trajectory.t[-1])
    image = render_still(plan, time=end, size=SIZE, aa=1, camera=camera)
    assert _is_cardboard(image[row, col]), image[row, col]
    before = render_still(plan, time=0.0, size=SIZE, aa=1, camera=camera)
    assert not _is_cardboard(before[row, col]), before[row, col]


@pytest.mark.parametrize("suffix", [".svg", ".html"])
def test_vector_and_viewer_outputs_name_the_parts(plan, suffix: str, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    """The SVG groups and the HTML viewer's body list carry the parts by name."""
    from click.testing import CliRunner

    from rmot.compiler.cli.render_cmd import render

    out = tmp_path / f"stack{suffix}"
    result = CliRunner().invoke(render, [str(STACK), "-o", str(out)])
    assert result.exit_code == 0, result.output
    text = out.read_text(encoding="utf-8")
    for name in ("b1", "b2", "b3"):
        assert f'"{name}"' in text or f">{name}<" in text or f"'{name}'" in text


def test_animation_frames_move_the_parts(tmp_path: Path) -> None:
    """A GIF of the stack program: the cardboard pixels' centre moves between the first and the
    last frame (b1 and b2 went from the infeed to the outfeed), and every frame shows cardboard."""
    import imageio.v3 as iio
    from click.testing import CliRunner

    from rmot.compiler.cli.render_cmd import render

    out = tmp_path / "stack.gif"
    result = CliRunner().invoke(render, [str(STACK), "-o", str(out), "--fps", "1", "--size", "240x180"])
    assert result.exit_code == 0, result.output
    frames = iio.imread(str(out), index=None)

    def centre(img: np.ndarray) -> np.ndarray:
        mask = np.array([[_is_cardboard(px) for px in row] for row in img[::2, ::2]])
        assert mask.any()
        return np.argwhere(mask).mean(axis=0)

    assert np.linalg.norm(centre(frames[0]) - centre(frames[-1])) > 3.0
