"""`sync` as the level-toggling I/O handshake (backends/handshake.py): the IR -> IR lowering on
its own, the cell's "sync" signals, the checks, and the five vendors without a multi-robot
barrier on a two-task program compiled through the real front end and planner."""

from __future__ import annotations

import re
import warnings
from dataclasses import replace

import pytest
from backend_fixtures import span_at
from hypothesis import given
from hypothesis import strategies as st

from rmot.backends import BACKENDS
from rmot.backends.handshake import (
    SYNC_SIGNAL, HandshakePorts, HandshakeSet, HandshakeWait, check_handshake, handshake_note,
    handshake_ports, sync_as_handshake,
)
from rmot.lang import ir, ir_tree, plan_types
from rmot.backends import controllers

PORTS = HandshakePorts(out=3, inp=4)
R1_PORTS, R2_PORTS = (3, 4), (5, 6)

CELL = """
cell duo {
  robot r1 = abb_irb1600 at pose(z=400mm)
  robot r2 = abb_irb1600 at pose(x=1800mm, rz=180deg)
%s}
"""
SIGNALS = """\
  io out[3] = "sync" on r1
  io in[4]  = "sync" on r1
  io out[5] = "sync" on r2
  io in[6]  = "sync" on r2
"""
PROGRAM = """
program meet {
  speed 250 mm/s
  task r1 {
    move joint joints(0, -10, 20, 0, 60, 0) deg
    sync meet
    move joint joints(10, -10, 20, 0, 60, 0) deg
    sync part
    move joint joints(0, -10, 20, 0, 60, 0) deg
    sync done
    sync meet
  }
  task r2 {
    move joint joints(0, -10, 20, 0, 60, 0) deg
    sync meet
    move joint joints(-10, -10, 20, 0, 60, 0) deg
    sync part
    sync done
    sync meet
  }
}
"""
SYNC_LINES = {"r1": [15, 17, 19, 20], "r2": [24, 26, 27, 28]}  # in duo.rmot (CELL + SIGNALS + PROGRAM)
VENDORS = tuple(t for t in controllers() if BACKENDS[t].SYNC_HANDSHAKE)  # RAPID has a barrier
MAIN_FILE = {"krl": "meet_{t}.src", "fanuc": "MEET_{T}.ls", "urscript": "meet_{t}.script",
             "inform": "MEET_{T}.JBI", "val3": "meet_{t}/start.pgx"}
# (set, wait) patterns per vendor: groups (port, level)
IO_PATTERNS = {
    "krl": (r"\$OUT\[(\d+)\]=(TRUE|FALSE)", r"WAIT FOR \$IN\[(\d+)\]==(TRUE|FALSE)"),
    "fanuc": (r"DO\[(\d+):sync\]=(ON|OFF)", r"WAIT DI\[(\d+):sync\]=(ON|OFF)"),
    "urscript": (r"set_standard_digital_out\((\d+), (True|False)\)",
                 r"while not \(get_standard_digital_in\((\d+)\) == (True|False)\):"),
    "inform": (r"DOUT OT#\((\d+)\) (ON|OFF)", r"WAIT IN#\((\d+)\)=(ON|OFF)"),
    "val3": (r"dOut\[(\d+)\] = (true|false)", r"wait\(dIn\[(\d+)\] == (true|false)\)"),
}
# the first handshake of task r1 as printed (indentation and TP line numbers removed), reviewed
# against each vendor's I/O instruction syntax (see the vendor modules' docstrings)
GOLDEN_FIRST = {
    "krl": ["; sync meet (handshake 1)", "$OUT[3]=TRUE ; sync", "; duo.rmot:15", "WAIT FOR $IN[4]==TRUE ; sync"],
    "fanuc": ["!sync meet (handshake 1) ;", "DO[3:sync]=ON ;", "!duo.rmot:15 ;", "WAIT DI[4:sync]=ON ;"],
    "urscript": ["# sync meet (handshake 1)", "set_standard_digital_out(3, True)", "# duo.rmot:15",
                 "while not (get_standard_digital_in(4) == True):", "sync()", "end"],
    "inform": ["'sync meet (handshake 1)", "DOUT OT#(3) ON", "'duo.rmot:15", "WAIT IN#(4)=ON"],
    "val3": ["// sync meet (handshake 1)", "dOut[3] = true", "// duo.rmot:15", "wait(dIn[4] == true)"],
}


def _sync(uid: int, name: str = "meet") -> ir.Sync:
    return ir.Sync(uid=uid, name=name, span=span_at(uid))


