"""Every failure of the third robustness campaign, replayed through the command line as a user
types it: each row runs `rmot` in a child process (its own cache folder) under the campaign's
caps, 60 s and 4 GiB of address space, and must end with a located diagnostic or the right
verdict, never a traceback or E550, with no input replaced.

Rows whose reproducer is a small project live in tests/robust/cases.py (run here by name, in a
child process rather than in this one); the rest need steps a case cannot express (a FIFO, a
cache edited between two runs, a closed pipe) and are written out below. The witness of each
cache row is the same command with --no-cache; of `place`, a full `rmot check` of the cell it
wrote; of the caption, the PNG's pixels."""

from __future__ import annotations

import functools
import json
import os
import resource
import shutil
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from tests.robust.cases import CASES
from tests.robust.runner import materialise
from tests.robust.test_caches import _entries, damage_lalr

ROOT = Path(__file__).resolve().parents[2]
LIMIT_S = 60
LIMIT_BYTES = 4 << 30
_CLI = "import sys; from rmot.compiler.cli import cli; sys.argv[0] = 'rmot'; cli(prog_name='rmot')"
_CASES = {c.name: c for c in CASES}


def _cap() -> None:  # in the child, before exec: the campaign's memory cap
    resource.setrlimit(resource.RLIMIT_AS, (LIMIT_BYTES, LIMIT_BYTES))


def rmot(cwd: Path, *args: str, cache: Path | None = None) -> subprocess.CompletedProcess[str]:
    """`rmot ARGS` in `cwd` under the caps; a run past LIMIT_S fails the row as a hang."""
    env = {**os.environ, "RMOT_CACHE_DIR": str(cache or cwd / ".rmot-test-cache")}
    try:
        done = subprocess.run([sys.executable, "-c", _CLI, *args], cwd=cwd, env=env, capture_output=True, text=True,
                              timeout=LIMIT_S, preexec_fn=_cap)
    except subprocess.TimeoutExpired:
        pytest.fail(f"hang: rmot {' '.join(args)[:200]} ran past {LIMIT_S} s")
    both = done.stdout + done.stderr
    assert "Traceback" not in both and "E550" not in both and "MemoryError" not in both, both[-3000:]
    return done


def _out(done: subprocess.CompletedProcess[str]) -> str:
    return done.stdout + done.stderr


# ----------------------------------------------------------------------------- rows from cases.py
def _case(name: str) -> Callable[[Path], None]:
    def run(d: Path) -> None:
        case = _CASES[name]
        argv = materialise(case, str(d))
        done = rmot(d, *argv)
        assert done.returncode in case.exit_codes, _out(done)
        for code in case.codes:
            assert code in _out(done), _out(done)
        if case.setup == "keep_inputs":  # nothing the project held was replaced
            for rel, text in case.files.items():
                assert (d / rel).read_text(encoding="utf-8") == text, rel
    return run


# ----------------------------------------------------------------------------- caches
COLLISION = ROOT / "examples" / "collision.rmot"


def _cache_attack(attack: Callable[[Path, Path], None], program: Path = COLLISION, command: str = "check") -> Callable[[Path], None]:
    """Run once with a cache, `attack(cache, d)` it, run again: the uncached verdict. The
    uncached run and the filled cache are the same for every row of one program and command:
    made once (`_filled_once`), and each row attacks its own byte copy of the cache."""
    def run(d: Path) -> None:
        cache = d / "cache"
        baseline, template = _filled_once(d.parent, program, command)
        shutil.copytree(template, cache, symlinks=True)
        attack(cache, d)
        again = rmot(d, command, str(program), cache=cache)
        assert (again.returncode, again.stdout) == (baseline.returncode, baseline.stdout), _out(again)
    return run


