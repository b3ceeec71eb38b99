"""The same triangles through VTK's off-screen OpenGL (Mesa llvmpipe here), for the benchmark.

Benchmark-only: VTK is not a dependency of rmot (pip install vtk into the venv to run it).
Set LP_NUM_THREADS=1 before VTK loads to keep llvmpipe on one core.
"""

from __future__ import annotations

import numpy as np

import render_cell
from rmot.sim.render.camera import Camera


class VtkScene:
    """A VTK render window holding one actor with the triangles, per-vertex normals and colours."""

    def __init__(self, vertices: np.ndarray, normals: np.ndarray, colors: np.ndarray, camera: Camera,
                 size: tuple[int, int]) -> None:
        import vtk
        from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray

        n_tri = len(vertices)
        points = vtk.vtkPoints()
        points.SetData(numpy_to_vtk(np.ascontiguousarray(vertices.reshape(-1, 3), np.float32), deep=True))
        offsets = numpy_to_vtkIdTypeArray(np.arange(0, 3 * n_tri + 1, 3, dtype=np.int64), deep=True)
        connectivity = numpy_to_vtkIdTypeArray(np.arange(3 * n_tri, dtype=np.int64), deep=True)
        polys = vtk.vtkCellArray()
        polys.SetData(offsets, connectivity)  # triangle i is points 3i, 3i+1, 3i+2
        poly = vtk.vtkPolyData()
        poly.SetPoints(points)
        poly.SetPolys(polys)
        poly.GetPointData().SetNormals(numpy_to_vtk(np.ascontiguousarray(normals.reshape(-1, 3), np.float32), deep=True))
        rgb = np.repeat((np.asarray(colors) * 255).astype(np.uint8), 3, axis=0)
        scalars = numpy_to_vtk(rgb, deep=True)
        scalars.SetName("colors")
        poly.GetPointData().SetScalars(scalars)
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputData(poly)
        mapper.SetColorModeToDirectScalars()
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetInterpolationToGouraud()
        actor.GetProperty().SetAmbient(0.28)
        actor.GetProperty().SetDiffuse(0.72)
        actor.GetProperty().SetSpecular(0.22)
        actor.GetProperty().SetSpecularPower(24.0)
        renderer = vtk.vtkRenderer()
        renderer.AddActor(actor)
        renderer.SetBackground(0.92, 0.93, 0.95)
        renderer.RemoveAllLights()
        light = vtk.vtkLight()
        light.SetLightTypeToSceneLight()
        light.SetPositional(False)
        light.SetPosition(*render_cell.LIGHT_DIRECTION)
        light.SetIntensity(1.0)
        light.SetFocalPoint(0.0, 0.0, 0.0)
        renderer.AddLight(light)
        cam = renderer.GetActiveCamera()
        cam.SetPosition(*camera.eye)
        cam.SetFocalPoint(*camera.center)
        cam.SetViewUp(*camera.up)
        cam.SetViewAngle(camera.fov_deg)
        cam.SetClippingRange(camera.near, camera.far)
        window = vtk.vtkRenderWindow()
        window.SetOffScreenRendering(1)
        window.AddRenderer(renderer)
        window.SetSize(*size)
        window.SetMultiSamples(0)
        self.window, self.size, self._keep = window, size, (poly, mapper, actor, renderer)
        window.Render()

    def renderer_name(self) -> str:
        text = self.window.ReportCapabilities()
        return next((line.split(":", 1)[1].strip() for line in text.splitlines() if "renderer string" in line), "?")

    def frame(self) -> np.ndarray:
        """Render and read the pixels back: (H, W, 3) uint8, top row first."""
        from vtk.util.numpy_support import vtk_to_numpy
        import vtk

        self.window.Modified()
        self.window.Render()
        width, height = self.size
        data = vtk.vtkUnsignedCharArray()
        self.window.GetPixelData(0, 0, width - 1, height - 1, 1, data, 0)
        return vtk_to_numpy(data).reshape(height, width, 3)[::-1]
