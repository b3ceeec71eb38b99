"""Rendering speed: a 640x480 frame of a 50,000-triangle cell, without anti-aliasing and with
4x supersampling (2x2), against VTK's off-screen OpenGL (Mesa llvmpipe) on the same triangles,
everything on one core; plus numba's cold-start cost with and without its on-disk cache.

Run (pytest-benchmark, wall-clock medians):
    .venv/bin/python -m pytest tests/benchmarks/bench_render.py --benchmark-only -s
or, for an interleaved table of wall and CPU medians that stays fair on a busy machine:
    .venv/bin/python tests/benchmarks/bench_render.py

VTK is a benchmark-only dependency (pip install vtk). One core: NUMBA_NUM_THREADS=1,
LP_NUM_THREADS=1 (llvmpipe), OPENBLAS_NUM_THREADS=1, set before numba or VTK load.
"""

from __future__ import annotations

import os

for _name in ("NUMBA_NUM_THREADS", "LP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402

sys.path.insert(0, str(Path(__file__).parent))
import render_cell  # noqa: E402

from rmot.sim.render.pipeline import downsample  # noqa: E402
from rmot.sim.render.pipeline import render_triangles as _render  # noqa: E402
from rmot.sim.render.shade import Light  # noqa: E402

SIZE = (640, 480)
LIGHT = (Light(render_cell.LIGHT_DIRECTION, 1.0),)  # one directional light, as in VTK's scene


def render_triangles(vertices, normals, colors, camera, size, aa):  # type: ignore[no-untyped-def]
    """Our pipeline with the benchmark's single light."""
    return _render(vertices, normals, colors, camera, size, aa, LIGHT)


@pytest.fixture(scope="module")
def cell():  # type: ignore[no-untyped-def]
    vertices, normals, colors, camera = render_cell.cell()
    render_triangles(vertices, normals, colors, camera, SIZE, 2)  # compile (or load) the kernels first
    return vertices, normals, colors, camera


def _vtk(cell, size):  # type: ignore[no-untyped-def]
    from vtk_reference import VtkScene

    vertices, normals, colors, camera = cell
    return VtkScene(vertices, normals, colors, camera, size)


def _vtk_ss4(scene) -> np.ndarray:  # type: ignore[no-untyped-def]
    """VTK at twice the size, box-filtered 2x2 like ours: the same 4x supersampling."""
    return downsample(scene.frame().astype(np.float32) * (1 / 255), 2)


def test_rmot_640x480_no_aa(benchmark, cell) -> None:  # type: ignore[no-untyped-def]
    """Our pipeline, one sample per pixel."""
    image = benchmark(render_triangles, *cell, SIZE, 1)
    assert image.shape == (480, 640, 3)


def test_rmot_640x480_ss4(benchmark, cell) -> None:  # type: ignore[no-untyped-def]
    """Our pipeline, 2x2 supersampling."""
    image = benchmark(render_triangles, *cell, SIZE, 2)
    assert image.shape == (480, 640, 3)


def test_vtk_640x480_no_aa(benchmark, cell) -> None:  # type: ignore[no-untyped-def]
    """VTK llvmpipe, one sample per pixel, pixels read back."""
    scene = _vtk(cell, SIZE)
    benchmark.extra_info["renderer"] = scene.renderer_name()
    assert benchmark(scene.frame).shape == (480, 640, 3)


def test_vtk_640x480_ss4(benchmark, cell) -> None:  # type: ignore[no-untyped-def]
    """VTK llvmpipe at 1280x960, read back and box-filtered to 640x480."""
    scene = _vtk(cell, (1280, 960))
    assert benchmark(_vtk_ss4, scene).shape == (480, 640, 3)


_COLD = """
import time
t0 = time.perf_counter()
import sys; sys.path.insert(0, {here!r})
import render_cell
from rmot.sim.render.pipeline import render_triangles
v, n, c, cam = render_cell.cell()
t1 = time.perf_counter()
render_triangles(v, n, c, cam, (640, 480), 2)  # compiles the kernels, or loads them from the cache
t2 = time.perf_counter()
render_triangles(v, n, c, cam, (640, 480), 2)
t3 = time.perf_counter()
print((t2 - t1) - (t3 - t2))
"""


def cold_start(runs: int = 3) -> tuple[float, float]:
    """(seconds of first-frame overhead with an empty numba cache, with a filled one), medians."""
    code = _COLD.format(here=str(Path(__file__).parent))
    cold, warm = [], []
    for _ in range(runs):
        with tempfile.TemporaryDirectory() as cache:
            env = {**os.environ, "NUMBA_CACHE_DIR": cache}
            for out in (cold, warm):  # the first run compiles and fills the cache, the second loads it
                done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
                out.append(float(done.stdout.strip().splitlines()[-1]))
    return float(np.median(cold)), float(np.median(warm))


def test_numba_cold_start(benchmark) -> None:  # type: ignore[no-untyped-def]
    """First-frame overhead of a new process: compiling the kernels vs loading them from numba's cache."""
    cold, warm = benchmark.pedantic(cold_start, rounds=1, iterations=1)
    benchmark.extra_info.update(cold_compile_s=cold, cached_s=warm)
    print(f"\nnumba first-frame overhead: {cold:.2f} s without cache, {warm:.2f} s with cache")
    assert cold > 0


def _medians(fn, rounds: int) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    wall, cpu = [], []
    for _ in range(rounds):
        w, c = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - w)
        cpu.append(time.process_time() - c)
    return float(np.median(wall)) * 1e3, float(np.median(cpu)) * 1e3


def main(rounds: int = 15) -> None:
    """Interleave the four cases round by round so machine load hits them alike; print medians."""
    vertices, normals, colors, camera = render_cell.cell()
    data = (vertices, normals, colors, camera)
    render_triangles(*data, SIZE, 2)
    vtk1, vtk2 = _vtk(data, SIZE), _vtk(data, (1280, 960))
    cases = {
        "rmot 640x480 no AA": lambda: render_triangles(*data, SIZE, 1),
        "rmot 640x480 4x SS": lambda: render_triangles(*data, SIZE, 2),
        "vtk  640x480 no AA": vtk1.frame,
        "vtk  640x480 4x SS": lambda: _vtk_ss4(vtk2),
    }
    samples: dict[str, list[tuple[float, float]]] = {k: [] for k in cases}
    for _ in range(rounds):
        for name, fn in cases.items():
            samples[name].append(_medians(fn, 1))
    print(f"{len(vertices)} triangles, {SIZE[0]}x{SIZE[1]}, VTK renderer: {vtk1.renderer_name()}, one core")
    med = {k: (float(np.median([s[0] for s in v])), float(np.median([s[1] for s in v]))) for k, v in samples.items()}
    for name, (wall, cpu) in med.items():
        print(f"  {name}: wall {wall:6.1f} ms   cpu {cpu:6.1f} ms")
    for aa in ("no AA", "4x SS"):
        ours, theirs = med[f"rmot 640x480 {aa}"], med[f"vtk  640x480 {aa}"]
        print(f"  ratio rmot/vtk {aa}: wall {ours[0] / theirs[0]:.2f}  cpu {ours[1] / theirs[1]:.2f}")
    cold, warm = cold_start()
    print(f"  numba first-frame overhead: {cold:.2f} s without cache, {warm:.2f} s with cache")


if __name__ == "__main__":
    main()
