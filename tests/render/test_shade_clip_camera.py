"""Illumination, homogeneous clipping and the camera, against independent computations."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.sim.render.camera import Camera, CameraSpecError, parse_camera
from rmot.sim.render.clip import clip_triangles, plane_distances
from rmot.sim.render.pipeline import render_triangles
from rmot.sim.render.shade import Light, Material, Shading, shade
from rmot.sim.render.transform import to_clip, to_screen

LAMBERT_ONLY = Material(ambient=0.0, diffuse=1.0, specular=0.0)


class TestLambert:
    @pytest.mark.parametrize("light", [(0.0, 0.0, 1.0), (1.0, 0.0, 1.0), (0.3, -0.8, 0.4), (1.0, 1.0, 0.05), (0.2, 0.1, -1.0)])
    def test_pixel_intensity_is_max_0_n_dot_l(self, light: tuple[float, float, float]) -> None:
        """A white plane lit by one light shows 255 * max(0, n.l) within 1/255 at every covered pixel."""
        n = np.array([0.0, 0.0, 1.0])
        quad = np.array([[[-1, -1, 0], [1, -1, 0], [1, 1, 0]], [[-1, -1, 0], [1, 1, 0], [-1, 1, 0]]], float)
        camera = Camera(eye=(0.0, -0.5, 3.0), center=(0.0, 0.0, 0.0), fov_deg=30.0)
        img = render_triangles(quad, np.broadcast_to(n, quad.shape), np.ones((2, 3)), camera, (64, 48),
                               lights=(Light(light, 1.0),), material=LAMBERT_ONLY, shading=Shading.PHONG,
                               background=(0.5, 0.5, 0.5))
        to_light = np.asarray(light) / np.linalg.norm(light)
        expected = 255 * max(0.0, float(n @ to_light))
        assert np.all(np.abs(img[8:40, 8:56].astype(float) - expected) <= 1.0)

    def test_surface_is_lit_on_the_side_the_eye_sees(self) -> None:
        """Two-sided lighting: a normal pointing away from the eye is turned round before Lambert's law."""
        out = shade(np.array([[0.0, 0.0, -1.0]]), np.zeros((1, 3)), np.ones((1, 3)), np.array([0.0, 0.0, 5.0]),
                    (Light((0.0, 0.0, 1.0)),), LAMBERT_ONLY)
        np.testing.assert_allclose(out, [[1.0, 1.0, 1.0]], atol=1e-6)

    def test_blinn_highlight_peaks_at_the_mirror_direction(self) -> None:
        """Blinn and Phong specular terms are 1 when the eye sits on the reflected light ray, less elsewhere."""
        normals = np.tile([0.0, 0.0, 1.0], (2, 1))
        points = np.array([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0]])
        eye = np.array([1.0, 0.0, 1.0])  # mirror of the light (-1, 0, 1) about z, seen from the origin
        for blinn in (True, False):
            spec_only = Material(ambient=0.0, diffuse=0.0, specular=1.0, shininess=50.0, blinn=blinn)
            out = shade(normals, points, np.zeros((2, 3)), eye, (Light((-1.0, 0.0, 1.0)),), spec_only)
            assert out[0, 0] == pytest.approx(1.0, abs=1e-5)
            assert out[1, 0] < 0.9


def _random_clip(rng: np.random.Generator, n: int) -> np.ndarray:
    clip = rng.uniform(-3.0, 3.0, (n, 3, 4))
    clip[..., 3] = rng.uniform(-1.0, 3.0, (n, 3))
    return clip


class TestClip:
    @settings(max_examples=60, deadline=None)
    @given(st.integers(0, 2**32 - 1))
    def test_every_output_vertex_is_inside_the_six_planes(self, seed: int) -> None:
        """Sutherland–Hodgman output lies in -w<=x,y<=w, 0<=z<=w (to rounding), whatever the input."""
        clip = _random_clip(np.random.default_rng(seed), 20)
        out, attrs, source = clip_triangles(clip, clip[..., :1].astype(np.float32))
        assert out.shape[0] == attrs.shape[0] == source.shape[0]
        if len(out):
            assert plane_distances(out).min() >= -1e-9

    def test_new_vertices_interpolate_attributes_linearly_in_clip_space(self) -> None:
        """An attribute equal to a linear function of the clip position stays equal to it at new vertices."""
        rng = np.random.default_rng(3)
        clip = _random_clip(rng, 200)
        coef = np.array([0.3, -1.2, 0.7, 2.0])
        attrs = (clip @ coef)[..., None].astype(np.float64)
        out, out_attrs, _ = clip_triangles(clip, attrs)
        np.testing.assert_allclose(out_attrs[..., 0], out @ coef, atol=1e-9)

    def test_triangles_inside_pass_through_unchanged(self) -> None:
        """A triangle already inside the volume is neither split nor moved."""
        tri = np.array([[[0.1, 0.2, 0.5, 1.0], [-0.3, 0.1, 0.2, 1.0], [0.0, -0.4, 0.9, 1.0]]])
        out, _, source = clip_triangles(tri, np.zeros((1, 3, 0), np.float32))
        np.testing.assert_array_equal(out, tri)
        np.testing.assert_array_equal(source, [0])

    def test_near_plane_cut_keeps_the_area_in_front(self) -> None:
        """Cutting a triangle at z_clip = 0 leaves the polygon of the front part (a quad: two triangles)."""
        tri = np.array([[[0.0, 0.0, -1.0, 1.0], [0.5, 0.0, 1.0, 1.0], [0.0, 0.5, 1.0, 1.0]]])
        out, _, _ = clip_triangles(tri, np.zeros((1, 3, 0), np.float32))
        assert len(out) == 2
        area = sum(0.5 * np.linalg.norm(np.cross(t[1, :3] - t[0, :3], t[2, :3] - t[0, :3])) for t in out)
        full = 0.5 * np.linalg.norm(np.cross(tri[0, 1, :3] - tri[0, 0, :3], tri[0, 2, :3] - tri[0, 0, :3]))
        assert area == pytest.approx(full * 0.75, rel=1e-12)  # the cut at mid-height removes a quarter


