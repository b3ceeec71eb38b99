"""KRL globals the program itself sets and tests, read as rmot task variables (§12).

A KRL program may assign and test a scalar it does not declare: a global of the robot's
`$config.dat` (KSS 8.x Operating and Programming Instructions for System Integrators,
"Variables and declarations": a variable declared in `$config.dat` is known to every program;
it keeps its value when a program ends, as a data list's does). Such a name is a task variable
`var name: type = v` where what the program does with it is certain:
- its type is the `$config.dat` found's declaration (`DECL BOOL name`, `INT`, `REAL`), or,
  with no `$config.dat` found, BOOL where the main DEF assigns it only `TRUE` and `FALSE` and
  both (an INT and a REAL cannot be told apart from the assignments: those stay native);
- a BOOL the program only ever sets to one value (`SALIR=FALSE` after testing `IF SALIR ==
  TRUE`) is a handshake flag another program (the submit interpreter, a PLC) raises: it is
  never a task variable (the test stays native);
- no other routine of the file assigns it (rmot's procs do not see a task's variables).
Its start value is the `$config.dat`'s (else FALSE / 0); W542 at its first assignment says that
it is a global: its value at the start is what the last run or another program left (unless
the program sets it first thing), and another program's writes while this one runs are not
seen by the task variable (written back, the variable is the DEF's own `DECL`).
"""

from __future__ import annotations

import re

from rmot.backends.readers.common import rmot_name
from rmot.backends.readers.krl_text import Decl, Line, declarations, lines
from rmot.backends.readers.model import Where
from rmot.lang.record import record

__all__ = ["Global", "global_vars", "global_note", "flag_names", "FLAG", "raised_elsewhere", "raised_why"]
__all__ += ["axis_speed_loop", "counted_loop", "SETUP_FOLD", "outside_setup"]

_TYPES = ("INT", "REAL", "BOOL")
_ASSIGN = re.compile(r"(?i)^(\$FLAG\s*\[\s*\d+\s*\]|[A-Za-z_]\w*)\s*=(?!=)\s*(.+)$")
# the controller's flags (KSS 8.x System Integrators, "Flags": $FLAG[1..1024], BOOL, global, set
# by any program or an interrupt; $CYCFLAG[n], a cyclic flag the controller re-evaluates from the
# expression last assigned to it, all the time)
FLAG = re.compile(r"(?i)\$FLAG\s*\[\s*(\d+)\s*\]")
# the words that open and close KRL's blocks (KSS 8.x program flow control)
_OPENS = frozenset({"FOR", "IF", "WHILE", "LOOP", "REPEAT", "SWITCH"})
_CLOSES = frozenset({"ENDFOR", "ENDIF", "ENDWHILE", "ENDLOOP", "UNTIL", "ENDSWITCH"})
# the folds of controller set-up the import keeps as a comment (the template's INI, BASISTECH,
# USER INI, SPSMAKRO): what they assign never reaches the rmot program
SETUP_FOLD = re.compile(r"(?i)INI\b|BASISTECH|USER\s+INI|SPSMAKRO")


@record(slots=True)
class Global:
    """A `$config.dat` global or a `$FLAG[n]` (named `FLAG_n`) read as a task variable: its KRL
    type, name and declared value, its first assignment, and the path of the `$config.dat` that
    declares it (None: none found)."""

    type: str  # INT, REAL or BOOL
    name: str
    value: str | None
    where: Where
    config: str | None
    flag: bool = False


def _assignments(found: list[Line]) -> dict[str, list[tuple[str, str, Where]]]:
    """NAME -> its assignments in `found` (the name as written, the value, where), in order."""
    out: dict[str, list[tuple[str, str, Where]]] = {}
    for ln in found:
        m = _ASSIGN.match(ln.text) if ln.fold is None else None
        if m:
            name = flag_names(m.group(1))
            out.setdefault(name.upper(), []).append((name, m.group(2).strip(), ln.where))
    return out


