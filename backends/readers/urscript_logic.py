"""URScript variables and the logic on them, read into rmot's runtime logic (lang/REFERENCE.md §12).

A variable the program's own body (not a function, not a thread) tests in an `if`/`elif`/
`while` header, and every variable those read, is a task variable when each of its assignments
is there and is a number or bool expression rmot can write (logic.py): `var name: int|num|bool`
declared at the top of the main routine, its assignments `name = e`. A variable a function or a
thread assigns stays native (a thread changes it while the program runs; rmot's procs do not see
a task's variables). Where the program's outermost `while True:` is read as one cycle, a
variable the loop assigns must be assigned at the loop's top level before anything reads it
(else its value carries over from one turn to the next, which a repeated cycle would reset).

URScript's operators bind as Python's (URScript manual, "The URScript Programming Language":
`or` loosest, then `and`, `not`, comparisons, `+ -`, `* /`); `not` before a comparison, chained
comparisons (Python's `a < b < c`), `%`, and the division of two integers are refused.
"""

from __future__ import annotations

import re

from rmot.backends.readers.logic import fits, fold_first_values, translate
from rmot.backends.readers.model import Assign, Cond, Conds, Stmt, VarDecl, Where
from rmot.lang.parse import KEYWORDS

__all__ = ["URSCRIPT", "UrVars", "condition"]

# binary operator -> (priority, rmot operator); higher binds tighter (Python's order); `<>` is
# URScript's `!=` as logic.py tokenises it
URSCRIPT = {"OR": (1, "or"), "AND": (2, "and"), "==": (3, "=="), "<>": (3, "!="), "<": (3, "<"), "<=": (3, "<="),
            ">": (3, ">"), ">=": (3, ">="), "+": (4, "+"), "-": (4, "-"), "*": (5, "*"), "/": (5, "/")}
_COMPARE = {"==", "!=", "<", "<=", ">", ">="}
_WORDS = {"true": "True", "false": "False", "and": "and", "or": "or", "not": "not"}
_TOKENS = re.compile(r"\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+|\w+|==|!=|<=|>=|\S")
_ASSIGN = re.compile(r"(?:global\s+|local\s+)?([A-Za-z_]\w*)\s*=(?!=)\s*(.*)")
_HEADER = re.compile(r"(?:if|elif|while)\b\s*(.*):")
_MAX_VARS = 200  # more task variables than any program the corpus holds (a few): the rest stay native
_INPUT = {"get_standard_digital_in": 0, "get_configurable_digital_in": 8, "get_digital_in": 0}
_OUTPUT = {"get_standard_digital_out": 0, "get_configurable_digital_out": 8, "get_digital_out": 0}


def _python_shaped(text: str) -> bool:
    """Whether the operators of `text` mean in rmot's priorities what they mean in Python's: no
    `not` directly before a comparison or arithmetic, no chained comparison, keywords spelled as
    URScript spells them."""
    tokens = _TOKENS.findall(text)
    if "%" in tokens or any(t.lower() in _WORDS and t != _WORDS[t.lower()] for t in tokens):
        return False
    depth_ops: dict[int, int] = {}
    depth = 0
    for k, t in enumerate(tokens):
        depth += (t == "(") - (t == ")")
        if t in ("and", "or", "(", ")"):
            depth_ops[depth] = 0
        elif t in _COMPARE:
            depth_ops[depth] = depth_ops.get(depth, 0) + 1
            if depth_ops[depth] > 1:
                return False
        if t == "not" and not _operand_ends_cleanly(tokens, k + 1):
            return False
    return True


def _operand_ends_cleanly(tokens: list[str], k: int) -> bool:
    """After `not` at k-1: its operand (a parenthesised group, a name or call) is followed by the
    end, `and`, `or` or `)`, so Python's `not` (looser than comparisons) reads it as rmot's does."""
    while k < len(tokens) and tokens[k] == "not":
        k += 1
    if k < len(tokens) and re.fullmatch(r"\w+", tokens[k]):
        k += 1
    if k < len(tokens) and tokens[k] == "(":
        depth = 0
        while k < len(tokens):
            depth += (tokens[k] == "(") - (tokens[k] == ")")
            k += 1
            if depth == 0:
                break
    return k >= len(tokens) or tokens[k] in ("and", "or", ")")


def _input(tokens: list[str], i: int) -> tuple[Cond, int] | None:
    """`get_standard_digital_in(n)` (n + 8 for the configurable ones; `get_digital_in`, the
    CB-Series name, for n 0..7) as the input read."""
    t = tokens[i:i + 4]
    if len(t) == 4 and t[0] in _INPUT and t[1] == "(" and re.fullmatch(r"\d+", t[2]) and t[3] == ")":
        n = int(t[2])
        if t[0] == "get_digital_in" and n > 7:
            return None
        return Cond(n + _INPUT[t[0]], True), 4
    if len(t) == 4 and t[0] in _OUTPUT and t[1] == "(" and re.fullmatch(r"\d+", t[2]) and t[3] == ")":
        n = int(t[2])
        if t[0] == "get_digital_out" and n > 7:
            return None
        return Cond(n + _OUTPUT[t[0]], True, output=True), 4  # the output's state
    return None


