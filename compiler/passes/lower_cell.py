"""Pass 3: the cell block -> ir.Cell, and the cell scope programs resolve names against.

Choices (LANGUAGE.md is silent):
  * Geometry arguments: box(x, y, z) full edge lengths, cylinder(r, h), sphere(r),
    capsule(r, length) (length between the cap centres), mesh(path, unit=mm | scale=0.001);
    by position or by name. Every length must be > 0.
  * A fixture, robot or frame name used as a pose means its pose in world
    (`frame table_top = table * pose(z=15mm)`).
  * `tool t = none tcp ... on r1` is a tool without geometry; `at pose(...)` places the
    tool's geometry in the flange frame; `mass` defaults to 0 kg, `tcp` to the flange.
  * `io out[1] = "name"` without `on ROBOT` is a cell-wide signal.
"""

from __future__ import annotations

import os

from dataclasses import replace
from pathlib import Path

from rmot.lang import check_codes as codes, ir
from rmot.compiler.passes.context import Entry, Reporter, RobotInfo, RobotLookupError, Scope
from rmot.compiler.passes.urdf_paths import check_urdf_files
from rmot.compiler.passes.lower_model import described_urdf
from rmot.compiler.passes.lower_axes import CellAxes
from rmot.compiler.passes.limits import MAX_MESH_SCALE, MAX_SIZE_M, MIN_MESH_SCALE, MIN_SIZE_M, within
from rmot.compiler.passes.evaluate import eval_expr, expect_integer, expect_pose, expect_quantity, match_args
from rmot.compiler.passes.load_files import resolve_path
from rmot.compiler.passes.scopes import declare, misplaced
from rmot.compiler.passes.state import FrontendState
from rmot.compiler.passes.values import LENGTH, MASS, RATIO, UNIT_TABLE, PoseV, Quantity
from rmot.lang import ast
import json
from rmot.lang.model_spec import model_key

__all__ = ["program_feeders", "lower_cell", "IO_DIRECTIONS"]

IO_DIRECTIONS = {"out": ir.IoDirection.DIGITAL_OUT, "in": ir.IoDirection.DIGITAL_IN,
                 "aout": ir.IoDirection.ANALOG_OUT, "ain": ir.IoDirection.ANALOG_IN,
                 "gin": ir.IoDirection.GROUP_IN}
GROUP_MAX_BITS = 32  # a group input is read as one unsigned integer; 32 bits is the widest a controller's INT holds
_GEOMETRY_ARGS = {"box": ("x", "y", "z"), "cylinder": ("r", "h"), "sphere": ("r",),
                  "capsule": ("r", "length"), "mesh": ("path", "unit", "scale")}


