"""STEP part 21 files written entity by entity (ISO 10303-21 syntax, ISO 10303-42 B-rep
entities, the AP214 product structure), so the STEP tests need no CAD program: a box of
planar faces and a cylinder (two circles, a seam, a cylindrical face). Lengths in mm."""

from __future__ import annotations

import itertools

__all__ = ["step_box", "step_cylinder"]


class _Writer:
    def __init__(self) -> None:
        self.entities: list[str] = []

    def add(self, text: str) -> str:
        self.entities.append(text)
        return f"#{len(self.entities)}"

    def point(self, x: float, y: float, z: float) -> str:
        return self.add(f"CARTESIAN_POINT('',({x:.6f},{y:.6f},{z:.6f}))")

    def direction(self, x: float, y: float, z: float) -> str:
        return self.add(f"DIRECTION('',({x:.6f},{y:.6f},{z:.6f}))")

    def placement(self, p: str, z: str, x: str) -> str:
        return self.add(f"AXIS2_PLACEMENT_3D('',{p},{z},{x})")

    def face(self, edges: list[tuple[str, bool]], surface: str) -> str:
        oriented = [self.add(f"ORIENTED_EDGE('',*,*,{e},{'.T.' if same else '.F.'})") for e, same in edges]
        loop = self.add(f"EDGE_LOOP('',({','.join(oriented)}))")
        bound = self.add(f"FACE_OUTER_BOUND('',{loop},.T.)")
        return self.add(f"ADVANCED_FACE('',({bound}),{surface},.T.)")

    def file(self, name: str, faces: list[str]) -> str:
        shell = self.add(f"CLOSED_SHELL('',({','.join(faces)}))")
        solid = self.add(f"MANIFOLD_SOLID_BREP('{name}',{shell})")
        world = self.placement(self.point(0, 0, 0), self.direction(0, 0, 1), self.direction(1, 0, 0))
        length = self.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))")
        angle = self.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))")
        solid_angle = self.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())")
        accuracy = self.add(f"UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),{length},'distance_accuracy_value','')")
        context = self.add(f"(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT(({accuracy}))"
                           f"GLOBAL_UNIT_ASSIGNED_CONTEXT(({length},{angle},{solid_angle}))REPRESENTATION_CONTEXT('',''))")
        rep = self.add(f"ADVANCED_BREP_SHAPE_REPRESENTATION('',({world},{solid}),{context})")
        app = self.add("APPLICATION_CONTEXT('automotive design')")
        self.add(f"APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,{app})")
        product = self.add(f"PRODUCT('{name}','{name}','',({self.add(f'PRODUCT_CONTEXT({chr(39)}{chr(39)},{app},{chr(39)}mechanical{chr(39)})')}))")
        formation = self.add(f"PRODUCT_DEFINITION_FORMATION('','',{product})")
        dctx = self.add(f"PRODUCT_DEFINITION_CONTEXT('part definition',{app},'design')")
        definition = self.add(f"PRODUCT_DEFINITION('design','',{formation},{dctx})")
        shape = self.add(f"PRODUCT_DEFINITION_SHAPE('','',{definition})")
        self.add(f"SHAPE_DEFINITION_REPRESENTATION({shape},{rep})")
        body = "\n".join(f"#{k}={e};" for k, e in enumerate(self.entities, 1))
        return ("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('rmot test part'),'2;1');\n"
                f"FILE_NAME('{name}.step','',(''),(''),'','','');\n"
                "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
                f"{body}\nENDSEC;\nEND-ISO-10303-21;\n")


def step_box(sx: float, sy: float, sz: float) -> str:
    """A box [0, sx] x [0, sy] x [0, sz] (mm), its six planar faces oriented outward."""
    w = _Writer()
    size = (sx, sy, sz)
    corners = {c: w.add(f"VERTEX_POINT('',{w.point(*(c[m] * size[m] for m in range(3)))})")
               for c in itertools.product((0, 1), repeat=3)}
    edges: dict[tuple[tuple[int, ...], tuple[int, ...]], str] = {}

    def edge(a: tuple[int, ...], b: tuple[int, ...]) -> tuple[str, bool]:
        key = (min(a, b), max(a, b))
        if key not in edges:
            p, q = (tuple(k[m] * size[m] for m in range(3)) for k in key)
            d = [q[m] - p[m] for m in range(3)]
            n = sum(x * x for x in d) ** 0.5
            vec = w.add(f"VECTOR('',{w.direction(*(x / n for x in d))},1.)")
            edges[key] = w.add(f"EDGE_CURVE('',{corners[key[0]]},{corners[key[1]]},{w.add(f'LINE({chr(39)}{chr(39)},{w.point(*p)},{vec})')},.T.)")
        return edges[key], (a, b) == key

    faces = []
    for axis, side in itertools.product(range(3), (0, 1)):
        u, v = [m for m in range(3) if m != axis]
        loop = []
        for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
            c = [0, 0, 0]
            c[axis], c[u], c[v] = side, du, dv
            loop.append(tuple(c))
        if ((u - axis) % 3 == 1) != bool(side):  # counter-clockwise seen from outside
            loop.reverse()
        normal = [0.0, 0.0, 0.0]
        normal[axis] = 1.0 if side else -1.0
        ref = [0.0, 0.0, 0.0]
        ref[u] = 1.0
        origin = w.point(*(loop[0][m] * size[m] for m in range(3)))
        plane = w.add(f"PLANE('',{w.placement(origin, w.direction(*normal), w.direction(*ref))})")
        faces.append(w.face([edge(loop[k], loop[(k + 1) % 4]) for k in range(4)], plane))
    return w.file("box", faces)


def step_cylinder(r: float, h: float) -> str:
    """A cylinder of radius r about z from z = 0 to h (mm): a lateral face and two disks."""
    w = _Writer()
    up, down, x = w.direction(0, 0, 1), w.direction(0, 0, -1), w.direction(1, 0, 0)
    v0 = w.add(f"VERTEX_POINT('',{w.point(r, 0, 0)})")
    v1 = w.add(f"VERTEX_POINT('',{w.point(r, 0, h)})")
    c0 = w.add(f"CIRCLE('',{w.placement(w.point(0, 0, 0), up, x)},{r:.6f})")
    c1 = w.add(f"CIRCLE('',{w.placement(w.point(0, 0, h), up, x)},{r:.6f})")
    e0 = w.add(f"EDGE_CURVE('',{v0},{v0},{c0},.T.)")
    e1 = w.add(f"EDGE_CURVE('',{v1},{v1},{c1},.T.)")
    seam_line = w.add(f"LINE('',{w.point(r, 0, 0)},{w.add(f'VECTOR({chr(39)}{chr(39)},{up},1.)')})")
    seam = w.add(f"EDGE_CURVE('',{v0},{v1},{seam_line},.T.)")
    lateral = w.face([(e0, True), (seam, True), (e1, False), (seam, False)],
                     w.add(f"CYLINDRICAL_SURFACE('',{w.placement(w.point(0, 0, 0), up, x)},{r:.6f})"))
    bottom = w.face([(e0, False)], w.add(f"PLANE('',{w.placement(w.point(0, 0, 0), down, x)})"))
    top = w.face([(e1, True)], w.add(f"PLANE('',{w.placement(w.point(0, 0, h), up, x)})"))
    return w.file("cylinder", [lateral, bottom, top])