def flag_names(text: str) -> str:
    """`text` with each `$FLAG[n]` written as the task variable's name `FLAG_n`."""
    return FLAG.sub(lambda m: f"FLAG_{int(m.group(1))}", text)


def _bool_type(values: list[str]) -> bool:
    """Whether the assigned values are TRUE and FALSE literals only, both present."""
    words = {v.upper() for v in values}
    return words == {"TRUE", "FALSE"}


def _tested(found: list[Line], key: str) -> bool:
    """Whether a condition of `found` (IF, ELSE IF, WHILE, UNTIL, WAIT FOR) names `key`."""
    word = re.compile(rf"(?i)(?<![\w$]){re.escape(key)}(?!\w)")
    return any(re.match(r"(?i)(IF|WHILE|UNTIL|WAIT\s+FOR)\b", ln.text) and word.search(flag_names(ln.text))
               for ln in found if ln.fold is None)


def global_vars(main: list[Line], others: list[Line], known: set[str],
                config: tuple[str, str] | None) -> list[Global]:
    """The globals the main DEF's lines `main` assign (never `others`, the file's other lines),
    declared neither in the program nor its .dat (`known`, upper case: their declarations,
    signals, data), whose type is certain (module docstring), in the order first assigned."""
    assigned, elsewhere = _assignments(main), _assignments(others)
    flagged = {flag_names(m.group(0)).upper() for ln in main for m in FLAG.finditer(ln.text)}
    declared: dict[str, Decl] = {}
    for d in declarations(lines(*config)) if config is not None else []:
        declared.setdefault(d.name.upper(), d)
    out: list[Global] = []
    for key, found in assigned.items():
        flag = key in flagged
        if key in known or key in elsewhere or (key in flagged and key in declared):
            continue
        values = [v for _, v, _ in found]
        decl = declared.get(key)
        if flag:
            type_ = "BOOL" if _bool_type(values) else None
        elif config is None:
            type_ = "BOOL" if _bool_type(values) and _tested(main, key) else None
        else:
            type_ = decl.type if decl is not None and decl.type in _TYPES else None
        if type_ is None or (type_ == "BOOL" and len({v.upper() for v in values}) < 2):
            continue
        value = decl.value.strip() if decl is not None and decl.value else None
        name = decl.name if decl is not None else found[0][0]
        out.append(Global(type_, name, value, found[0][2], config[0] if decl is not None and config else None, flag))
    return out


def global_note(found: Global, init: str, folded: bool) -> str:
    """W542's message for the global `found` starting at `init` (rmot text; `folded`: the program
    sets it before it reads it)."""
    name = rmot_name(found.name)
    if found.flag:
        where = "a controller flag (KSS 8.x \"Flags\": global, any program or interrupt may set it) the program sets"
        start = ("(the program sets it before it reads it)" if folded else f"starting at {init} (on the controller "
                 "it starts where the last run or another program left it)")
        return (f"`$FLAG[{name[5:]}]` is {where}: read as the task variable `{name}` {start}; another program "
                "writing it while this one runs is not seen")
    where = (f"declared in {found.config}" if found.config is not None else
             "no $config.dat found: a BOOL by its TRUE/FALSE assignments, unless it is an output SIGNAL there")
    stored = "the value the file stores" if found.value is not None else "no declaration found gives it a value"
    start = ("(the program sets it before it reads it)" if folded else
             f"starting at {init} ({stored}; on the controller it starts where the last run or another program "
             "left it)")
    return (f"`{name}` is a global of $config.dat ({where}) the program sets: read as a task variable {start}; "
            "another program (the submit interpreter, another task) writing it while this one runs is not seen"
            + ("" if found.config is not None else "; give the $config.dat beside the program to check it"))