class _CellBuilder:
    def __init__(self, state: FrontendState, decl: ast.CellDecl, scope: Scope | None = None) -> None:
        self.state = state
        self.rep: Reporter = state.reporter
        self.decl = decl
        self.file = decl.span.file
        self.scope = Scope() if scope is None else scope
        self.robots: list[ir.RobotInstance] = []
        self.infos: dict[str, RobotInfo] = {}
        self.fixtures: list[ir.Fixture] = []
        self.tools: list[ir.Tool] = []
        self.frames: list[ir.Frame] = []
        self.io: list[ir.IoSignal] = []
        self.io_seen: dict[tuple[ir.IoDirection, int, str | None], ast.IoDecl] = {}
        self.models: dict[str, tuple[str | None, ast.ModelDecl]] = {}  # name -> (load key or None if bad, decl)
        self.parts: list[ir.Part] = []
        self.axes = CellAxes(self.rep, self.scope)  # tracks, positioners and what rides on them

    def build(self) -> ir.Cell:
        for stmt in self.decl.body:
            handler = getattr(self, f"_{type(stmt).__name__}", None)
            if handler is None:
                misplaced(stmt, f"cell '{self.decl.name.name}'", self.rep)
            else:
                handler(stmt)
        return ir.Cell(self.decl.name.name, tuple(self.robots), tuple(self.fixtures), tuple(self.tools),
                       tuple(self.frames), tuple(self.io), span=self.decl.span, parts=tuple(self.parts),
                       external=self.axes.result())

    def _pose(self, e: ast.Expr | None, what: str) -> ir.Pose | None:
        if e is None:
            return ir.Pose()
        pose = expect_pose(eval_expr(e, self.scope, self.rep), what, e.span, self.rep)
        far = max((abs(c) for c in pose.position), default=0.0) if pose is not None else 0.0
        if far > MAX_SIZE_M:  # a cell a kilometre across at most, as its solids: 10^9 m only costs work later
            self.rep.error(codes.PHYSICAL_RANGE, f"{what} must be within {MAX_SIZE_M:g} m of the origin (got {far:.6g} m)", e.span)
            return None
        return pose

    def _RobotDecl(self, s: ast.RobotDecl) -> None:
        start = len(self.rep.sink)
        self._robot_decl(s)
        if s.name.name not in self.infos and self.rep.sink.errors_since(start):
            self.rep.failed_declarations.add(s.name.name)

    def _robot_decl(self, s: ast.RobotDecl) -> None:
        base = self._pose(s.at, f"placement of robot '{s.name.name}'")
        if s.on is not None:
            base = self.axes.carried(s.on, base, "robot", s.name.name, s.span)
        if s.library is not None and s.library.name in self.models:  # a model of this cell
            key, span = self.models[s.library.name][0], s.library.span
            if key is None:  # the model block has errors, reported there
                return
            source = ir.RobotSource(ir.RobotSourceKind.MODEL, key)
        elif s.library is not None:
            key, source = s.library.name, ir.RobotSource(ir.RobotSourceKind.LIBRARY, s.library.name)
            span = s.library.span
        else:
            assert s.urdf is not None
            span = s.urdf.span
            path = resolve_path(s.urdf.value, self.file, self.state.roots, span, self.rep, "URDF")
            if path is not None:
                path = described_urdf(s, path, self.file, self.state.roots, self.rep)
            if path is None or not check_urdf_files(path, self.state.roots, span, self.rep):
                return
            key, source = path, ir.RobotSource(ir.RobotSourceKind.URDF, path)
            if any(a.name is None or a.name.name != "packages" for a in s.urdf_args):
                from rmot.compiler.passes.lower_model import urdf_chain  # late: loads coal only when this runs

                chain = urdf_chain(s, path, self.rep)
                if chain is None:
                    return

                base_link, tip_link, maker = chain
                parts = [path, base_link, tip_link] + ([maker] if maker is not None else [])
                key = "urdf-chain:" + json.dumps(parts)  # sim/robots/loader.py
                source = ir.RobotSource(ir.RobotSourceKind.URDF_CHAIN, key)
        try:
            info = self.state.robot_loader(key)
        except RobotLookupError as exc:
            if source.kind is ir.RobotSourceKind.LIBRARY:
                self.rep.unknown(key, "robot model", span, list(exc.candidates), codes.UNKNOWN_ROBOT)
            else:
                what = "model" if source.kind is ir.RobotSourceKind.MODEL else "URDF"
                self.rep.error(codes.ROBOT_LOAD, f"{what} robot must load (got: {exc})", span)
            return
        if s.shares:
            shares = self._shares(s)
            if shares is None:
                return
            source = ir.RobotSource(source.kind, source.ref, *shares)
        if base is None or not declare(self.scope, Entry("robot", s.name.name, PoseV(base, s.name.name), s.name.span), self.rep):
            return
        self.infos[s.name.name] = info
        release = self._kss_release(s)
        self.robots.append(ir.RobotInstance(s.name.name, source, base, info.dof, span=s.span,
                                            kss_release=release))

    def _kss_release(self, s: ast.RobotDecl) -> float | None:
        """The KUKA system software release of `robot r1 = NAME controller kss 8.3` (major.minor
        as KUKA numbers its releases: 8.2, 8.3, 8.5, ...), None when the cell gives none; E118
        (a value the setting does not allow) for other software or a release that is not a
        plain number 1..99."""
        if s.software is None:
            return None
        name, e = s.software
        value = eval_expr(e, self.scope, self.rep)
        number = value.value if isinstance(value, Quantity) and not value.unit else None
        if name.name != "kss" or number is None or not 1.0 <= number < 100.0:
            shown = value.shown() if isinstance(value, Quantity) else "a value that is not a number"
            self.rep.error(codes.OUT_OF_RANGE, "a robot's controller software must "
                           f"be 'kss' with its release as a number, e.g. `controller kss 8.3` (got "
                           f"'{name.name}' {shown})", name.span)
            return None
        return float(number)

    def _shares(self, s: ast.RobotDecl) -> tuple[float, float] | None:
        """(speed share, acceleration share) of `robot r1 = NAME speed S % accel A %`: the arm's
        limits calibrated to its controller, each 1 %..300 % (E125 outside; each at most once,
        in this order, by the grammar)."""
        got: dict[str, float] = {}
        for setting in s.shares:
            e: ast.Expr = setting.value  # type: ignore[assignment]
            x = expect_quantity(eval_expr(e, self.scope, self.rep), RATIO, f"{setting.kind} of robot "
                                f"'{s.name.name}'", e.span, self.rep)
            x = within(x, 0.01, 3.0, f"{setting.kind} of robot '{s.name.name}'", "%", 0.01, e.span, self.rep)
            if x is None:
                return None
            got[setting.kind] = x
        return got.get("speed", 1.0), got.get("accel", 1.0)

    def _geometry(self, g: ast.Geometry) -> ir.Geometry | None:
        kind = g.kind.name
        names = _GEOMETRY_ARGS.get(kind)
        if names is None:
            self.rep.unknown(kind, "geometry", g.kind.span, list(_GEOMETRY_ARGS))
            return None
        if kind == "mesh":
            return self._mesh(g)
        bound = match_args(g.args, names, kind, g.span, self.rep, required=len(names))
        if bound is None:
            return None
        sizes = []
        for n in names:
            x = expect_quantity(eval_expr(bound[n].value, self.scope, self.rep), LENGTH, f"{kind} '{n}'", bound[n].span, self.rep)
            if x is not None and x <= 0:
                self.rep.error(codes.OUT_OF_RANGE, f"{kind} '{n}' must be > 0 mm (got {x * 1000:g} mm)", bound[n].span)
                x = None
            x = None if x is None else within(x, MIN_SIZE_M, MAX_SIZE_M, f"{kind} '{n}'", "m", 1.0, bound[n].span, self.rep)
            sizes.append(x)
        if any(x is None for x in sizes):
            return None
        if kind == "box":
            return ir.Box((sizes[0], sizes[1], sizes[2]))  # type: ignore[arg-type]
        if kind == "cylinder":
            return ir.Cylinder(sizes[0], sizes[1])  # type: ignore[arg-type]
        if kind == "sphere":
            return ir.Sphere(sizes[0])  # type: ignore[arg-type]
        return ir.Capsule(sizes[0], sizes[1])  # type: ignore[arg-type]

    def _mesh(self, g: ast.Geometry) -> ir.Geometry | None:
        bound = match_args(g.args, _GEOMETRY_ARGS["mesh"], "mesh", g.span, self.rep, required=1)
        if bound is None:
            return None
        path_arg = bound["path"].value
        if not isinstance(path_arg, ast.String):
            self.rep.error(codes.WRONG_TYPE, "mesh path must be a string such as \"meshes/part.stl\"", path_arg.span)
            return None
        scale = 1.0
        if "unit" in bound:
            unit = bound["unit"].value
            text = unit.name if isinstance(unit, ast.Name) else unit.value if isinstance(unit, ast.String) else None
            if text not in UNIT_TABLE or UNIT_TABLE[text][1] != LENGTH:
                self.rep.error(codes.WRONG_DIMENSION, "mesh unit must be a length unit: mm, cm, m or in", unit.span)
                return None
            scale = UNIT_TABLE[text][0]
        if "scale" in bound:
            v = eval_expr(bound["scale"].value, self.scope, self.rep)
            if not (isinstance(v, Quantity) and v.unit is None and v.value > 0):
                self.rep.error(codes.WRONG_TYPE, "mesh scale must be a positive number such as 0.001", bound["scale"].span)
                return None
            scale = v.value
            if within(scale, MIN_MESH_SCALE, MAX_MESH_SCALE, "mesh scale", "", 1.0, bound["scale"].span, self.rep) is None:
                return None
        path = resolve_path(path_arg.value, self.file, self.state.roots, path_arg.span, self.rep, "mesh")
        if path is not None and os.path.splitext(path)[1].lower() in (".step", ".stp") and ("unit" in bound or "scale" in bound):
            given = bound["unit"] if "unit" in bound else bound["scale"]
            self.rep.error(codes.STEP_UNIT, "a STEP mesh must be given without unit= or scale= (the file states its "
                           "own length unit, which OpenCASCADE applies)", given.span)
            return None
        return None if path is None else ir.Mesh(path, scale, span=path_arg.span)

    def _FixtureDecl(self, s: ast.FixtureDecl) -> None:
        geometry = self._geometry(s.geometry)
        pose = self._pose(s.at, f"placement of fixture '{s.name.name}'")
        if s.on is not None:
            pose = self.axes.carried(s.on, pose, "fixture", s.name.name, s.span)
        if geometry is None or pose is None:
            return
        if declare(self.scope, Entry("fixture", s.name.name, PoseV(pose, s.name.name), s.name.span), self.rep):
            self.fixtures.append(ir.Fixture(s.name.name, geometry, pose, span=s.span))

    def _ToolDecl(self, s: ast.ToolDecl) -> None:
        geometry = self._geometry(s.geometry) if s.geometry is not None else None
        at = self._pose(s.at, f"geometry placement of tool '{s.name.name}'")
        tcp = self._pose(s.tcp, f"tcp of tool '{s.name.name}'")
        mass = 0.0
        if s.mass is not None:
            mass = expect_quantity(eval_expr(s.mass, self.scope, self.rep), MASS, "tool mass", s.mass.span, self.rep)  # type: ignore[assignment]
            if mass is not None and mass < 0:
                self.rep.error(codes.OUT_OF_RANGE, f"tool mass must be >= 0 kg (got {mass:g} kg)", s.mass.span)
                mass = None  # type: ignore[assignment]
        if s.robot.name not in self.infos:
            self.rep.unknown(s.robot.name, "robot", s.robot.span, list(self.infos))
            return
        if (s.geometry is not None and geometry is None) or at is None or tcp is None or mass is None:
            return
        number = self._number(s.number, f"tool '{s.name.name}'")
        tool = ir.Tool(s.name.name, s.robot.name, geometry, tcp, mass, at, span=s.span, number=number)
        if declare(self.scope, Entry("tool", s.name.name, tool, s.name.span), self.rep):
            self.tools.append(tool)

    def _FrameDecl(self, s: ast.FrameDecl) -> None:
        pose = self._pose(s.value, f"frame '{s.name.name}'")
        if pose is not None and declare(self.scope, Entry("frame", s.name.name, PoseV(pose, s.name.name), s.name.span), self.rep):
            self.frames.append(ir.Frame(s.name.name, pose, span=s.span,
                                        number=self._number(s.number, f"frame '{s.name.name}'")))
            self.axes.frame(s.name.name, s.value, pose, s.span, s.number)

    def _MechanismDecl(self, s: ast.MechanismDecl) -> None:
        flange = self.axes.mechanism(s, self._pose(s.at, f"placement of {s.kind} '{s.name.name}'"))
        if flange is not None:
            declare(self.scope, Entry("mechanism", s.name.name, PoseV(flange, s.name.name), s.name.span), self.rep)
            self.fixtures += self.axes.solids(s, self._geometry)  # the axes' own solids (lower_axis_solids.py)

    def _number(self, e: ast.Expr | None, what: str) -> int | None:
        """`number n` of a tool or frame: the controller's number, an integer >= 0 (which
        numbers a vendor accepts is the backend's to check)."""
        if e is None:
            return None
        n = expect_integer(eval_expr(e, self.scope, self.rep), f"number of {what}", e.span, self.rep)
        if n is not None and n < 0:
            self.rep.error(codes.OUT_OF_RANGE, f"number of {what} must be >= 0 (got {n})", e.span)
            return None
        return n

    def _IoDecl(self, s: ast.IoDecl) -> None:
        port = expect_integer(eval_expr(s.io.index, self.scope, self.rep), "I/O port", s.io.index.span, self.rep)
        robot = s.robot.name if s.robot is not None else None
        if robot is not None and robot not in self.infos:
            self.rep.unknown(robot, "robot", s.robot.span, list(self.infos))  # type: ignore[union-attr]
            return
        if port is None:
            return
        direction = IO_DIRECTIONS[s.io.kind]
        key = (direction, port, robot)
        if key in self.io_seen:
            self.rep.error(codes.DUPLICATE, f"{s.io.kind}[{port}] must be declared once (got it twice)", s.span,
                           (("first declared here", self.io_seen[key].span),))
            return
        self.io_seen[key] = s
        self.io.append(ir.IoSignal(direction, port, s.signal.value, robot, span=s.span, bits=self._io_bits(s)))

    def _io_bits(self, s: ast.IoDecl) -> int | None:
        """The width of a group input (`io gin[n] = "name" bits B`), B in 1..32."""
        if s.bits is None:
            return None
        if s.io.kind != "gin":
            self.rep.error(codes.GROUP_INPUT_WIDTH, f"'bits' must be given on a group input gin[n] only "
                           f"(got it on {s.io.kind}[...])", s.bits.span)
            return None
        bits = expect_integer(eval_expr(s.bits, self.scope, self.rep), "group input width", s.bits.span, self.rep)
        if bits is not None and not 1 <= bits <= GROUP_MAX_BITS:
            self.rep.error(codes.GROUP_INPUT_WIDTH, f"a group input's width must be 1..{GROUP_MAX_BITS} bits "
                           f"(got {bits})", s.bits.span)
            return None
        return bits

    def _ModelDecl(self, s: ast.ModelDecl) -> None:
        from rmot.compiler.passes.lower_model import check_model_name, lower_model  # late: loads coal only when this runs

        name = s.name.name
        if name in self.models:
            first = self.models[name][1]
            self.rep.error(codes.DUPLICATE, f"model '{name}' must be defined once in this cell (got a second one)",
                           s.name.span, ((f"'{name}' is first defined here", first.name.span),))
            return
        check_model_name(s, self.rep)
        spec = lower_model(s, self.scope, self.rep, self._geometry)
        self.models[name] = (None if spec is None else model_key(spec), s)

    def _PartDecl(self, s: ast.PartDecl) -> None:
        """`part box1 = box(...) at pose(...) mass 2kg`: its name used as a pose is
        where it starts (`move linear box1 * pose(z=100mm)`)."""
        geometry = self._geometry(s.geometry)
        pose = self._pose(s.at, f"placement of part '{s.name.name}'")
        mass: float | None = 0.0
        if s.mass is not None:
            mass = expect_quantity(eval_expr(s.mass, self.scope, self.rep), MASS, "part mass", s.mass.span, self.rep)
            if mass is not None and mass < 0:
                self.rep.error(codes.OUT_OF_RANGE, f"part mass must be >= 0 kg (got {mass:g} kg)", s.mass.span)
                mass = None
        if geometry is None or pose is None or mass is None:
            return
        if declare(self.scope, Entry("part", s.name.name, PoseV(pose, s.name.name), s.name.span), self.rep):
            self.parts.append(ir.Part(s.name.name, geometry, pose, mass, span=s.span))

    def _FeederDecl(self, s: ast.FeederDecl) -> None:
        """`feeder infeed = box(...) at pose(...) mass 6 kg count 28`: a part of the cell whose
        `attach` takes the part it presents (its name used as a pose is where it presents them)."""
        count = None
        if s.count is not None:
            count = expect_integer(eval_expr(s.count, self.scope, self.rep), "feeder count", s.count.span, self.rep,
                                   minimum=1)
            if count is None:
                return
        before = len(self.parts)
        self._PartDecl(ast.PartDecl(s.name, s.geometry, s.at, s.mass, s.span))
        if len(self.parts) > before:
            self.parts[-1] = replace(self.parts[-1], feeder=True, count=count)

    def _ConstDecl(self, s: ast.ConstDecl) -> None:
        v = eval_expr(s.value, self.scope, self.rep)
        if v is not None:
            declare(self.scope, Entry("const", s.name.name, v, s.name.span), self.rep)


