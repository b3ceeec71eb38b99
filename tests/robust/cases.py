"""Reproducers of hostile or damaged input, one per failure class ingredient (written anew,
same ingredients).

Each case is a small project: files (path -> text or bytes), the `rmot` argument list (`{d}`
is the project directory) and what must come back: an exit code and the diagnostic codes the
output must name. Used by tests/robust/test_reproducers.py (in-process, the suite) and by
tests/robust/survey.py (each in a subprocess under a time and memory cap).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["CASES", "Case"]


@dataclass(frozen=True)
class Case:
    name: str
    files: dict[str, str | bytes]
    argv: tuple[str, ...]
    exit_codes: frozenset[int] = frozenset({2})
    codes: tuple[str, ...] = ()   # each must appear in the output
    absent: tuple[str, ...] = ()  # text that must not appear in any output file
    setup: str = ""               # a named extra step (chmod, ...) done by the runner
    extra: dict[str, str] = field(default_factory=dict)  # symbolic links the runner makes: name -> target


_EXAMPLES_MODEL_CELL = (Path(__file__).resolve().parents[2] / "examples" / "cells" / "model_arm.rmot").read_text(encoding="utf-8")


def _prog(body: str, head: str = "") -> str:
    return f"{head}\nprogram p on r1 {{\n  target home = joints(0, -10, 10, 0, 90, 0) deg\n{body}\n}}\n"


def _ir(name: str, body: str, codes: tuple[str, ...], exit_codes: frozenset[int] = frozenset({2}), head: str = "") -> Case:
    return Case(name, {"p.rmot": _prog(body, head)}, ("ir", "{d}/p.rmot"), exit_codes, codes)


def _check(name: str, body: str, codes: tuple[str, ...], exit_codes: frozenset[int] = frozenset({2})) -> Case:
    return Case(name, {"p.rmot": _prog(body)}, ("check", "{d}/p.rmot"), exit_codes, codes)


_CELL2 = """cell c {
  robot r1 = abb_irb1600 at pose(z=400mm)
  robot r2 = ur5e at pose(x=1500mm, z=800mm)
}
"""

_ALL = ("--target", "rapid", "--target", "krl", "--target", "fanuc", "--target", "urscript", "--target", "inform",
        "--target", "val3", "--target", "csv", "--target", "json")


def _cell2(a: str, b: str) -> str:
    return _CELL2.replace("r1 =", f"{a} =").replace("r2 =", f"{b} =")


_FAN = "\n".join(
    ["  proc a0() { }"]
    + [f"  proc a{i}() {{ {'; '.join([f'a{i - 1}()'] * 10)} }}" for i in range(1, 8)]
    + ["  a7()"])

_MESH_PROG = ("cell c {\n  robot r1 = abb_irb1600\n  fixture f = mesh(\"@F@\") at pose(x=2m)\n}\n"
              "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n")
_MODEL_PROG = """cell c {
  model lifter {
    joint revolute dh(a=300mm, alpha=0deg, d=400mm, theta=0deg) range(-170deg, 170deg) speed 180 deg/s accel 720 deg/s^2
    joint revolute dh(a=250mm, alpha=180deg, d=0mm, theta=0deg) range(-145deg, 145deg) speed 240 deg/s accel 960 deg/s^2
    joint prismatic dh(a=0mm, alpha=0deg, d=0mm, theta=0deg) range(0mm, 200mm) speed 1000 mm/s accel 4000 mm/s^2
  }
  robot r1 = lifter at pose(x=1m)
}
program p on r1 {
  move joint joints(0deg, 0deg, 100mm)
  move joint joints(10deg, 0deg, 100mm)
}
"""
def _nested(levels: int) -> str:
    return _prog("  repeat 1 {\n" * levels + "  move joint home\n" + "  }\n" * levels)


_URDF_PROG = "cell c {\n  robot r1 = urdf(\"arm.urdf\")\n}\nprogram p on r1 {\n  wait 1 s\n}\n"


def _chain_urdf(joints: int) -> str:
    """A serial chain of `joints` revolute joints (a URDF too long for any arm)."""
    links = "".join(f'<link name="l{i}"/>' for i in range(joints + 1))
    chain = "".join(f'<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
                    f'<origin xyz="0 0 0.01"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>'
                    for i in range(joints))
    return f'<?xml version="1.0"?><robot name="long">{links}{chain}</robot>'


CASES: tuple[Case, ...] = (
    # ---- tracebacks
    Case("traceback_second_robot_without_task", {"p.rmot": _CELL2 + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n"},
         ("compile", "{d}/p.rmot", "--target", "rapid", "--target", "urscript", "-o", "{d}/out"), frozenset({0})),
    _check("traceback_joint_move_12deg", "  move joint home\n  move joint joints(12, -10, 10, 0, 90, 0) deg\n"
           "  move joint joints(0, 2, 10, 0, 90, 0) deg\n  move joint joints(0, -10, 10, 0, 102, 12) deg", (), frozenset({0, 1})),
    _ir("traceback_joint_speed_tiny", "  joint_speed 1e-9 %\n  move joint home", ("E125",)),
    _ir("traceback_time_huge_joint_move", "  move joint home time 1e6 s", ("E125",)),
    # ---- hangs
    _ir("hang_empty_for_loop", "  for i in 0 .. 1000000000 { }", ("E124",)),
    _ir("hang_settings_only_loop", "  for i in 0 .. 1000000000 { speed 100 mm/s }", ("E124",)),
    _ir("hang_loop_body_errors", "  for i in 0 .. 1000000000 { move joint nowhere }", ("E124",)),
    _ir("slow_loop_body_errors_under_limit", "  for i in 0 .. 190000 { move joint nowhere }", ("E101",)),
    _ir("slow_many_waits", "  repeat 20000 { wait 10 ms }", (), frozenset({0})),
    _ir("hang_repeat_empty", "  repeat 1000000000 { zone fine }", ("E124",)),
    _ir("hang_nested_empty_loops", "  for i in 0 .. 100000 { for j in 0 .. 100000 { } }", ("E124",)),
    _ir("slow_settings_loop_under_limit", "  for i in 0 .. 150000 { speed 100 mm/s }", (), frozenset({0})),
    _ir("hang_proc_fan_out", _FAN, ("E124",)),
    # ---- memory
    _ir("memory_wait_1e9", "  move joint home\n  wait 1e9 s", ("E125",)),
    _ir("memory_wait_10000", "  move joint home\n  wait 10000 s", ("E125",)),
    _check("memory_circular_far_via", "  move joint home\n  move circular via pose(x=100000 m, z=1 m, ry=180deg) "
           "to pose(x=900mm, z=1000mm, ry=180deg)", ("E125",)),
    _ir("memory_speed_tiny", "  speed 1e-9 mm/s\n  move linear pose(x=900mm, z=1000mm, ry=180deg)", ("E125",)),
    _ir("memory_linear_time_huge", "  move linear pose(x=900mm, z=1000mm, ry=180deg) time 1e5 s", ("E125",)),
    _check("memory_many_hours_of_waits", "  move joint home\n  repeat 7 { wait 150 s }", ("E124",), frozenset({1, 2})),
    # ---- non-finite numbers
    _ir("nonfinite_literal", "  move linear pose(x=1e999 mm)", ("E013",)),
    _ir("nonfinite_nan_rotation", "  const big = 1 deg / 1e-320\n  move linear pose(x=900mm, rx=big - big)", ("E123",)),
    _ir("nonfinite_nan_difference", "  move linear pose(x=(1 mm / 1e-320) - (1 mm / 1e-320))", ("E123",)),
    _ir("huge_literal_product", "  const big = 1e308 mm\n  move linear pose(x=(big * 10) - (big * 10))", ("E125",)),
    _ir("nonfinite_quaternion", "  move linear pose(x=900mm, z=1m, q=((1 / 1e-320), 0, 0, 0))", ("E123",)),
    _ir("nonfinite_quaternion_huge", "  move linear pose(x=900mm, z=1m, q=(1e200, 1e200, 0, 0))", ("E125",)),
    _ir("nonfinite_io_port", "  set out[(1 / 1e-320)] = on", ("E123",)),
    _ir("huge_io_port", "  set out[1e15] = on", ("E125",)),
    _ir("nonfinite_loop_bound", "  for i in 0 .. (1 / 1e-320) { }", ("E123",)),
    _ir("nonfinite_wait", "  wait 1 s / 1e-320", ("E123",)),
    _ir("nonfinite_speed", "  speed 1 mm/s / 1e-320", ("E123",)),
    _ir("huge_speed", "  speed 1e8 m/s\n  move linear pose(x=900mm, z=1m, ry=180deg)", ("E125",)),
    _ir("nonfinite_zone", "  zone 1 mm / 1e-320", ("E123",)),
    _ir("huge_zone", "  zone 5000 m", ("E125",)),
    _ir("nonfinite_pulse", "  pulse out[1] for 1 s / 1e-320", ("E123",)),
    _ir("huge_pulse", "  pulse out[1] for 1e7 s", ("E125",)),
    _ir("nonfinite_timeout", "  wait until in[1] timeout 1 s / 1e-320", ("E123",)),
    _ir("huge_timeout", "  wait until in[1] timeout 1e7 s", ("E125",)),
    _ir("huge_position", "  move linear pose(x=500 km)", ("E007",)),
    _ir("far_position", "  move linear pose(x=1e8 m, z=1m, ry=180deg)", ("E125",)),
    Case("nonfinite_box", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600\n  fixture f = box(1 mm / 1e-320, 1 m, 1 m) at pose(x=2m)\n}\n"
                           + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n"}, ("check", "{d}/p.rmot"), frozenset({2}), ("E123",)),
    Case("huge_box", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600\n  fixture f = box(1e8 m, 1 m, 1 m) at pose(x=2m)\n}\n"
                      + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n"}, ("check", "{d}/p.rmot"), frozenset({2}), ("E125",)),
    Case("mesh_scale_huge", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600\n  fixture f = mesh(\"part.stl\", scale=1e300) at pose(x=2m)\n}\n"
                             + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n",
                             "part.stl": "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n"},
         ("check", "{d}/p.rmot"), frozenset({2}), ("E125",)),
    Case("mesh_scale_tiny", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600\n  fixture f = mesh(\"part.stl\", scale=1e-320) at pose(x=2m)\n}\n"
                             + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n",
                             "part.stl": "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\nendloop\nendfacet\nendsolid t\n"},
         ("check", "{d}/p.rmot"), frozenset({2}), ("E125",)),  # SIGSEGV in coal before (make fuzz, seed 25011)
    Case("torque_bound_everywhere", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600 at pose(z=296mm)\n"
                                     "  tool g = box(90mm, 70mm, 120mm) at pose(z=100mm) tcp pose(z=204 in) mass 4.395 kg on r1\n}\n"
                                     "program p on r1 {\n  tool g\n  target home = joints(12.42, -47.2, 17.52, 59.58, 42.14, 30.6) deg\n"
                                     "  target t = pose(x=617.8mm, y=-65mm, z=1086mm, rx=151.38deg)\n  move joint home\n"
                                     "  move joint shift(t, z=-92.8mm)\n  move linear t tool flange\n}\n"},
         ("check", "{d}/p.rmot"), frozenset({1}), ()),  # 200 s before: the timing's grid refinement quadrupled every round (fuzz seed 837)
    Case("flat_mesh", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600\n  fixture f = mesh(\"part.stl\") at pose(x=2m)\n}\n"
                       + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n", "part.stl": "@STL@"},
         ("check", "{d}/p.rmot"), frozenset({0, 1}), ()),  # one triangle: a warning (W560), no traceback
    # ---- wrong diagnostics: line breaks, NUL
    Case("linebreak_form_feed", {"p.rmot": "program p on r1 {\f\n  move joint nowhere\n}\n"}, ("ir", "{d}/p.rmot"), frozenset({2}),
         ("p.rmot:2:14", "2 |   move joint nowhere")),
    Case("linebreak_u2028", {"p.rmot": "program p on r1 {\u2028  move joint home\n}\n"}, ("ir", "{d}/p.rmot"), frozenset({2}), ("E012", "p.rmot:1:18")),
    Case("linebreak_cr_only", {"p.rmot": "program p on r1 {\r  move joint home\r}\r"}, ("ir", "{d}/p.rmot"), frozenset({2}), ("E011", "p.rmot:1:18")),
    Case("linebreak_crlf_ok", {"p.rmot": "program p on r1 {\r\n  move joint nowhere\r\n}\r\n"}, ("ir", "{d}/p.rmot"), frozenset({2}),
         ("p.rmot:2:14", "2 |   move joint nowhere\n")),
    Case("nul_after_64k", {"p.rmot": "# " + "x" * 70000 + "\nprogram p on r1 {\n  wait 1 s\n}\n# \x00\n"}, ("ir", "{d}/p.rmot"),
         frozenset({2}), ("E010",)),
    Case("clearance_infinite", {"p.rmot": _prog("  move joint home")}, ("check", "{d}/p.rmot", "--clearance", "1e999mm"),
         frozenset({2}), ("at most 10 m",)),
    # ---- OS errors
    Case("os_check_output_missing_dir", {"p.rmot": _prog("  move joint home")}, ("check", "{d}/p.rmot", "-o", "{d}/nodir/report.txt"),
         frozenset({2}), ("E520", "nodir")),
    Case("os_plan_csv_missing_dir", {"p.rmot": _prog("  move joint home")}, ("plan", "{d}/p.rmot", "--csv", "{d}/nodir/t.csv"),
         frozenset({2}), ("E520", "nodir")),
    Case("os_check_images_under_file", {"p.rmot": _prog("  move joint home\n  move linear pose(x=0mm, y=0mm, z=300mm)"), "afile": "x"},
         ("check", "{d}/p.rmot", "--images", "{d}/afile/imgs"), frozenset({1, 2}), ("afile",)),
    Case("os_import_name_max", {"p.rmot": _prog("  move joint home", head=f'import "{"a" * 300}.rmot"')}, ("ir", "{d}/p.rmot"),
         frozenset({2}), ("E501",)),
    Case("os_import_unreadable_folder", {"p.rmot": _prog("  move joint home", head='import "locked/lib.rmot"'),
                                         "locked/lib.rmot": "const x = 1 mm\n"}, ("ir", "{d}/p.rmot"), frozenset({2}), ("E521",),
         setup="lock"),
    Case("os_unreadable_stl", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600\n  fixture f = mesh(\"part.stl\") at pose(x=2m)\n}\n"
                               + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n", "part.stl": "solid t\n"},
         ("check", "{d}/p.rmot"), frozenset({1}), ("E521",), setup="lock_stl"),  # meshes load in sim: a finding, as E561
    # ---- output safety
    Case("inject_file_name_newline", {"p\nMoveL Offs(pHome,0,0,-500), v5000, fine, tool0;\n.rmot": _prog("  move joint home")},
         ("compile", "{d}/p\nMoveL Offs(pHome,0,0,-500), v5000, fine, tool0;\n.rmot", "--target", "rapid", "--target", "krl",
          "--target", "fanuc", "--target", "urscript", "--target", "inform", "--target", "val3", "-o", "{d}/out"),
         frozenset({0}), absent=("\nMoveL Offs",)),
    Case("inject_signal_name_fanuc", {"p.rmot": "cell c {\n  robot r1 = abb_irb1600\n  io out[1] = \"a]\\\\n=1;\\\" ! x\" on r1\n}\n"
                                      + "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n  set out[1] = on\n}\n"},
         ("compile", "{d}/p.rmot", "--target", "fanuc", "--target", "rapid", "--target", "krl", "--target", "urscript",
          "--target", "inform", "--target", "val3", "-o", "{d}/out"), frozenset({0, 2}), ()),
    Case("task_name_case_clash", {"p.rmot": _cell2("Left", "left") + "program p {\n  task Left {\n    move joint joints(0, -10, 10, 0, 90, 0) deg\n  }\n"
                                  "  task left {\n    move joint joints(0, -90, 0, -90, 0, 0) deg\n  }\n}\n"},
         ("compile", "{d}/p.rmot", *_ALL, "-o", "{d}/out"), frozenset({1}), ("E522",)),
    Case("task_name_truncation_clash", {"p.rmot": _cell2("pick_and_place_number_one", "pick_and_place_number_two")
                                        + "program p {\n  task pick_and_place_number_one {\n"
                                        "    move joint joints(0, -10, 10, 0, 90, 0) deg\n  }\n"
                                        "  task pick_and_place_number_two {\n    move joint joints(0, -90, 0, -90, 0, 0) deg\n  }\n}\n"},
         ("compile", "{d}/p.rmot", *_ALL, "-o", "{d}/out"), frozenset({1}), ("E522",)),
    # ---- paths
    Case("urdf_mesh_outside_project", {"proj/p.rmot": "cell c {\n  robot r1 = urdf(\"arm.urdf\")\n}\nprogram p on r1 {\n  wait 1 s\n}\n",
                                       "proj/arm.urdf": "@URDF:../outside.stl@", "outside.stl": "@STL@"},
         ("ir", "{d}/proj/p.rmot"), frozenset({2}), ("E504",)),
    Case("urdf_mesh_package_uri", {"proj/p.rmot": "cell c {\n  robot r1 = urdf(\"arm.urdf\")\n}\nprogram p on r1 {\n  wait 1 s\n}\n",
                                   "proj/arm.urdf": "@URDF:package://../outside.stl@", "outside.stl": "@STL@"},
         ("ir", "{d}/proj/p.rmot"), frozenset({2}), ("E504",)),
    Case("urdf_mesh_absolute", {"proj/p.rmot": "cell c {\n  robot r1 = urdf(\"arm.urdf\")\n}\nprogram p on r1 {\n  wait 1 s\n}\n",
                                "proj/arm.urdf": "@URDF:{d}/outside.stl@", "outside.stl": "@STL@"},
         ("ir", "{d}/proj/p.rmot"), frozenset({2}), ("E504",)),
    Case("urdf_zero_axis", {"p.rmot": "cell c {\n  robot r1 = urdf(\"arm.urdf\")\n}\nprogram p on r1 {\n  wait 1 s\n}\n",
                            "arm.urdf": "@URDF0@"}, ("ir", "{d}/p.rmot"), frozenset({2}), ("E505",)),
    # ---- round 3: what a URDF declares is loaded or refused (urdfdom only printed on stderr)
    *(Case(f"urdf_{name}", {"p.rmot": _URDF_PROG, "arm.urdf": f"@URDFSUB:{old}=>{new}@"}, ("check", "{d}/p.rmot"),
           frozenset({2}), ("E505", "p.rmot:2:"))
      for name, old, new in (
          ("collision_length_nan", '<cylinder radius="0.09" length="0.2"/></geometry></collision>',
           '<cylinder radius="0.09" length="nan"/></geometry></collision>'),
          ("collision_radius_negative", '<cylinder radius="0.09" length="0.2"/></geometry></collision>',
           '<cylinder radius="-0.09" length="0.2"/></geometry></collision>'),
          ("collision_box_inf", '<cylinder radius="0.09" length="0.2"/></geometry></collision>',
           '<box size="0.1 inf 0.1"/></geometry></collision>'),
          ("velocity_zero", 'velocity="3.0"', 'velocity="0"'),
          ("mass_negative", '<mass value="6"/>', '<mass value="-6"/>'),
          ("inertia_nan", 'ixx="0.04"', 'ixx="nan"'),
          # make fuzz FUZZ_MIX=1 seed 2502: a 1e-320 m radius made verification allocate 4.5 GiB (E550 MemoryError),
          # an origin of one number was read as the parser guessed
          ("collision_radius_denormal", '<cylinder radius="0.09" length="0.2"/></geometry></collision>',
           '<cylinder radius="1e-320" length="0.2"/></geometry></collision>'),
          ("origin_one_number", '<origin xyz="0 0 0.2"/>', '<origin xyz="0"/>'),
          ("geometry_two_shapes", '<cylinder radius="0.09" length="0.2"/></geometry></collision>',
           '<cylinder radius="0.09" length="0.2"/><box size="1 1 1"/></geometry></collision>'),  # seed 8566
          # urdfdom printed "Could not parse inertial element" on stderr, and rmot check said ok (fuzz stderr)
          ("inertial_without_mass", '<mass value="6"/>', ""),
          ("inertia_without_ixx", 'ixx="0.04"', ""))),
    Case("urdf_1000_joints", {"p.rmot": _URDF_PROG, "arm.urdf": _chain_urdf(1000)}, ("check", "{d}/p.rmot"),
         frozenset({2}), ("E505", "at most")),
    # ---- round 3: an output never replaces an input or a folder rmot did not write (inputs compared after)
    Case("keep_check_output_is_program", {"p.rmot": _prog("  move joint home")}, ("check", "{d}/p.rmot", "-o", "{d}/p.rmot"),
         frozenset({2}), ("E564",), setup="keep_inputs"),
    Case("keep_check_output_is_link_to_program", {"p.rmot": _prog("  move joint home")},
         ("check", "{d}/p.rmot", "-o", "{d}/link.rmot"), frozenset({2}), ("E564",), setup="keep_inputs",
         extra={"link.rmot": "p.rmot"}),
    Case("keep_plan_csv_is_program", {"p.rmot": _prog("  move joint home")}, ("plan", "{d}/p.rmot", "--csv", "{d}/p.rmot"),
         frozenset({2}), ("E564",), setup="keep_inputs"),
    Case("keep_place_output_is_cell", {"p.rmot": 'use cell "c.rmot"\nprogram p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n',
                                       "c.rmot": "cell c {\n  robot r1 = abb_irb1600\n}\n"},
         ("place", "{d}/p.rmot", "--region", "x=0mm..100mm, y=0mm..100mm", "-o", "{d}/c.rmot"), frozenset({2}), ("E564",),
         setup="keep_inputs"),
    Case("keep_compile_foreign_vendor_folder", {"p.rmot": _prog("  move joint home"), "json/mine.txt": "the user's own notes\n"},
         ("compile", "{d}/p.rmot", "--target", "json", "--target", "rapid", "-o", "{d}"), frozenset({2}), ("E565",),
         setup="keep_inputs"),
    # ---- round 3: a mesh is what its file declares, and has area (zero-area triangles crashed the collision library)
    *(Case(f"mesh_{name}", {"p.rmot": _MESH_PROG.replace("@F@", file), file: body}, ("check", "{d}/p.rmot"), frozenset({1}), (code,))
      for name, file, body, code in (
          ("off_fewer_faces", "part.off", "OFF\n4 6 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 3\n", "E563"),
          ("off_fewer_vertices", "part.off", "OFF 4 1 0\n0 0 0\n1 0 0\n", "E563"),
          ("off_face_of_no_corners", "part.off", "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 0\n1 0 1\n0 0 1 2\n3 3 4 5\n",
           "E563"),  # trimesh dropped the face; make fuzz FUZZ_MIX=1 seed 3906
          ("zero_area_stl", "part.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 1 1 1\nvertex 1 1 1\nvertex 1 1 1\n"
           "endloop\nendfacet\nendsolid t\n", "E562"),
          ("zero_area_polygon", "part.mesh", "3 1\n0 0 0\n0 0 0\n0 0 0\n3 0 1 2\n", "E562"))),
    Case("mesh_zero_area_compile", {"p.rmot": _MESH_PROG.replace("@F@", "part.mesh"), "part.mesh": "3 1\n0 0 0\n0 0 0\n0 0 0\n3 0 0 0\n"},
         ("compile", "{d}/p.rmot", "--target", "json", "-o", "{d}/out"), frozenset({1, 2}), ("E562",)),
    # ---- round 3: an arm that does not verify has no cycle time to rank by
    Case("compare_unreachable_arm_has_no_cycle_time",
         {"p.rmot": "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n"
                    "  move linear pose(x=1400mm, y=0mm, z=600mm, ry=180deg)\n}\n"},
         ("compare", "{d}/p.rmot", "--robot", "ur5e", "--format", "json"), frozenset({1}),
         ('"cycle_time_s": null', '"verified": false', "E220")),
    # ---- round 3: absurd lengths in a model block are refused where they are written (verification allocated 90 GiB)
    *(Case(f"model_{name}", {"p.rmot": _MODEL_PROG.replace(old, new, 1)}, ("check", "{d}/p.rmot"), frozenset({2}), ("E125", where))
      for name, old, new, where in (
          ("dh_a_huge", "a=300mm", "a=999999999999mm", "p.rmot:3:"),
          ("dh_d_huge", "d=400mm", "d=-1e9 m", "p.rmot:3:"),
          ("prismatic_range_huge", "range(0mm, 200mm)", "range(0mm, 1e15mm)", "p.rmot:5:"),
          ("flange_far", "  }\n  robot", "    flange pose(z=999999999999mm)\n  }\n  robot", "p.rmot:6:"))),
    # ---- round 3: the nesting the front end allows is what every later stage handles (backends recursed out near 125)
    Case("nest_repeat_200", {"p.rmot": _nested(200)}, ("compile", "{d}/p.rmot", *_ALL, "-o", "{d}/out"), frozenset({2}),
         ("E121", "p.rmot:69:3", "at most 64")),
    Case("nest_repeat_at_limit", {"p.rmot": _nested(64)},
         ("compile", "{d}/p.rmot", *_ALL[:8], *_ALL[10:], "-o", "{d}/out"), frozenset({0}), ()),  # INFORM: E431, 50 loop variables
    Case("nest_repeat_at_limit_check", {"p.rmot": _nested(64)}, ("check", "{d}/p.rmot"), frozenset({0}), ("ok: cycle",)),
    # ---- round 3: merge-reports of a hostile report names the file and what is wrong, not E550
    Case("merge_json_200000_deep", {"deep.json": "[" * 200_000 + "]" * 200_000}, ("merge-reports", "{d}/deep.json"),
         frozenset({2}), ("E531", "deep.json", "too deeply")),
    Case("merge_json_900_deep_programs", {"r.json": '{"version": 1, "programs": ' + "[" * 900 + "]" * 900 + "}"},
         ("merge-reports", "{d}/r.json"), frozenset({2}), ("E531", "r.json", "64")),
    *(Case(f"merge_sarif_{name}", {"r.sarif": '{"version": "2.1.0", "runs": [' + run + "]}"}, ("merge-reports", "{d}/r.sarif"),
           frozenset({2}), ("E531", "r.sarif" if name != "unknown_rule" else "E1"))
      for name, run in (("tool_number", '{"tool": 5, "results": []}'),
                        ("driver_string", '{"tool": {"driver": "x"}, "results": []}'),
                        ("results_object", '{"tool": {"driver": {"rules": []}}, "results": {}}'),
                        ("result_without_rule", '{"results": [{"message": {}}]}'),
                        ("location_number", '{"results": [{"ruleId": "E1", "locations": [7]}]}'),
                        ("unknown_rule", '{"results": [{"ruleId": "E1", "locations": [{"physicalLocation": 7}]}]}'))),
    # ---- round 3: an unknown word in a cell is answered with what a cell declares, not program statements
    _ir("cell_unknown_declaration", "  wait 1 s", ("E006", "p.rmot:3:3", "a cell declaration starts with robot, fixture"),
        head="cell c {\n  robot r1 = abb_irb1600\n  xyzzy f = box(1m, 1m, 1m)\n}"),
    _ir("cell_misspelt_declaration", "  wait 1 s", ("E006", "p.rmot:3:3", "unknown declaration 'fixtre'; did you mean 'fixture'?"),
        head="cell c {\n  robot r1 = abb_irb1600\n  fixtre f = box(1m, 1m, 1m)\n}"),
    # ---- round 3: a cell model's name in W452 is quoted in balanced quotes
    Case("w452_cell_model_quotes", {"p.rmot": 'use cell "c.rmot"\nprogram p on r1 {\n  move joint joints(0, 0, 0, 0, 30, 0) deg\n'
                                               '  move joint joints(20, 0, 0, 0, 30, 0) deg\n}\n',
                                    "c.rmot": _EXAMPLES_MODEL_CELL},
         ("compile", "{d}/p.rmot", "--target", "urscript", "-o", "{d}/out"), frozenset({0}),
         ("warning[W452]: urscript: robot model 'my_arm' (a cell model) must be",)),
    # ---- round 3: 64 levels of if, while or proc calls compile to every target; one more is E121
    *(Case(f"nest_{kind}_{levels}", {"p.rmot": _prog(text)}, ("compile", "{d}/p.rmot", *_ALL, "-o", "{d}/out"),
           frozenset({0} if levels == 64 else {2}), () if levels == 64 else ("E121", "at most 64"))
      for levels in (64, 65)
      for kind, text in (("if", "  if in[1] {\n" * levels + "  move joint home\n" + "  }\n" * levels),
                         ("while", "  while in[1] {\n" * levels + "  move joint home\n" + "  }\n" * levels),
                         ("proc", "  proc a0() { move joint home }\n"
                          + "".join(f"  proc a{i}() {{ a{i - 1}() }}\n" for i in range(1, levels)) + f"  a{levels - 1}()"))),
    # ---- round 3: cell placements beyond a kilometre are refused where they are written
    *(Case(f"cell_far_{name}", {"p.rmot": "cell c {\n" + decl + "\n}\nprogram p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n"},
           ("check", "{d}/p.rmot"), frozenset({2}), ("E125", "p.rmot:" + where, "within 1000 m"))
      for name, decl, where in (
          ("robot", "  robot r1 = abb_irb1600 at pose(x=999999999999mm)", "2:29"),
          ("fixture", "  robot r1 = abb_irb1600\n  fixture f = box(1m, 1m, 1m) at pose(z=1e9 m)", "3:34"),
          ("tool_tcp", "  robot r1 = abb_irb1600\n  tool g = box(10mm, 10mm, 10mm) tcp pose(z=1e9 m) on r1", "3:38"))),
    # ---- round 3 (make fuzz FUZZ_MIX=1, seed 1042): a text STL with a bad normal line made trimesh log a
    # Python traceback on stderr; its triangles load (normals are not used), and nothing but rmot's words is printed
    Case("mesh_stl_bad_normal_line", {"p.rmot": _MESH_PROG.replace("@F@", "part.stl"),
                                      "part.stl": "solid t\nfacet normal 0 0 1&amp;\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\n"
                                                  "vertex 0 0.1 0\nendloop\nendfacet\nendsolid t\n"},
         ("check", "{d}/p.rmot"), frozenset({0, 1}), ("W560",)),
    # ---- round 3 (make fuzz FUZZ_MIX=1): merge-reports merged JSON reports of another version or shape (exit 0)
    *(Case(f"merge_json_{name}", {"r.json": text}, ("merge-reports", "{d}/r.json"), frozenset({2}), ("E531", "r.json", why))
      for name, text, why in (("version_text", '{"version": "x", "programs": []}', "$.version: must be of type integer"),
                              ("program_not_a_report", '{"version": 2, "programs": [{"$t": 1}]}', "must have key 'file'"),
                              ("program_cycle_string", '{"version": 2, "programs": [{"file": "p.rmot", "cycle_time_s": "x", '
                               '"assumptions": null, "tasks": [], "diagnostics": []}]}', "cycle_time_s"))),
    # make fuzz FUZZ_MIX=1 seed 3906: a flat mesh 170 m out (scale=1000) made coal's hull crash (SIGSEGV)
    Case("mesh_flat_far_out", {"p.rmot": _MESH_PROG.replace('"@F@"', '"part.mesh", scale=1000').replace("x=2m", "x=0m"),
                               "part.mesh": "3 1\n0.13049570990143062 0.027678012752656578 0.08053198025178649\n"
                                            "0.04479475918153486 0.1340248411746556 0.09746116970084935\n"
                                            "0.03220630161663727 0.1692231340574423 0.09838042348229114\n3 0 1 2\n"},
         ("check", "{d}/p.rmot"), frozenset({0, 1}), ("W560",)),
    Case("merge_sarif_run_without_tool", {"r.sarif": '{"version": "2.1.0", "runs": [{"results": []}]}'},
         ("merge-reports", "{d}/r.sarif"), frozenset({0}), ('"driver"',)),  # E550 KeyError 'tool' (fuzz seed 3614)
    Case("merge_junit_unknown_encoding", {"r.xml": '<?xml version="1.0" encoding="UTFinf"?>\n<testsuites/>\n'},
         ("merge-reports", "{d}/r.xml"), frozenset({2}), ("E531", "r.xml", "UTFinf")),  # E550 LookupError (fuzz seed 2031)
)