class TestCamera:
    def test_view_puts_the_eye_at_the_origin_looking_down_minus_z(self) -> None:
        """The viewing transform maps the eye to 0 and the centre of interest onto the -z axis."""
        cam = Camera(eye=(2.0, -3.0, 1.5), center=(0.2, 0.4, 0.3))
        v = cam.view()
        np.testing.assert_allclose(v @ [2.0, -3.0, 1.5, 1.0], [0, 0, 0, 1], atol=1e-12)
        c = v @ [0.2, 0.4, 0.3, 1.0]
        np.testing.assert_allclose(c[:2], [0, 0], atol=1e-12)
        assert c[2] < 0

    def test_depth_maps_near_to_0_and_far_to_1(self) -> None:
        """The perspective transform gives device depth 0 at the near plane and 1 at the far plane."""
        cam = Camera(eye=(0.0, 0.0, 0.0), center=(0.0, 0.0, -1.0), up=(0.0, 1.0, 0.0), near=0.3, far=30.0)
        screen, _ = to_screen(to_clip(cam.matrix(1.0), np.array([[0, 0, -0.3], [0, 0, -30.0]])), 10, 10)
        np.testing.assert_allclose(screen[:, 2], [0.0, 1.0], atol=1e-12)

    @settings(max_examples=50, deadline=None)
    @given(st.lists(st.floats(-5, 5), min_size=3, max_size=3), st.lists(st.floats(0.01, 4), min_size=3, max_size=3),
           st.sampled_from([1.0, 4 / 3, 16 / 9, 0.75]))
    def test_framing_contains_the_whole_scene(self, lo: list[float], extent: list[float], aspect: float) -> None:
        """Every corner of the framed box projects inside the picture and between near and far."""
        bounds = np.array([lo, np.add(lo, extent)])
        corners = np.array([[bounds[i, 0], bounds[j, 1], bounds[k, 2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
        cam = Camera.framing(bounds, aspect=aspect).fitted(corners)  # depth planes fitted to what is drawn
        clip = to_clip(cam.matrix(aspect), corners)
        ndc = clip[:, :3] / clip[:, 3:]
        assert np.all(clip[:, 3] > 0)
        assert np.all(np.abs(ndc[:, :2]) <= 1.0) and np.all((ndc[:, 2] > 0) & (ndc[:, 2] < 1))

    def test_parse_camera_reads_every_key(self) -> None:
        """The --camera text sets eye, centre, up, view angle and clipping distances."""
        cam = parse_camera("eye=3,-3,2; center=0.5,0,0.5; fov=35; up=0,0,1; near=0.1; far=40")
        assert cam == Camera((3.0, -3.0, 2.0), (0.5, 0.0, 0.5), (0.0, 0.0, 1.0), 35.0, 0.1, 40.0)

    @pytest.mark.parametrize(("text", "message"), [
        ("eye=1,2;center=0,0,0", "camera eye must be three numbers x,y,z (got '1,2')"),
        ("eye=1,2,3", "camera must give eye=x,y,z and center=x,y,z (got 'eye=1,2,3')"),
        ("eye=1,2,3;center=0,0,0;fov=200", "camera fov must be in (0, 180) degrees (got 200.0)"),
        ("eye=1,1,1;center=1,1,1", "camera eye and center must differ (both (1.0, 1.0, 1.0))"),
        ("eye=1,2,3;center=0,0,0;zoom=2", "camera setting must be one of ['center', 'eye', 'far', 'fov', 'near', 'up'] as key=value (got 'zoom=2')"),
        ("eye=a,2,3;center=0,0,0", "camera eye must be numbers (got 'a,2,3')"),
    ])
    def test_parse_camera_rejects_bad_text_with_a_clear_message(self, text: str, message: str) -> None:
        """Bad --camera text is an error that names the key and the value."""
        with pytest.raises(CameraSpecError) as err:
            parse_camera(text)
        assert str(err.value) == message
