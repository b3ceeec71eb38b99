"""Commands import only what they need: the import set of real `rmot` processes (`-X importtime`).

Speed itself is measured in tests/benchmarks/bench_startup.py; here only which packages load.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

RMOT = [sys.executable, "-X", "importtime", "-c", "import sys; from rmot.compiler.cli import main; sys.argv[0] = 'rmot'; main()"]
THREE = """program three on r1 {
  tool gripper
  target home = joints(0, -10, 10, 0, 90, 0) deg
  target a = pose(x=-100mm, y=0mm, z=100mm, rx=180deg)
  move joint home
  frame table_top
  move linear a
  move joint home zone fine
}
"""
_LINE = re.compile(r"^import time:\s+\d+ \|\s+\d+ \|\s*(\S+)\s*$", re.M)


def imported(args: list[str], env: dict[str, str]) -> set[str]:
    """Top-level package names a `rmot ARGS` process imported."""
    proc = subprocess.run(RMOT + args, env=env, capture_output=True, text=True, check=False)
    names = {m.group(1).split(".")[0] for m in _LINE.finditer(proc.stderr)}
    assert "rmot" in names, proc.stderr[-2000:]
    return names


@pytest.fixture
def env(tmp_path: Path) -> dict[str, str]:
    return dict(os.environ, RMOT_CACHE_DIR=str(tmp_path / "cache"))


def test_help_loads_no_numeric_library(env: dict[str, str]) -> None:
    names = imported(["--help"], env)
    assert not names & {"numpy", "pinocchio", "numba", "lark", "scipy", "matplotlib"}


def test_robots_ik_loads_neither_the_parser_nor_the_planner(env: dict[str, str]) -> None:
    names = imported(["robots", "ik", "abb_irb120", "300", "0", "400", "180", "0", "0"], env)
    assert "pinocchio" in names  # it did run
    assert not names & {"matplotlib", "toppra", "ruckig", "lark", "cvxpy", "trimesh", "fcl", "PIL"}
    assert "numba" not in names  # one pose: the closed form runs in the interpreter (lang/jit.py)


@pytest.mark.parametrize("args", [["robots", "list"], ["robots", "fk", "abb_irb120", "0", "0", "0", "0", "30", "0"]])
def test_robot_library_without_ik_loads_no_numba(env: dict[str, str], args: list[str]) -> None:
    names = imported(args, env)
    assert "pinocchio" in names
    assert not names & {"numba", "scipy", "lark", "matplotlib", "toppra"}


def test_check_with_a_cached_plan_loads_no_planner_nor_plotting(env: dict[str, str], tmp_path: Path) -> None:
    prog = tmp_path / "three.rmot"
    prog.write_text(THREE, encoding="utf-8")
    future = prog.stat().st_mtime + 3600  # never "settled": no load entry, the front end runs
    os.utime(prog, (future, future))
    first = subprocess.run(RMOT + ["check", str(prog)], env=env, capture_output=True, text=True, check=False)
    assert first.returncode == 0, first.stdout + first.stderr[-2000:]
    names = imported(["check", str(prog)], env)
    assert "pinocchio" in names  # the front end ran
    assert not names & {"matplotlib", "toppra", "ruckig", "cvxpy", "PIL", "imageio"}
    assert not names & {"numba", "scipy"}  # a small job: FK in numpy, no compiled kernel loaded


def test_check_without_cache_loads_no_plotting(env: dict[str, str], tmp_path: Path) -> None:
    prog = tmp_path / "three.rmot"
    prog.write_text(THREE, encoding="utf-8")
    names = imported(["check", "--no-cache", str(prog)], env)
    assert "pinocchio" in names
    assert "matplotlib" not in names
    assert "numba" not in names  # a small grid: TOPP and IK kernels run in the interpreter
    assert "scipy" not in names  # the path splines are numpy (compiler/plan/cubic.py)


@pytest.mark.parametrize("command", [["check"], ["compile", "--target", "rapid", "-o", "OUT"]])
def test_a_command_after_check_loads_neither_parser_nor_robot_library(
        env: dict[str, str], tmp_path: Path, command: list[str]) -> None:
    """Plan, verification and front-end result all come from the cache (compiler/cli/
    load_cache.py): no lark, no pinocchio. The file is saved a minute before the runs (a file
    modified within 2 s before a run gets no load entry)."""
    prog = tmp_path / "three.rmot"
    prog.write_text(THREE, encoding="utf-8")
    os.utime(prog, (prog.stat().st_mtime - 60, prog.stat().st_mtime - 60))
    first = subprocess.run(RMOT + ["check", str(prog)], env=env, capture_output=True, text=True, check=False)
    assert first.returncode == 0, first.stdout + first.stderr[-2000:]
    args = [str(tmp_path / "out") if a == "OUT" else a for a in command]
    names = imported([args[0], str(prog), *args[1:]], env)
    assert not names & {"lark", "pinocchio", "coal", "numba", "scipy", "toppra", "matplotlib"}
    # nor what only other output needs: JUnit's xml, a library search's subprocess (ldconfig)
    assert not names & {"xml", "subprocess"}
