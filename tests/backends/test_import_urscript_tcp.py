"""URScript `set_tcp` inside a block: which TCP a later move uses is the run time's.

`set_tcp(pose)` changes the TCP of every later move (URScript manual, module interfaces,
set_tcp). Set inside an `if` arm, the TCP after the `if` is the arm's only when the arm ran; set
inside a loop's body, the body's later turns start with it. The reader took the last `set_tcp` in
the text for the TCP of every later move: the move after `if ...: set_tcp(B) end` was planned
with B whatever the input, without a word. Witness: the semantics above, applied here by hand
to each case.
"""

from __future__ import annotations

from pathlib import Path

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, walk


def _read(tmp_path: Path, body: str) -> tuple[list[object], list[str]]:
    path = tmp_path / "t.script"
    path.write_text("def prog():\n" + body + "end\nprog()\n")
    doc = read_files([str(path)])
    return [s for r in doc.routines for s in walk(r.body) if isinstance(s, (Move, Native))], \
        [d.message for d in doc.diagnostics]


A, B = "set_tcp(p[0,0,0.1,0,0,0])\n", "set_tcp(p[0,0,0.2,0,0,0])\n"
MOVE = "movel(p[0.4,0,0.3,3.14159,0,0], a=1.2, v=0.25)\n"


def test_a_tcp_set_in_an_if_arm_leaves_the_tcp_after_it_unknown(tmp_path: Path) -> None:
    moves, messages = _read(tmp_path, f"  {A}  {MOVE}  if get_standard_digital_in(1):\n    {B}  end\n  {MOVE}  {B}  {MOVE}")
    assert [type(m).__name__ for m in moves] == ["Move", "Native", "Move"]
    assert [m.tool for m in moves if isinstance(m, Move)] == ["tcp_1", "tcp_2"]
    assert any("a block or call before it may set the TCP (set_tcp)" in m for m in messages)


def test_a_tcp_set_in_a_loop_body_reaches_its_later_turns(tmp_path: Path) -> None:
    """In `while ..: movel; set_tcp(B); movel end` the first move of a later turn runs with B,
    the first turn's with A: native; the move after set_tcp in the body runs with B."""
    moves, _ = _read(tmp_path, f"  {A}  while get_standard_digital_in(1):\n    {MOVE}    {B}    {MOVE}  end\n")
    assert [type(m).__name__ for m in moves] == ["Native", "Move"]
    assert isinstance(moves[1], Move) and moves[1].tool == "tcp_2"


def test_a_tcp_set_in_a_function_body_is_the_function_s(tmp_path: Path) -> None:
    moves, _ = _read(tmp_path, f"  def tool_b():\n    {B}    {MOVE}  end\n  {A}  {MOVE}  tool_b()\n")
    assert all(isinstance(m, Move) for m in moves)


def test_the_same_tcp_set_again_in_a_block_changes_nothing(tmp_path: Path) -> None:
    """rmot's own URScript sets the TCP again at the start of each block (backends/urscript.py):
    the same TCP, so nothing becomes uncertain."""
    moves, _ = _read(tmp_path, f"  {A}  while get_standard_digital_in(1):\n    {MOVE}    {A}    {MOVE}  end\n  {MOVE}")
    assert all(isinstance(m, Move) and m.tool == "tcp_1" for m in moves)
