"""URScript threads that stay native say precisely why, and the program's own moves around them
are read.

The scripts imitate PolyScope exports (Nils-Treuheit's `interactiveCubes.script`: a MoveL with a
Direction node "Until (tool_contact_detection)"; Unitedplastic's `test_x_plus.script`: a
Direction node "Until (distance)" as the program's first move) and a hand-written thread that
polls in its own loop (`thread Thread_1(): while (True): ... end end`, `run Thread_1()`).

Witness: the expectations are written by hand from what PolyScope writes for the node (its
thread moves, the program's `while (True):` waits for the thread's flag or for
`tool_contact()`) and from the URScript manual ("Threads": a thread runs beside the program).
"""

from __future__ import annotations

from pathlib import Path

from rmot.backends.readers.model import Cond, Move, Native, WaitIn, While
from tests.backends.test_import_urscript_forms import HELPER, _direction_node, _read

_CONTACT = _direction_node([0.0] * 6, "[0.0,0.0,-1.0]", 0.4).replace("    while (True):\n", """    while (True):
      local targetTcpDirection=get_target_tcp_speed()
      local stepsToRetract=tool_contact(direction=targetTcpDirection)
      if (stepsToRetract > 0):
        kill move_thread_han_7
        stopl(3.0)
        local retractTo=get_forward_kin(get_actual_joint_positions_history(stepsToRetract))
        movel(retractTo, a=3.0, v=0.1)
        break
      end
""")  # PolyScope's loop for "Until (tool_contact_detection)" before the distance test


def _reasons(doc, lines: range) -> set[str]:  # type: ignore[no-untyped-def]
    return {d.message.split(";")[0] for d in doc.diagnostics if d.span.start.line in lines}


def test_direction_until_tool_contact(tmp_path: Path) -> None:
    """Every line of the node, from its thread to the end of the loop that waits for it, stays
    native for one reason (tool contact); the moves before and after it are read."""
    text = (f"def prog():\n{HELPER}  global w_p=p[0.4, -0.1, 0.3, 0.0, 3.14159, 0.0]\n"
            f"    movel(w_p, a=1.2, v=0.25)\n{_CONTACT}    movel(w_p, a=1.2, v=0.25)\nend\n")
    doc, stmts = _read(tmp_path, text)
    lines = text.split("\n")
    first = lines.index("    thread move_thread_7():") + 1
    last = first + _CONTACT.count("\n") - 2
    assert [s.where.line for s in stmts if isinstance(s, Move)] == [first - 2, last + 1]
    native = [s.where.line for s in stmts if isinstance(s, Native) and s.where.line >= first]
    assert native == [n for n in range(first, last + 1) if not lines[n - 1].strip().startswith("$")]
    assert _reasons(doc, range(first, last + 1)) == {
        "a PolyScope Direction node moving until tool contact: a motion that ends on a condition has no rmot form"}
    assert not any(d.code.id == "W518" for d in doc.diagnostics)  # its `while (True)` is not the program's loop


def test_direction_until_distance_with_no_known_start(tmp_path: Path) -> None:
    """A Direction node that is the program's first move starts from a target the file does not
    give: it stays native, saying so; its waiting `while (True)` is not read as the program's
    loop (no W518)."""
    node = _direction_node([0.0] * 6, "[1.0,0.0,0.0]", 0.3)
    text = f"def prog():\n{HELPER}{node}end\n"
    doc, stmts = _read(tmp_path, text)
    first = text.split("\n").index("    thread move_thread_7():") + 1
    reasons = _reasons(doc, range(first, first + node.count("\n") - 1))
    assert len(reasons) == 1 and reasons.pop().startswith(
        "a PolyScope Direction node: it moves from the last move's target (`get_target_waypoint()`), not known here")
    assert not any(d.code.id == "W518" for d in doc.diagnostics)
    assert not any(isinstance(s, Move) for s in stmts)


def test_a_concurrent_thread(tmp_path: Path) -> None:
    """A thread of the program's own (it loops beside the program) stays native as a thread; the
    program's moves are read."""
    text = ("def prog():\n  thread Thread_1():\n    while (True):\n      set_standard_digital_out(1, True)\n"
            "      sleep(0.5)\n      sync()\n    end\n  end\n  threadId_Thread_1 = run Thread_1()\n"
            "  movej([0, -1.5, 1.5, 0, 1.5, 0], a=1.4, v=1.05)\nend\n")
    doc, stmts = _read(tmp_path, text)
    assert [s.where.line for s in stmts if isinstance(s, Move)] == [10]
    assert _reasons(doc, range(2, 9)) == {"a thread runs beside the program (rmot has no concurrent thread)"}


def test_polled_input_waits(tmp_path: Path) -> None:
    """Hand-written polls (MustafaImran287's Robotiq scripts poll with `sleep(0.01)`; here on an
    input): `while (not get_standard_digital_in(1)): sleep(0.01) end` waits for in[1] on, with
    W528 naming the interval; `sleep` then `sync()` too; PolyScope's `sync()` alone is a plain
    wait (no W528); a body that does anything else is a `while` loop, not a wait."""
    text = ("def prog():\n  while (not get_standard_digital_in(1)):\n    sleep(0.01)\n  end\n"
            "  while get_digital_in(2) == True:\n    sleep(0.5)\n    sync()\n  end\n"
            "  while (not(get_standard_digital_in(3) == True)):\n    sync()\n  end\n"
            "  while (not get_standard_digital_in(4)):\n    textmsg(\"waiting\")\n    sleep(0.01)\n  end\nend\n")
    doc, stmts = _read(tmp_path, text)
    waits = [(s.cond, s.where.line) for s in stmts if isinstance(s, WaitIn)]
    assert waits == [(Cond(1, True), 2), (Cond(2, False), 5), (Cond(3, True), 9)]
    polled = [(d.span.start.line, d.message) for d in doc.diagnostics if d.code.id == "W528"]
    assert [line for line, _ in polled] == [2, 5] and "every 0.01 s" in polled[0][1] and "0.5 s" in polled[1][1]
    assert [s.where.line for s in stmts if isinstance(s, While)] == [12]
