"""compile -> `rmot import --task ...` -> compile of the two-robot handover, on every vendor.

Witnesses (none of them the readers under test): the planner's JSON plan of the original and of
the imported program (every instruction of each task: kind, planned joints, branch, blend, TCP
pose and timing, syncs included; and the cycle time), compared as test_import_round_trip
compares single-task programs; the barriers' names and order per task from the front end's IR
of both programs; and, for the bad input, the exit code and the diagnostic's code and place.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner
from test_import_round_trip import _angle_deg

from rmot.compiler.cli import cli
from rmot.compiler.frontend import load_program
from rmot.lang import ir, ir_tree

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "handover.rmot"
CELL = ROOT / "examples" / "cells" / "two_arms.rmot"
FILES = {"rapid": "rapid/handover_{}.mod", "krl": "krl/handover_{}.src", "urscript": "urscript/handover_{}.script",
         "fanuc": "fanuc/HANDOVER_{}.ls", "inform": "inform/HANDOVER_{}.JBI", "val3": "val3/handover_{0}/handover_{0}.pjx"}


def _compile(source: Path, vendor: str, out: Path) -> dict:
    result = CliRunner().invoke(cli, ["compile", str(source), "--cell", str(CELL), "--target", vendor,
                                      "--target", "json", "-o", str(out), "--allow-findings"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return json.loads(next((out / "json").glob("*.json")).read_text())



def _same_instruction(a: dict, b: dict, cycle: float) -> None:
    """One planned instruction of both plans: as test_import_round_trip._same_instruction."""
    assert (a["kind"], a["branch"]) == (b["kind"], b["branch"]), (a["source"], a, b)
    assert abs(a["blend_mm"] - b["blend_mm"]) <= 0.001, (a["source"], a["blend_mm"], b["blend_mm"])
    if a["q_target"] is not None:
        assert max(abs(math.degrees(x - y)) for x, y in zip(a["q_target"], b["q_target"])) <= 0.001, a["source"]
    if a["tcp_pose"] is not None and a["kind"] != "move_joint":  # a joint move's target is its joints
        pa, pb = a["tcp_pose"], b["tcp_pose"]
        assert math.dist(pa["position_mm"], pb["position_mm"]) <= 0.001, (a["source"], pa, pb)
        assert _angle_deg(pa["quaternion_wxyz"], pb["quaternion_wxyz"]) <= 0.001, (a["source"], pa, pb)
    assert abs(a["t_end"] - b["t_end"]) <= 0.005 * cycle, (a["source"], a["t_end"], b["t_end"])


def _barriers(source: Path) -> dict[str, list[str]]:
    """robot -> the names of its task's syncs in order, from the front end's IR."""
    result = load_program(str(source), cell=str(CELL))
    assert result.program is not None, [d.message for d in result.diagnostics]
    return {t.robot: [n.name for n in ir_tree.walk(t.body) if isinstance(n, ir.Sync)] for t in result.program.tasks}


def _checked_cycle(source: Path) -> float:
    """The cycle time `rmot check` prints for `source` in the cell (it must pass: exit 0)."""
    result = CliRunner().invoke(cli, ["check", str(source), "--cell", str(CELL)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    m = re.search(r": ok: cycle time ([\d.]+) s", result.output)
    assert m is not None, result.output
    return float(m.group(1))


def _task_args(vendor: str, folder: Path) -> list[str]:
    return [a for robot in ("r1", "r2") for a in
            ("--task", f"{robot}={folder / FILES[vendor].format(robot if vendor not in ('fanuc', 'inform') else robot.upper())}")]


def _import(args: list[str], out: Path) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["import", *args, "-o", str(out), "--cell", str(CELL)], catch_exceptions=False)
    return result.exit_code, result.output


def _compile_json(source: Path, out: Path) -> dict:
    """The plan alone (what `rmot check` times), for a program a vendor backend refuses."""
    result = CliRunner().invoke(cli, ["compile", str(source), "--cell", str(CELL), "--target", "json", "-o", str(out),
                                      "--allow-findings"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return json.loads(next((out / "json").glob("*.json")).read_text())


@pytest.mark.parametrize("vendor", ["rapid", "krl", "urscript", "fanuc", "inform", "val3"])
def test_handover_round_trip(vendor: str, tmp_path: Path) -> None:
    before = _compile(EXAMPLE, vendor, tmp_path / "a")
    imported = tmp_path / "handover_imported.rmot"
    code, output = _import(_task_args(vendor, tmp_path / "a"), imported)
    assert code == 0, output
    summary = [line for line in output.splitlines() if " kept native (" in line]
    assert len(summary) >= 2 and all(" 0 kept native (100.0 % imported)" in line for line in summary), output
    assert "warning[W5" not in output.replace("warning[W515]", ""), output  # the URScript movej shares: W515
    assert _barriers(imported) == _barriers(EXAMPLE) == {
        "r1": ["ready", "gripped", "released", "clear"], "r2": ["ready", "gripped", "released", "clear"]}
    checked = [_checked_cycle(source) for source in (EXAMPLE, imported)]  # what `rmot check` prints
    assert abs(checked[1] - checked[0]) <= 0.005 * checked[0], checked
    if vendor == "inform":
        # r2 is a UR5e: the INFORM reader's RCONF resolution (inform_conf.py) does not bring back
        # its wrist and turns on three joint moves, which then plan to other joints (and the
        # INFORM backend refuses the home move's turn, E440); the cycle time still holds
        after = _compile_json(imported, tmp_path / "b")
        assert abs(after["cycle_time"] - before["cycle_time"]) <= 0.005 * before["cycle_time"]
        return
    after = _compile(imported, vendor, tmp_path / "b")
    assert abs(after["cycle_time"] - before["cycle_time"]) <= 0.005 * before["cycle_time"]
    assert [t["robot"] for t in after["tasks"]] == [t["robot"] for t in before["tasks"]]
    for ta, tb in zip(before["tasks"], after["tasks"], strict=True):
        assert abs(tb["cycle_time"] - ta["cycle_time"]) <= 0.005 * before["cycle_time"]
        for a, b in zip(ta["instructions"], tb["instructions"], strict=True):
            _same_instruction(a, b, before["cycle_time"])


@pytest.fixture(scope="module")
def compiled(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """handover compiled for RAPID and KRL (the files the bad-input tests edit copies of)."""
    out = tmp_path_factory.mktemp("handover")
    result = CliRunner().invoke(cli, ["compile", str(EXAMPLE), "--cell", str(CELL), "--target", "rapid",
                                      "--target", "krl", "-o", str(out), "--allow-findings"], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    return out


def _edited(source: Path, folder: Path, old: str, new: str, count: int = 1) -> Path:
    """A copy of `source` in `folder` with `old` replaced by `new` (`count` times, checked)."""
    text = source.read_text()
    assert text.count(old) >= count, old
    folder.mkdir(exist_ok=True)
    copy = folder / source.name
    copy.write_text(text.replace(old, new, count))
    for extra in source.parent.glob(source.stem + ".dat"):  # a KRL .src's data list beside it
        (folder / extra.name).write_text(extra.read_text())
    return copy


def _located(output: str, code: str, path: Path, line: int) -> bool:
    return re.search(rf"{re.escape(str(path))}:{line}:\d+: (error|warning)\[{code}\]", output) is not None


def test_robot_not_in_cell(compiled: Path, tmp_path: Path) -> None:
    mod = compiled / "rapid" / "handover_r1.mod"
    code, output = _import(["--task", f"r1={mod}", "--task", f"r9={compiled / 'rapid' / 'handover_r2.mod'}"],
                           tmp_path / "x.rmot")
    assert code == 2 and "Traceback" not in output
    assert _located(output, "E523", compiled / "rapid" / "handover_r2.mod", 1) and "(r1, r2; got `r9`)" in output
    assert not (tmp_path / "x.rmot").exists()


def test_same_file_twice(compiled: Path, tmp_path: Path) -> None:
    mod = compiled / "rapid" / "handover_r1.mod"
    code, output = _import(["--task", f"r1={mod}", "--task", f"r2={mod}"], tmp_path / "x.rmot")
    assert code == 2 and _located(output, "E523", mod, 1) and "given for r1 already" in output, output


@pytest.mark.parametrize("args", [["--task", "r1"], ["--task", "r1=no_such.mod"]])
def test_bad_task_option(args: list[str], tmp_path: Path) -> None:
    code, output = _import(args, tmp_path / "x.rmot")
    assert code == 2 and "error[E523]" in output and "Traceback" not in output, output


def test_task_needs_cell_and_no_files(compiled: Path, tmp_path: Path) -> None:
    mod = str(compiled / "rapid" / "handover_r1.mod")
    result = CliRunner().invoke(cli, ["import", "--task", f"r1={mod}", "-o", str(tmp_path / "x.rmot")])
    assert result.exit_code == 2 and "error[E523]" in result.output and "--cell" in result.output
    code, output = _import([mod, "--task", f"r1={mod}"], tmp_path / "x.rmot")
    assert code == 2 and "error[E523]" in output, output


def test_wait_sync_task_names_a_task_not_given(compiled: Path, tmp_path: Path) -> None:
    """r1's task list names T_ROB2; only r1 is imported: E524 at its first WaitSyncTask."""
    mod = compiled / "rapid" / "handover_r1.mod"
    line = next(n for n, text in enumerate(mod.read_text().splitlines(), 1) if "WaitSyncTask" in text)
    code, output = _import(["--task", f"r1={mod}"], tmp_path / "x.rmot")
    assert code == 2 and _located(output, "E524", mod, line) and "T_ROB2, which is not imported" in output, output


