"""URScript text and values: the statements of a line, PolyScope's URCap installation nodes,
comments, conditions on digital inputs, pose literals (the parts of reading URScript that see
only text).

URScript manual ("The URScript Programming Language", e-Series): statements need no separator;
`not`, `and`, `or` bind as in Python; `get_standard_digital_in(n)` n 0..7,
`get_configurable_digital_in(n)` the configurable inputs, rmot's n + 8.
"""

from __future__ import annotations

import math
import re

from rmot.backends.readers.common import number, split_top
from rmot.backends.readers.model import Cond, Conds, ToolData, Where
from rmot.lang import ir

__all__ = [
    "ANY_ASSIGN", "NUMBER_ASSIGN", "Line", "balanced", "block_end", "compose", "input_cond", "installation_nodes",
    "outer", "polled_wait", "pose_numbers", "scan_assignments", "scoped_defs", "split_statements", "split_word",
    "strip_hash", "ur_pose", "TCP_UNKNOWN", "functions", "tcp_after_call", "statements_follow",
]


class Line:
    """One statement of the script and where it begins."""

    def __init__(self, text: str, where: Where) -> None:
        self.text = text
        self.where = where

    @property
    def head(self) -> str:
        m = re.match(r"\s*(\w+)", self.text)
        return m.group(1) if m else ""


def ur_pose(values: list[float]) -> ir.Pose:
    """p[x, y, z, rx, ry, rz] (m, rotation vector rad) as an ir.Pose."""
    x, y, z, rx, ry, rz = values
    angle = math.sqrt(rx * rx + ry * ry + rz * rz)
    if angle < 1e-15:
        return ir.Pose((x, y, z))
    s = math.sin(angle / 2) / angle
    q = [0.0 if abs(v) < 1e-12 else v for v in (math.cos(angle / 2), rx * s, ry * s, rz * s)]  # cos(pi/2) noise
    n = math.sqrt(sum(v * v for v in q))
    w, qx, qy, qz = (v / n for v in q)
    if w < 0:
        w, qx, qy, qz = -w, -qx, -qy, -qz
    return ir.Pose((x, y, z), (w, qx, qy, qz))


def pose_numbers(text: str) -> list[float] | None:
    values = [number(v) for v in split_top(text)]
    return None if any(v is None for v in values) else values  # type: ignore[return-value]


def installation_nodes(raw: list[str]) -> dict[int, tuple[str, int]]:
    """Line number -> (URCap, first line) for the lines of PolyScope's URCap installation nodes:
    from `# begin: URCap Installation Node` (its `#   Source: NAME, version, vendor` line names
    the URCap) to the next `# end: URCap Installation Node`, where its blocks are closed in it
    (every `if`, loop, def and thread ends before the node does)."""
    out: dict[int, tuple[str, int]] = {}
    first = None
    for n, line in enumerate(raw, 1):
        text = line.strip()
        if text.startswith("# begin: URCap Installation Node"):
            first = n
        elif text.startswith("# end: URCap Installation Node") and first is not None:
            span = range(first, n + 1)
            heads = [re.match(r"(\w+)", raw[k - 1].split("#")[0].strip() or "#") for k in span]
            words = [h.group(1) for h in heads if h]
            if sum(w in ("if", "while", "for", "def", "thread") for w in words) == words.count("end"):
                source = next((re.sub(r"^#\s*Source:\s*", "", raw[k - 1].strip()) for k in span
                               if re.match(r"#\s*Source:", raw[k - 1].strip())), "unnamed")
                out.update({k: (source, first) for k in span})
            first = None
    return out


def strip_hash(line: str) -> str:
    quote = False
    for i, ch in enumerate(line):
        if ch == '"':
            quote = not quote
        elif ch == "#" and not quote:
            return line[:i]
    return line


_HEADER = re.compile(r"(?:if|elif|while|for|def|thread)\b|else\s*:")
_OPERATORS = {"and", "or", "xor", "not", "True", "False"}


