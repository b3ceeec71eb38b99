"""`rmot compile`'s writer (compiler/cli/output_tree.py): per vendor all-or-nothing, atomic
even under SIGKILL, refusing vendors keep their old output, others are still written."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from rmot.compiler.cli import cli
from rmot.compiler.cli.output_tree import recover, write_vendor_dirs

ROOT = Path(__file__).resolve().parents[2]
OLD = {"rapid": {"a.mod": "old a\n", "gone.mod": "old only\n"}, "krl": {"a.src": "old\n", "a.dat": "old\n"},
       "fanuc": {"A.ls": "old\n"}}
NEW = {"rapid": {"a.mod": "new a\n", "b.mod": "new b\n"}, "krl": {"a.src": "new\n", "a.dat": "new\n", "b.src": "new\n"},
       "fanuc": {"A.ls": "new\n", "B.ls": "new\n"}}

_CHILD = textwrap.dedent("""
    import os, signal, sys
    sys.path.insert(0, {root!r})
    from rmot.compiler.cli import output_tree
    kill_at, hook, fallback = int(sys.argv[1]), sys.argv[2], sys.argv[3] == "1"
    calls = [0]
    real = getattr(os, hook)
    def deadly(*a, **k):
        calls[0] += 1
        if calls[0] == kill_at:
            os.kill(os.getpid(), signal.SIGKILL)
        return real(*a, **k)
    setattr(os, hook, deadly)
    if fallback:
        output_tree.exchange = lambda a, b: False
    output_tree.write_vendor_dirs(sys.argv[4], {new!r})
    print(calls[0])
""")


def _tree(folder: Path) -> dict[str, dict[str, str]]:
    out: dict[str, dict[str, str]] = {}
    for vendor in sorted(p for p in folder.iterdir() if not p.name.startswith(".")):
        out[vendor.name] = {str(f.relative_to(vendor)): f.read_text() for f in sorted(vendor.rglob("*")) if f.is_file()}
    return out


def _child(tmp_path: Path, kill_at: int, hook: str, fallback: bool) -> subprocess.CompletedProcess[str]:
    script = _CHILD.format(root=str(ROOT.parent), new=NEW)
    return subprocess.run([sys.executable, "-c", script, str(kill_at), hook, "1" if fallback else "0", str(tmp_path)],
                          capture_output=True, text=True, timeout=60)


@pytest.mark.parametrize("hook,fallback", [("fsync", False), ("rename", True), ("fsync", True)])
def test_sigkill_at_every_step_never_mixes_old_and_new(tmp_path: Path, hook: str, fallback: bool) -> None:
    """Killed (SIGKILL) at the k-th file flush or directory rename, for every k: each vendor
    directory is wholly old or wholly new (after the next run's recovery where the fallback
    left it aside), and a later write succeeds and leaves no staging directory."""
    write_vendor_dirs(str(tmp_path / "probe"), OLD)
    first = _child(tmp_path / "probe", 10_000, hook, fallback)
    assert first.returncode == 0, first.stderr
    steps = int(first.stdout.strip())
    assert steps >= 3
    for k in range(1, steps + 1):
        out = tmp_path / f"k{k}"
        write_vendor_dirs(str(out), OLD)
        run = _child(out, k, hook, fallback)
        assert run.returncode == -9, (k, run.stderr)
        recover(str(out))
        tree = _tree(out)
        assert set(tree) == set(OLD), (k, tree)
        for vendor, files in tree.items():
            assert files in (OLD[vendor], NEW[vendor]), (k, vendor, files)
        write_vendor_dirs(str(out), NEW)
        assert _tree(out) == NEW
        assert [n for n in os.listdir(out) if n.startswith(".rmot-")] == []


PROGRAM = """
program p on r1 {
  move joint joints(0, -10, 10, 0, 90, 0) deg
  wait 1 s
}
"""


def _files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_refusing_vendor_keeps_old_output_and_others_are_written(tmp_path: Path) -> None:
    """Vendors that refuse the program (RAPID and KRL: two tasks whose files differ only in
    case, E522) are reported and keep their earlier files; JSON is still written; exit 1."""
    (tmp_path / "p.rmot").write_text(PROGRAM, encoding="utf-8")
    out = tmp_path / "out"
    first = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "rapid", "--target", "krl", "-o", str(out)])
    assert first.exit_code == 0, first.output
    before = _files(out)
    two = ("cell c {\n  robot Left = abb_irb1600\n  robot left = abb_irb1600 at pose(x=3m)\n}\n"
           "program p {\n  task Left {\n    wait 1 s\n  }\n  task left {\n    wait 2 s\n  }\n}\n")
    (tmp_path / "p.rmot").write_text(two, encoding="utf-8")
    second = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "rapid", "--target", "krl",
                                      "--target", "json", "-o", str(out)])
    assert second.exit_code == 1, second.output
    assert "E522" in second.output and "not written for rapid, krl" in second.output
    after = _files(out)
    assert {k: v for k, v in after.items() if not k.startswith("json/") and k != ".rmot.output"} == \
        {k: v for k, v in before.items() if k != ".rmot.output"}
    assert "json/p.json" in after


def test_output_directory_that_cannot_be_made_is_e520(tmp_path: Path) -> None:
    (tmp_path / "p.rmot").write_text(PROGRAM, encoding="utf-8")
    (tmp_path / "afile").write_text("x")
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "rapid", "-o", str(tmp_path / "afile" / "o")])
    assert result.exit_code == 2 and "error[E520]" in result.output and "afile" in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="renameat2 is Linux's")
def test_the_exchange_swaps_two_directories_in_one_call(tmp_path: Path) -> None:
    """The C library's renameat2(RENAME_EXCHANGE) is found (dlopen of the process itself, no
    ldconfig search) and swaps: each name then holds the other's files."""
    from rmot.compiler.cli import output_tree

    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    (a / "f").write_text("from a")
    (b / "f").write_text("from b")
    assert output_tree.exchange(str(a), str(b)) is True
    assert (a / "f").read_text() == "from b" and (b / "f").read_text() == "from a"
    with pytest.raises(FileNotFoundError):
        output_tree.exchange(str(a), str(tmp_path / "missing"))