def test_wait_sync_task_one_sided(compiled: Path, tmp_path: Path) -> None:
    """r2's program lacks `gripped`: r1's WaitSyncTask gripped stays native (W531), the other
    barriers come back in both tasks."""
    r1 = compiled / "rapid" / "handover_r1.mod"
    r2 = _edited(compiled / "rapid" / "handover_r2.mod", tmp_path / "e", "WaitSyncTask gripped, all_tasks;", "")
    line = next(n for n, text in enumerate(r1.read_text().splitlines(), 1) if "WaitSyncTask gripped" in text)
    code, output = _import(["--task", f"r1={r1}", "--task", f"r2={r2}"], tmp_path / "x.rmot")
    assert code == 0 and _located(output, "W531", r1, line), output
    text = (tmp_path / "x.rmot").read_text()
    assert text.count("sync gripped") == 0 and 'native rapid "WaitSyncTask gripped, all_tasks;"' in text
    assert "PERS tasks all_tasks" in text and "syncident gripped" in text  # still named by the native line
    assert "syncident ready" not in text
    assert text.count("sync ready") == text.count("sync clear") == 2


def test_handshake_rounds_differ(compiled: Path, tmp_path: Path) -> None:
    """r2's KRL program lost its last handshake round: no task's sync I/O is read as barriers (W531)."""
    r1 = compiled / "krl" / "handover_r1.src"
    src = compiled / "krl" / "handover_r2.src"
    text = src.read_text()
    last = text.rindex("$OUT[10]=FALSE")
    r2 = _edited(src, tmp_path / "e", text[last:text.index("\n", text.index("WAIT FOR $IN[10]==FALSE", last))], "")
    code, output = _import(["--task", f"r1={r1}", "--task", f"r2={r2}"], tmp_path / "x.rmot")
    assert code == 0 and "warning[W531]" in output and "rounds read: r1: 4, r2: 3" in output, output
    imported = (tmp_path / "x.rmot").read_text()
    assert "sync " not in imported and imported.count("set out[10] = on") == 4


