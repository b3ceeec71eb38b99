"""Fanuc TP numeric registers and flags read as task variables or as state set elsewhere.

A numeric register `R[i]` holds an integer or a real, a flag `F[i]` ON or OFF. Both are the
controller's data (FANUC R-30iB Operator's Manual B-83284EN, "Register instructions", "Flag
(F)"): they keep their value when a program ends, and every program, background logic and the
PLC interface may read and write them. The import reads them in `IF`, `WAIT` and assignments so
(every other use stays native, W510):

* **A task variable** (W536): a register or flag of the program that runs (the job's first) that
  this program sets, whose first mention is a constant assignment nothing can skip (at the
  program's outermost level, with no jump before it), that it sets to more than one value (a
  register or flag only ever reset, `F[5]=(OFF)` after `IF (F[5])`, is a handshake another
  program raises, as a KRL flag), and that no other program of the job mentions (rmot's procs do
  not see a task's variables): `var r11_stan_det_1: int = 0`. The value it had before the run is
  never read; another program writing it while this one runs is not seen (the warning says so).
* **State set elsewhere** (W535): a register a program tests but never sets, compared with a
  whole number of 0 or more (`IF (R[1:stan chwytaka 1]=1) THEN`): a program it calls, another
  task or the PLC sets it. It is read as the group input `gin[k]` named after the register, so
  every arm of a branch on it is planned and verified (§7); compiled back, it is that group
  input, not the register.
* **Bits set elsewhere** (W549): a flag the program tests but never sets (another program, the
  background logic or the PLC sets it), and a marker it does not assign (the background logic
  sets a marker, again and again, to the expression a program assigned it: FANUC R-30iB mixed
  logic, "Marker"), are read as the digital inputs named after them (`F[525]`, `M[3]`), as a KRL
  flag or BOOL global the program never sets is. A flag the program resets (a handshake another
  program raises) and a marker it assigns (background logic it defines) stay native.
* Nothing is read in a program that writes a register or flag through another (`R[R[1]]=`,
  `R[AR[1]]=`): any of them may change there.

A condition is read where each parenthesised level joins its terms with one of AND or OR (which
binds first when a level mixes them is not read), `!` negates, a comparison (`= <> < > <= >=`)
has a register, a group input or a number on each side, and a bool term is a digital input or
output (`DI[n]`, `DO[n]`, optionally `=ON|OFF`), a flag variable or a bit set elsewhere. An assignment's value is
one term or two joined by `+ - * /` (the TP standard form `R[i]=(value) (operator) (value)`): a
longer one would need TP's operator priorities, which the import does not assume.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable, Sequence

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally, rmot_name
from rmot.backends.readers.model import (
    Assign, Cond, Conds, GroupIn, If, Native, Stmt, VarDecl, WaitIn, Where, While, group_reads, leaves, walk,
)

__all__ = ["Registers", "plain", "negated"]

_REF = re.compile(r"\b([RF])\[(\d+)(?::([^\]]*))?\]")
_SET = re.compile(r"([RF])\[(\d+)(?::[^\]]*)?\]\s*=\s*(.+)")
_FOR = re.compile(r"FOR\s+R\[(\d+)")
_MARKER_SET = re.compile(r"M\[(\d+)\]\s*=")
_INDIRECT = re.compile(r"\b[RF]\[\s*A?R\[")
_JUMP = re.compile(r"\bJMP\b|TIMEOUT\s*,\s*LBL")
_COUNTER = re.compile(r"IF R\[(\d+)\]<=-?\d+,JMP LBL\[\d+\]")  # the counting loop fanuc.py reads as `for`
_MAX_PASSES = 8  # typing the variables settles in one to three passes; a file needing more gets none
_COMMENT = re.compile(r"\b([A-Z]+)\[(\d+):[^\]]*\]")
_TOKEN = re.compile(r"\s*([A-Z]+\[\d+\]|\d+\.\d*|\.\d+|\d+|ON\b|OFF\b|AND\b|OR\b|<>|<=|>=|[!()=<>+\-*/])")
_COMPARE = {"=": "==", "<>": "!=", "<": "<", ">": ">", "<=": "<=", ">=": ">="}
_MIRROR = {"<": ">", ">": "<", "<=": ">=", ">=": "<="}
_MAX_TOKENS = 200

_Key = tuple[str, int]  # ("R" | "F" | "M", index)
_Term = tuple[str, str, "Cond | GroupIn | None"]  # (rmot text or "{}", type, the I/O read it is)


def plain(text: str) -> str:
    """A TP instruction with its data comments dropped (`R[1:count]` -> `R[1]`)."""
    return _COMMENT.sub(r"\1[\2]", text)


class _Refused(Exception):
    """The expression has no rmot form here."""


class Registers:
    """The registers and flags one TP program reads as task variables or as group inputs."""

    def __init__(self, tally: Tally, instructions: Sequence[tuple[str, Where]], others: Iterable[str], main: bool,
                 taken: Iterable[str] = (), not_vars: Iterable[_Key] = ()) -> None:
        self.tally = tally
        self.not_vars = set(not_vars)
        self.taken = {t.lower() for t in taken}  # the program's other names (targets, tools, frames)
        self.texts = [(plain(t), w) for t, w in instructions if not t.startswith(("!", "//"))]
        self.labels: dict[_Key, str] = {}
        for text, _ in instructions:
            for kind, n, label in _REF.findall(text):
                if label.strip():
                    self.labels.setdefault((kind, int(n)), label.strip())
        self.label_uses = Counter(self.labels.values())
        sets = self._sets()
        # a register or flag written through another (`R[R[2]]=`): any of them may change
        self.indirect = any(_INDIRECT.search(t) for t, _ in self.texts)
        tested = {k for t, _ in self.texts for k in self._mentions(t)} - set(sets)
        self.external: set[int] = set() if self.indirect else {n for kind, n in tested if kind == "R"}
        self.external_flags: set[int] = set() if self.indirect else {n for kind, n in tested if kind == "F"}
        # a marker the program assigns is background logic it defines (kept native); one it only
        # reads is another program's or the background's
        self.markers_set = {int(m.group(1)) for t, _ in self.texts for m in [_MARKER_SET.match(t)] if m}
        self.vars: dict[_Key, tuple[str, str]] = {}
        self.decls: list[VarDecl] = []
        self.warned: set[_Key] = set()
        if main and not self.indirect:
            mentioned_elsewhere = {k for text in others for k in self._mentions(plain(text))}
            self._choose_vars({k: v for k, v in sets.items() if k not in mentioned_elsewhere})

    # ---------------------------------------------------------------- which are read

    @staticmethod
    def _mentions(text: str) -> set[_Key]:
        return {(kind, int(n)) for kind, n, _ in _REF.findall(text)}

    def _sets(self) -> dict[_Key, list[tuple[int, str]]]:
        """(kind, n) -> (instruction index, value text) of every instruction setting it; a FOR
        counter and the reader's counting loop (`R[v]=R[v]+1` with `IF R[v]<=b,JMP`) with no value."""
        sets: dict[_Key, list[tuple[int, str]]] = {}
        for i, (text, _) in enumerate(self.texts):
            m = _SET.fullmatch(text)
            f = _FOR.match(text)
            if m:
                sets.setdefault((m.group(1), int(m.group(2))), []).append((i, m.group(3)))
            if f:
                sets.setdefault(("R", int(f.group(1))), []).append((i, ""))
        counters = {int(c.group(1)) for t, _ in self.texts for c in [_COUNTER.fullmatch(t)] if c}
        for (kind, n), found in sets.items():
            if kind == "R" and n in counters:
                found.append((-1, ""))  # a counting loop's counter: the reader's `for`
        return sets

    def _choose_vars(self, sets: dict[_Key, list[tuple[int, str]]]) -> None:
        first, clear = self._first_mentions()
        candidates = {k: found for k, found in sets.items() if found[0][0] == first[k] and clear[first[k]]
                      and k not in self.not_vars and self._starts_set(found)}
        types = {k: "bool" if k[0] == "F" else "int" for k in candidates}
        for _ in range(_MAX_PASSES):  # each pass drops candidates or widens types
            self.vars = {k: (self._var_name(k), types[k]) for k in candidates}
            values = {k: [self._value(k, v, fit=False) for _, v in found] for k, found in candidates.items()}
            dropped = [k for k, vs in values.items() if any(v is None for v in vs)]
            widened = [k for k, vs in values.items() if k not in dropped and types[k] == "int"
                       and any(v is not None and v[1] == "num" for v in vs)]
            for k in dropped:
                del candidates[k]
            for k in widened:
                types[k] = "num"
            if not dropped and not widened:
                break
        else:
            candidates = {}
        self.vars = {k: (self._var_name(k), types[k]) for k in candidates}
        for k, found in candidates.items():
            value = self._value(k, found[0][1])
            assert value is not None
            name, type_ = self.vars[k]
            where = self.texts[found[0][0]][1]
            self.decls.append(VarDecl(name, type_, value[0], where))
            self.tally.warn(codes.REGISTER_READ_AS_VARIABLE, f"`{self._spelled(k)}` keeps its value between runs and "
                            f"every program may write it; this program sets it before it reads it: read as the task "
                            f"variable `{name}` (another program writing it while this one runs is not seen)", where)

    def _first_mentions(self) -> tuple[dict[_Key, int], list[bool]]:
        """(each register's and flag's first instruction, whether nothing before an instruction
        can skip it: it is at the program's outermost level, with no jump before it)."""
        first: dict[_Key, int] = {}
        clear: list[bool] = []
        depth, jumped = 0, False
        for i, (text, _) in enumerate(self.texts):
            clear.append(depth == 0 and not jumped)
            for key in self._mentions(text):
                first.setdefault(key, i)
            depth += 1 if re.match(r"IF\s*\(.*\)\s*THEN$|FOR\s", text) else -1 if text in ("ENDIF", "ENDFOR") else 0
            jumped = jumped or _JUMP.search(text) is not None
        return first, clear

    @staticmethod
    def _starts_set(found: list[tuple[int, str]]) -> bool:
        """Whether the first assignment is of a constant, every one has a value (not a FOR or a
        counting loop), and they set more than one value."""
        if any(i < 0 or not v for i, v in found):
            return False
        constant = re.fullmatch(r"\(?\s*(-?\d+(?:\.\d*)?|ON|OFF)\s*\)?", found[0][1].strip())
        return constant is not None and len({re.sub(r"\s+", "", v) for _, v in found}) > 1

    def _var_name(self, key: _Key) -> str:
        """The register's comment as an rmot name where no other register or name of the program
        has it (rmot's own TP output comments each register with its variable's name), else
        `r11_comment`, `r11` without a comment."""
        label = self.labels.get(key)
        own = rmot_name(re.sub(r"[^A-Za-z0-9]", "_", label)) if label else ""
        fallback_like = re.fullmatch(r"[rf]\d+(?:_\w*)?", own.lower()) is not None  # another register's name
        if label and not fallback_like and own.lower() not in self.taken and self.label_uses[label] == 1:
            return own
        return rmot_name(re.sub(r"[^A-Za-z0-9]", "_", f"{key[0].lower()}{key[1]}" + (f"_{label}" if label else ""))).lower()

    def _spelled(self, key: _Key) -> str:
        label = self.labels.get(key)
        return f"{key[0]}[{key[1]}" + (f":{label}" if label else "") + "]"

    # ---------------------------------------------------------------- reading

    def condition(self, text: str) -> Cond | Conds | None:
        """The rmot condition of a TP condition (`(R[1]=1 AND DI[2])`, `R[3]<>0`), or None."""
        tokens = _tokens(plain(text))
        if tokens is None:
            return None
        parser = _Parser(tokens, self)
        try:
            found = parser.level()
        except (_Refused, RecursionError):
            return None
        return found if parser.i == len(tokens) else None

    def assignment(self, text: str, where: Where) -> Assign | None:
        """`R[i]=value` / `F[i]=(ON)` on a task variable, as an rmot assignment; else None."""
        m = _SET.fullmatch(plain(text))
        key = (m.group(1), int(m.group(2))) if m else None
        if m is None or key not in self.vars:
            return None
        value = self._value(key, m.group(3))
        return Assign(self.vars[key][0], value[0], where) if value is not None else None

    def _value(self, key: _Key, text: str, fit: bool = True) -> tuple[Conds, str] | None:
        """(the value as rmot logic, its type) of an assignment to `key`, where it fits the
        variable's type (with `fit`; without, whatever its type)."""
        tokens = _tokens(text)
        if tokens is None:
            return None
        parser = _Parser(tokens, self)
        try:
            if key[0] == "F":
                found = parser.level()
                value = found if isinstance(found, Conds) and found.op == "logic" else _as_logic(found)
                type_ = "bool"
            else:
                value, type_ = parser.arithmetic()
            if parser.i != len(tokens):
                return None
        except (_Refused, RecursionError):
            return None
        want = self.vars[key][1] if key in self.vars and fit else type_
        fits = type_ == want or (want == "num" and type_ == "int")
        return (value, type_) if fits else None

    def used_natively(self, body: tuple[Stmt, ...]) -> set[_Key]:
        """The variables a native line of `body` reads or writes: compiled back, the line would use
        the vendor's register while the variable is another one the backend numbers."""
        return {k for s in walk(body) if isinstance(s, Native) for k in self._mentions(plain(s.text)) if k in self.vars}

    def set_elsewhere(self, kind: str, n: int) -> bool:
        """Whether flag or marker `kind`[n] is one this program reads but never sets: another
        program, the background logic or the PLC sets it (read as an input, W549)."""
        return (kind == "F" and n in self.external_flags) or (kind == "M" and not self.indirect
                                                                and n not in self.markers_set)

    def warn_reads(self, body: tuple[Stmt, ...]) -> None:
        """W535 at the first statement of `body` (the program as read) reading each register as a
        group input, W549 at the first reading each flag or marker as an input."""
        for s in walk(body):
            value = s.cond if isinstance(s, (If, WaitIn, While)) else s.value if isinstance(s, Assign) else None
            for g in group_reads(value) if value is not None else ():
                n = re.fullmatch(r"R\[(\d+)\]", str(g.signal))
                if n is None or ("R", int(n.group(1))) in self.warned:
                    continue
                self.warned.add(("R", int(n.group(1))))
                self.tally.warn(codes.REGISTER_READ_AS_GROUP_INPUT, f"`{self._spelled(('R', int(n.group(1))))}` is a "
                                "register this program tests but never sets (a program it calls, another task or the "
                                f"PLC sets it): read as the group input `{g.signal}`, so each arm is planned and "
                                "verified; give --cell to wire it", s.where)
            for c in leaves(value) if value is not None else ():
                self._warn_bit(c, s.where)

    def _warn_bit(self, c: Cond, where: Where) -> None:
        """W549 the first time flag or marker `c` is read as an input."""
        m = re.fullmatch(r"([FM])\[(\d+)\]", str(c.signal))
        if m is None or (m.group(1), int(m.group(2))) in self.warned:
            return
        key = (m.group(1), int(m.group(2)))
        self.warned.add(key)
        what = ("a flag this program tests but never sets (another program, the background logic or the PLC sets it)"
                if key[0] == "F" else "a marker: the background logic sets it, again and again, to the expression a "
                "program assigned it")
        self.tally.warn(codes.BIT_READ_AS_INPUT, f"`{self._spelled(key)}` is {what}: read as the input `{c.signal}`, "
                        "so each arm is planned and verified; compiled back, it is that input, not the "
                        f"{'flag' if key[0] == 'F' else 'marker'}: give --cell to wire it", where)


