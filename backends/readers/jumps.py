"""Conditions written as chains of conditional jumps (TP `IF ..,JMP LBL[n]`, INFORM `JUMP *Ln IF ..`).

Both backends write an if's `and` and `or` as jumps over the then-arm (backends/inform.py
`_jump`, backends/fanuc_tp.py): `if A and B` is a jump to the arm's end when A fails, then
one when B fails (the arm runs when none is taken); `if A or B` is a jump to a label Ls past
the other tests when A holds, then a jump to the arm's end when B fails, then Ls's line (the
arm runs when the first is taken or the last is not). A reader reads the whole chain as one
condition, and reads no chain whose labels another line also jumps to (the chain's labels are
removed with it: that line would jump to a label the program no longer has).
"""

from __future__ import annotations

from collections.abc import Callable

from rmot.backends.readers.model import Cond, Conds

__all__ = ["Jump", "jump_chain", "jumped_to_elsewhere"]

# one conditional jump: (its label, the condition under which it is taken, the condition under
# which it falls through, the line after it)
Jump = tuple[str, Cond | Conds, Cond | Conds, int]


def _all(parts: list[Cond | Conds]) -> Cond | Conds:
    return parts[0] if len(parts) == 1 else Conds("and", tuple(parts))


def jump_chain(jump_at: Callable[[int], Jump | None], text_at: Callable[[int], str], i: int,
               label_line: Callable[[str], str]) -> tuple[str, Cond | Conds, int, tuple[str, ...]] | None:
    """The if condition whose jumps start at line `i` (`jump_at(k)`: the conditional jump at
    line k, or None; `label_line(name)`: the text of a label's line): (the label that ends the
    then-arm, the condition under which the arm runs, its first line, the labels the chain
    consumes besides the first), or None where line `i` is no conditional jump."""
    first = jump_at(i)
    if first is None:
        return None
    label, taken, falls, k = first[0], [first[1]], [first[2]], first[3]
    nxt = jump_at(k)
    while nxt is not None and nxt[0] == label:
        taken, falls, k = taken + [nxt[1]], falls + [nxt[2]], nxt[3]
        nxt = jump_at(k)
    if nxt is not None and nxt[0] != label and text_at(nxt[3]) == label_line(label):
        parts = (*taken, nxt[2])  # the `or` form: any of the first taken, or the last not
        return nxt[0], Conds("or", parts), nxt[3] + 1, (label,)
    return label, _all(falls), k, ()


def jumped_to_elsewhere(text_at: Callable[[int], str], lines: int, labels: tuple[str, ...],
                        mentions: Callable[[str, str], bool], consumed: set[int]) -> bool:
    """Whether a line of the routine (0..lines-1) other than those an if reads (`consumed`)
    names one of its `labels` (`mentions(text, label)`)."""
    return any(k not in consumed and mentions(text_at(k), label) for k in range(lines) for label in labels)