@functools.cache
def _filled_once(session: Path, program: Path, command: str) -> tuple[subprocess.CompletedProcess[str], Path]:
    """`rmot COMMAND PROGRAM --no-cache` and a cache folder filled by `rmot COMMAND PROGRAM`,
    both under `session` (pytest's temporary folder of the run, the parent of every tmp_path);
    entries are sealed by key and the folder's secret, so a copy is the same cache."""
    d = session / f"issue-table-{command}-{program.stem}"
    d.mkdir()
    baseline = rmot(d, command, str(program), "--no-cache", cache=d / "other")
    rmot(d, command, str(program), cache=d / "cache")
    assert (d / "cache" / "secret").is_file(), "the run filled no cache"
    return baseline, d / "cache"


def _edit_verify(cache: Path, d: Path) -> None:
    """The verification entry's findings emptied and its cycle time made NaN."""
    for path in _entries(cache, "verify"):
        data = path.read_bytes()
        start = data.index(b"{")
        doc = json.loads(data[start:])
        program_file, _, _, tasks = doc["doc"]["$t"]
        doc["doc"]["$t"] = [program_file, {"$d": [["collision", float("nan")]]}, {"$t": []}, tasks]
        path.write_bytes(data[:start] + json.dumps(doc).encode())


def _special_entries(kind: str) -> Callable[[Path, Path], None]:
    def attack(cache: Path, d: Path) -> None:
        for folder in ("lalr", "source", "plans", "verify", "load"):
            for path in _entries(cache, folder):
                path.unlink()
                if kind == "fifo":
                    os.mkfifo(path)
                else:
                    path.symlink_to("/dev/zero")
    return attack


def _list_dev_zero(cache: Path, d: Path) -> None:
    """Each load/ entry names /dev/zero as a file it read (its stamp would read it forever)."""
    for path in _entries(cache, "load"):
        data = path.read_bytes()
        start = data.index(b"{")
        text = data[start:].decode()
        path.write_bytes(data[:start] + text.replace(str(COLLISION), "/dev/zero").encode())


def _deep_plan(cache: Path, d: Path) -> None:
    for path in _entries(cache, "plans"):
        path.write_bytes(b"[" * 200_000 + b"]" * 200_000)


def _damage_lalr(cache: Path, d: Path) -> None:
    for path in _entries(cache, "lalr"):
        damage_lalr(path)


# ----------------------------------------------------------------------------- FIFOs and closed pipes
def _fifo(name: str, program: str, *args: str, code: str = "E521") -> Callable[[Path], None]:
    """`name` is a FIFO nobody writes to: refused at once, never a blocked read."""
    def run(d: Path) -> None:
        if name != "p.rmot":
            (d / "p.rmot").write_text(program, encoding="utf-8")
        os.mkfifo(d / name)
        done = rmot(d, *args)
        assert done.returncode == 2 or (done.returncode == 1 and code in _out(done)), _out(done)
        assert code in _out(done), _out(done)
    return run


_MESH = 'cell c {\n  robot r1 = abb_irb1600\n  fixture f = mesh("part.stl") at pose(x=2m)\n}\nprogram p on r1 {\n  wait 1 s\n}\n'
_URDF = 'cell c {\n  robot r1 = urdf("arm.urdf")\n}\nprogram p on r1 {\n  wait 1 s\n}\n'
_USE = 'use cell "c.rmot"\nprogram p on r1 {\n  wait 1 s\n}\n'


def _closed_stdout(*args: str, status: int = 141) -> Callable[[Path], None]:
    """stdout a pipe whose reader is gone (`rmot robots list | head -1`): quiet, SIGPIPE's status
    (click's own --help ends with 1)."""
    def run(d: Path) -> None:
        env = {**os.environ, "RMOT_CACHE_DIR": str(d / "cache")}
        proc = subprocess.Popen([sys.executable, "-c", _CLI, *args], cwd=d, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, preexec_fn=_cap)
        assert proc.stdout is not None
        proc.stdout.close()
        _, err = proc.communicate(timeout=LIMIT_S)
        assert proc.returncode == status and err == b"", (proc.returncode, err.decode()[-2000:])
    return run


