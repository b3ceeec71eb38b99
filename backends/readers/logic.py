"""Runtime expressions of RAPID and KRL read into rmot's (lang/REFERENCE.md §12): task variables
(int, num, bool), numbers, digital inputs, `+ - * /`, comparisons, `and`, `or`, `not`.

Each vendor's operator priorities, highest first (a bare operand of NOT must be unambiguous):
RAPID (Technical reference manual – RAPID kernel, "Expressions", priority between operators):
`* / DIV MOD`, `+ -`, `< <= = >= > <>`, `AND`, `XOR OR NOT`. KRL (KUKA System Software 8.x,
Operating and Programming Instructions for System Integrators, "Priority of operators"):
`NOT`, `* /`, `+ -`, `AND`, `EXOR`, `OR`, `== <> < > <= >=` (comparisons bind loosest).
What has no rmot meaning is refused (None), never approximated: DIV, MOD, XOR/EXOR, the bit
operators, strings, arrays, function calls other than the digital input reads, reading an
output, KRL's `/` of two integers (an integer division), comparing two bool expressions.
The result is a `Conds` of op "logic": rmot text with `{n}` where the n-th input condition of
`parts` is written (the writer gives each its port), and the expression's rmot type.
"""

from __future__ import annotations

import re
from dataclasses import replace
from collections.abc import Callable, Mapping

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally
from rmot.backends.readers.model import Assign, Cond, Conds, GroupIn, Stmt, VarDecl
from rmot.lang.diagnostics import Diagnostic, Severity
from rmot.lang.source import Pos, SourceFile, Span

__all__ = ["translate", "RAPID", "KRL", "fits", "fold_first_values", "warn_persistent"]

# binary operator -> (vendor priority, rmot operator); higher binds tighter
RAPID = {"OR": (1, "or"), "AND": (2, "and"), "=": (3, "=="), "<>": (3, "!="), "<": (3, "<"), "<=": (3, "<="),
         ">": (3, ">"), ">=": (3, ">="), "+": (4, "+"), "-": (4, "-"), "*": (5, "*"), "/": (5, "/")}
KRL = {"==": (1, "=="), "<>": (1, "!="), "<": (1, "<"), "<=": (1, "<="), ">": (1, ">"), ">=": (1, ">="),
       "OR": (2, "or"), "AND": (4, "and"), "+": (5, "+"), "-": (5, "-"), "*": (6, "*"), "/": (6, "/")}
_RMOT_PRIORITY = {"or": 1, "and": 2, "not": 3, "==": 4, "!=": 4, "<": 4, "<=": 4, ">": 4, ">=": 4,
                  "+": 5, "-": 5, "*": 6, "/": 6}
_TOKEN = re.compile(r"\s*(\d+\.\d*(?:[Ee][+-]?\d+)?|\.\d+(?:[Ee][+-]?\d+)?|\d+(?:[Ee][+-]?\d+)?|\$?\w+|<>|<=|>=|==|"
                    r"[-+*/()<>=\[\],])")
_MAX_TOKENS = 400

# (rmot text, type, rmot priority); an input condition is ("{n}", "bool", 4)
_Node = tuple[str, str, int]


class _Refused(Exception):
    """The expression has no rmot form."""


