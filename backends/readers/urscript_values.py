"""URScript values computed from the text: arithmetic over numbers and variables whose value is
certain, targets moved by an offset (`pose_add` along the base, `pose_trans` along the tool),
and what tells whether a value is certain: the statements that may change a variable they do not
name, the names threads set, counted loops, a parameter's test, why a move's value is unknown.

URScript manual ("The URScript Programming Language", e-Series): the arithmetic operators
`+ - * /` bind as Python's (`*` `/` tighter than `+` `-`, unary minus tightest); module urmath:
`d2r(d)` "Returns the radian value of 'd' degrees" ((d / 180) * pi) and `r2d(r)` its inverse.
A division whose two operands may both be integers is not computed (URScript's integer
division would differ from rmot's), nor a name whose value is not certain where it is read: the
caller's `value_of` says which names are.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

from rmot.backends.readers.common import num_expr, number, split_top
from rmot.backends.readers.model import Conds, Target, Where
from rmot.backends.readers.rapid import num_text
from rmot.backends.readers.urscript_text import ANY_ASSIGN
from rmot.lang import ir

__all__ = [
    "arithmetic", "base_offset", "counted_loop", "may_change", "parameter_test", "thread_assigned", "tool_offset",
    "unknown_value",
]

_TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?)|([A-Za-z_]\w*)|([-+*/(),]))")
_MAX_DEPTH = 32  # parentheses and signs nested in one value: more than any program writes
_FUNCTIONS = {"d2r": math.radians, "r2d": math.degrees}

Resolved = tuple[str, str | None, Target | None]


class _Parser:
    """One arithmetic expression read by recursive descent: each value is (number, whether it
    may be an integer), None where a part is unknown or the text is not arithmetic."""

    def __init__(self, tokens: list[tuple[str, str]], value_of: Callable[[str], float | None]) -> None:
        self.tokens = tokens
        self.k = 0
        self.value_of = value_of

    def peek(self) -> tuple[str, str]:
        return self.tokens[self.k] if self.k < len(self.tokens) else ("", "")

    def sum(self, depth: int) -> tuple[float, bool] | None:
        return self.binary(depth, ("+", "-"), self.product)

    def product(self, depth: int) -> tuple[float, bool] | None:
        return self.binary(depth, ("*", "/"), self.unary)

    def binary(self, depth: int, ops: tuple[str, str],
               operand: Callable[[int], tuple[float, bool] | None]) -> tuple[float, bool] | None:
        """Operands joined left to right by `ops`; a division by zero, or of two values that may
        both be integers, is unknown."""
        left = operand(depth)
        while left is not None and self.peek()[1] in ops:
            op = self.tokens[self.k][1]
            self.k += 1
            right = operand(depth)
            if right is None or (op == "/" and (right[0] == 0.0 or (left[1] and right[1]))):
                return None
            a, b = left[0], right[0]
            value = a + b if op == "+" else a - b if op == "-" else a * b if op == "*" else a / b
            left = (value, op != "/" and left[1] and right[1])
        return left

    def unary(self, depth: int) -> tuple[float, bool] | None:
        if depth > _MAX_DEPTH:
            return None
        kind, text = self.peek()
        if kind == "op" and text in ("-", "+"):
            self.k += 1
            inner = self.unary(depth + 1)
            return None if inner is None else (-inner[0] if text == "-" else inner[0], inner[1])
        return self.atom(depth)

    def atom(self, depth: int) -> tuple[float, bool] | None:
        kind, text = self.peek()
        self.k += 1
        if kind == "num":
            return float(text), re.fullmatch(r"\d+", text) is not None
        if kind == "op" and text == "(":
            inner = self.sum(depth + 1)
            return inner if inner is not None and self.close() else None
        if kind != "name":
            return None
        if self.peek()[1] == "(":  # d2r(..) / r2d(..): a float in radians or degrees
            self.k += 1
            inner = self.sum(depth + 1) if text in _FUNCTIONS else None
            return (_FUNCTIONS[text](inner[0]), False) if inner is not None and self.close() else None
        value = self.value_of(text)
        return None if value is None else (value, value == int(value))

    def close(self) -> bool:
        if self.peek()[1] != ")":
            return False
        self.k += 1
        return True


def arithmetic(text: str, value_of: Callable[[str], float | None]) -> float | None:
    """The number `text` computes (`0.001*t`, `-(width+gap)`, `d2r(90)`), names read through
    `value_of`; None when a part is unknown or `text` is not plain arithmetic."""
    tokens: list[tuple[str, str]] = []
    pos, text = 0, text.strip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            return None
        num, name, op = m.groups()
        tokens.append(("num", num) if num else ("name", name) if name else ("op", op))
        pos = m.end()
    parser = _Parser(tokens, value_of)
    found = parser.sum(0) if tokens else None
    if found is None or parser.k != len(tokens) or not math.isfinite(found[0]):
        return None
    return found[0]


def base_offset(parts: list[str], target_of: Callable[[str], Resolved | None], names: set[str]) -> Resolved | None:
    """`pose_add(P, p[dx, dy, dz, 0, 0, 0])`: P moved along the base axes = `shift(P, ..)` (the
    offsets numbers or arithmetic over the loop counters in `names`)."""
    base = target_of(parts[0]) if len(parts) == 2 else None
    shift = re.fullmatch(r"p\[(.*)\]", parts[1]) if base else None
    offs = split_top(shift.group(1)) if shift else []
    if base is None or len(offs) != 6 or any(number(o) != 0.0 for o in offs[3:]):
        return None
    exprs = [e for e in (num_expr(o, names) for o in offs[:3]) if e is not None]
    if len(exprs) != 3:
        return None
    terms = ", ".join(f"{a}={e} m" if number(e) is not None else f"{a}=({e}) * 1 m"
                      for a, e in zip("xyz", exprs) if number(e) != 0.0)
    values = [number(e) for e in exprs]
    pose = base[2].pose if base[2] is not None else None
    moved = None
    if pose is not None and all(v is not None for v in values):  # a loop counter's offset: no one pose
        x, y, z = (p + (v or 0.0) for p, v in zip(pose.position, values))
        moved = ir.Pose((x, y, z), pose.quaternion)
    return (f"shift({base[0]}, {terms})" if terms else base[0], base[1], _pose(moved))


def tool_offset(parts: list[str], target_of: Callable[[str], Resolved | None],
                offset_of: Callable[[str], list[float] | None]) -> Resolved | None:
    """`pose_trans(P, D)`, D a translation `p[dx, dy, dz, 0, 0, 0]` (written, or a pose known
    here): P moved along its own (tool) axes (URScript manual, pose_trans: the second pose is
    expressed in the first's frame) = `P * pose(..)`."""
    base = target_of(parts[0]) if len(parts) == 2 else None
    offs = offset_of(parts[1]) if base else None
    if base is None or offs is None or len(offs) != 6 or any(o != 0.0 for o in offs[3:]):
        return None
    terms = ", ".join(f"{a}={num_text(1000.0 * o)}mm" for a, o in zip("xyz", offs[:3]) if o != 0.0)
    pose = base[2].pose if base[2] else None
    return (f"{base[0]} * pose({terms})" if terms else base[0], base[1],
            _pose(pose * ir.Pose((offs[0], offs[1], offs[2])) if pose else None))


def _pose(pose: ir.Pose | None) -> Target | None:
    """The declaration a resolved target carries: its own pose (never its base's)."""
    return Target("", pose, None, None, Where("", 0)) if pose is not None else None


# URScript's built-in functions that set no variable of the program (URScript manual, modules
# motion, interfaces, math, urmath, internals: they return a value or act on the robot)
_BUILT_IN = re.compile(r"move[jlpc]|servo[jc]|speed[jl]|stop[jl]|sleep|sync|textmsg|popup|set_\w+|get_\w+|pose_\w+|"
                       r"d2r|r2d|sqrt|sin|cos|tan|asin|acos|atan|atan2|norm|floor|ceil|pow|log|interpolate_pose|"
                       r"point_dist|length|to_str|str_\w+|write_\w+|read_\w+|is_\w+|if|elif|while|not|and|or")


def may_change(text: str) -> bool:
    """Whether the statement `text` may set a variable it does not name: a thread's `run`, `join`
    or `kill` (URScript manual, "Threads"), or a call of anything but URScript's built-in
    functions above (a function of the file, of the robot's installation, of another file)."""
    if re.search(r"\b(?:run|join|kill)\b", text):
        return True
    return any(not _BUILT_IN.fullmatch(m.group(1)) for m in re.finditer(r"\b([A-Za-z_]\w*)\s*\(", text))


def thread_assigned(texts: list[str], heads: list[str]) -> set[str]:
    """The names a thread's body sets, whole or an element (`p[2] = ..`): a thread runs beside
    the program (URScript manual, "Threads"), so their value is never certain in between."""
    out: set[str] = set()
    stack: list[bool] = []  # each open block: whether it is a thread
    for text, head in zip(texts, heads):
        m = ANY_ASSIGN.match(text) or re.match(r"(?:global\s+|local\s+)?(\w+)\s*\[", text)
        if m and any(stack):
            out.add(m.group(1))
        if head in ("if", "while", "for", "def", "thread"):
            stack.append(head == "thread")
        elif head == "end" and stack:
            stack.pop()
    return out


def counted_loop(head: list[str], inner: list[str], value_of: Callable[[str], float | None]) -> tuple[str, int, int] | None:
    """(v, a, the bound past the last turn) of `v = a`, `while v <= b:` (or PolyScope's `while (v
    < b):`; b a number or a variable `value_of` knows), body, `v = v + 1`, `end` (statements
    without spaces; `inner` the body's with the step), the body neither assigning v nor
    breaking out: for v in a .. b + 1 (a .. b)."""
    m = re.fullmatch(r"(\w+)=(-?\d+)", head[0]) if len(head) == 2 else None
    w = re.fullmatch(rf"while\(?{m.group(1)}(<=|<)(-?\w+)\)?:", head[1]) if m else None
    bound = value_of(w.group(2)) if w else None
    if m is None or w is None or bound is None or bound != int(bound) or not inner or \
            inner[-1] != f"{m.group(1)}={m.group(1)}+1" or any(
                x in ("break", "continue") or (ANY_ASSIGN.match(x) or [None, None])[1] == m.group(1) for x in inner[:-1]):
        return None
    return m.group(1), int(m.group(2)), int(bound) + (w.group(1) == "<=")


_NOT_VALUES = {"True", "False", "and", "or", "not", "p"}


def unknown_value(text: str, assigned: dict[str, int], parameters: tuple[str, ...],
                  known: Callable[[str], bool]) -> str | None:
    """Why the arguments of the call `text` (a move) are not known here: a value computed at run
    time (`get_actual_tcp_pose()`, a function of the file, ..; not the pose functions read),
    a function's parameter, a name the file never sets (another file or the robot's installation
    does), or one whose value here is not certain; None when each name is known (another form
    kept the line native)."""
    inner = text[text.find("(") + 1:text.rfind(")")]
    read = re.search(r"\b(?!(?:pose_trans|pose_add|get_inverse_kin|d2r|r2d)\b)([A-Za-z_]\w*)\s*\(", inner)
    if read:
        return f"`{read.group(1)}(..)` is computed at run time"
    for m in re.finditer(r"\b([A-Za-z_]\w*)\b(?!\s*[(=\[])", inner):
        name = m.group(1)
        if name in _NOT_VALUES or known(name):
            continue
        if name in parameters:
            return f"`{name}` is a parameter of the function: its value is the caller's"
        count = assigned.get(name, 0)
        if count == 0:
            return f"`{name}` is not set in this file (another file or the robot's installation sets it)"
        return f"`{name}`'s value here is not known for certain (the file sets it at {count} places)"
    return None


def parameter_test(text: str, parameters: tuple[str, ...]) -> Conds | None:
    """A function's parameter compared with a number (RoboDK's `if value == 0:` in `SprayOn(value)`):
    a test the compiler decides at each call (`value == 0` in rmot; URScript's comparison
    operators are rmot's)."""
    m = re.fullmatch(r"\(?\s*(\w+)\s*(==|!=|<=|>=|<|>)\s*([-+\d.eE]+)\s*\)?", text.strip())
    value = number(m.group(3)) if m and m.group(1) in parameters else None
    return Conds("expr", (), f"{m.group(1)} {m.group(2)} {num_text(value)}") if m and value is not None else None