def lower_cell(state: FrontendState) -> FrontendState:
    mod = state.cell_module
    if mod is None:
        return state
    cells = [s for s in mod.module.body if isinstance(s, ast.CellDecl)]
    if not cells:
        state.reporter.error(codes.NO_CELL, f"cell file must contain a 'cell NAME {{ ... }}' block (got none in {Path(mod.path).name})",
                             mod.module.body[0].span if mod.module.body else None)
        return state
    for extra in cells[1:]:
        state.reporter.error(codes.NO_CELL, "a file must contain at most one cell (got a second one)", extra.name.span,
                             (("the first cell is here", cells[0].name.span),))
    builder = _CellBuilder(state, cells[0])
    cell = builder.build()
    return replace(state, cell=cell, cell_scope=builder.scope, robots=builder.infos)


def program_feeders(state: FrontendState, prog: ast.ProgramDecl, scope: Scope) -> FrontendState:
    """The feeders declared at a program's top level (`feeder infeed = box(...) at ...`), added
    to the cell's parts as if the cell declared them; their names are declared in `scope` (the
    program's), their numbers read in it. A name the cell already gives a part is a second definition
    (E102)."""
    decls = [s for s in prog.body if isinstance(s, ast.FeederDecl)]
    if not decls or state.cell is None:
        return state
    builder = _CellBuilder(state, ast.CellDecl(prog.name, (), prog.span), scope)
    taken = {p.name: p for p in state.cell.parts}
    for decl in decls:
        first = taken.get(decl.name.name)
        if first is not None:
            state.reporter.error(codes.DUPLICATE, f"'{decl.name.name}' must be defined once (the cell already has a part "
                                 "of that name)", decl.name.span, ((f"'{decl.name.name}' is first defined here", first.span),))
            continue
        builder._FeederDecl(decl)
    return replace(state, cell=replace(state.cell, parts=state.cell.parts + tuple(builder.parts)))