# ----------------------------------------------------------------------------- sizes and work
_HOME = "program p on r1 {\n  target a = joints(0, -10, 10, 0, 90, 0) deg\n  target b = joints(25, -10, 15, 0, 90, 0) deg\n"


def _big(name: str, text: str, *args: str, codes: tuple[str, ...], exit_code: int = 2, within_s: float = LIMIT_S) -> Callable[[Path], None]:
    def run(d: Path) -> None:
        (d / name).write_text(text, encoding="utf-8")
        started = time.monotonic()
        done = rmot(d, *args)
        spent = time.monotonic() - started
        assert done.returncode == exit_code, _out(done)[-2000:]
        for code in codes:
            assert code in _out(done), _out(done)[-2000:]
        assert spent < within_s, f"{spent:.1f} s"
    return run


def _moves(n: int, joint: bool) -> str:
    if joint:
        return _HOME + "".join("  move joint a\n  move joint b\n" for _ in range(n // 2)) + "}\n"
    return _HOME + "  move joint a\n" + "".join(f"  move linear pose(x={900 + 10 * (i % 2)}mm, z=1000mm, ry=180deg)\n"
                                                for i in range(n)) + "}\n"


_TWO = ("cell c {\n  robot r1 = abb_irb1600 at pose(z=400mm)\n  robot r2 = ur5e at pose(x=1500mm, z=800mm)\n}\n"
        "program p {\n  task r1 {\n" + "    while in[1] {\n" * 100 + "    move joint joints(0, -10, 10, 0, 90, 0) deg\n"
        + "    }\n" * 100 + "  }\n  task r2 {\n    move joint joints(0, -90, 0, -90, 0, 0) deg\n  }\n}\n")


# ----------------------------------------------------------------------------- diagnostics
_ARC = ("program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n  move linear pose(x=900mm, y=0mm, z=1000mm, ry=180deg)\n"
        "  move circular via pose(x=5000mm, y=100mm, z=1000mm, ry=180deg) to pose(x=900mm, y=200mm, z=1000mm, ry=180deg)\n"
        "  move circular via pose(x=950mm, y=100mm, z=1000mm, ry=180deg) to pose(x=900mm, y=0mm, z=1000mm, ry=180deg)\n}\n")


def _arc_consequence(d: Path) -> None:
    (d / "p.rmot").write_text(_ARC, encoding="utf-8")
    out = _out(rmot(d, "check", "p.rmot"))
    assert "p.rmot:4:3: error[E220]" in out, out
    e226 = next(line for line in out.splitlines() if "E226" in line)
    assert e226.startswith("p.rmot:5:3:") and "a consequence of the failed move before it" in e226, out
    assert "p.rmot:4:3: note: the failed move" in out, out


def _failed_robot_not_unknown(d: Path) -> None:
    """A robot whose URDF does not load is one error where it is declared; its uses (the
    program's `on r1`, a tool `on r1`) are not each an `unknown robot` of their own."""
    (d / "p.rmot").write_text('cell c {\n  robot r1 = urdf("arm.urdf")\n  tool g = box(10mm, 10mm, 10mm) tcp pose(z=10mm) on r1\n}\n'
                              "program p on r1 {\n  wait 1 s\n}\n", encoding="utf-8")
    (d / "arm.urdf").write_text("<robot name='a'><link name='l0'/>", encoding="utf-8")
    done = rmot(d, "check", "p.rmot")
    assert done.returncode == 2 and "p.rmot:2:19: error[E505]" in done.stdout, _out(done)
    assert "E101" not in _out(done) and "1 error," in done.stdout, _out(done)


def _relative_cell_path(d: Path) -> None:
    (d / "a").mkdir()
    (d / "a" / "p.rmot").write_text('use cell "c.rmot"\nprogram p on r1 {\n  wait 1 s\n}\n', encoding="utf-8")
    (d / "a" / "c.rmot").write_text("cell c {\n  robot r1 = abb_irb1600\n  xyzzy\n}\n", encoding="utf-8")
    out = _out(rmot(d, "check", "a/p.rmot"))
    assert out.startswith("a/c.rmot:3:3: error[E006]") and str(d) not in out, out
    out = _out(rmot(d, "check", str(d / "a" / "p.rmot")))
    assert out.startswith(f"{d}/a/c.rmot:3:3: error[E006]"), out


def _every_unknown_word(d: Path) -> None:
    (d / "p.rmot").write_text("cell c {\n  robot r1 = abb_irb1600\n  fixtre f = box(1m, 1m, 1m)\n}\n"
                              "program p on r1 {\n  mvoe joint joints(0, 0, 0, 0, 90, 0) deg\n  wiat 1 s\n}\n", encoding="utf-8")
    done = rmot(d, "check", "p.rmot")
    assert done.returncode == 2
    for where in ("p.rmot:3:3: error[E006]", "p.rmot:6:3: error[E006]", "p.rmot:7:3: error[E006]"):
        assert where in _out(done), _out(done)


def _render_output(d: Path) -> None:
    (d / "p.rmot").write_text("program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n"
                              "  move joint joints(30, -10, 10, 0, 90, 0) deg\n}\n", encoding="utf-8")
    done = rmot(d, "render", "p.rmot", "-o", "a.gif", "--size", "64x48", "--fps", "4")
    assert done.returncode == 0 and done.stdout == "wrote a.gif\n" and "\r" not in done.stderr, _out(done)
    assert len(done.stderr.splitlines()) <= 1, done.stderr


def _caption_area(d: Path) -> None:
    from PIL import Image

    from tests.robust.test_captions import BAND_RGB, PROGRAM

    (d / "p.rmot").write_text(PROGRAM, encoding="utf-8")
    done = rmot(d, "render", "p.rmot", "-o", "s.png", "--at", "0.2")
    assert done.returncode == 0, _out(done)
    pixels = np.asarray(Image.open(d / "s.png").convert("RGB")).astype(int)
    band = (np.abs(pixels - BAND_RGB).sum(axis=-1) < 6).mean(axis=1) > 0.5
    assert pixels.shape[:2] == (480, 640) and band.mean() <= 0.2, f"{band.mean():.0%}"


def _prismatic_mm(d: Path) -> None:
    from tests.robust.cases import _MODEL_PROG

    (d / "p.rmot").write_text(_MODEL_PROG, encoding="utf-8")
    done = rmot(d, "plot", "p.rmot", "-o", "j.svg")
    assert done.returncode == 0, _out(done)
    svg = (d / "j.svg").read_text(encoding="utf-8")
    assert "J3 [mm]" in svg and "J3 [deg]" not in svg and "J1 [deg]" in svg


# ----------------------------------------------------------------------------- place
_WALLS = """cell c {
  robot r1 = abb_irb1600 at pose(x=150mm)
  fixture west = box(700mm, 1600mm, 300mm) at pose(x=-450mm, z=150mm)
  fixture east = box(700mm, 1600mm, 300mm) at pose(x=750mm, z=150mm)
  fixture north = box(500mm, 550mm, 300mm) at pose(x=150mm, y=525mm, z=150mm)
  fixture south = box(500mm, 550mm, 300mm) at pose(x=150mm, y=-525mm, z=150mm)
}
"""
_WORK = ('use cell "c.rmot"\nprogram p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n'
         "  move linear pose(x=750mm, y=0mm, z=700mm, ry=180deg) frame world\n"
         "  move linear pose(x=750mm, y=200mm, z=700mm, ry=180deg) frame world\n}\n")


def _place_far_pose(d: Path) -> None:
    """Walls around a pocket at x=150 mm, y=0: every pose near the work collides with them, so
    the poses ranked first fail; place checks on until poses in the pocket verify."""
    (d / "c.rmot").write_text(_WALLS, encoding="utf-8")
    (d / "p.rmot").write_text(_WORK, encoding="utf-8")
    done = rmot(d, "place", "p.rmot", "--region", "x=-600mm..600mm, y=-600mm..600mm", "-o", "placed.rmot")
    assert done.returncode == 0, _out(done)
    assert "planned and verified" in done.stdout and "clean (only those are ranked)" in done.stdout, done.stdout
    verified = int(done.stdout.split("planned and verified ")[1].split()[0])
    assert verified > 24, done.stdout  # past the 24 the first version gave up after
    check = rmot(d, "check", "p.rmot", "--cell", "placed.rmot")
    assert check.returncode == 0 and "ok: cycle" in check.stdout, _out(check)


ROWS: list[tuple[str, str, Callable[[Path], None]]] = [
    # (issue row, reproducer, replay)
    ("missed collision", "urdf collision length=nan", _case("urdf_collision_length_nan")),
    ("verdict faked by the cache", "verify/ entry edited, NaN cycle", _cache_attack(_edit_verify)),
    ("wrong answer", "OFF declaring 6 faces holding 3", _case("mesh_off_fewer_faces")),
    ("wrong answer", "URDF velocity=0", _case("urdf_velocity_zero")),
    ("wrong answer", "negative link mass", _case("urdf_mass_negative")),
    ("crash signal", "zero-area STL (check)", _case("mesh_zero_area_stl")),
    ("fuzz of the new mix", "text STL with a bad normal line (trimesh's traceback)", _case("mesh_stl_bad_normal_line")),
    ("crash signal", "zero-area polygon mesh (check)", _case("mesh_zero_area_polygon")),
    ("crash signal", "zero-area polygon mesh (compile)", _case("mesh_zero_area_compile")),
    ("memory", "DH a=999999999999mm", _case("model_dh_a_huge")),
    ("memory", "1000-joint URDF", _case("urdf_1000_joints")),
    ("memory", "cache entry listing /dev/zero", _cache_attack(_list_dev_zero)),
    ("memory", "cache entries linked to /dev/zero", _cache_attack(_special_entries("dev_zero"))),
    ("hang", "program file is a FIFO", _fifo("p.rmot", "", "check", "p.rmot")),
    ("hang", "used cell file is a FIFO", _fifo("c.rmot", _USE, "check", "p.rmot")),
    ("hang", "mesh file is a FIFO", _fifo("part.stl", _MESH, "check", "p.rmot")),
    ("hang", "URDF file is a FIFO", _fifo("arm.urdf", _URDF, "check", "p.rmot")),
    ("hang", "report to merge is a FIFO", _fifo("r.json", "", "merge-reports", "r.json", code="E530")),
    ("hang", "cache entries are FIFOs", _cache_attack(_special_entries("fifo"))),
    ("hang", "30k plain joint moves", _big("p.rmot", _moves(30_000, True), "check", "p.rmot", codes=("p.rmot:1:1: error[E124]",),
                                   exit_code=1, within_s=30)),
    ("hang", "30k plain linear moves", _big("p.rmot", _moves(30_000, False), "check", "p.rmot", codes=("p.rmot:1:1: error[E124]",),
                                   exit_code=1, within_s=30)),
    ("hang", "100k plain joint moves", _big("p.rmot", _moves(100_000, True), "check", "p.rmot", codes=("p.rmot:1:1: error[E124]",),
                                   exit_code=1, within_s=30)),
    ("hang", "100 nested while, two robots", _big("p.rmot", _TWO, "check", "p.rmot", codes=("p.rmot:72:5: error[E121]",))),
    ("hang", "repeat 199990 { wait 1 ms }",
     _big("p.rmot", _HOME + "  move joint a\n  repeat 199990 { wait 1 ms }\n}\n", "plan", "p.rmot", codes=("cycle time 199.99",),
          exit_code=0)),
    ("internal error", "200 nested repeat 1, every backend", _case("nest_repeat_200")),
    ("internal error", "deeply nested plan entry", _cache_attack(_deep_plan)),
    ("internal error", "damaged lalr/ table", _cache_attack(_damage_lalr, ROOT / "examples" / "pick_place.rmot")),
    ("internal error", "merge-reports of 200,000-deep JSON", _case("merge_json_200000_deep")),
    ("internal error", 'merge-reports of SARIF "tool": 5', _case("merge_sarif_tool_number")),
    ("fuzz of the new mix", "merge-reports of a JSON report whose version is text", _case("merge_json_version_text")),
    ("fuzz of the new mix", "merge-reports of a JSON program entry that is no report", _case("merge_json_program_not_a_report")),
    ("fuzz of the new mix", "OFF face line of no corners (trimesh dropped it)", _case("mesh_off_face_of_no_corners")),
    ("fuzz of the new mix", "flat mesh 170 m out (coal's hull: SIGSEGV)", _case("mesh_flat_far_out")),
    ("fuzz of the new mix", "merge-reports of a SARIF run without tool", _case("merge_sarif_run_without_tool")),
    ("fuzz of the new mix", "URDF cylinder radius 1e-320 (4.5 GiB in verification)", _case("urdf_collision_radius_denormal")),
    ("fuzz of the new mix", 'URDF origin xyz="0"', _case("urdf_origin_one_number")),
    ("fuzz of the new mix", "URDF geometry of two shapes (the second dropped)", _case("urdf_geometry_two_shapes")),
    ("fuzz of the new mix", "URDF inertial without mass (urdfdom's stderr only)", _case("urdf_inertial_without_mass")),
    ("fuzz of the new mix", "merge-reports of JUnit declaring encoding UTFinf", _case("merge_junit_unknown_encoding")),
    ("data loss", "check p.rmot -o p.rmot", _case("keep_check_output_is_program")),
    ("data loss", "plan p.rmot --csv p.rmot", _case("keep_plan_csv_is_program")),
    ("data loss", "place p.rmot ... -o c.rmot (its cell)", _case("keep_place_output_is_cell")),
    ("data loss", "compile --target json -o . over a user json/", _case("keep_compile_foreign_vendor_folder")),
    ("wrong answer (design)", "place: only a far pose (x=150 mm, y=0) verifies", _place_far_pose),
    ("wrong answer (design)", "compare: unreachable arm has a null cycle time", _case("compare_unreachable_arm_has_no_cycle_time")),
    ("last paragraph", "E006 inside a cell", _case("cell_unknown_declaration")),
    ("last paragraph", "parsing stops at the first unknown word", _every_unknown_word),
    ("last paragraph", "failed arc then E226 0.000 mm apart", _arc_consequence),
    ("last paragraph", "cell path absolute, program relative", _relative_cell_path),
    ("last paragraph", "a robot that does not load, then E101 unknown robot", _failed_robot_not_unknown),
    ("last paragraph", "W452 unbalanced quotes", _case("w452_cell_model_quotes")),
    ("last paragraph", "render silent on success, GIF bar floods logs", _render_output),
    ("last paragraph", "captions cover 45% of 640x480", _caption_area),
    ("last paragraph", "prismatic joint plotted in [deg]", _prismatic_mm),
    ("closed stdout", "rmot --help | head -1", _closed_stdout("--help", status=1)),
    *(("closed stdout", f"rmot {' '.join(args).replace(str(ROOT) + os.sep, '')} | head -1", _closed_stdout(*args))
      for args in (("robots", "list"), ("robots", "show", "abb_irb1600"), ("ir", str(ROOT / "examples" / "pick_place.rmot")),
                   ("check", str(ROOT / "examples" / "pick_place.rmot")), ("plan", str(ROOT / "examples" / "pick_place.rmot")),
                   ("diff", *(str(ROOT / "tests/data/vendor_programs/rapid" / n) for n in ("rosi_ROS_motion.mod", "rosi_ROS_motionServer.mod"))))),
]


@pytest.mark.parametrize("row, reproducer, replay", ROWS, ids=[f"{r}: {name}" for r, name, _ in ROWS])
def test_issue_row(row: str, reproducer: str, replay: Callable[[Path], None], tmp_path: Path) -> None:
    replay(tmp_path)
