"""The files a URDF names (collision and visual meshes) checked like the cell's own paths.

A URDF is a side file of the project: every `<mesh filename="...">` in it must lead to a
file inside the project root, exactly as `mesh("...")` in a cell must (E504), before the
URDF is handed to pinocchio (which would read the mesh). Resolution, as ROS tools do it:
  * `package://PKG/rest`: `<dir>/PKG/rest` for the URDF's folder and its ancestors, *only
    those inside the project root*, the first that exists (outside the root: not searched);
  * `file:///abs/path`: the absolute path; a relative name: relative to the URDF's folder;
  * after resolution (symbolic links followed) the file must lie inside a root (E504); a
    mesh that is inside the project but simply not there is E501, with the paths searched.
Also refused here, with the joint's name: a revolute, continuous or prismatic joint whose
axis is the zero vector (no direction to move along; E505). The file is parsed with the
standard library's expat parser, which refuses entity-expansion bombs.

Every value pinocchio's parser (urdfdom) would drop with only a line on stderr, or accept and
plan with silently, is refused here with the element's name (E505), so what loads is what the
file declares: a collision or visual shape's dimensions (box size, cylinder and sphere radius,
cylinder length, mesh scale) must be finite and positive; a moving joint's velocity limit,
when given, finite and positive (urdfdom reads velocity="0" as "no limit", which rmot would
plan at a made-up 1 rad/s); a link's mass finite and >= 0 and its inertia entries finite. A
file with more than MAX_JOINTS joints or MAX_LINKS links is refused before it is parsed into
a model (a 1,000-joint file exhausted memory in verification).
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Reporter
from rmot.compiler.passes.limits import MAX_MESH_SCALE, MAX_SIZE_M, MIN_MESH_SCALE, MIN_SIZE_M
from rmot.lang.input_file import read_regular
from rmot.lang.source import Span

__all__ = ["check_urdf_files"]

_MOVING = ("revolute", "continuous", "prismatic")
MAX_JOINTS = 64  # industrial arms have 6-7 (plus a rail, a gripper's fingers): far above any real cell
MAX_LINKS = 256
MAX_URDF_BYTES = 64 * 1024 * 1024  # a 64-joint URDF with inline geometry is a few hundred KiB
_SHAPES = {"box": ("size",), "cylinder": ("radius", "length"), "sphere": ("radius",), "capsule": ("radius", "length"),
           "mesh": ("scale",)}
_COUNTS = {"size": (3,), "scale": (1, 3)}  # how many numbers each attribute holds (URDF spec)


def check_urdf_files(urdf: str, roots: tuple[str, ...], span: Span | None, rep: Reporter) -> bool:
    """True when every mesh the URDF names lies inside a root and every moving joint has an axis."""
    try:
        tree: ET.ElementTree[ET.Element] = ET.ElementTree(ET.fromstring(read_regular(urdf, MAX_URDF_BYTES)))
    except (ET.ParseError, OSError, ValueError) as exc:
        rep.error(codes.ROBOT_LOAD, f"URDF robot must be a readable XML file (got: {str(exc)[:200]})", span)
        return False
    ok = True
    folder = Path(urdf).resolve().parent
    for mesh in tree.iter("mesh"):
        name = mesh.get("filename") or ""
        target = _resolve(name, folder, roots)
        missing = _missing_mesh(name, target, folder, roots)
        if missing is not None:
            rep.error(codes.FILE_NOT_FOUND, f"mesh named by {os.path.basename(urdf)} must exist (got '{name[:200]}': "
                      f"{missing})", span)
            ok = False
        elif target is None or not any(_inside(target, Path(r)) for r in roots):
            rep.error(codes.PATH_ESCAPES, f"mesh named by the URDF must stay inside the project directory {roots[0]} "
                      f"(got '{name[:200]}' in {os.path.basename(urdf)})", span)
            ok = False
    ok = _check_values(tree, os.path.basename(urdf), span, rep) and ok
    for joint in tree.iter("joint"):
        if joint.get("type") not in _MOVING:
            continue
        axis = joint.find("axis")
        text = axis.get("xyz", "1 0 0") if axis is not None else "1 0 0"  # URDF's default axis is x
        try:
            values = [float(v) for v in text.split()]
        except ValueError:
            values = []
        if len(values) != 3 or not all(math.isfinite(v) for v in values) or math.hypot(*values) < 1e-9:
            rep.error(codes.ROBOT_LOAD, f"URDF joint '{joint.get('name', '?')[:80]}' must have a non-zero finite axis "
                      f"(got xyz=\"{text[:60]}\")", span)
            ok = False
    return ok


def _missing_mesh(name: str, target: Path | None, folder: Path, roots: tuple[str, ...]) -> str | None:
    """Why a mesh inside the project is simply not there (the paths searched), else None: a
    name that leads out of the project, or a file that exists, is judged by the caller."""
    if name.startswith("package://"):
        if target is not None:
            return None
        rest = name[len("package://"):]
        dirs = [folder, *folder.parents]
        inside = [d for d in dirs if any(_inside(d, Path(r)) for r in roots)]
        if any(Path(os.path.normpath(d / rest)).exists() for d in dirs if d not in inside):
            return None  # it exists, but only outside the project: E504
        searched = [Path(os.path.normpath(d / rest)) for d in inside]
        shown = ", ".join(str(p) for p in searched[:3]) + (", ..." if len(searched) > 3 else "")
        return f"no file at {shown}"
    if target is None or target.exists() or not any(_inside(target, Path(r)) for r in roots):
        return None
    return f"no file at {target}"


def _resolve(name: str, folder: Path, roots: tuple[str, ...]) -> Path | None:
    if name.startswith("package://"):
        rest = name[len("package://"):]
        for d in [folder, *folder.parents]:
            if not any(_inside(d, Path(r)) for r in roots):
                continue
            candidate = Path(os.path.normpath(d / rest))
            if candidate.exists():
                return candidate
        return None
    if name.startswith("file://"):
        name = name[len("file://"):]
    return Path(os.path.normpath(name if os.path.isabs(name) else folder / name))


def _inside(path: Path, root: Path) -> bool:
    try:
        path.resolve().relative_to(root.resolve())
    except (ValueError, OSError):
        return False
    return True


def _positive_numbers(text: str, counts: tuple[int, ...], low: float = 0.0, high: float = math.inf) -> bool:
    """`counts` numbers, each finite and within [low, high] (above 0 when low is 0)."""
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        return False
    return len(values) in counts and all(math.isfinite(v) and v > 0 and low <= v <= high for v in values)


def _form_problems(tree: "ET.ElementTree[ET.Element]") -> list[str]:
    """An <origin> whose xyz or rpy is not three finite numbers (`xyz="0"`: the parser's guess),
    a <geometry> of other than one shape (the parser reads the first and drops the rest), an
    <inertial> without its mass value and six inertia entries (the parser skips the link's
    inertia with only a message on stderr, and the torque check would go without it)."""
    problems = [f"a geometry must hold exactly one shape (got {len(g)}: {', '.join(c.tag for c in g)[:60]})"
                for g in tree.iter("geometry") if len(g) != 1]
    for inertial in tree.iter("inertial"):
        mass, inertia = inertial.find("mass"), inertial.find("inertia")
        if mass is None or mass.get("value") is None or inertia is None or any(
                inertia.get(k) is None for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")):
            problems.append("an inertial must have a mass value and the inertia entries ixx, ixy, ixz, iyy, iyz, izz")
    for origin in tree.iter("origin"):
        for attribute in ("xyz", "rpy"):
            text = origin.get(attribute)
            if text is not None and not _three_finite(text):
                problems.append(f"origin {attribute}=\"{text[:40]}\" must be three finite numbers")
    return problems


def _three_finite(text: str) -> bool:
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        return False
    return len(values) == 3 and all(math.isfinite(v) for v in values)


def _check_values(tree: "ET.ElementTree[ET.Element]", name: str, span: Span | None, rep: Reporter) -> bool:
    """Sizes, shapes, velocity limits and inertias the parser would drop or misread (module doc)."""
    joints, links = list(tree.iter("joint")), list(tree.iter("link"))
    if len(joints) > MAX_JOINTS or len(links) > MAX_LINKS:
        rep.error(codes.ROBOT_LOAD, f"URDF robot must have at most {MAX_JOINTS} joints and {MAX_LINKS} links "
                  f"(got {len(joints)} joints, {len(links)} links in {name})", span)
        return False
    problems: list[str] = []
    for link in links:
        label = f"link '{link.get('name', '?')[:80]}'"
        for shape, attributes in _SHAPES.items():
            for element in link.iter(shape):
                for attribute in attributes:
                    text = element.get(attribute)
                    counts = _COUNTS.get(attribute, (1,))
                    low, high = (MIN_MESH_SCALE, MAX_MESH_SCALE) if shape == "mesh" else (MIN_SIZE_M, MAX_SIZE_M)
                    if (text is not None or shape != "mesh") and not _positive_numbers(text or "", counts, low, high):
                        problems.append(f"{label}: {shape} {attribute}=\"{(text or '')[:40]}\" must be finite and "
                                        f"within {low:g} .. {high:g}{'' if shape == 'mesh' else ' m'}")
        for mass in link.iter("mass"):
            if not _finite(mass.get("value", ""), lambda v: v >= 0):
                problems.append(f"{label}: mass value=\"{mass.get('value', '')[:40]}\" must be a finite number >= 0")
        for inertia in link.iter("inertia"):
            if not all(_finite(v, lambda _: True) for v in inertia.attrib.values()):
                problems.append(f"{label}: inertia entries must be finite numbers")
    for joint in joints:
        limit = joint.find("limit")
        velocity = limit.get("velocity") if limit is not None else None
        if joint.get("type") in _MOVING and velocity is not None and not _finite(velocity, lambda v: v > 0):
            problems.append(f"joint '{joint.get('name', '?')[:80]}': limit velocity=\"{velocity[:40]}\" must be finite and positive")
    problems += _form_problems(tree)
    for problem in problems[:5]:
        rep.error(codes.ROBOT_LOAD, f"URDF {name}, {problem}", span)
    return not problems


def _finite(text: str, accept: Callable[[float], bool]) -> bool:
    try:
        value = float(text)
    except ValueError:
        return False
    return math.isfinite(value) and accept(value)