class _Parser:
    def __init__(self, tokens: list[str], ops: Mapping[str, tuple[int, str]], names: Mapping[str, tuple[str, str]],
                 signal: Callable[[list[str], int], tuple[Cond | GroupIn, int] | None], int_division: bool) -> None:
        self.tokens, self.i, self.ops, self.names = tokens, 0, ops, names
        self.signal, self.int_division = signal, int_division
        self.parts: list[Cond | GroupIn] = []

    def peek(self) -> str:
        return self.tokens[self.i].upper() if self.i < len(self.tokens) else ""

    def take(self, token: str) -> None:
        if self.peek() != token:
            raise _Refused(token)
        self.i += 1

    def expr(self, floor: int = 0) -> _Node:
        left = self.unary()
        while self.peek() in self.ops and self.ops[self.peek()][0] > floor:
            prio, op = self.ops[self.peek()]
            self.i += 1
            left = self.binary(op, left, self.expr(prio))
        return left

    def unary(self) -> _Node:
        if self.peek() == "NOT":
            self.i += 1
            operand = self.unary()
            if self.ops is RAPID and self.peek() in self.ops:
                raise _Refused("NOT before a binary operator: RAPID's priority makes it ambiguous")
            return self.negate(operand)
        if self.peek() == "-" and self.i + 1 < len(self.tokens) and re.fullmatch(r"[\d.]+\w*", self.tokens[self.i + 1]):
            self.i += 1
            text, type_, prio = self.atom()
            return ("-" + text, type_, prio)
        return self.atom()

    def negate(self, node: _Node) -> _Node:
        if node[1] != "bool":
            raise _Refused("NOT of a number")
        m = re.fullmatch(r"\{(\d+)\}", node[0])
        if m:  # an input condition: its level flips
            cond = self.parts[int(m.group(1))]
            assert isinstance(cond, Cond)  # a group input's node is an int, refused above
            self.parts[int(m.group(1))] = cond.negated()
            return node
        return (f"not {_wrap(node, 3)}", "bool", 3)

    def binary(self, op: str, left: _Node, right: _Node) -> _Node:
        prio = _RMOT_PRIORITY[op]
        if op in ("and", "or"):
            if left[1] != "bool" or right[1] != "bool":
                raise _Refused(op)
            return (f"{_wrap(left, prio)} {op} {_wrap(right, prio + 1)}", "bool", prio)
        if left[1] == "bool" or right[1] == "bool":
            return self.bool_compare(op, left, right)
        if self.is_group(left) or self.is_group(right):
            return self.group_compare(op, left, right)
        if op in ("==", "!=", "<", "<=", ">", ">="):
            return (f"{_wrap(left, 5)} {op} {_wrap(right, 5)}", "bool", prio)
        if op == "/" and left[1] == right[1] == "int" and self.int_division:
            raise _Refused("an integer division")
        type_ = "int" if left[1] == right[1] == "int" and op != "/" else "num"
        return (f"{_wrap(left, prio)} {op} {_wrap(right, prio + 1)}", type_, prio)

    def is_group(self, node: _Node) -> bool:
        m = re.fullmatch(r"\{(\d+)\}", node[0])
        return m is not None and isinstance(self.parts[int(m.group(1))], GroupIn)

    def group_compare(self, op: str, left: _Node, right: _Node) -> _Node:
        """A group input compared with a whole number or a variable, the input on the left (rmot
        reads `gin[n] op value`; `3 < k` is `k > 3`); arithmetic on it, a comparison of two of
        them or with a fraction (which never equals a whole number: E168) are refused."""
        if self.is_group(right):
            left, right, op = right, left, {"<": ">", ">": "<", "<=": ">=", ">=": "<="}.get(op, op)
        if op not in ("==", "!=", "<", "<=", ">", ">=") or self.is_group(right):
            raise _Refused("arithmetic on a group input")
        if right[1] != "int" and re.fullmatch(r"-?[\d.]+(?:e[-+]?\d+)?", right[0]):
            raise _Refused("a group input compared with a fraction")
        return (f"{left[0]} {op} {_wrap(right, 5)}", "bool", _RMOT_PRIORITY[op])

    def bool_compare(self, op: str, left: _Node, right: _Node) -> _Node:
        """`b == TRUE` is b, `b == FALSE` (or `<> TRUE`) is not b; other comparisons of bools are refused."""
        literal = right if right[0] in ("on", "off") else left if left[0] in ("on", "off") else None
        other = left if literal is right else right
        if literal is None or other[1] != "bool" or op not in ("==", "!="):
            raise _Refused("a comparison of two bool expressions")
        if other[2] < 4:  # KRL's `$IN[1] AND $IN[2]==FALSE` compares the AND: rarely what was meant, refused
            raise _Refused("a comparison of an and/or/not")
        return other if (op == "==") == (literal[0] == "on") else self.negate(other)

    def atom(self) -> _Node:
        token = self.peek()
        if token == "(":
            self.i += 1
            inner = self.expr()
            self.take(")")
            return inner
        found = self.signal(self.tokens, self.i)
        if found is not None:
            cond, used = found
            self.i += used
            self.parts.append(cond)
            if isinstance(cond, GroupIn):  # a group input: an unsigned integer
                return ("{%d}" % (len(self.parts) - 1), "int", 9)
            return ("{%d}" % (len(self.parts) - 1), "bool", 4)
        self.i += 1
        if token in ("TRUE", "FALSE"):
            return ("on" if token == "TRUE" else "off", "bool", 9)
        if re.fullmatch(r"\d+", token):
            return (str(int(token)), "int", 9)
        if re.fullmatch(r"(?:\d+\.?\d*|\.\d+)(?:E[+-]?\d+)?", token):  # a number (not `.` or the end: "")
            return (f"{float(token)!r}", "num", 9)
        if token in self.names and self.peek() not in ("(", "["):
            name, type_ = self.names[token]
            return (name, type_, 9)
        raise _Refused(token)