def _cell(io: tuple[ir.IoSignal, ...]) -> ir.Cell:
    return ir.Cell("c", (), io=io)


def _sig(direction: ir.IoDirection, port: int, robot: str | None, name: str = SYNC_SIGNAL) -> ir.IoSignal:
    return ir.IoSignal(direction, port, name, robot)


OUT, IN = ir.IoDirection.DIGITAL_OUT, ir.IoDirection.DIGITAL_IN


def _io_pairs(body: tuple[ir.Instr, ...]) -> list[tuple[str, int, bool]]:
    out: list[tuple[str, int, bool]] = []
    for n in ir_tree.walk(body):
        if isinstance(n, ir.SetDigital):
            out.append(("set", n.port, n.value))
        elif isinstance(n, ir.WaitInput):
            out.append(("wait", n.condition.port, n.condition.value))
    return out


# --------------------------------------------------------------------------- the lowering


class TestLowering:
    def test_levels_alternate_on_off_with_the_robots_ports(self) -> None:
        """The k-th sync is set out[3] then wait in[4], on for odd k and off for even k."""
        body = (_sync(1), ir.WaitTime(uid=2, duration=0.5), _sync(3, "part"), _sync(4))
        out = sync_as_handshake(body, PORTS)
        assert _io_pairs(out) == [("set", 3, True), ("wait", 4, True), ("set", 3, False),
                                  ("wait", 4, False), ("set", 3, True), ("wait", 4, True)]
        assert out[2] == body[1]

    def test_generated_nodes_keep_span_uid_and_name_the_barrier(self) -> None:
        """Set keeps the sync's uid, wait gets -uid-1; both keep its span, signal "sync" and barrier name."""
        s, w = sync_as_handshake((_sync(7, "part"),), PORTS)
        assert isinstance(s, HandshakeSet) and isinstance(w, HandshakeWait)
        assert isinstance(s, ir.SetDigital) and isinstance(w, ir.WaitInput)
        assert (s.uid, w.uid) == (7, -8)
        assert s.span == w.span == span_at(7)
        assert (s.signal, w.condition.signal, w.timeout) == (SYNC_SIGNAL, SYNC_SIGNAL, None)
        assert (s.barrier, s.round, w.barrier, w.round) == ("part", 1, "part", 1)
        assert handshake_note(s) == "sync part (handshake 1)" and handshake_note(w) is None

    def test_counts_in_source_order_through_proc_calls(self) -> None:
        """Syncs inside (nested) proc bodies take their place in the task's count."""
        inner = ir.ProcCall(uid=3, proc="inner", args=(), body=(_sync(4),), span=span_at(3))
        body = (_sync(1), ir.ProcCall(uid=2, proc="outer", args=(), body=(inner, _sync(5)), span=span_at(2)), _sync(6))
        out = sync_as_handshake(body, PORTS)
        rounds = [(n.uid, n.round, n.value) for n in ir_tree.walk(out) if isinstance(n, HandshakeSet)]
        assert rounds == [(1, 1, True), (4, 2, False), (5, 3, True), (6, 4, False)]
        assert isinstance(out[2], ir.ProcCall) and out[2].proc == "outer"

    def test_counts_through_every_loop_iteration(self) -> None:
        """A sync in a `repeat 2` runs twice: two barriers with their own levels (the
        lowering went through if arms and proc calls only and left the loop's syncs as they
        were, a barrier no handshake vendor writes)."""
        its = tuple(ir.LoopIteration(value=v, body=(_sync(10 + v),)) for v in (0, 1))
        loop = ir.Loop(uid=2, var=None, first=0, last=2, iterations=its, span=span_at(2))
        out = sync_as_handshake((_sync(1), loop), PORTS)
        assert not [n for n in ir_tree.walk(out) if isinstance(n, ir.Sync)]
        rounds = [(n.uid, n.round, n.value) for n in ir_tree.walk(out) if isinstance(n, HandshakeSet)]
        assert rounds == [(1, 1, True), (10, 2, False), (11, 3, True)]

    @given(st.lists(st.booleans(), max_size=12))
    def test_every_barrier_toggles_the_level(self, kinds: list[bool]) -> None:
        """Property: each sync becomes one set+wait pair at the same level, and consecutive
        barriers alternate starting with on; other instructions are unchanged."""
        body = tuple(_sync(k + 1) if is_sync else ir.WaitTime(uid=k + 1, duration=0.1)
                     for k, is_sync in enumerate(kinds))
        pairs = _io_pairs(sync_as_handshake(body, PORTS))
        n = sum(kinds)
        assert len(pairs) == 2 * n
        assert [p[2] for p in pairs[::2]] == [k % 2 == 0 for k in range(n)]
        assert all(s[2] == w[2] and (s[1], w[1]) == (3, 4) for s, w in zip(pairs[::2], pairs[1::2]))
        waits = [x for x in sync_as_handshake(body, PORTS) if type(x) is ir.WaitTime]
        assert len(waits) == len(kinds) - n


