"""A Fanuc controller's saved data (`.VA` files of a backup) read beside its TP programs.

A TP program names data the controller keeps, not the program: numeric registers (`R[24]` as a
speed), position registers (`Offset,PR[17]`, `L PR[30]`) and the tool and user frames
(`UTOOL_NUM=1`). A controller backup saves them as ASCII variable files: `NUMREG.VA`
(`[*NUMREG*]$NUMREG`), `POSREG.VA` (`[*POSREG*]$POSREG`) and `SYSFRAME.VA` (`[*SYSTEM*]$MNUTOOL`,
`$MNUFRAME`). Their layout (the same in every backup seen: a section header
`[*PROG*]$NAME  Storage: ..  Access: ..  : ARRAY[..] OF ..`, then one entry per index) is the
controller's variable listing:

    [*NUMREG*]$NUMREG  Storage: SHADOW  Access: RW  : ARRAY[999] OF Numeric Reg
      [24] = 150  'speed'
    [*POSREG*]$POSREG  Storage: SHADOW  Access: RW  : ARRAY[1,100] OF Position Reg
        [1,17] =   'offset GO'
      Group: 1   Config: N U T, 0, 0, 0
      X:     0.000   Y:     0.000   Z:    50.000
      W:     0.000   P:     0.000   R:     0.000
        [1,18] =   '' Uninitialized
        [1,19] =   'Home'   Group: 1
      J1 =     0.000 deg   J2 =   -45.000 deg   ...

Only motion group 1 (the arm: the first index of a position array) is read. An entry whose
numbers are not finite, or a file with none of these sections, is E510 at its line.

The values are the controller's when the backup was taken. A register no program given writes
is read at its saved value (W543 names it once: another program or the PLC may change it
before this one runs); a register a given program writes, or any register where one is written
through another (`R[R[1]]=`), stays a run-time value.
"""

from __future__ import annotations

import math
import re

from rmot.backends.readers import codes
from rmot.backends.readers.common import NUMBER_RE, Tally
from rmot.backends.readers.model import Where
from rmot.lang.record import record

__all__ = ["Saved", "ControllerData", "Controller", "read_va", "written_registers", "empty"]

_SECTION = re.compile(r"^\s*\[\*(\w+)\*\]\$(\w+)\b")
_READ = {"NUMREG": "numreg", "POSREG": "posreg", "MNUTOOL": "utool", "MNUFRAME": "uframe"}
_SCALAR = re.compile(rf"^\s*\[(\d+)\]\s*=\s*({NUMBER_RE.pattern})\s*(?:'[^']*')?\s*$")
_ENTRY = re.compile(r"^\s*\[(\d+),(\d+)\]\s*=\s*('[^']*')?(.*)$")
_AXIS = re.compile(rf"\b([XYZWPR])\s*:\s*({NUMBER_RE.pattern})")
_JOINT = re.compile(rf"\bJ([1-9])\s*=\s*({NUMBER_RE.pattern})")
_CONFIG = re.compile(r"Config\s*:\s*([NF])\s*([UD])\s*([TB])", re.I)
MAX_ENTRIES = 100_000  # no controller holds more registers; a file naming more is refused


@record(slots=True)
class Saved:
    """One saved position: X Y Z (mm) W P R (deg) with its configuration string, or joints (deg)."""

    xyzwpr: tuple[float, ...] | None
    joints: tuple[float, ...] | None
    config: str | None  # `N U T` as saved
    comment: str
    where: Where


@record(slots=True)
class ControllerData:
    """The registers and frames of the `.VA` files given (index -> value, with its place)."""

    numreg: dict[int, tuple[float, Where]]
    posreg: dict[int, Saved | None]  # None: saved as Uninitialized
    utool: dict[int, Saved]
    uframe: dict[int, Saved]


def empty() -> ControllerData:
    return ControllerData({}, {}, {}, {})


def read_va(path: str, text: str, into: ControllerData) -> None:
    """Add what `text` (one .VA file) saves to `into`; raises ImportError_ (E510) on a file that
    is not one of the variable files read here, or an entry that is not finite."""
    tally = Tally(path, text, "fanuc")
    lines = text.split("\n")
    section: str | None = None
    found = False
    entry: tuple[int, int, str, int] | None = None  # (group, index, comment, line) of the open entry
    body: list[str] = []
    for n, line in enumerate(lines, 1):
        head = _SECTION.match(line)
        if head is not None or _ENTRY.match(line) is not None:
            _close(tally, section, entry, body, into)
            entry, body = None, []
        if head is not None:
            section = _READ.get(head.group(2).upper()) if head.group(1).upper() in ("NUMREG", "POSREG", "SYSTEM") else None
            found = found or section is not None
            continue
        if section == "numreg":
            _scalar(tally, line, n, into)
        elif section is not None:
            m = _ENTRY.match(line)
            if m is not None:
                entry = (int(m.group(1)), int(m.group(2)), (m.group(3) or "''")[1:-1].strip(), n)
                body = [m.group(4)]
            elif entry is not None:
                body.append(line)
        if len(into.numreg) + len(into.posreg) > MAX_ENTRIES:
            raise tally.fail(f"a .VA file holds at most {MAX_ENTRIES} registers", Where(path, n))
    _close(tally, section, entry, body, into)
    if not found:
        raise tally.fail("a Fanuc .VA file read with TP programs saves $NUMREG, $POSREG, $MNUTOOL or $MNUFRAME "
                         "(NUMREG.VA, POSREG.VA, SYSFRAME.VA)", Where(path, 1))