def split_statements(code: str) -> list[tuple[int, str]]:
    """The statements of one line, each with its offset: URScript ends a statement at the line's
    end or where the next begins (URScript manual, "The URScript Programming Language": no
    separator is needed), so `if (c): movej(q) end` and `movel(p, a=1, v=0.1)  sleep(0.5)`
    are three and two statements. A block header ends at its `:` outside brackets; a statement
    ends after a closing bracket followed by a name that is not an operator, and before `end`.
    One pass over the line (a hostile long line costs its length)."""
    out: list[tuple[int, str]] = []
    start, depth, quote, header, prev = 0, 0, False, _HEADER.match(code) is not None, ""
    i = 0
    while i < len(code):
        ch = code[i]
        if ch == '"':
            quote = not quote
        elif quote:
            pass
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif depth == 0 and ch == ":" and header:
            out.append((start, code[start:i + 1]))
            start, header, prev, i = i + 1, False, "", i + 1
            continue
        elif depth == 0 and ch.isspace() and prev:
            word = re.match(r"\s+([A-Za-z_]\w*)", code[i:i + 80])
            if word and (word.group(1) == "end" or prev in ")]" and word.group(1) not in _OPERATORS):
                out.append((start, code[start:i]))
                start = i + len(word.group(0)) - len(word.group(1))
                header, prev, i = _HEADER.match(code, start) is not None, "", start
                continue
        if not ch.isspace():
            prev = ch
        i += 1
    out.append((start, code[start:]))
    return [(offset + len(part) - len(part.lstrip()), part.strip()) for offset, part in out if part.strip()]


def balanced(text: str) -> bool:
    depth = 0
    for ch in text:
        depth += (ch == "(") - (ch == ")")
        if depth < 0:
            return False
    return depth == 0


_MAX_DEPTH = 64  # operators nested in one condition: more than any program writes


def input_cond(text: str, depth: int = 0) -> Cond | Conds | None:
    """A condition on digital inputs: `get_standard_digital_in(n) == True|False` (or `!=`, or
    bare), combined by `not`, `and`, `or` with URScript's (Python's) priority, `not` binding
    tightest and `or` loosest, in any parentheses (configurable: n + 8); nested at most
    _MAX_DEPTH deep (a hostile file's deeper condition stays native)."""
    if depth > _MAX_DEPTH:
        return None
    text = outer(text)
    for op in ("or", "and"):
        parts = split_word(text, op)
        if len(parts) > 1:
            read = [input_cond(part, depth + 1) for part in parts]
            return None if any(c is None for c in read) else Conds(op, tuple(read))  # type: ignore[arg-type]
    negated = re.fullmatch(r"not\b\s*(.*)", text, re.S)
    if negated:
        inner = input_cond(negated.group(1), depth + 1)
        if inner is None or isinstance(inner, Cond):
            return inner.negated() if inner else None
        return Conds("not", (inner,))
    # get_digital_in(n): the CB-Series name of get_standard_digital_in for n 0..7 (8, 9 are the tool's)
    # get_*_digital_out(n): the output's state, read as out[n]
    m = re.fullmatch(r"get_(standard_|configurable_|)digital_(in|out)\((\d+)\)(?:(==|!=)(True|False))?",
                     text.replace(" ", ""))
    if m is None or (m.group(1) == "" and int(m.group(3)) > 7):
        return None
    on = (m.group(5) or "True") == "True"
    return Cond(int(m.group(3)) + (8 if m.group(1) == "configurable_" else 0), on != (m.group(4) == "!="),
                m.group(2) == "out")


def polled_wait(header: str, body: list[str]) -> tuple[Cond | Conds, float, int] | None:
    """(the condition waited for, the test's interval in s, the statements it spans) of a wait
    loop on digital inputs: `while TEST:` (PolyScope: `while (not(get_standard_digital_in(0) ==
    True)):`), whose body (statements without spaces, then `end`) only waits, `sync()` (one
    controller step), `sleep(T)` or both (a hand-written poll); the wait ends when TEST fails."""
    w = re.fullmatch(r"while\b(.*):", header)
    end = next((k for k in (1, 2) if k < len(body) and body[k] == "end"), 0)
    sleeps = [re.fullmatch(r"sleep\(([\d.]+(?:[eE][+-]?\d+)?)\)", t) for t in body[:end]]
    syncs = [t == "sync()" for t in body[:end]]
    seconds = [number(m.group(1)) for m in sleeps if m]
    if w is None or not end or not all(m or sync for m, sync in zip(sleeps, syncs)) or sum(syncs) > 1 or \
            len(seconds) > 1 or any(v is None or not math.isfinite(v) for v in seconds):
        return None
    looped = input_cond(w.group(1))
    if looped is None:
        return None
    cond = looped.negated() if isinstance(looped, Cond) else Conds("not", (looped,))
    return cond, (seconds[0] or 0.0) if seconds else 0.0, end + 2


def outer(text: str) -> str:
    """`text` stripped, without parentheses that enclose all of it."""
    text = text.strip()
    while text.startswith("(") and text.endswith(")") and balanced(text[1:-1]):
        text = text[1:-1].strip()
    return text