def raised_elsewhere(found: list[Line], skip: set[str], config: tuple[str, str] | None) -> dict[str, str]:
    """NAME (or `$FLAG[n]`, upper case) -> the one value (TRUE or FALSE) the file ever assigns it,
    for the names it tests but sets only to that value (a handshake: another program raises what
    this one resets), and -> "" for a `$FLAG[n]` or a BOOL global of the `$config.dat` found that
    it tests and never sets; `skip`: the task variables, signals and declared names (upper case)."""
    assigned = _assignments(found)
    bools = {d.name.upper() for d in declarations(lines(*config)) if d.type == "BOOL"} if config else set()
    out: dict[str, str] = {}
    for key, values in assigned.items():
        words = {v.upper() for _, v, _ in values}
        if key not in skip and len(words) == 1 and words <= {"TRUE", "FALSE"} and _tested(found, values[0][0]):
            out[key] = words.pop()
    for ln in found:
        for m in FLAG.finditer(ln.text) if ln.fold is None else ():
            key = flag_names(m.group(0)).upper()
            if key not in assigned and key not in skip and re.match(r"(?i)(IF|WHILE|UNTIL|WAIT\s+FOR)\b", ln.text):
                out[key] = ""
        test = re.match(r"(?i)(?:IF|WHILE|UNTIL|WAIT\s+FOR)\b(.*)", ln.text) if ln.fold is None else None
        for name in re.findall(r"(?<![\w$])[A-Za-z_]\w*", test.group(1)) if test else []:
            if name.upper() in bools and name.upper() not in assigned and name.upper() not in skip:
                out[name.upper()] = ""
    return out


def raised_why(text: str, raised: dict[str, str]) -> str | None:
    """Why a line reading or resetting a handshake flag (`raised`, raised_elsewhere) stays native."""
    if re.search(r"(?i)\$CYCFLAG\s*\[", text):
        return ("it reads a cyclic flag ($CYCFLAG[n]: the controller re-evaluates the expression last assigned to it "
                "all the time, KSS 8.x \"Cyclic flags\"), which no rmot variable does")
    for m in re.finditer(r"(?i)\$FLAG\s*\[\s*\d+\s*\]|(?<![\w$])[A-Za-z_]\w*", text):
        key = flag_names(m.group(0)).upper()
        value = raised.get(key)
        if value is None:
            continue
        shown = m.group(0)
        what = "only sets to " + value if value else "never sets"
        return (f"`{shown}` is a global flag the program {what}: another program (the submit interpreter, a PLC, "
                "an interrupt, Ethernet KRL for $FLAG) raises it, which no rmot variable sees")
    return None


def axis_speed_loop(found: list[Line], i: int) -> tuple[str, int] | None:
    """`FOR X=1 TO 6` `$VEL_AXIS[X]=v` [`$ACC_AXIS[X]=a`] `ENDFOR` with number values (ingeniado
    saco_20_m2.src, Shangmc main.src): every axis's speed (and acceleration) v % of its maximum
    (KSS 8.x System Integrators, $VEL_AXIS/$ACC_AXIS), as rmot's own helper sets them (RMOT_PTP(v,
    a): the same loop) or `BAS(#VEL_PTP,v)` without the acceleration: that text and the index after
    ENDFOR. None where it is another loop, or X is read anywhere else in the file than its
    declaration and such loops (after the loop KRL leaves it at 7)."""
    head = re.fullmatch(r"(?i)FOR\s+(\w+)\s*=\s*1\s+TO\s+6", found[i].text)
    near = [k for k in range(i + 1, min(i + 5, len(found))) if found[k].text or found[k].fold is not None]
    end = next((n for n, k in enumerate(near) if found[k].word == "ENDFOR"), None)
    if head is None or end not in (1, 2):
        return None
    index = re.escape(head.group(1))
    values: dict[str, str] = {}
    for k in near[:end]:
        m = re.fullmatch(rf"(?i)\$(VEL|ACC)_AXIS\s*\[\s*{index}\s*\]\s*=\s*(\d+(?:\.\d*)?)", found[k].text)
        if m is None or m.group(1).upper() in values or not 0 < float(m.group(2)) <= 100:
            return None
        values[m.group(1).upper()] = m.group(2)
    word = re.compile(rf"(?i)(?<![\w$]){index}(?!\w)")
    loop_only = re.compile(rf"(?i)FOR\s+{index}\s*=.*|\$(?:VEL|ACC)_AXIS\s*\[\s*{index}\s*\]\s*=.*|(?:DECL\s+)?INT\s+[\w\s,]+")
    if "VEL" not in values or any(word.search(ln.text) and not loop_only.fullmatch(ln.text) for ln in found):
        return None
    text = f"RMOT_PTP({values['VEL']},{values['ACC']})" if "ACC" in values else f"BAS(#VEL_PTP,{values['VEL']})"
    return text, near[end] + 1