def _scalar(tally: Tally, line: str, n: int, into: ControllerData) -> None:
    m = _SCALAR.match(line)
    if m is None:
        return
    value = float(m.group(2))
    if not math.isfinite(value):
        raise tally.fail(f"register R[{m.group(1)}] must be a finite number (got `{m.group(2)}`)", Where(tally.path, n))
    into.numreg[int(m.group(1))] = (value, Where(tally.path, n))


def _close(tally: Tally, section: str | None, entry: tuple[int, int, str, int] | None, body: list[str],
           into: ControllerData) -> None:
    """File the open position entry of `section` (group 1 only)."""
    if section is None or section == "numreg" or entry is None or entry[0] != 1:
        return
    group, index, comment, line = entry
    text = re.sub(r"'[^']*'", "", " ".join(body))
    where = Where(tally.path, line)
    axes = {k: float(v) for k, v in _AXIS.findall(text)}
    joints = {int(k): float(v) for k, v in _JOINT.findall(text)}
    values = list(axes.values()) + list(joints.values())
    if not all(math.isfinite(v) for v in values):
        raise tally.fail(f"position [{group},{index}] must hold finite numbers", where)
    conf = _CONFIG.search(text)
    saved: Saved | None = None
    if all(k in axes for k in "XYZWPR"):
        saved = Saved(tuple(axes[k] for k in "XYZWPR"), None, " ".join(conf.groups()).upper() if conf else None,
                      comment, where)
    elif all(k in joints for k in range(1, 7)):
        saved = Saved(None, tuple(joints[k] for k in range(1, 7)), None, comment, where)
    if section == "posreg":
        into.posreg[index] = saved  # Uninitialized (or a form not read): no value
    elif saved is not None and saved.xyzwpr is not None:
        (into.utool if section == "utool" else into.uframe)[index] = saved


# a line's own register write (`  12:  R[5:count]=..`, `PR[3,2]=..`, `FOR R[1]=..`): every part within the
# line ([ \t], never \s, and no `]` or newline inside the comment), so a long text that is no
# program (a controller's logbook saved as .LS) is scanned in linear time
_WRITE = re.compile(r"^[ \t]*(?:\d*[ \t]*:)?[ \t]*(?:FOR[ \t]+)?(PR|R)\[[ \t]*(\d+)[ \t]*(?:,[ \t]*\d+[ \t]*)?"
                    r"(?::[^\]\n]*)?\][ \t]*=", re.M)
_INDIRECT = re.compile(r"^[ \t]*(?:\d*[ \t]*:)?[ \t]*(?:FOR[ \t]+)?(?:PR|R)\[[ \t]*A?R\[", re.M)


def written_registers(programs: list[str]) -> tuple[set[int], set[int], bool]:
    """(the R and the PR indices the TP programs' lines write, whether one writes a register
    through another: then any may change)."""
    r: set[int] = set()
    pr: set[int] = set()
    for text in programs:
        for kind, n in _WRITE.findall(text):
            (pr if kind == "PR" else r).add(int(n))
    return r, pr, any(_INDIRECT.search(t) for t in programs)


class Controller:
    """The saved data of one import and what of it a program reads as a constant: a register
    no program given writes. W543 names each register read, once per program file."""

    def __init__(self, data: ControllerData, programs: list[str]) -> None:
        self.data = data
        self.r_written, self.pr_written, self.indirect = written_registers(programs)
        self.noted: set[tuple[Tally, str]] = set()  # (a reading of a program, a register) warned

    def register(self, n: int) -> float | str:
        """R[n]'s saved value, or why it is a run-time value here."""
        why = self._run_time("R", n, self.r_written, n in self.data.numreg, "NUMREG.VA")
        if why is not None:
            return why
        return self.data.numreg[n][0]

    def position(self, n: int) -> Saved | str:
        """PR[n]'s saved position (group 1), or why it is a run-time value here."""
        why = self._run_time("PR", n, self.pr_written, n in self.data.posreg, "POSREG.VA")
        saved = self.data.posreg.get(n)
        if why is None and saved is None:
            why = f"`PR[{n}]` is saved as Uninitialized (or in a form not read) in POSREG.VA"
        return saved if why is None and saved is not None else why or ""

    def _run_time(self, kind: str, n: int, written: set[int], saved: bool, file: str) -> str | None:
        if self.indirect:
            return f"a program given writes a register through another (`R[R[i]]=`): `{kind}[{n}]` may change anywhere"
        if n in written:
            return f"`{kind}[{n}]` is set at run time by a program given"
        if not saved:
            return (f"`{kind}[{n}]` is the controller's register and no file given holds its value "
                    f"(give the backup's {file} too)")
        return None

    def note(self, tally: Tally, where: Where, kind: str, n: int) -> None:
        """W543 at `where` for the saved value of `kind`[n] a statement there was read with (once per reading)."""
        if (tally, f"{kind}[{n}]") in self.noted:
            return
        self.noted.add((tally, f"{kind}[{n}]"))
        if kind == "R":
            number, saved = self.data.numreg[n]
            value = f"{number:g}"
        else:
            position = self.data.posreg[n]
            assert position is not None
            value, saved = "(" + ", ".join(f"{v:g}" for v in position.xyzwpr or position.joints or ()) + ")", position.where
        name = f"{kind}[{n}]"
        tally.warn(codes.CONTROLLER_VALUE_READ, f"`{name}` is read at {value}, the value the controller saved "
                   f"({saved.path}:{saved.line}): no program given writes it, but another program or the PLC may "
                   "change it before this one runs", where)
