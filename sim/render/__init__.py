"""rmot.sim.render: the graphic simulator's display pipeline and the pictures it makes.

    camera.py     Camera (eye, centre of interest, up, view angle), --camera parsing
    transform.py  viewing -> perspective -> divide -> viewport, over point arrays
    clip.py       Sutherland–Hodgman against the six planes, in homogeneous coordinates
    raster.py     z-buffer scan conversion with perspective-correct barycentrics (numba)
    shade.py      ambient + Lambert + Blinn/Phong specular; flat, Gouraud, Phong shading
    pipeline.py   the stages wired together on plain triangle arrays; k x k supersampling
    tessellate.py solids -> triangle meshes with smooth normals
    scene.py      cell + Plan at an instant -> coloured triangles (bodies named as in sim)
    overlay.py    depth-tested lines (TCP path, hidden-line edges)
    still.py      render_still, render_finding;  animate.py  GIF / MP4
    svg.py        hidden-line wire-frame;  html.py  self-contained WebGL viewer

Rendering only draws: it never changes what verification decided.
"""

from rmot.sim.render.animate import render_animation
from rmot.sim.render.camera import Camera
from rmot.sim.render.pipeline import render_triangles
from rmot.sim.render.shade import Light, Material, Shading
from rmot.sim.render.still import render_finding, render_still

__all__ = [
    "Camera", "Light", "Material", "Shading",
    "render_animation", "render_finding", "render_still", "render_triangles",
]