def _translate(text: str, names: dict[str, tuple[str, str]]) -> tuple[Conds, str] | None:
    if not _python_shaped(text) or "<>" in text:
        return None
    # logic.py's tokens spell "not equal" `<>` (URScript has no `<>`: its `!=` is written so)
    return translate(text.replace("!=", "<>"), URSCRIPT, names, _input, int_division=True)


def condition(text: str, names: dict[str, tuple[str, str]]) -> Conds | None:
    """A URScript bool expression over the task variables and digital inputs, None without an rmot form."""
    found = _translate(text, names)
    return found[0] if found is not None and found[1] == "bool" else None


def _words(text: str) -> set[str]:
    return set(re.findall(r"[A-Za-z_]\w*", text))


class UrVars:
    """The task variables of one script, found from its statements (text and first word; `program`:
    the first is the program's own `def`; `installation`: the URCap installation nodes'
    statements), and the statements on them."""

    def __init__(self, texts: list[str], heads: list[str], program: bool, taken: set[str],
                 installation: list[str]) -> None:
        main = own_body(heads, texts, program)
        self.vars: dict[str, tuple[str, str]] = {}  # upper-case name -> (rmot name, type)
        self.decls: list[VarDecl] = []
        assigned: dict[str, list[str]] = {}
        outside = {m.group(1) for t in installation for m in [_ASSIGN.fullmatch(t)] if m}  # a URCap's, a
        # function's or a thread's (the installation's threads run beside the program)
        tested: set[str] = set()
        for text, own in zip(texts, main):
            m = _ASSIGN.fullmatch(text)
            if m:
                (assigned.setdefault(m.group(1), []).append(m.group(2)) if own else outside.add(m.group(1)))
            h = _HEADER.fullmatch(text)
            if h and own:
                tested |= _words(h.group(1))
        uppers = [n.upper() for n in set(assigned) | outside]
        wanted = self._closure(tested, assigned)
        candidates = {n for n in wanted if n in assigned and n not in outside and uppers.count(n.upper()) == 1}
        if len(candidates) > _MAX_VARS:  # typing is quadratic in their number: a hostile file's stay native
            candidates = set()
        self._type(candidates - counters(texts), assigned, taken)
        self.drop_carried(forever_body(heads, texts, main, program))

    @staticmethod
    def _closure(tested: set[str], assigned: dict[str, list[str]]) -> set[str]:
        out, todo = set(), list(tested)
        while todo:
            n = todo.pop()
            if n in out or n not in assigned:
                continue
            out.add(n)
            for expr in assigned[n]:
                todo += list(_words(expr))
        return out

    def _type(self, candidates: set[str], assigned: dict[str, list[str]], taken: set[str]) -> None:
        """Each candidate's rmot type: every assigned expression translates and fits (ints and nums
        as num, bools alone), the types of the names they read assumed and checked until none
        changes; a candidate whose expressions do not all translate is dropped."""
        types: dict[str, str] = {}
        for _ in range(2 * len(candidates) + 2):
            names = {n.upper(): (n, t) for n, t in types.items()}
            new: dict[str, str] = {}
            for n in sorted(candidates):
                found = [_translate(e, names) for e in assigned[n]]
                kinds = {f[1] for f in found if f is not None}
                if n in types and None in found:
                    continue  # dropped: a name it reads has no type (or an expression no form)
                type_ = "bool" if kinds == {"bool"} else "int" if kinds == {"int"} else \
                    "num" if kinds and "bool" not in kinds else ""
                if type_:
                    new[n] = type_
            if new == types:
                break
            types = new
        used = {t.lower() for t in taken} | {k.lower() for k in KEYWORDS}
        types = {n: t for n, t in types.items() if n.lower() not in used}  # a clash stays native:
        # a renamed variable would part from the native lines that read it by its URScript name
        for _ in range(len(types) + 1):
            kept = {n: t for n, t in types.items()
                    if all(_translate(e, {k.upper(): (k, v) for k, v in types.items()}) for e in assigned[n])}
            if kept == types:
                break
            types = kept
        for n in sorted(types):
            self.vars[n.upper()] = (n, types[n])
            default = "off" if types[n] == "bool" else "0" if types[n] == "int" else "0.0"
            self.decls.append(VarDecl(n, types[n], Conds("logic", (), default), Where("", 0)))

    def drop_carried(self, loop: list[str]) -> None:
        """The outermost `while True:` read as one cycle (its statements `loop`, its own level
        depth 0): a variable it assigns must be assigned at its top level before anything reads it."""
        depth = 0
        first: dict[str, bool] = {}
        for text in loop:
            m = _ASSIGN.fullmatch(text)
            for n in _words(m.group(2) if m else text):
                first.setdefault(n, False)
            if m:
                first.setdefault(m.group(1), depth == 0)
            depth += bool(re.match(r"(if|while|for|def|thread)\b", text)) - (text == "end")
        assigned = {m.group(1) for t in loop for m in [_ASSIGN.fullmatch(t)] if m}
        for n, ok in first.items():
            if not ok and n.upper() in self.vars and n in assigned:
                self.vars.pop(n.upper())
        self.decls = [d for d in self.decls if any(v[0] == d.name for v in self.vars.values())]

    def assign(self, text: str, where: Where) -> Assign | None:
        """`[global|local] name = e` on a task variable."""
        m = _ASSIGN.fullmatch(text)
        found = self.vars.get(m.group(1).upper()) if m else None
        if m is None or found is None:
            return None
        value = _translate(m.group(2), self.vars)
        if value is None or not fits(found[1], value[1]):
            return None
        return Assign(found[0], value[0], where)

    def condition(self, text: str) -> Conds | None:
        return condition(text, self.vars)

    def hoist(self, body: tuple[Stmt, ...]) -> tuple[Stmt, ...]:
        """The main routine's body with the task variables declared at its top (logic.py folds the
        values it starts by assigning, an I/O read too: the backend writes `var b: bool = out[1]`
        as `global b = False` among the program's globals and `b = get_standard_digital_out(1)`
        where the declaration stands)."""
        if not self.decls:
            return body
        decls, rest = fold_first_values(self.decls, body, reads=True)
        return (*decls, *rest)


