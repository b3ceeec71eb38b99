"""RAPID's `AccSet Acc, Ramp` holds for every later move, whichever routine set it (RAPID
Instructions, AccSet; 100, 100 when the program starts from the beginning). `rmot import`
reads a move's joint acceleration share from the AccSet in force where the move runs, not the
last one in file order (a routine declared above main does not set main's first moves): after
a call the one the routine leaves, and where only the run time knows it (set in an IF arm) the
move stays native.

Witness: a small interpreter written here runs the module (PROC calls, IF on a digital input at
a given level, AccSet, MoveL) and records the AccSet in force at each move; every move the
import reads must carry its Acc (None for 100 %). A Hypothesis property draws modules.
"""

from __future__ import annotations

import re
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Call, Document, If, Move, Native, Stmt

HEAD = """MODULE M
  CONST robtarget p10:=[[500,0,600],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
"""


def _witness(module: str, level: bool) -> list[float | None]:
    """The AccSet Acc in force at each MoveL the module runs (None where it is 100)."""
    procs: dict[str, list[str]] = {}
    name = ""
    for line in (ln.strip().rstrip(";") for ln in module.splitlines()):
        m = re.match(r"PROC (\w+)\(\)", line)
        if m:
            name = m.group(1)
            procs[name] = []
        elif line == "ENDPROC":
            name = ""
        elif name:
            procs[name].append(line)
    acc = [100.0]
    out: list[float | None] = []

    def run(lines: list[str]) -> None:
        skipping = False
        for line in lines:
            if line.startswith("IF "):
                skipping = not level
            elif line == "ENDIF":
                skipping = False
            elif skipping:
                continue
            elif line.startswith("AccSet"):
                acc[0] = float(line.split()[1].rstrip(","))
            elif line.startswith("MoveL"):
                out.append(None if acc[0] == 100.0 else acc[0])
            elif line in procs:
                run(procs[line])

    run(procs["main"])
    return out


def _read(doc: Document) -> list[float | None | str]:
    """The joint acceleration share of each move the import reads, in run order (calls
    followed; both arms of an if are the witness's level's), "native" for a move kept native."""
    procs = {r.name: r.body for r in doc.routines}

    def run(body: tuple[Stmt, ...], level: bool) -> list[float | None | str]:
        out: list[float | None | str] = []
        for s in body:
            if isinstance(s, Move):
                out.append(s.joint_accel)
            elif isinstance(s, Native) and s.text.startswith("MoveL"):
                out.append("native")
            elif isinstance(s, Native) and s.text.rstrip(";") in procs:
                out += ["native" for _ in run(procs[s.text.rstrip(";")], level)]
            elif isinstance(s, Call):
                out += run(procs[s.name], level)
            elif isinstance(s, If):
                out += run(s.then if level else s.orelse, level)
        return out

    return run(procs[doc.main], LEVEL[0])


LEVEL = [False]


def _check(tmp_path: Path, module: str, level: bool = False) -> list[float | None | str]:
    path = tmp_path / "M.mod"
    path.write_text(module)
    LEVEL[0] = level
    read = _read(read_files([str(path)]))
    ran = _witness(module, level)
    assert len(read) == len(ran), (read, ran, module)
    for r, w in zip(read, ran):
        assert r == "native" or r == w, (read, ran, module)
    return read


def test_a_routines_accset_holds_from_its_call_on(tmp_path: Path) -> None:
    module = HEAD + """  PROC slow()
    AccSet 50, 100;
  ENDPROC
  PROC main()
    MoveL p10,v100,fine,tool0;
    slow;
    MoveL p10,v100,fine,tool0;
    AccSet 100, 100;
    MoveL p10,v100,fine,tool0;
  ENDPROC
ENDMODULE
"""
    assert _check(tmp_path, module) == [None, 50.0, None]


def test_an_accset_in_an_if_arm_leaves_the_moves_after_it_native(tmp_path: Path) -> None:
    module = HEAD + """  PROC main()
    MoveL p10,v100,fine,tool0;
    IF DInput(di1) = 1 THEN
      AccSet 30, 100;
    ENDIF
    MoveL p10,v100,fine,tool0;
    AccSet 70, 100;
    MoveL p10,v100,fine,tool0;
    AccSet 70, 50;
    MoveL p10,v100,fine,tool0;
  ENDPROC
ENDMODULE
"""
    assert _check(tmp_path, module) == [None, "native", 70.0, "native"]
    # the AccSet with no rmot form stays in the program, so the native move after it keeps its ramp
    main = next(r for r in read_files([str(tmp_path / "M.mod")]).routines if r.name == "main")
    assert [s.text for s in main.body if isinstance(s, Native) and s.text.startswith("AccSet")] == ["AccSet 70, 50;"]


STEP = st.sampled_from(["move", "acc40", "acc100", "ramp50", "call_a", "call_b", "if_acc"])


@settings(max_examples=80, deadline=None)
@given(steps=st.lists(STEP, min_size=1, max_size=8), level=st.booleans(), b_moves=st.booleans())
def test_every_move_read_has_the_accset_it_runs_with(tmp_path_factory, steps: list[str], level: bool,  # type: ignore[no-untyped-def]
                                                      b_moves: bool) -> None:
    lines = ["  PROC a()", "    AccSet 60, 100;", "  ENDPROC", "  PROC b()"]
    lines += ["    MoveL p10,v100,fine,tool0;"] if b_moves else []
    lines += ["    AccSet 25, 100;", "  ENDPROC", "  PROC main()"]
    for step in steps:
        lines += {"move": ["    MoveL p10,v100,fine,tool0;"], "acc40": ["    AccSet 40, 100;"],
                  "acc100": ["    AccSet 100, 100;"], "ramp50": ["    AccSet 40, 50;"], "call_a": ["    a;"],
                  "call_b": ["    b;"],
                  "if_acc": ["    IF DInput(di1) = 1 THEN", "      AccSet 80, 100;", "    ENDIF"]}[step]
    lines += ["    MoveL p10,v100,fine,tool0;", "  ENDPROC", "ENDMODULE", ""]
    _check(tmp_path_factory.mktemp("rapid"), HEAD + "\n".join(lines), level)
