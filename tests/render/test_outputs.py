"""Animations and the offline HTML viewer: every frame present, nothing fetched from elsewhere."""

from __future__ import annotations

import base64
import json
import re

import imageio.v3 as iio
import numpy as np
import pytest
from PIL import Image
from render_fixtures import arm3, plan

from rmot.sim.render.animate import AnimationError, frame_times, write_animation
from rmot.sim.render.html import render_html
from rmot.sim.render.scene import body_poses, prepare


@pytest.fixture(scope="module")
def scene():  # type: ignore[no-untyped-def]
    return prepare(plan(duration=0.5), robots={"r1": arm3()})


def test_frame_times_cover_the_program_and_end_on_its_last_instant() -> None:
    """1/fps apart from 0, and the final instant always shown."""
    np.testing.assert_allclose(frame_times(0.5, 10), [0.0, 0.1, 0.2, 0.3, 0.4, 0.5])
    np.testing.assert_allclose(frame_times(0.25, 10), [0.0, 0.1, 0.2, 0.25])
    np.testing.assert_allclose(frame_times(0.0, 25), [0.0])


def test_gif_has_one_frame_per_instant_and_the_robot_moves(scene, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """The GIF holds len(frame_times) frames of the requested size; first and last differ."""
    out = tmp_path / "a.gif"
    write_animation(scene, str(out), fps=10, size=(96, 72), progress=False)
    with Image.open(out) as gif:
        assert gif.n_frames == 6 and gif.size == (96, 72)
        gif.seek(0)
        first = np.asarray(gif.convert("RGB")).astype(int)
        gif.seek(5)
        last = np.asarray(gif.convert("RGB")).astype(int)
    assert np.abs(first - last).sum() > 1000


def test_mp4_decodes_to_the_expected_frames(scene, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """The MP4 (ffmpeg via imageio) decodes to one frame per instant at the requested size."""
    out = tmp_path / "a.mp4"
    calls: list[tuple[int, int]] = []
    write_animation(scene, str(out), fps=10, size=(96, 72), progress=lambda d, n: calls.append((d, n)))
    frames = np.stack(list(iio.imiter(out, plugin="FFMPEG")))
    assert frames.shape == (6, 72, 96, 3)
    assert calls[-1] == (6, 6)


def test_same_program_gives_the_same_gif_bytes(scene, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """Animations are deterministic: two runs write identical files."""
    a, b = tmp_path / "a.gif", tmp_path / "b.gif"
    for out in (a, b):
        write_animation(scene, str(out), fps=10, size=(64, 48), progress=False)
    assert a.read_bytes() == b.read_bytes()


def test_unknown_animation_format_is_refused(scene, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """Only .gif and .mp4 are animations."""
    with pytest.raises(AnimationError, match=r"animation file must end in \.gif or \.mp4 \(got '.*a\.avi'\)"):
        write_animation(scene, str(tmp_path / "a.avi"))


class TestHtml:
    def test_page_is_self_contained(self, scene) -> None:  # type: ignore[no-untyped-def]
        """No external script, style, image or URL: the file works offline."""
        page = render_html(scene)
        assert not re.search(r"""(src|href)\s*=|https?://|@import|url\(""", page)
        assert page.count("<script") == 2 and "WebGL" in page

    def test_embedded_poses_are_the_bodies_poses_at_each_frame(self, scene) -> None:  # type: ignore[no-untyped-def]
        """The JSON block holds each body's triangles once and, per frame, its 3x4 pose."""
        page = render_html(scene, fps=10)
        data = json.loads(re.search(r'<script id="rmot-data" type="application/json">(.*?)</script>', page, re.S).group(1))
        decode = lambda s: np.frombuffer(base64.b64decode(s), "<f4")  # noqa: E731
        assert [b["name"] for b in data["bodies"]] == list(scene.names)
        for body, mesh in zip(data["bodies"], scene.meshes):
            np.testing.assert_allclose(decode(body["vertices"]).reshape(-1, 3, 3), mesh.vertices, atol=1e-6)
        times = np.array(data["times"])
        np.testing.assert_allclose(times, frame_times(0.5, 10))
        poses = decode(data["poses"]).reshape(len(times), len(scene.names), 3, 4)
        np.testing.assert_allclose(poses, body_poses(scene, times)[:, :, :3, :], atol=1e-6)

    def test_same_scene_gives_the_same_page(self, scene) -> None:  # type: ignore[no-untyped-def]
        """Byte-identical output for the same input."""
        assert render_html(scene) == render_html(scene)
