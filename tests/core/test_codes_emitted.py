"""No dead diagnostic codes: every code a codes module registers is used by the
code that reports diagnostics, so a user can meet it.

A code counts as used when some module of the package (not its own codes module, not a test)
imports its codes module and names the constant. Codes dropped by every caller (built, then
replaced by another code) are caught by their own tests; this scan catches the codes nothing
names at all.
"""

from __future__ import annotations

import functools
import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = {"lang": "rmot.lang", "compiler": "rmot.compiler", "sim": "rmot.sim",
            "backends": "rmot.backends"}


def _sources() -> dict[str, str]:
    """Import name -> text of every module of the package."""
    out = {}
    for folder, package in PACKAGES.items():
        for path in sorted((ROOT / folder).rglob("*.py")):
            rel = path.relative_to(ROOT / folder).with_suffix("")
            name = ".".join((package, *rel.parts)).removesuffix(".__init__")
            out[name] = path.read_text(encoding="utf-8")
    return out


SOURCES = _sources()
_DEFINES = re.compile(r'^\w+ = Code\(\s*"', re.M)
CODE_MODULES = sorted(m for m, text in SOURCES.items() if _DEFINES.search(text))


def _registered() -> list[tuple[str, str, str]]:
    """(codes module, constant name, code id) of every code defined in a codes module."""
    out = []
    for module in CODE_MODULES:
        for name, value in vars(importlib.import_module(module)).items():
            defined_here = re.search(rf"^{name} = Code\(", SOURCES[module], re.M)
            if type(value).__name__ == "Code" and defined_here:
                out.append((module, name, value.id))
    return out


WORDS = {m: set(re.findall(r"\b[A-Z][A-Z0-9_]*\b", text)) for m, text in SOURCES.items()}


@functools.cache
def _importers(module: str) -> tuple[str, ...]:
    """The modules that import `module` (by its dotted name or `from parent import leaf`)."""
    parent, _, leaf = module.rpartition(".")
    imports = re.compile(rf"\b{re.escape(module)}\b"
                         rf"|from {re.escape(parent)} import [^\n]*\b{leaf}\b")
    return tuple(m for m, text in SOURCES.items() if m != module and imports.search(text))


def _users(module: str, name: str) -> list[str]:
    return [m for m in _importers(module) if name in WORDS[m]]


def test_the_scan_sees_every_codes_module() -> None:
    """The codes modules are found (a broken pattern would make the test below vacuous)."""
    main = {"rmot.lang.codes", "rmot.lang.check_codes", "rmot.backends.codes", "rmot.sim.codes"}
    assert main <= set(CODE_MODULES)
    assert len(_registered()) > 100


@pytest.mark.parametrize(("module", "name", "code"), _registered(), ids=lambda v: str(v))
def test_registered_code_is_used(module: str, name: str, code: str) -> None:
    assert _users(module, name), f"{code} ({module}.{name}) is registered but nothing reports it"


def test_an_unused_code_is_found() -> None:
    """The scan fails on a code nothing names (a constant only its own module mentions)."""
    assert not _users("rmot.sim.robots.codes", "NO_SUCH_CONSTANT")
    assert _users("rmot.sim.robots.codes", "BAD_URDF")


# an unknown library name is the design commands' own E804 (it names --robot and
# points to `rmot robots list`); a URDF that does not load keeps the loader's E202
@pytest.mark.parametrize(("robot", "code"), [("no_such_arm", "E804"), ("broken.urdf", "E202")])
def test_robot_load_codes_reach_the_user(robot: str, code: str, tmp_path: Path) -> None:
    """E202 (a RobotError's code) is reported as it is by the design commands, an unknown name
    as their E804 (the front end and the planner report a robot that does not load under their
    own codes; there is no E201, which nothing would report)."""
    from click.testing import CliRunner

    from rmot.compiler.cli import cli

    (tmp_path / "broken.urdf").write_text('<robot name="x"></robot>\n', encoding="utf-8")
    arg = str(tmp_path / robot) if robot.endswith(".urdf") else robot
    result = CliRunner().invoke(cli, ["reach", "--robot", arg, "-o", str(tmp_path / "m.png")])
    assert result.exit_code == 2 and f"error[{code}]" in result.output, result.output