def _wrap(node: _Node, floor: int) -> str:
    return node[0] if node[2] >= floor else f"({node[0]})"


def translate(text: str, ops: Mapping[str, tuple[int, str]], names: Mapping[str, tuple[str, str]],
              signal: Callable[[list[str], int], tuple[Cond | GroupIn, int] | None],
              int_division: bool = False) -> tuple[Conds, str] | None:
    """(Conds "logic", rmot type) of a vendor expression, None when it has no rmot form. `names`:
    upper-case vendor name -> (rmot name, type) of the task variables and constants it may read;
    `signal(tokens, i)`: the input condition the tokens at i read and how many tokens that takes."""
    tokens = _TOKEN.findall(text)
    if "".join(tokens).replace(" ", "") != re.sub(r"\s+", "", text) or not tokens or len(tokens) > _MAX_TOKENS:
        return None
    parser = _Parser(tokens, ops, names, signal, int_division)
    try:
        node = parser.expr()
        if parser.i != len(tokens):
            return None
    except (_Refused, RecursionError, ValueError):
        return None
    return Conds("logic", tuple(parser.parts), node[0]), node[1]


def fits(var_type: str, value_type: str) -> bool:
    """rmot's assignment rule (§12, E151): an int takes an int, a num an int or a num, a bool a
    bool (KRL would round a REAL into an INT, RAPID has one num: neither is read otherwise)."""
    return value_type == var_type or (var_type == "num" and value_type == "int")


def fold_first_values(decls: list[VarDecl], body: tuple[Stmt, ...],
                      reads: bool = False) -> tuple[list[VarDecl], tuple[Stmt, ...]]:
    """The declarations, each with the value the routine assigns it first thing (`x := 0;`
    before any other statement, from constants only, or with `reads` also from I/O reads where
    the declarations stand at the routine's top: nothing reads the declared value), and the
    rest of the body."""
    by_name = {d.name: d for d in decls}
    k = 0
    while k < len(body) and isinstance(body[k], Assign):
        a = body[k]
        assert isinstance(a, Assign)
        if a.name not in by_name or (a.value.parts and not reads) or any(re.search(rf"\b{n}\b", a.value.text) for n in by_name):
            break
        by_name[a.name] = replace(by_name[a.name], init=a.value)
        k += 1
    return list(by_name.values()), body[k:]


def warn_persistent(tally: Tally, declared: list[VarDecl], folded: list[VarDecl], persistent: set[str],
                    texts: Mapping[str, str] | None = None) -> None:
    """W541 at each persistent variable whose declared value the routine does not replace first
    thing (located in its own file: `texts`, path -> text, holds the files other than the tally's)."""
    for before, after in zip(declared, folded):
        if before.name not in persistent or after.init is not before.init:
            continue
        w = before.where
        source = tally.source if w.path == tally.path else SourceFile(w.path, (texts or {}).get(w.path, ""))
        tally.diagnostics.append(Diagnostic(
            codes.PERSISTENT_VARIABLE, Severity.WARNING, f"`{before.name}` keeps its value from one run to the next "
            "on the controller: read as a task variable starting at the value the file stores",
            Span(source, Pos(w.line, w.col), Pos(w.line, w.col))))