def own_body(heads: list[str], texts: list[str], program: bool) -> list[bool]:
    """Which statements are the program's own body: not inside a function or thread (the
    program's own `def`, when the script is one, is the body)."""
    out: list[bool] = []
    stack: list[bool] = []  # stack: whether each open block is a function or thread
    for k, head in enumerate(heads[:len(texts)]):
        opens = head in ("if", "while", "for", "def", "thread")
        inside = any(stack[1:] if program else stack)
        out.append(not inside and not (opens and head in ("def", "thread") and not (program and k == 0)))
        if opens:
            stack.append(head in ("def", "thread"))
        elif head == "end" and stack:
            stack.pop()
    return out


def counters(texts: list[str]) -> set[str]:
    """Names a counted loop uses (`i = 0` then `while i < n:`): read as a `for`, not a variable."""
    out = set()
    for a, b in zip(texts, texts[1:]):
        m = re.fullmatch(r"([A-Za-z_]\w*)\s*=\s*-?\d+", a)
        if m and re.fullmatch(rf"while\(?{m.group(1)}(<=|<)(-?\w+)\)?:", b.replace(" ", "")):
            out.add(m.group(1))
    return out


def forever_body(heads: list[str], texts: list[str], main: list[bool], program: bool) -> list[str]:
    """The statements of the program's outermost `while True:` (read as one cycle), or []."""
    depth = 0
    for k, (head, text) in enumerate(zip(heads, texts)):
        if main[k] and depth == int(program) and re.fullmatch(r"while\s*\(?\s*True\s*\)?\s*:", text):
            inner: list[str] = []
            d = 1
            for t, h in zip(texts[k + 1:], heads[k + 1:]):
                d += h in ("if", "while", "for", "def", "thread")
                d -= h == "end"
                if d == 0:
                    return inner
                inner.append(t)
            return inner
        depth += head in ("if", "while", "for", "def", "thread")
        depth -= head == "end"
    return []


def timed_wait(t: list[str]) -> tuple[float, bool] | None:
    """(timeout s, whether it ends in popup + halt) of the backend's timed wait, its statements
    `t` without spaces: `rmot_waited=0.0`, `whilenot(c)andrmot_waited<T:`, `sync()`, the step,
    `end`, `ifnot(c):`, then popup + halt + `end` (no else branch) or the else branch's statements."""
    w = re.fullmatch(r"whilenot\((.*)\)andrmot_waited<([\d.]+):", t[1]) if len(t) >= 6 and t[0] == "rmot_waited=0.0" else None
    if w is None or t[2:5] != ["sync()", "rmot_waited=rmot_waited+get_steptime()", "end"] or t[5] != f"ifnot({w.group(1)}):":
        return None
    halts = len(t) >= 9 and t[6].startswith("popup(") and t[7:9] == ["halt", "end"]
    return float(w.group(2)), halts
