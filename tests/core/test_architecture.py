"""The pipeline's one-way data flow and the CLI's light start, enforced."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("pinocchio", "toppra", "ruckig", "cvxpy", "numba", "fcl", "coal", "trimesh")


def _imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
    return names


def _modules(folder: str) -> list[Path]:
    return sorted((ROOT / folder).rglob("*.py"))


@pytest.mark.parametrize("path", _modules("backends"), ids=lambda p: p.name)
def test_backends_never_import_heavy_libraries(path: Path) -> None:
    """A backend only formats: it never imports pinocchio/toppra/ruckig/cvxpy. Which rmot
    folders each folder may import is the layer contract in pyproject.toml (`lint-imports`)."""
    bad = {name for name in _imports(path) if name.split(".")[0] in ("pinocchio", "toppra", "ruckig", "cvxpy")}
    assert not bad, f"{path.relative_to(ROOT)} imports {sorted(bad)}"


def test_help_imports_nothing_heavy() -> None:
    """`rmot --help` loads no numerics library: the CLI imports a command's stage only when it runs."""
    code = (
        "import sys\n"
        "from rmot.compiler.cli import cli\n"
        "try:\n    cli(['--help'], prog_name='rmot')\nexcept SystemExit:\n    pass\n"
        f"print(sorted(m for m in sys.modules if m.split('.')[0] in {HEAVY!r}))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "[]"


def test_version_flag_prints_the_package_version() -> None:
    """`rmot --version` prints the installed distribution's version."""
    from importlib.metadata import version

    from click.testing import CliRunner

    from rmot.compiler.cli import cli

    result = CliRunner().invoke(cli, ["--version"], prog_name="rmot")
    assert result.exit_code == 0
    assert result.output == f"rmot {version('rmot')}\n"


def test_unknown_command_is_a_usage_error() -> None:
    """A misspelt command exits 2 with click's usage message, not a traceback."""
    from click.testing import CliRunner

    from rmot.compiler.cli import cli

    result = CliRunner().invoke(cli, ["chek"], prog_name="rmot")
    assert result.exit_code == 2
    assert "No such command 'chek'" in result.output