class TestPortsAndChecks:
    def test_ports_are_the_robots_own_sync_signals(self) -> None:
        """The robot's "sync" out and in; other robots', cell-wide and other names are ignored."""
        cell = _cell((_sig(OUT, 1, None), _sig(OUT, 2, "r2"), _sig(OUT, 7, "r1", "gripper"),
                      _sig(OUT, 3, "r1"), _sig(IN, 4, "r1"), _sig(IN, 6, "r2")))
        assert handshake_ports(cell, "r1") == HandshakePorts(3, 4)
        assert handshake_ports(cell, "r2") == HandshakePorts(2, 6)

    def test_missing_or_doubled_signals_give_none(self) -> None:
        """No input, or two outputs named "sync", is not a usable handshake."""
        assert handshake_ports(_cell((_sig(OUT, 3, "r1"),)), "r1") is None
        assert handshake_ports(_cell((_sig(OUT, 3, "r1"), _sig(OUT, 5, "r1"), _sig(IN, 4, "r1"))), "r1") is None

    def test_missing_signals_are_an_error_at_every_sync(self) -> None:
        """E409 at each sync's span, naming the vendor and the cell lines to add."""
        found = check_handshake((_sync(3), ir.WaitTime(uid=4, duration=1.0), _sync(5, "part")), _cell(()), "r1", "krl")
        assert [(d.code.id, d.severity.value, d.span) for d in found] == [
            ("E409", "error", span_at(3)), ("E409", "error", span_at(5))]
        assert found[0].message == ("krl: sync 'meet' needs an I/O handshake on krl: declare "
                                    "io out[n] = \"sync\" on r1 and io in[m] = \"sync\" on r1 in the cell "
                                    "(exactly one of each)")

    def test_sync_in_an_if_arm_is_refused(self) -> None:
        """A sync inside an if arm has no compile-time level: E405 at its span."""
        cond = ir.InputCondition(port=1, value=True)
        body = (_sync(1), ir.If(uid=2, condition=cond, then=(), otherwise=(_sync(3),), span=span_at(2)))
        found = check_handshake(body, _cell((_sig(OUT, 3, "r1"), _sig(IN, 4, "r1"))), "r1", "val3")
        assert [(d.code.id, d.span) for d in found] == [("E405", span_at(3))]

    def test_odd_barrier_count_warns_once_at_the_last(self) -> None:
        """An odd number of barriers leaves the output on: W410 at the last sync; even: silent."""
        cell = _cell((_sig(OUT, 3, "r1"), _sig(IN, 4, "r1")))
        found = check_handshake((_sync(1), _sync(2), _sync(3)), cell, "r1", "inform")
        assert [(d.code.id, d.severity.value, d.span) for d in found] == [("W410", "warning", span_at(3))]
        assert check_handshake((_sync(1), _sync(2)), cell, "r1", "inform") == ()


# --------------------------------------------------------------------------- the vendors


@pytest.fixture(scope="module")
def duo(plan_from_text) -> plan_types.Plan:  # type: ignore[no-untyped-def]
    return plan_from_text(CELL % SIGNALS + PROGRAM, "duo.rmot")


def _without_signals(plan: plan_types.Plan, keep_robot: str | None = None) -> plan_types.Plan:
    """The same plan in a cell whose "sync" signals are gone (except `keep_robot`'s)."""
    cell = plan.program.cell
    io = tuple(s for s in cell.io if s.name != SYNC_SIGNAL or s.robot == keep_robot)
    return replace(plan, program=replace(plan.program, cell=replace(cell, io=io)))


def _main(files: dict[str, str], vendor: str, task: str) -> list[str]:
    """The main program's lines, stripped of indentation (and of TP line numbers)."""
    text = files[MAIN_FILE[vendor].format(t=task, T=task.upper())]
    return [re.sub(r"^\d+:\s+", "", line.strip()) for line in text.splitlines()]