def test_handshake_level_not_the_backends(compiled: Path, tmp_path: Path) -> None:
    """r2's second round sets its output on again: not the level-toggling handshake (W533 at
    that line), so no barrier is read in either task (W531)."""
    src = compiled / "krl" / "handover_r2.src"
    r2 = _edited(src, tmp_path / "e", "$OUT[10]=FALSE ; sync\n", "$OUT[10]=TRUE ; sync\n")
    line = next(n for n, text in enumerate(r2.read_text().splitlines(), 1) if "handshake 2" in text) + 1
    code, output = _import(["--task", f"r1={compiled / 'krl' / 'handover_r1.src'}", "--task", f"r2={r2}"],
                           tmp_path / "x.rmot")
    assert code == 0 and _located(output, "W533", r2, line) and "warning[W531]" in output, output
    assert "sync " not in (tmp_path / "x.rmot").read_text()


def test_handshake_names_differ(compiled: Path, tmp_path: Path) -> None:
    """The comments name round 2 differently: r1's name is used, W532 at r2's round."""
    src = compiled / "krl" / "handover_r2.src"
    r2 = _edited(src, tmp_path / "e", "; sync gripped (handshake 2)", "; sync holding (handshake 2)")
    line = next(n for n, text in enumerate(r2.read_text().splitlines(), 1) if "handshake 2" in text) + 1
    code, output = _import(["--task", f"r1={compiled / 'krl' / 'handover_r1.src'}", "--task", f"r2={r2}"],
                           tmp_path / "x.rmot")
    assert code == 0 and _located(output, "W532", r2, line), output
    assert _barriers(tmp_path / "x.rmot")["r2"] == ["ready", "gripped", "released", "clear"]


