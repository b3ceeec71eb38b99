"""Read Universal Robots URScript (`.script`) back into a neutral Document.

Conventions are the URScript backend's, read in reverse (Universal Robots, "The URScript
Programming Language", e-Series): poses `p[x, y, z, rx, ry, rz]` in metres and a rotation
vector (rad), always in the robot base; `movej` joints in rad, `v`/`a` in rad/s, rad/s² the
plan's leading-axis peak rates (shares of `backends.urscript.JOINT_LIMITS` on the task's first
move, which is not planned); `movel`/`movec` `v` m/s, `a` m/s², `r` the blend radius in m, `t`
a fixed duration; `pose_add(P, p[dx, dy, dz, 0, 0, 0])` a translation in the base (= `shift`);
`set_tcp` the tool (named by its TCP: matched to the cell's tools by value); standard digital
I/O 0..7, configurable 8..15, analog out volts / 10 on the 0..10 V domain; the backend's
timed wait (a `get_steptime()` counting loop, then popup + halt) is `wait until .. timeout`.
"""

from __future__ import annotations

import math
import re

from rmot.backends.readers import codes
from rmot.backends.readers.common import Tally, number, split_top
from rmot.backends.readers.model import (
    Call, Cond, For, If, Move, Pulse, SetOut, Stmt, Stop, Target, ToolData, Wait, WaitIn, Where, While, Routine,
)
from rmot.backends.readers.rapid import num_text, pose_expr
from rmot.backends.readers.urscript_logic import UrVars, timed_wait
from rmot.backends.readers.urscript_qnear import qnear_of
from rmot.backends.readers.urscript_motion import (
    DIRECTION_FUNCTION, DIRECTION_LINES, direction_target, kept_direction, move_arguments, rest_to_rest_shares, share,
)
from rmot.backends.readers.urscript_text import (
    TCP_UNKNOWN, Line, block_end, compose, functions, input_cond, installation_nodes, polled_wait, scan_assignments,
    scoped_defs, split_statements, statements_follow, strip_hash, tcp_after_call, ur_pose,
)
from rmot.backends.readers.jump_spans import exit_spans
from rmot.backends.readers.urscript_values import (
    arithmetic, base_offset, counted_loop, may_change, parameter_test, thread_assigned, tool_offset, unknown_value,
)
from rmot.backends.urscript import DEFAULT_LIMITS, JOINT_LIMITS
from rmot.lang import ir

__all__ = ["read_urscript", "ur_pose"]

DEFAULT_TCP_ACCEL = 2.0  # m/s^2: what the backend writes for rmot's default acceleration