def _tokens(text: str) -> list[str] | None:
    tokens: list[str] = []
    rest = text.strip()
    while rest:
        m = _TOKEN.match(rest)
        if m is None or len(tokens) >= _MAX_TOKENS:
            return None
        tokens.append(m.group(1))
        rest = rest[m.end():].strip()
    return tokens or None


def _numbered(text: str) -> str:
    """`{}` placeholders numbered in order (`{0}`, `{1}`): the writer fills them with the reads."""
    count = iter(range(text.count("{}")))
    return re.sub(r"\{\}", lambda _: "{%d}" % next(count), text)


def negated(c: Cond | Conds) -> Cond | Conds:
    """The condition that holds exactly when `c` does not: a comparison with the opposite
    operator, and/or by De Morgan's laws, else `not (c)`."""
    if isinstance(c, Cond):
        return c.negated()
    if c.op in ("and", "or") and all(isinstance(p, (Cond, Conds)) for p in c.parts):
        return Conds("or" if c.op == "and" else "and", tuple(negated(p) for p in c.parts))  # type: ignore[arg-type]
    compare = re.fullmatch(r"(\S+) (==|!=|<=|>=|<|>) (\S+)", c.text) if c.op == "logic" else None
    if compare is not None:
        flipped = {"==": "!=", "!=": "==", "<": ">=", ">=": "<", ">": "<=", "<=": ">"}[compare.group(2)]
        return Conds("logic", c.parts, f"{compare.group(1)} {flipped} {compare.group(3)}")
    if c.op == "logic" and re.fullmatch(r"(not )?[a-z_]\w*", c.text) and c.text not in ("on", "off"):
        return Conds("logic", c.parts, c.text[4:] if c.text.startswith("not ") else f"not {c.text}")
    return Conds("not", (c,))