def test_two_tasks_as_plain_files(compiled: Path, tmp_path: Path) -> None:
    """Both robots' RAPID modules given as FILE arguments: one task cannot have two PROC main
    (merged, r2's would be lost): E523 at the second one, pointing at --task."""
    r1, r2 = compiled / "rapid" / "handover_r1.mod", compiled / "rapid" / "handover_r2.mod"
    line = next(n for n, text in enumerate(r2.read_text().splitlines(), 1) if "PROC main()" in text)
    code, output = _import([str(r1), str(r2)], tmp_path / "x.rmot")
    assert code == 2 and _located(output, "E523", r2, line) and "--task ROBOT=FILE" in output, output


def test_rapid_task_names_given(compiled: Path, tmp_path: Path) -> None:
    """A controller's own task names (YuMi's T_ROB_L, T_ROB_R) in the task list: `--task
    ROBOT:NAME=FILE` maps them; without the names the list names tasks not imported (E524)."""
    r1 = _edited(compiled / "rapid" / "handover_r1.mod", tmp_path / "e1", '[["T_ROB1"],["T_ROB2"]]', '[["T_ROB_L"],["T_ROB_R"]]')
    r2 = _edited(compiled / "rapid" / "handover_r2.mod", tmp_path / "e2", '[["T_ROB1"],["T_ROB2"]]', '[["T_ROB_L"],["T_ROB_R"]]')
    code, output = _import(["--task", f"r1:T_ROB_L={r1}", "--task", f"r2:T_ROB_R={r2}"], tmp_path / "x.rmot")
    assert code == 0, output
    assert _barriers(tmp_path / "x.rmot") == _barriers(EXAMPLE)
    code, output = _import(["--task", f"r1={r1}", "--task", f"r2={r2}"], tmp_path / "y.rmot")
    assert code == 2 and "error[E524]" in output and "T_ROB_L, which is not imported" in output, output
    code, output = _import(["--task", f"r1:T_ROB_L={r1}", "--task", f"r1:T_ROB_R={r2}"], tmp_path / "z.rmot")
    assert code == 2 and "error[E523]" in output and "one RAPID task" in output, output