class _Script:
    def __init__(self, path: str, text: str, model: str | None,
                 limits: tuple[tuple[float, ...], tuple[float, ...]] | None) -> None:
        self.tally = Tally(path, text, "urscript")
        self.lines: list[Line] = []
        # URCap installation nodes: (the URCap's name, where the node begins, its statements)
        self.installation: list[tuple[str, Where, list[Line]]] = []
        nodes = installation_nodes(text.split("\n"))
        for n, raw in enumerate(text.split("\n"), 1):
            code = raw.split("#")[0].strip() if '"' not in raw else strip_hash(raw).strip()
            if n in nodes and nodes[n][1] == n:
                self.installation.append((nodes[n][0], Where(path, n, len(raw) - len(raw.lstrip()) + 1), []))
            if code and not code.startswith("$"):
                indent = len(raw) - len(raw.lstrip())
                lines = self.installation[-1][2] if n in nodes else self.lines
                for offset, part in split_statements(code):
                    lines.append(Line(part, Where(path, n, indent + offset + 1)))
        self.lines = scoped_defs(self.lines)  # a function local to another, renamed where its name is taken
        self.vmax, self.amax = JOINT_LIMITS.get(model or "", DEFAULT_LIMITS)
        self.limits = limits
        self.rest_joints: tuple[float, ...] | None = None  # where the last exact-stop movej ended, deg
        self.last_target: tuple[str, ir.Pose] | None = None  # the last move's target (get_target_waypoint)
        self.resolved: dict[str, tuple[str, str | None, Target | None]] = {}  # a node's own target variable
        self.moved = False  # a move was read: the next one is not the task's first
        self.targets: dict[str, Target] = {}
        self.tools: dict[tuple[float, ...], ToolData] = {}
        self.tool: str | None = None
        self.pulses: dict[str, tuple[int, float]] = {}
        self.routines: list[Routine] = []
        self.defs: set[str] = set()
        self.direction = False  # the file holds PolyScope's Direction helper as PolyScope writes it
        self.current_domain: set[int] = set()  # analog outputs the file sets to current (mA)
        self.names: set[str] = set()
        self.parameters: dict[str, tuple[str, ...]] = {}  # a function's parameters
        self.name = self.main = "imported"
        self.enclosing = 0  # loops and sub-routine bodies around the statement being read
        self.in_sub = 0  # sub-routine bodies around the statement being read
        self.values: dict[str, float] = {}  # numeric variables as straight-line code has set them
        self.assigned: dict[str, int] = {}  # name -> how many assignments the file holds
        self.constants: dict[str, float] = {}  # name -> the number its one assignment sets
        self.scoped: dict[tuple[str, str], int] = {}  # (function or "", name) -> assignments there
        self.scope: list[str] = []  # the functions around the statement being read
        self.local_poses: dict[tuple[str, str], ir.Pose] = {}  # a function's own pose variables
        self.nested_set: set[str] = set()  # names assigned inside a loop, branch or sub-routine
        self.pose_values: dict[str, tuple[str, str | None, Target | None]] = {}  # see _remember
        self.fresh: dict[str, float | tuple[str, str | None, Target | None]] = {}  # see _remember

    # ---------------------------------------------------------------- structure

    def read(self) -> None:
        for source, where, lines in self.installation:
            self.tally.warn(codes.URCAP_INSTALLATION, f"URCap installation code ({source}): the robot's installation, "
                            "which PolyScope runs before every program; kept as a comment (a call of its functions "
                            "stays native)", where)
            for ln in lines:
                self.tally.comment(ln.text, ln.where)
        if not self.lines:
            raise self.tally.fail("a URScript program must hold statements (got an empty file)", Where(self.tally.path, 1))
        self.defs, self.tcp_setters = functions(self.lines)
        first = self.lines[0]
        m = re.fullmatch(r"def\s+(\w+)\s*\(\s*\)\s*:", first.text)
        program = m is not None and not statements_follow(self.lines, m.group(1))  # else: its top-level statements run
        self._scan_numbers(program)
        every = self.lines + [ln for _, _, node in self.installation for ln in node]
        self.threaded = thread_assigned([ln.text for ln in every], [ln.head for ln in every])
        self.logic = UrVars([ln.text for ln in self.lines], [ln.head for ln in self.lines], program, self.defs,
                            [ln.text for _, _, node in self.installation for ln in node])
        texts = [ln.text.replace(" ", "") for ln in self.lines]
        self.direction = any(tuple(texts[k:k + len(DIRECTION_FUNCTION)]) == DIRECTION_FUNCTION
                             for k, t in enumerate(texts) if t == DIRECTION_FUNCTION[0])
        library = re.match(r"(def|thread)\s+\w+\s*\(.*\)\s*:$|global\s+\w+\s*=", first.text)  # a file of functions
        if m is None and not library and not re.match(r"[\w.\[\]]+\s*(=|\()", first.text):
            raise self.tally.fail("a URScript program must start with `def name():` or a statement "
                                  f"(got `{first.text[:40]}`)", first.where)
        if m and program:
            self.name = self.main = m.group(1)
            body, _ = self._block(1, ("end",))
        else:  # a script whose top-level statements run: its defs are functions it calls
            body, _ = self._block(0, ())
        self.routines.append(Routine(self.main, (), self.logic.hoist(tuple(body)), first.where))

    def _end_of(self, i: int) -> int:
        """The index of the `end` that closes the block opened at line `i`."""
        return block_end([ln.head for ln in self.lines], i)

    def _scan_numbers(self, program: bool) -> None:
        """Which names the file assigns, how often, where (urscript_text.scan_assignments); the
        URCap installation nodes (inside the program's def, before its statements) count too."""
        lines = self.lines[:1] + [ln for _, _, node in self.installation for ln in node] + self.lines[1:]
        self.assigned, self.scoped, self.nested_set, self.constants = scan_assignments(
            [ln.text for ln in lines], [ln.head for ln in lines], program)

    def _remember(self, text: str) -> None:
        """`[global] name = VALUE` read for the statements after it: a number (RoboDK's `speed_ms =
        0.250`, then `movel(p[..],accel_mss,speed_ms,0,blend_radius_m)`) or a pose or joint list
        known here (literal, known target or variable, composition of known poses: `p_5 = p[..]`,
        `global p_5=p_5`), read where certain (`_value`, `_target`): in the program's own body
        where no nested block sets the name, or up to the next block boundary, call or thread
        start where no thread sets it (`fresh`). Any other value, or a changed element, forgets it."""
        m = re.fullmatch(r"(?:global\s+|local\s+)?(\w+)\s*(\[[^=]*\])?\s*=(?!=)\s*(.*)", text)
        if m is None:
            return
        value = self._value(m.group(3).replace(" ", "")) if m.group(2) is None else None
        pose = self._target(m.group(3).replace(" ", "")) if m.group(2) is None and value is None else None
        for known in (self.values, self.pose_values, self.fresh):
            known.pop(m.group(1), None)
        if value is not None:
            self.values[m.group(1)] = self.fresh[m.group(1)] = value
        if pose is not None and self.in_sub == 0:
            self.pose_values[m.group(1)] = pose
        if pose is not None:
            self.fresh[m.group(1)] = pose

    def _value(self, text: str) -> float | None:
        """A move argument: a number, a variable whose value at this move is certain (set once
        in the file; or, outside sub-routines, never set inside a nested block), or arithmetic
        over them (urscript_values)."""
        value = number(text)
        if value is None and not re.fullmatch(r"[A-Za-z_]\w*", text):
            return arithmetic(text, self._value)  # `0.001*t`, `-(width+gap)`, `d2r(90)`
        fresh = self.fresh.get(text)
        if isinstance(fresh, float) and text not in self.threaded:
            return fresh
        once = self.assigned.get(text, 0) == 1
        if value is None and once and text in self.constants:
            return self.constants[text]  # set once in the file: a function reading it runs after it
        if value is not None or text not in self.values:
            return value
        return self.values[text] if once or (self.in_sub == 0 and text not in self.nested_set) else None

    def _block(self, i: int, ends: tuple[str, ...]) -> tuple[list[Stmt], int]:
        """The statements from `i` to the block's end; where a block starts or ends, the joints are not known."""
        self.rest_joints, self.last_target, self.fresh = None, None, {}
        tool, head = self.tool, self.lines[i - 1].head if i > 0 else ""  # a function's body: its own
        if head in ("while", "for") and self._sets_another_tcp(i, tool):
            self.tool = TCP_UNKNOWN  # a later turn starts with the TCP the body set
        found = self.tally.nested(self.lines[min(i, len(self.lines) - 1)].where, lambda: self._block_body(i, ends))
        self.fresh, self.tool = {}, TCP_UNKNOWN if head in _RUNS_MAYBE and self.tool != tool else self.tool
        return found

    def _sets_another_tcp(self, i: int, tool: str | None) -> bool:
        """Whether the block from `i` sets a TCP other than `tool` (the backend sets the same one again at each block)."""
        sets = [re.fullmatch(r"set_tcp\(p\[(.*)\]\)", x.text.replace(" ", "")) for x in self.lines[i:block_end([x.head for x in self.lines], i - 1)]]
        keys = {tuple(round(v, 6) for v in self._numbers(m.group(1)) or [math.nan]) for m in sets if m}  # nan: unread
        return any(tool is None or k not in self.tools or self.tools[k].name != tool for k in keys)

    def _block_body(self, i: int, ends: tuple[str, ...]) -> tuple[list[Stmt], int]:
        body: list[Stmt] = []
        while i < len(self.lines):
            ln = self.lines[i]
            if ln.head in ends or (ln.text.startswith("else") and "else" in ends) or \
                    (ln.head == "elif" and "elif" in ends):
                return body, i
            stmts, i = self._statement(i)
            body += stmts
            if ln.head in ("if", "while", "for") or may_change(ln.text):
                self.fresh = {}  # a block, a call or a thread may have set any variable
            self.tool = tcp_after_call(ln, self.tcp_setters, self.tools) or self.tool
            if not all(isinstance(s, (Move, SetOut, Wait, WaitIn, Pulse)) for s in stmts):
                self.last_target = None  # a native line, a call or a block may have moved the robot
        if ends:
            raise self.tally.fail(f"missing `{ends[0]}`", self.lines[-1].where)
        return body, i

    def _statement(self, i: int) -> tuple[list[Stmt], int]:
        ln = self.lines[i]
        m = re.fullmatch(r"def\s+(\w+)\s*\(\s*\)\s*:", ln.text)
        if m:
            body, j = self._function_body(m.group(1), i)
            self.routines.append(Routine(m.group(1), (), tuple(body), ln.where))
            return [], j + 1
        params = re.fullmatch(r"def\s+(\w+)\s*\(\s*(\w+(?:\s*=\s*[^,()]+)?(?:\s*,\s*\w+(?:\s*=\s*[^,()]+)?)*)\s*\)\s*:",
                              ln.text)
        if params:  # a function with parameters: a proc; the lines that use a parameter stay native
            names = self.parameters[params.group(1)] = tuple(p.split("=")[0].strip() for p in params.group(2).split(","))
            self.tally.warn(codes.PARAMETERS_NUMBER, f"`{params.group(1)}`'s parameters ({', '.join(names)}) are "
                            "untyped in URScript: declared `number`; the lines that use them stay native but "
                            "for an `if` comparing one with a number", ln.where)
            body, j = self._function_body(params.group(1), i)
            self.routines.append(Routine(params.group(1), tuple((n, "number") for n in names), tuple(body), ln.where))
            return [], j + 1
        if re.match(r"(def|thread)\s+\w+\s*\(", ln.text):
            return self._thread(i)
        step = re.fullmatch(r"(\w+)\s*=\s*(\w+)\s*\+\s*1", ln.text)
        if step and step.group(1) == step.group(2) and step.group(1) in self.names and \
                i + 1 < len(self.lines) and self.lines[i + 1].head == "end":
            return [], i + 1  # a loop's counter step: part of the `for` read by _loop
        for pattern in (self._timed_wait, self._wait, self._loop, self._direction):
            found = pattern(i)
            if found is not None:
                self.tally.imported += 1
                return found
        if ln.head in ("if", "while"):
            return self._compound(i)
        if ln.head in ("set_payload", "set_target_payload") and not (i > 0 and self.lines[i - 1].head == "set_tcp"):
            # not the load of a tool just selected: a switch of the held load (an attach/detach)
            return [self.tally.keep(ln.text, ln.where, "a payload switch (`rmot import --cell` reads an attach or detach)")], i + 1
        if self._setting(ln.text, ln.where) or self._declare(ln):
            return [], i + 1
        self._remember(ln.text)  # for the moves that read it; the assignment is kept native
        assign = self.logic.assign(ln.text, ln.where) if self.in_sub == 0 else None
        stmt = assign or self._simple(ln)
        why = unknown_value(ln.text, self.assigned, self.parameters.get(self.scope[-1] if self.scope else "", ()),
                            lambda n: self._value(n) is not None or self._target(n) is not None) \
            if stmt is None and ln.head in ("movej", "movel", "movep", "movec") else None
        if stmt is None:
            why = why or ("a block or call before it may set the TCP (set_tcp): which one holds here is known only at run time"
                          if self.tool == TCP_UNKNOWN and (ln.head in ("movej", "movel", "movep", "movec") or
                                                           ln.head in self.defs) else None)
            return [self.tally.keep(ln.text, ln.where, why or "no rmot form")], i + 1
        self.tally.imported += 1
        return [stmt], i + 1

    def _function_body(self, name: str, i: int) -> tuple[list[Stmt], int]:
        """The body of the function defined at line `i`, read in its own scope (URScript manual,
        "Scoping rules": a variable a function assigns without `global` is its own)."""
        # its moves before a set_tcp of its own run with its caller's TCP: no tool of their own
        self.in_sub, tool, self.tool = self.in_sub + 1, self.tool, None
        self.scope.append(name)
        try:
            body, j = self._enclosed(i + 1)
            return list(exit_spans(tuple(body), self.tally, self.lines[i + 1:j])), j
        finally:
            self.scope.pop()
            self.in_sub, self.tool = self.in_sub - 1, tool  # a definition runs nothing: the TCP before it holds

    def _enclosed(self, i: int) -> tuple[list[Stmt], int]:
        """The body of a loop or of a sub-routine, up to its `end`: a `while True:` in it is not
        the program's outermost loop."""
        self.enclosing += 1
        try:
            return self._block(i, ("end",))
        finally:
            self.enclosing -= 1

    def _thread(self, i: int) -> tuple[list[Stmt], int]:
        """A thread: the backend's pulse thread (out on, sleep, out off) is remembered as a
        pulse for the `run` that starts it; any other thread is kept native."""
        ln = self.lines[i]
        j = self._end_of(i)
        name = re.match(r"(?:def|thread)\s+(\w+)", ln.text).group(1)  # type: ignore[union-attr]
        inner = [x.text.replace(" ", "") for x in self.lines[i + 1:j]]
        m = re.fullmatch(r"set_(standard|configurable)_digital_out\((\d+),True\)", inner[0]) if len(inner) == 3 else None
        s = re.fullmatch(r"sleep\(([\d.]+)\)", inner[1]) if m else None
        if m and s and inner[2] == inner[0].replace("True", "False"):
            self.pulses[name] = (int(m.group(2)) + (8 if m.group(1) == "configurable" else 0), float(s.group(1)))
            return [], j + 1
        node = kept_direction([x.text.replace(" ", "") for x in self.lines], [x.head for x in self.lines], i)
        reason, j = node if node else ("a thread runs beside the program (rmot has no concurrent thread)", j + 1)
        return [self.tally.keep(x.text, x.where, reason) for x in self.lines[i:j]], j

    def _direction(self, i: int) -> tuple[list[Stmt], int] | None:
        """PolyScope's Direction node moving "Until (distance)" right after a move whose target is
        known: a linear move to that target shifted along the direction (urscript_motion)."""
        node = direction_target(self._texts(i, DIRECTION_LINES), self.last_target, self._known_pose) \
            if self.direction else None
        if node is None:
            return None
        self.resolved["towardsPos"] = (node[0], None, Target("", node[1], None, None, Where("", 0)))
        move = self._move("movel", ["towardsPos", *node[2]], self.lines[i + 5].where)
        self.resolved.clear()
        return ([move], i + DIRECTION_LINES) if move else None

    def _texts(self, i: int, n: int) -> list[str]:
        return [ln.text.replace(" ", "") for ln in self.lines[i:i + n]]

    def _timed_wait(self, i: int) -> tuple[list[Stmt], int] | None:
        """The backend's timed wait (urscript_logic.timed_wait): popup + halt, or its else branch."""
        found = timed_wait(self._texts(i, 9))
        test = re.fullmatch(r"while\s*not\s*\((.*)\)\s*and\s*rmot_waited\s*<\s*[\d.]+\s*:", self.lines[i + 1].text) \
            if found else None
        cond = input_cond(test.group(1)) if found and test else None
        if cond is None or found is None:
            return None
        if found[1]:
            return [WaitIn(cond, found[0], self.lines[i + 1].where)], i + 9
        orelse, j = self._block(i + 6, ("end",))
        return [WaitIn(cond, found[0], self.lines[i + 1].where, tuple(orelse))], j + 1

    def _wait(self, i: int) -> tuple[list[Stmt], int] | None:
        found = polled_wait(self.lines[i].text, self._texts(i + 1, 3))
        if found is not None and found[1] > 0.0:
            self.tally.warn(codes.POLLED_WAIT, f"a wait testing its condition every {num_text(found[1])} s, read as "
                            f"`wait until`: the controller goes on up to {num_text(found[1])} s after the condition "
                            "holds", self.lines[i].where)
        return ([WaitIn(found[0], None, self.lines[i].where)], i + found[2]) if found else None

    def _loop(self, i: int) -> tuple[list[Stmt], int] | None:
        """A counted loop (urscript_values.counted_loop) as a `for`."""
        if i + 1 >= len(self.lines) or self.lines[i + 1].head != "while":
            return None  # (finding a block's end costs the file's length: only for a loop)
        inner = [ln.text.replace(" ", "") for ln in self.lines[i + 2:self._end_of(i + 1)]]
        found = counted_loop(self._texts(i, 2), inner, self._value)
        if found is None:
            return None
        saved = set(self.names)
        self.names.add(found[0])
        body, j = self._enclosed(i + 2)
        self.names = saved
        return [For(*found, tuple(body), self.lines[i + 1].where)], j + 1

    def _compound(self, i: int) -> tuple[list[Stmt], int]:
        ln = self.lines[i]
        m = re.fullmatch(r"(if|elif|while)\b\s*(.*):", ln.text)
        forever = m is not None and m.group(1) == "while" and re.fullmatch(r"\(?\s*True\s*\)?", m.group(2)) \
            and self.enclosing == 0
        logic = self.logic.condition(m.group(2)) if m and self.in_sub == 0 else \
            parameter_test(m.group(2), self.parameters.get(self.scope[-1], ())) if m and self.scope else None
        cond = _FOREVER if forever else (input_cond(m.group(2)) or logic) if m else None
        if cond is None:
            out, j, depth = [], i, 0
            while j < len(self.lines):
                depth += self.lines[j].head in ("if", "while", "def", "thread")
                depth -= self.lines[j].head == "end"
                out.append(self.tally.keep(self.lines[j].text, self.lines[j].where, f"this {ln.head} has no rmot form"))
                j += 1
                if depth <= 0:
                    break
            return out, j  # type: ignore[return-value]
        self.tally.imported += 1
        if ln.head == "while":
            body, j = self._enclosed(i + 1) if cond is not _FOREVER else self._block(i + 1, ("end",))
            if cond is _FOREVER:  # PolyScope's "Program loops forever": rmot's program is one cycle
                self.tally.warn(codes.LOOP_READ_ONCE, "`while True` is read as one cycle of the program "
                                "(the controller repeats an rmot program)", ln.where)
                return body, j + 1
            return [While(cond, tuple(body), ln.where)], j + 1
        then, j = self._block(i + 1, ("end", "else", "elif"))
        if self.lines[j].head == "elif":
            orelse, j = self._compound(j)
            return [If(cond, tuple(then), tuple(orelse), ln.where)], j
        orelse = []
        if self.lines[j].text.startswith("else"):
            orelse, j = self._block(j + 1, ("end",))
        return [If(cond, tuple(then), tuple(orelse), ln.where)], j + 1

    def _setting(self, text: str, where: Where) -> bool:
        compact = text.replace(" ", "")
        m = re.fullmatch(r"set_tcp\(p\[(.*)\]\)", compact)
        if m:
            values = self._numbers(m.group(1))
            if values is None or len(values) != 6:
                return False
            key = tuple(round(v, 6) for v in values)
            if key not in self.tools:
                self.tools[key] = ToolData(f"tcp_{len(self.tools) + 1}", ur_pose(values), 0.0, where)
            self.tool, self.last_target = self.tools[key].name, None
            return True
        m = re.fullmatch(r"set_(?:target_)?payload\(([\d.]+)(?:,.*)?\)", compact)  # set_target_payload: PolyScope 5.10+
        if m and self.tool is not None:
            key = next(k for k, t in self.tools.items() if t.name == self.tool)
            t = self.tools[key]
            self.tools[key] = ToolData(t.name, t.tcp, float(m.group(1)), t.where)
            return True
        # set_analog_outputdomain(n, 0|1): port n's output is a current (4..20 mA) or a voltage (0..10 V)
        # (URScript manual, module interfaces); at current, set_standard_analog_out stays native (volts)
        domain = re.fullmatch(r"set_analog_outputdomain\((\d+),([01])\)", compact)
        if domain and domain.group(2) == "0":
            self.current_domain.add(int(domain.group(1)))
        return domain is not None and domain.group(2) == "1"

    def _simple(self, ln: Line) -> Stmt | None:
        text, where = ln.text.replace(" ", ""), ln.where
        m = re.fullmatch(r"(movej|movel|movec|movep)\((.*)\)", text)
        if m:
            return self._move(m.group(1), split_top(m.group(2)), where)
        # set_digital_out(n, b): the deprecated name of set_standard_digital_out for n in 0..7
        # (URScript manual CB3, module interfaces); a higher n stays native. A port or a duration
        # may be a numeric variable whose value here is certain (`LED = 3`, `sleep(dwell)`).
        m = re.fullmatch(r"set_(digital|standard_digital|configurable_digital)_out\(([\w.+-]+),(True|False)\)", text)
        port = self._port(m.group(2)) if m else None
        if m and port is not None and (m.group(1) != "digital" or port <= 7):
            return SetOut(port + (8 if m.group(1) == "configurable_digital" else 0),
                          1.0 if m.group(3) == "True" else 0.0, where)
        m = re.fullmatch(r"set_standard_analog_out\(([\w.+-]+),([\w.+-]+)\)", text)
        port, share = (self._port(m.group(1)), self._value(m.group(2))) if m else (None, None)
        if port is not None and share is not None and 0.0 <= share <= 1.0 and port not in self.current_domain:
            return SetOut(port, share * 10.0, where, analog=True)
        m = re.fullmatch(r"sleep\((.+)\)", text)
        seconds = self._value(m.group(1)) if m else None
        if seconds is not None and seconds >= 0.0:
            return Wait(seconds, where)
        m = re.fullmatch(r"(?:\w+=)?run(\w+)\(\)", text)
        if m and m.group(1) in self.pulses:
            port, seconds = self.pulses[m.group(1)]
            return Pulse(port, seconds, where)
        if text == "halt":
            return Stop(where)
        m = re.fullmatch(r"(\w+)\((.*)\)", text)  # a call: its arguments numbers certain here (RoboDK's `SprayOn(1)`)
        args = [self._value(a) for a in split_top(m.group(2))] if m and m.group(2) else []
        if m and m.group(1) in self.defs and len(args) == len(self.parameters.get(m.group(1), ())) and None not in args \
                and self.tool != TCP_UNKNOWN:  # its moves without a set_tcp of their own run with the TCP here
            return Call(m.group(1), tuple(num_text(a) for a in args), where, self.tool)  # type: ignore[arg-type]
        return None

    def _port(self, text: str) -> int | None:
        """A port number: a non-negative integer, written or held by a certain variable."""
        value = self._value(text)
        return int(value) if value is not None and value >= 0 and value == int(value) else None

    def _declare(self, ln: Line) -> bool:
        """`[global] name = p[...]`, `= [j1, ..]`, or `= pose_add(A, B)` / `pose_trans(A, B)` of
        poses known here, assigned once in the file: a target."""
        m = re.fullmatch(r"(?:global\s+|local\s+)?(\w+)\s*=\s*(p?)\[(.*)\]", ln.text)
        values = self._numbers(m.group(3)) if m else None
        combined = re.fullmatch(r"(?:global\s+|local\s+)?(\w+)\s*=\s*(pose_add|pose_trans)\((.*)\)", ln.text)
        name = (m or combined).group(1) if m or combined else ""  # type: ignore[union-attr]
        scope = self.scope[-1] if self.scope and not ln.text.startswith("global") else ""
        if scope and self.assigned.get(name, 0) > 1 and self.scoped.get((scope, name)) == 1:
            # a function's own variable, assigned once there: its pose composes the moves that
            # read it in that function (the assignment itself stays native)
            local = self._combined(combined.group(2), split_top(combined.group(3))) if combined else \
                ur_pose(values) if m and m.group(2) and values is not None and len(values) == 6 else None
            if local is not None:
                self.local_poses[(scope, name)] = local
            return False
        if self.assigned.get(name, 0) != 1 or name in self.targets:
            return False
        if combined:
            pose = self._combined(combined.group(2), split_top(combined.group(3)))
            if pose is not None:
                self.targets[name] = Target(name, pose, None, None, ln.where)
            return pose is not None
        if m is None or values is None or len(values) != 6:
            return False
        if m.group(2):
            self.targets[name] = Target(name, ur_pose(values), None, None, ln.where)
        else:
            self.targets[name] = Target(name, None, tuple(math.degrees(v) for v in values), None, ln.where)
        return True

    def _known_pose(self, text: str, depth: int = 0) -> ir.Pose | None:
        """A pose known here: a function's own pose variable, or a pose `_target` reads whole."""
        local = self.local_poses.get((self.scope[-1] if self.scope else "", text.strip()))
        found = self._target(text.replace(" ", ""), depth + 1) if local is None else None
        return local if local is not None else found[2].pose if found and found[2] else None

    def _combined(self, func: str, parts: list[str], depth: int = 0) -> ir.Pose | None:
        """`pose_trans(A, B)` / `pose_add(A, B)` of two poses known here."""
        a, b = (self._known_pose(p, depth) for p in parts) if len(parts) == 2 else (None, None)
        return compose(func, a, b) if a is not None and b is not None else None

    def _target(self, text: str, depth: int = 0) -> tuple[str, str | None, Target | None] | None:
        """(rmot expression, declared name, declaration) of a URScript pose or joint list
        (nested at most 8 deep)."""
        if depth > 8:
            return None
        if text in self.resolved:
            return self.resolved[text]
        if text in self.targets:
            t = self.targets[text]
            return (t.name, t.name, t)
        fresh = self.fresh.get(text)
        if isinstance(fresh, tuple) and text not in self.threaded:
            return fresh
        if text in self.pose_values and self.in_sub == 0 and text not in self.nested_set:
            return self.pose_values[text]
        m = re.fullmatch(r"get_inverse_kin\((.*),qnear=(?:\[.*\]|\w+)\)", text)  # PolyScope: `qnear=Waypoint_q`
        if m:
            return self._target(m.group(1), depth + 1)
        m = re.fullmatch(r"(p?)\[(.*)\]", text)
        if m:
            values = self._numbers(m.group(2))
            if values is None or len(values) != 6:
                return None
            if m.group(1):
                pose = ur_pose(values)
                return (pose_expr(pose), None, Target("", pose, None, None, Where("", 0)))
            joints = tuple(math.degrees(v) for v in values)
            return (f"joints({', '.join(num_text(j) for j in joints)}) deg", None,
                    Target("", None, joints, None, Where("", 0)))
        combined = re.fullmatch(r"(pose_trans|pose_add)\((.*)\)", text)
        parts = split_top(combined.group(2)) if combined else []
        found = None if combined is None else tool_offset(parts, lambda t: self._target(t, depth + 1), lambda t: self._offset(
            t, depth + 1)) if combined.group(1) == "pose_trans" else base_offset(parts, lambda t: self._target(t, depth + 1), self.names)
        composed = self._combined(combined.group(1), parts, depth) if combined and found is None else None
        if composed is not None:  # two poses known here, composed (not a plain translation of a target)
            return (pose_expr(composed), None, Target("", composed, None, None, Where("", 0)))
        return found

    def _numbers(self, text: str) -> list[float] | None:
        """The elements of a pose or joint list: numbers, or values certain here (`_value`)."""
        values = [self._value(v) for v in split_top(text)]
        return None if any(v is None for v in values) else values  # type: ignore[return-value]

    def _offset(self, text: str, depth: int) -> list[float] | None:
        """A pose written `p[..]`, or a pose known here without rotation, as its six numbers."""
        literal = re.fullmatch(r"p\[(.*)\]", text)
        if literal:
            return self._numbers(literal.group(1))
        pose = self._known_pose(text, depth)
        return None if pose is None or pose.quaternion != (1.0, 0.0, 0.0, 0.0) else [*pose.position, 0.0, 0.0, 0.0]

    def _joint_shares(self, joints: tuple[float, ...] | None, v: float | None, a: float | None,
                      zone: float, where: Where) -> tuple[float | None, float | None]:
        """(joint speed %, joint acceleration %) of a movej, None = rmot's default 100 %. The
        backend writes the plan's leading-axis peak rates (URScript manual, movej: `a`, `v` of the
        leading axis); the task's first move is not planned, so there it writes the shares of
        JOINT_LIMITS, read back exactly. Elsewhere the shares follow from the move's joint
        displacement, known when the movej starts where an exact-stop movej ended (rest to rest
        on the joint-space line, trapezoidal: the binding joint is the one with the least limit
        per degree; a triangular profile never reaches the speed limit, which stays 100 %)."""
        start, first = self.rest_joints, not self.moved
        self.rest_joints = joints if zone == 0.0 else None
        self.moved = True
        if first and v is not None and a is not None:
            return share(v / self.vmax), share(a / self.amax)
        if v is None or a is None or joints is None or start is None or self.limits is None or zone != 0.0:
            if v is not None or a is not None:
                self.tally.warn(codes.JOINT_RATES_READ, f"movej a={a}, v={v}: the plan's leading-axis peak "
                                "rates, whose shares need the move's start; read as 100 %", where)
            return None, None
        return rest_to_rest_shares(start, joints, v, a, self.limits)

    def _move(self, func: str, args: list[str], where: Where) -> Move | None:
        kind = {"movej": "joint", "movel": "linear", "movec": "circular", "movep": "linear"}[func]
        parsed = move_arguments(func, kind, args)
        if parsed is None or self.tool == TCP_UNKNOWN:
            return None
        points, named = parsed
        found = [self._target(p) for p in points]
        values = {k: self._value(v) for k, v in named.items()}
        if any(f is None for f in found) or any(v is None for v in values.values()):
            return None
        expr, name, decl = found[-1]  # type: ignore[misc]
        v, a = values.get("v"), values.get("a")
        zone = (values.get("r") or 0.0) * 1000.0
        if kind == "joint":
            speed, accel = None, None
            jpct, jacc = self._joint_shares(decl.joints if decl else None, v, a, zone, where)
        else:
            self.rest_joints, self.moved = None, True
            speed = 1000.0 * v if v is not None else 250.0
            accel = None if a is None or a == DEFAULT_TCP_ACCEL else 1000.0 * a
            jpct, jacc = None, None
        self.last_target = (expr, decl.pose) if decl and decl.pose else None  # decl: the target's own pose
        return Move(kind, expr, name, where, via=found[0][0] if kind == "circular" else None,  # type: ignore[index]
                    speed=speed, joint_pct=jpct, zone=zone or None, time=values.get("t") or None, tool=self.tool,
                    frame="base", pose=decl.pose if decl else None, joints=decl.joints if decl else None,
                    accel=accel, joint_accel=jacc, near=qnear_of(points[-1], self._target) if kind == "joint" else None)


_FOREVER = Cond(-1, True)  # the condition of an outermost `while True:` (read as one cycle)
_RUNS_MAYBE = ("if", "elif", "else", "while", "for")  # an arm or a loop body: it may not run


def read_urscript(path: str, text: str, model: str | None,
                  limits: tuple[tuple[float, ...], tuple[float, ...]] | None = None) -> _Script:
    """Read one URScript program; raises ImportError_ (E510) when it is not one."""
    script = _Script(path, text, model, limits)
    script.read()
    return script