def _handshake_io(lines: list[str], vendor: str) -> list[tuple[str, int, bool]]:
    set_re, wait_re = IO_PATTERNS[vendor]
    out = []
    for line in lines:
        for kind, pattern in (("set", set_re), ("wait", wait_re)):
            m = re.search(pattern, line)
            if m:
                out.append((kind, int(m.group(1)), m.group(2).lower() in ("true", "on")))
    return out


@pytest.mark.parametrize("vendor", VENDORS)
class TestVendors:
    def test_two_programs_with_alternating_set_wait_pairs(self, duo: plan_types.Plan, vendor: str) -> None:
        """One program per robot; its syncs are set own out / wait own in, levels on, off, on, off."""
        result = BACKENDS[vendor]().emit(duo)
        assert not result.has_errors, [d.message for d in result.diagnostics]
        for task, (o, i) in (("r1", R1_PORTS), ("r2", R2_PORTS)):
            lines = _main(result.files, vendor, task)
            levels = [True, False, True, False]
            assert _handshake_io(lines, vendor) == [p for lv in levels for p in (("set", o, lv), ("wait", i, lv))]
            notes = [line for line in lines if "(handshake" in line]
            assert [re.search(r"sync (\w+) \(handshake (\d)\)", n).groups() for n in notes] == [  # type: ignore[union-attr]
                ("meet", "1"), ("part", "2"), ("done", "3"), ("meet", "4")]

    def test_first_handshake_matches_golden_snippet(self, duo: plan_types.Plan, vendor: str) -> None:
        """The first barrier of r1 prints exactly as reviewed (comment, set, source ref, wait)."""
        lines = _main(BACKENDS[vendor]().emit(duo).files, vendor, "r1")
        start = lines.index(GOLDEN_FIRST[vendor][0])
        assert lines[start:start + len(GOLDEN_FIRST[vendor])] == GOLDEN_FIRST[vendor]

    def test_missing_signals_are_errors_at_the_sync_lines(self, duo: plan_types.Plan, vendor: str) -> None:
        """Without the cell's "sync" signals every sync is E409 at its own line, naming the vendor."""
        result = BACKENDS[vendor]().emit(_without_signals(duo))
        errors = [d for d in result.diagnostics if d.is_error]
        assert {d.code.id for d in errors} == {"E409"}
        assert sorted(d.span.start.line for d in errors) == sorted(SYNC_LINES["r1"] + SYNC_LINES["r2"])  # type: ignore[union-attr]
        assert all(f"needs an I/O handshake on {vendor}" in d.message for d in errors)

    def test_only_the_robot_without_signals_is_refused(self, duo: plan_types.Plan, vendor: str) -> None:
        """r1 keeps its signals: only r2's syncs are errors, and r1's program still has its handshakes."""
        result = BACKENDS[vendor]().emit(_without_signals(duo, keep_robot="r1"))
        errors = [d for d in result.diagnostics if d.is_error]
        assert sorted(d.span.start.line for d in errors) == SYNC_LINES["r2"]  # type: ignore[union-attr]
        assert len(_handshake_io(_main(result.files, vendor, "r1"), vendor)) == 8

    def test_deterministic(self, duo: plan_types.Plan, vendor: str) -> None:
        """Two emits of the two-task program are byte-identical."""
        assert BACKENDS[vendor]().emit(duo).files == BACKENDS[vendor]().emit(duo).files


class TestRapidKeepsWaitSyncTask:
    def test_multimove_declarations_and_rapidchecker(self, duo: plan_types.Plan) -> None:
        """RAPID needs no signals: WaitSyncTask with a syncident per barrier and the tasks list;
        every module passes rapidchecker."""
        files = BACKENDS["rapid"]().emit(_without_signals(duo)).files
        assert list(files) == ["meet_r1.mod", "meet_r2.mod"]
        for text in files.values():
            lines = [line.strip() for line in text.splitlines()]
            for name in ("meet", "part", "done"):
                assert f"VAR syncident {name};" in lines
            assert 'PERS tasks all_tasks{2}:=[["T_ROB1"],["T_ROB2"]];' in lines
            assert [line for line in lines if line.startswith("WaitSync")] == [
                "WaitSyncTask meet, all_tasks;", "WaitSyncTask part, all_tasks;",
                "WaitSyncTask done, all_tasks;", "WaitSyncTask meet, all_tasks;"]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            from rapidchecker.cli import check_file

            assert {name: [str(e) for e in check_file(text)] for name, text in files.items()} == {
                name: [] for name in files}