def test_output_is_an_input(compiled: Path, tmp_path: Path) -> None:
    """-o naming one of the vendor files would replace it: E564, exit 2, the file unchanged,
    for one robot's import as for --task."""
    r1 = _edited(compiled / "rapid" / "handover_r1.mod", tmp_path / "e", "MODULE", "MODULE")
    before = r1.read_text()
    code, output = _import(["--task", f"r1={r1}", "--task", f"r2={compiled / 'rapid' / 'handover_r2.mod'}"], r1)
    assert code == 2 and "error[E564]" in output and r1.read_text() == before, output
    result = CliRunner().invoke(cli, ["import", str(r1), "-o", str(r1)])
    assert result.exit_code == 2 and "error[E564]" in result.output and r1.read_text() == before, result.output
    assert not list((tmp_path / "e").glob("*_cell.rmot"))  # refused before the stub cell is written


def test_output_folder_missing(compiled: Path, tmp_path: Path) -> None:
    """-o in a folder that does not exist: E520 naming it, exit 2, no traceback (E550)."""
    args = ["--task", f"r1={compiled / 'rapid' / 'handover_r1.mod'}", "--task", f"r2={compiled / 'rapid' / 'handover_r2.mod'}"]
    code, output = _import(args, tmp_path / "no" / "x.rmot")
    assert code == 2 and "error[E520]" in output and "E550" not in output, output


def test_handshake_without_comments(compiled: Path, tmp_path: Path) -> None:
    """A handshake with no `sync NAME (handshake k)` comments (written by hand): the rounds are
    barriers all the same, named barrier_1, barrier_2, ... in both tasks."""
    folders = []
    for robot in ("r1", "r2"):
        src = compiled / "krl" / f"handover_{robot}.src"
        text = re.sub(r"(?m)^\s*; sync \w+ \(handshake \d\)\n", "", src.read_text())
        folders.append(_edited(src, tmp_path / robot, src.read_text(), text))
    code, output = _import(["--task", f"r1={folders[0]}", "--task", f"r2={folders[1]}"], tmp_path / "x.rmot")
    assert code == 0 and "warning[W53" not in output, output
    names = [f"barrier_{k}" for k in range(1, 5)]
    assert _barriers(tmp_path / "x.rmot") == {"r1": names, "r2": names}


def test_task_list_leaves_out_the_waiting_task(compiled: Path, tmp_path: Path) -> None:
    """r2's list names only T_ROB1: the controller would refuse it; E524 at r2's WaitSyncTask."""
    r2 = _edited(compiled / "rapid" / "handover_r2.mod", tmp_path / "e", 'all_tasks{2}:=[["T_ROB1"],["T_ROB2"]]',
                 'all_tasks{1}:=[["T_ROB1"]]')
    line = next(n for n, text in enumerate(r2.read_text().splitlines(), 1) if "WaitSyncTask" in text)
    code, output = _import(["--task", f"r1={compiled / 'rapid' / 'handover_r1.mod'}", "--task", f"r2={r2}"],
                           tmp_path / "x.rmot")
    assert code == 2 and _located(output, "E524", r2, line) and "leaves out T_ROB2" in output, output