def _as_logic(c: Cond | Conds) -> Conds:
    """A condition as one "logic" value (a flag variable's assignment)."""
    return Conds("logic", (c,), "{0}")


class _Parser:
    """Recursive descent over one TP condition or register value (see the module docstring)."""

    def __init__(self, tokens: list[str], regs: Registers) -> None:
        self.tokens, self.i, self.regs = tokens, 0, regs

    def peek(self, ahead: int = 0) -> str:
        return self.tokens[self.i + ahead] if self.i + ahead < len(self.tokens) else ""

    def take(self) -> str:
        if self.i >= len(self.tokens):
            raise _Refused("the expression ends early")
        self.i += 1
        return self.tokens[self.i - 1]

    def level(self) -> Cond | Conds:
        parts = [self.unary()]
        op = ""
        while self.peek() in ("AND", "OR"):
            if op not in ("", self.peek()):
                raise _Refused("AND and OR on one level")
            op = self.take()
            parts.append(self.unary())
        return parts[0] if not op else Conds(op.lower(), tuple(parts))

    def unary(self) -> Cond | Conds:
        if self.peek() == "!":
            self.take()
            return negated(self.unary())
        if self.peek() == "(" and not self._compares_after_paren():
            self.take()
            inner = self.level()
            if self.take() != ")":
                raise _Refused(")")
            return inner
        if self.peek(1) in _COMPARE and self.peek(2) not in ("ON", "OFF"):
            return self.comparison()
        return self.boolean()

    def _compares_after_paren(self) -> bool:
        """Whether a `(` opens a parenthesised value compared after its `)` (not a condition)."""
        depth, k = 0, self.i
        while k < len(self.tokens):
            depth += {"(": 1, ")": -1}.get(self.tokens[k], 0)
            if depth == 0:
                return self.tokens[k + 1] in _COMPARE if k + 1 < len(self.tokens) else False
            k += 1
        return False

    def boolean(self) -> Cond | Conds:
        token = self.take()
        if token in ("ON", "OFF"):
            return Conds("logic", (), token.lower())
        m = re.fullmatch(r"([A-Z]+)\[(\d+)\]", token)
        if m is None:
            raise _Refused("a bool term")
        on = True
        if self.peek() == "=" and self.peek(1) in ("ON", "OFF"):
            self.take()
            on = self.take() == "ON"
        kind, n = m.group(1), int(m.group(2))
        if kind in ("DI", "DO"):
            return Cond(n, on, kind == "DO")
        var = self.regs.vars.get(("F", n)) if kind == "F" else None
        if var is None and self.regs.set_elsewhere(kind, n):
            return Cond(f"{kind}[{n}]", on)
        if var is None:
            raise _Refused(f"{kind}[{n}]")
        return Conds("logic", (), var[0] if on else f"not {var[0]}")

    def comparison(self) -> Conds:
        left = self.term()
        op = self.take()
        right = self.term()
        groups = [t for t in (left, right) if t[2] is not None]
        if len(groups) == 2:
            raise _Refused("two group inputs compared")
        if groups and groups[0] is right:
            left, right, op = right, left, _MIRROR.get(op, op)
        if groups and not re.fullmatch(r"\d+|[a-z_]\w*", right[0]):
            raise _Refused("a group input compared with a fraction or a negative number")
        parts = tuple(t[2] for t in (left, right) if t[2] is not None)
        return Conds("logic", parts, _numbered(f"{left[0]} {_COMPARE[op]} {right[0]}"))

    def arithmetic(self) -> tuple[Conds, str]:
        """One term, or two joined by one of + - * /, optionally in parentheses."""
        if self.peek() == "(" and self.tokens[-1] == ")" and self.i == 0:
            self.tokens = self.tokens[1:-1]
        left = self.term()
        if self.peek() not in ("+", "-", "*", "/"):
            return Conds("logic", tuple(t for t in (left[2],) if t is not None), _numbered(left[0])), left[1]
        op = self.take()
        right = self.term()
        parts = tuple(t[2] for t in (left, right) if t[2] is not None)
        text = _numbered(f"{left[0]} {op} {right[0]}")
        type_ = "int" if left[1] == right[1] == "int" and op != "/" else "num"
        return Conds("logic", parts, text), type_

    def term(self) -> _Term:
        token = self.take()
        negative = token == "-"
        if negative:
            token = self.take()
            if not re.fullmatch(r"[\d.]+", token):
                raise _Refused("a minus before a register")
        if re.fullmatch(r"\d+", token):
            return (("-" if negative else "") + str(int(token)), "int", None)
        if re.fullmatch(r"\d+\.\d*|\.\d+", token):
            return (f"{-float(token) if negative else float(token)!r}", "num", None)
        m = re.fullmatch(r"(R|GI)\[(\d+)\]", token)
        if m is None:
            raise _Refused(token)
        n = int(m.group(2))
        if m.group(1) == "GI":
            return ("{}", "int", GroupIn(n))
        var = self.regs.vars.get(("R", n))
        if var is not None:
            return (var[0], var[1], None)
        if n in self.regs.external:
            return ("{}", "int", GroupIn(f"R[{n}]"))
        raise _Refused(f"R[{n}] is set here by a value the import does not read")