def counted_loop(found: list[Line], i: int) -> tuple[str, int, int, Where | None] | str | None:
    """How `FOR k = a TO b` at `i` reads (KSS 8.x "FOR": k = a, the body, k + 1, while k <= b):
    (k, a, the rmot loop's stop, None) where its body leaves k alone; where the body assigns k
    once, `k = k + c` (c a whole number > 0) outside its inner blocks with no GOTO or label after
    it (so it runs once in every iteration that ends; ingeniado caja_g_m1.src `PLANTA = PLANTA +
    1` inside `FOR PLANTA=1 TO 5`, which runs for 1, 3, 5), and k is read nowhere else in the body
    or after the loop: (k, a, a + the number of iterations, where that increment is: not read).
    Else the reason it stays native; None where it is not a FOR with number bounds and step 1."""
    head = re.fullmatch(r"(?i)FOR\s+(\w+)\s*=\s*(-?\d+)\s+TO\s+(-?\d+)(?:\s+STEP\s+1)?", found[i].text)
    if head is None:
        return None
    name, first, last = head.group(1), int(head.group(2)), int(head.group(3))
    word = re.compile(rf"(?i)(?<![\w$.]){re.escape(name)}(?!\w)")
    k, depth, body, sets = i + 1, 0, [], []  # the body's statements (depth, line), the assignments to k
    while k < len(found) and found[k].word != "END":
        ln = found[k]
        depth += (ln.word in _OPENS) - (ln.word in _CLOSES)
        if depth < 0:
            break
        body += [(depth, ln)] if ln.text and ln.fold is None else []
        m = _ASSIGN.match(ln.text) if ln.fold is None else None
        sets += [ln] if m and m.group(1).upper() == name.upper() else []
        k += 1
    if not sets:
        return name, first, last + 1, None
    later = []  # the routine's lines after the loop
    for ln in found[k + 1:]:
        if ln.word == "END":
            break
        later.append(ln)
    step = re.fullmatch(rf"(?i){re.escape(name)}\s*=\s*{re.escape(name)}\s*\+\s*(\d+)", sets[0].text)
    read = [ln for _, ln in body if ln is not sets[0] and word.search(ln.text)] + [
        ln for ln in later if word.search(ln.text)]
    top = (0, sets[0]) in body  # outside the body's inner blocks: it runs in every iteration that ends
    after = body[body.index((0, sets[0])) + 1:] if top else []
    jumps = [ln for _, ln in after if re.fullmatch(r"(?i)GOTO\s+\w+|\w+\s*:", ln.text)]
    if len(sets) > 1 or step is None or not top or jumps or read or int(step.group(1)) < 1:
        return f"the loop's counter `{name}` is assigned in its body (KRL then skips iterations)"
    count = (last - first) // (int(step.group(1)) + 1) + 1 if last >= first else 0
    return name, first, first + count, sets[0].where


def outside_setup(found: list[Line]) -> list[Line]:
    """`found` without the lines of its set-up folds (SETUP_FOLD), which the import does not read."""
    out: list[Line] = []
    depth = 0  # inside a set-up fold: its nesting depth
    for ln in found:
        if depth:
            depth += (ln.fold is not None) - ln.endfold
        elif ln.fold is not None and SETUP_FOLD.match(ln.fold):
            depth = 1 - ln.endfold
        else:
            out.append(ln)
    return out