def split_word(text: str, word: str) -> list[str]:
    """`text` split at the operator `word` outside parentheses, brackets and strings."""
    parts, depth, quote, start = [], 0, False, 0
    for i, ch in enumerate(text):
        if ch == '"':
            quote = not quote
        elif quote:
            continue
        depth += (ch in "([{") - (ch in ")]}")
        if depth == 0 and text.startswith(word, i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")) \
                and not (i + len(word) < len(text) and (text[i + len(word)].isalnum() or text[i + len(word)] == "_")):
            parts.append(text[start:i])
            start = i + len(word)
    return parts + [text[start:]]


NUMBER_ASSIGN = re.compile(r"(?:global\s+|local\s+)?(\w+)\s*=\s*([-+\d.eE]+)")  # `[global] x = 0.25`
_ELEMENT_ASSIGN = re.compile(r"(?:global\s+|local\s+)?(\w+)\s*\[[^=]*\]\s*=(?!=)")  # `offset[2] = e`
ANY_ASSIGN = re.compile(r"(?:global\s+|local\s+)?(\w+)\s*=(?!=)")  # any assignment's name


def scan_assignments(texts: list[str], heads: list[str], program: bool) -> tuple[
        dict[str, int], dict[tuple[str, str], int], set[str], dict[str, float]]:
    """Of a file's statements (and their first words): how often each name is assigned (any
    value), how often in each function's own scope (its name, "" outside functions or with
    `global`), the names assigned inside a nested block (an if, loop, function or thread
    deeper than the program's own body, counted by `end`s as PolyScope does not always
    indent; a list or pose changed element by element, `offset[2] = e`, counts as nested
    anywhere), and the number each numeric assignment sets: a move reads a variable, and a
    target is declared, only where its value is certain. `program`: the first statement is the
    program's own `def` (its body the program), not a function of a script."""
    assigned: dict[str, int] = {}
    scoped: dict[tuple[str, str], int] = {}
    nested: set[str] = set()
    constants: dict[str, float] = {}
    depth = 0
    top = 1 if program else 0
    functions: list[tuple[str, int]] = []  # the defs around the statement: (name, depth inside it)
    for text, head in zip(texts, heads):
        m = ANY_ASSIGN.match(text)
        if m:
            assigned[m.group(1)] = assigned.get(m.group(1), 0) + 1
            scope = functions[-1][0] if functions and not text.startswith("global") else ""
            scoped[(scope, m.group(1))] = scoped.get((scope, m.group(1)), 0) + 1
            if depth > top:
                nested.add(m.group(1))
        element = _ELEMENT_ASSIGN.match(text)
        if element:
            nested.add(element.group(1))
        function = re.match(r"def\s+(\w+)\s*\(", text)
        if function and (depth > 0 or not top):
            functions.append((function.group(1), depth + 1))
        if head == "end" and functions and functions[-1][1] == depth:
            functions.pop()
        literal = NUMBER_ASSIGN.fullmatch(text)
        value = number(literal.group(2)) if literal else None
        if literal and value is not None:
            constants[literal.group(1)] = value
        depth += head in ("if", "while", "for", "def", "thread")
        depth -= head == "end"
    return assigned, scoped, nested, constants


def block_end(heads: list[str], i: int) -> int:
    """The index of the `end` that closes the block opened at statement `i` (given each
    statement's first word; its ifs, loops and functions end before it), or len(heads)."""
    j, depth = i + 1, 1
    while j < len(heads):
        depth += heads[j] in ("if", "while", "for", "def", "thread")
        depth -= heads[j] == "end"
        if depth == 0:
            break
        j += 1
    return j


def statements_follow(lines: list[Line], name: str) -> bool:
    """Whether statements other than the call `name()` follow the first def's `end`: then the
    script's top-level statements are what runs (the def a function they may call)."""
    end = block_end([ln.head for ln in lines], 0)
    return any(not re.fullmatch(rf"{name}\s*\(\s*\)", x.text) for x in lines[end + 1:])


TCP_UNKNOWN = "?"  # the TCP after a block or call that may have set it: which one holds is the run time's


def functions(lines: list[Line]) -> tuple[set[str], dict[str, str | None]]:
    """The functions the lines define, and those that set a TCP when called (by a `set_tcp` of
    their own or in a function they call: the TCP is the controller's, URScript manual,
    set_tcp "Sets the active tcp offset", so a call leaves the one the function set) with the
    `set_tcp` line each ends with, None where that is not one line at its outermost level
    after every other setting."""
    heads = [ln.head for ln in lines]
    bodies = {m.group(1): (k + 1, block_end(heads, k)) for k, ln in enumerate(lines)
              for m in [re.match(r"def\s+(\w+)\s*\(", ln.text)] if m}
    setters: dict[str, str | None] = {}
    for _ in range(len(bodies) + 1):  # a function calling a setter sets the TCP too (a chain is that long at most)
        found = {name: _exit_tcp(lines[a:b], setters) for name, (a, b) in bodies.items()
                 if "set_tcp" in heads[a:b] or calls(lines[a:b], setters)}
        if found == setters:
            break
        setters = found
    return set(bodies), setters


def _exit_tcp(body: list[Line], setters: dict[str, str | None]) -> str | None:
    """The `set_tcp` line a function body ends with: the last TCP setting at its outermost
    level, where no block or call after it may set another."""
    last: str | None = None
    depth = 0
    for ln in body:
        if depth == 0 and ln.head == "set_tcp":
            last = ln.text
        elif ln.head == "set_tcp" or calls([ln], setters):
            last = None if depth > 0 else setters.get(_called(ln, setters) or "")
        depth += ln.head in ("if", "while", "for", "def", "thread")
        depth -= ln.head == "end"
    return last


def _called(line: Line, names: dict[str, str | None] | set[str]) -> str | None:
    """The last function of `names` a line (not a def) calls."""
    found = [m.group(1) for m in re.finditer(r"\b(\w+)\s*\(", line.text) if m.group(1) in names]
    return None if line.text.startswith("def ") or not found else found[-1]


def calls(lines: list[Line], names: dict[str, str | None] | set[str]) -> bool:
    """Whether a line (not a def) calls one of the functions `names`."""
    return any(_called(ln, names) is not None for ln in lines)


def tcp_after_call(line: Line, setters: dict[str, str | None], tools: dict[tuple[float, ...], ToolData]) -> str | None:
    """The tool a line leaves when it calls a function that sets a TCP: the one (`tools`: by the
    TCP's six numbers, rounded to 1e-6) whose `set_tcp(p[..])` of numbers that function ends
    with, else TCP_UNKNOWN; None where the line calls no such function."""
    name = _called(line, setters)
    if name is None:
        return None
    m = re.fullmatch(r"set_tcp\(p\[(.*)\]\)", (setters[name] or "").replace(" ", ""))
    values = [number(v) for v in m.group(1).split(",")] if m else []
    key = tuple(round(v, 6) for v in values if v is not None)
    tool = tools.get(key) if len(key) == 6 else None
    return TCP_UNKNOWN if tool is None else tool.name


def compose(func: str, a: ir.Pose, b: ir.Pose) -> ir.Pose:
    """URScript manual, module math: `pose_trans(A, B)` is B expressed in A's frame (A * B);
    `pose_add(A, B)` adds the positions and turns A's orientation by B's (R_B R_A), both in
    the base frame."""
    if func == "pose_trans":
        return a * b
    turned = ir.Pose((0.0, 0.0, 0.0), b.quaternion) * ir.Pose((0.0, 0.0, 0.0), a.quaternion)
    x, y, z = (u + v for u, v in zip(a.position, b.position))
    return ir.Pose((x, y, z), turned.quaternion)


def scoped_defs(lines: list[Line]) -> list[Line]:
    """Lines where a function defined inside another, whose name a function less deeply nested
    also has, is renamed `<enclosing>_<name>` with every call inside the enclosing function
    (URScript manual, "Scoping rules": the inner one is the enclosing function's own; rmot's
    procs share one scope, where two procs of one name are E102)."""
    found: list[tuple[int, str, int, int]] = []  # (line, name, enclosing def's line, depth)
    ends: dict[int, int] = {}
    stack: list[tuple[int, bool]] = []  # open blocks: (line, whether a def)
    for k, ln in enumerate(lines):
        if ln.head in ("if", "while", "for", "def", "thread"):
            m = re.match(r"def\s+(\w+)\s*\(", ln.text)
            if m:
                around = [j for j, is_def in stack if is_def]
                found.append((k, m.group(1), around[-1] if around else -1, len(around)))
            stack.append((k, ln.head == "def"))
        elif ln.head == "end" and stack:
            ends[stack.pop()[0]] = k
    shallowest: dict[str, int] = {}
    for _, name, _, depth in found:
        shallowest[name] = min(depth, shallowest.get(name, depth))
    taken = {name for _, name, _, _ in found}
    out = list(lines)
    for _, name, outer, depth in found:
        if depth == shallowest[name] or outer < 0:  # the outermost of a name (a name defined once) keeps it
            continue
        enclosing = re.match(r"def\s+(\w+)", lines[outer].text)
        new = f"{enclosing.group(1) if enclosing else 'local'}_{name}"
        while new in taken:
            new += "_"
        taken.add(new)
        for i in range(outer, ends.get(outer, len(out) - 1) + 1):
            out[i] = Line(re.sub(rf"\b{name}(\s*\()", rf"{new}\1", out[i].text), out[i].where)
    return out