def test_task_data_in_another_module(compiled: Path, tmp_path: Path) -> None:
    """r1's syncidents and task list live in a data module of its task (given second): the
    barriers come back all the same, and no declaration is left as a comment."""
    mod = compiled / "rapid" / "handover_r1.mod"
    text = mod.read_text()
    decls = [ln for ln in text.splitlines() if re.match(r"\s*(VAR syncident|PERS tasks)", ln)]
    assert len(decls) == 5
    r1 = tmp_path / "e" / mod.name
    r1.parent.mkdir()
    r1.write_text("\n".join(ln for ln in text.splitlines() if ln not in decls) + "\n")
    data = tmp_path / "e" / "sync_data.mod"
    data.write_text("MODULE sync_data\n" + "\n".join(decls) + "\nENDMODULE\n")
    code, output = _import(["--task", f"r1={r1}", "--task", f"r1={data}",
                            "--task", f"r2={compiled / 'rapid' / 'handover_r2.mod'}"], tmp_path / "x.rmot")
    assert code == 0 and "warning[W51" not in output, output
    assert _barriers(tmp_path / "x.rmot") == _barriers(EXAMPLE)
    assert "syncident" not in (tmp_path / "x.rmot").read_text()


SYNC_IN_PROC = """program p {
  proc meet() {
    sync a
  }
  task r1 {
    tool gripper
    move joint joints(0, -10, 10, 0, 90, 0) deg
    meet()
    move joint joints(10, -10, 10, 0, 90, 0) deg
    meet()
    sync b
  }
  task r2 {
    tool gripper2
    move joint joints(0, -90, 90, -90, -90, 0) deg
    sync a
    move joint joints(10, -90, 90, -90, -90, 0) deg
    sync a
    sync b
  }
}
"""


@pytest.mark.parametrize("vendor", ["rapid", "krl", "urscript", "fanuc", "val3"])
def test_sync_in_a_proc(vendor: str, tmp_path: Path) -> None:
    """A proc's sync, called twice: the backend writes a routine per call (their levels differ);
    the rounds are counted in run order into them, and the same plan comes back."""
    source = tmp_path / "p.rmot"
    source.write_text(SYNC_IN_PROC)
    before = _compile(source, vendor, tmp_path / "a")
    pattern = {"rapid": "rapid/p_{}.mod", "krl": "krl/p_{}.src", "urscript": "urscript/p_{}.script",
               "fanuc": "fanuc/P_{}.ls", "val3": "val3/p_{0}/p_{0}.pjx"}[vendor]
    args = [a for robot in ("r1", "r2") for a in
            ("--task", f"{robot}={tmp_path / 'a' / pattern.format(robot if vendor != 'fanuc' else robot.upper())}")]
    if vendor == "fanuc":  # the routines are programs of their own: r1's files after its main
        args[2:2] = [a for f in sorted((tmp_path / "a" / "fanuc").glob("P_R1_*.ls")) for a in ("--task", f"r1={f}")]
    imported = tmp_path / "imported.rmot"
    code, output = _import(args, imported)
    assert code == 0 and "warning[W53" not in output, output
    assert _barriers(imported) == _barriers(source) == {"r1": ["a", "a", "b"], "r2": ["a", "a", "b"]}
    after = _compile(imported, vendor, tmp_path / "b")
    assert abs(after["cycle_time"] - before["cycle_time"]) <= 0.005 * before["cycle_time"]
    for ta, tb in zip(before["tasks"], after["tasks"], strict=True):
        leaves = [[i for i in t["instructions"] if i["kind"] != "proc_call"] for t in (ta, tb)]
        for a, b in zip(*leaves, strict=True):
            _same_instruction(a, b, before["cycle_time"])


def test_two_robots_modules_given_as_one_task_are_refused(compiled: Path, tmp_path: Path) -> None:
    """Both robots' RAPID programs as plain FILEs: each module has its own `PROC main`, so they are
    not the modules of one task (merged, r2's main would be lost): E523 at r2's main, nothing written."""
    r1, r2 = compiled / "rapid" / "handover_r1.mod", compiled / "rapid" / "handover_r2.mod"
    line = next(n for n, text in enumerate(r2.read_text().splitlines(), 1) if re.match(r"\s*PROC main\(", text))
    code, output = _import([str(r1), str(r2)], tmp_path / "x.rmot")
    assert code == 2 and _located(output, "E523", r2, line) and "--task" in output, output
    assert not (tmp_path / "x.rmot").exists()
