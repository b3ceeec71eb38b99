"""ABB RAPID words apart from the RapidBackend class: reserved and predefined names,
speed and zone data, cf1/cf4/cf6/cfx and pose texts, and the helpers of its runtime
logic (types, operators, Offs, timed waits)."""

from __future__ import annotations

from collections.abc import Hashable
from typing import Any, TYPE_CHECKING

from rmot.backends import codes, runtime as _rt
from rmot.backends.base import axis_quadrant, fmt, fmt_list, position_mm
from rmot.backends.names import NameRules
from rmot.lang import ir

if TYPE_CHECKING:
    from rmot.backends.rapid import RapidBackend, RapidContext


__all__ = [
    "RESERVED", "RAPID_INSTRUCTIONS", "RAPID_FUNCTIONS", "RAPID_TYPES", "RAPID_PREDEFINED",
    "SPEEDS_MM_S", "ZONES_MM", "PREDEFINED", "RAPID_RULES", "DATA_ORDER", "EXTAX", "cfx_of",
    "num_name", "pose_text", "rapid_conf", "rapid_conf_match",
]


RESERVED = frozenset({
    "ALIAS", "AND", "BACKWARD", "CASE", "CONNECT", "CONST", "DEFAULT", "DIV", "DO", "ELSE",
    "ELSEIF", "ENDFOR", "ENDFUNC", "ENDIF", "ENDMODULE", "ENDPROC", "ENDRECORD", "ENDTEST",
    "ENDTRAP", "ENDWHILE", "ERROR", "EXIT", "FALSE", "FOR", "FROM", "FUNC", "GOTO", "IF",
    "INOUT", "LOCAL", "MOD", "MODULE", "NOSTEPIN", "NOT", "NOVIEW", "OR", "PERS", "PROC",
    "RAISE", "READONLY", "RECORD", "RETRY", "RETURN", "STEP", "SYSMODULE", "TEST", "THEN",
    "TO", "TRAP", "TRUE", "TRYNEXT", "UNDO", "VAR", "VIEWONLY", "WHILE", "WITH", "XOR",
    "MAIN", "TOOL0", "WOBJ0", "LOAD0", "VMAX", "FINE",
})


# Instructions, functions, data types and predefined data of RAPID: a module-level datum or
# routine named like one hides it in the whole module (a CONST robtarget `movel` makes every
# `MoveL` after it a reference to data: the module does not load). From ABB "Technical
# reference manual – RAPID Instructions, Functions and Data types" (3HAC050917-001, RW 6),
# chapters 1 (instructions), 2 (functions) and 3 (data types); predefined data from the
# data types' "Predefined data" sections (tool0, wobj0, load0, v*/z*, fine, vmax, ...).
RAPID_INSTRUCTIONS = frozenset({
    "ACCSET", "ACTUNIT", "ADD", "ALIASIO", "BITCLEAR", "BITSET", "BOOKERRNO", "BREAK",
    "CALLBYVAR", "CANCELLOAD", "CHECKPROGREF", "CIRPATHMODE", "CLEAR", "CLEARIOBUFF",
    "CLEARPATH", "CLEARRAWBYTES", "CLKRESET", "CLKSTART", "CLKSTOP", "CLOSE", "CLOSEDIR",
    "COMPACT", "CONFJ", "CONFL", "CONNECT", "COPYFILE", "COPYRAWBYTES", "CORRCLEAR",
    "CORRCON", "CORRDISCON", "CORRWRITE", "DEACTUNIT", "DECR", "DITHERACT", "DITHERDEACT",
    "DROPWOBJ", "EOFFSOFF", "EOFFSON", "EOFFSSET", "ERASEMODULE", "ERRLOG", "ERRRAISE",
    "ERRWRITE", "EXITCYCLE", "GETDATAVAL", "GETSYSDATA", "GETTRAPDATA", "GOTO",
    "GRIPLOAD", "IDELETE", "IDISABLE", "IENABLE", "IERROR", "INCR", "INVERTDO", "IODISABLE",
    "IOENABLE", "IPERS", "ISIGNALAI", "ISIGNALAO", "ISIGNALDI", "ISIGNALDO", "ISIGNALGI",
    "ISIGNALGO", "ISLEEP", "ITIMER", "IVARVAL", "IWATCH", "LOAD", "LOADID", "MAKEDIR",
    "MECHUNITLOAD", "MOTIONSUP", "MOVEABSJ", "MOVEC", "MOVECDO", "MOVECGO", "MOVECSYNC",
    "MOVEEXTJ", "MOVEJ", "MOVEJDO", "MOVEJGO", "MOVEJSYNC", "MOVEL", "MOVELDO", "MOVELGO",
    "MOVELSYNC", "MTOOLRTRAJ", "OPEN", "OPENDIR", "PACKDNHEADER", "PACKRAWBYTES",
    "PATHACCLIM", "PATHRESOL", "PDISPOFF", "PDISPON", "PDISPSET", "PROCCALL", "PULSEDO",
    "RAISE", "READANYBIN", "READBLOCK", "READCFGDATA", "READERRDATA", "READRAWBYTES",
    "REMOVEDIR", "REMOVEFILE", "RENAMEFILE", "RESET", "RESETPPMOVED", "RESETRETRYCOUNT",
    "RESTOPATH", "RETRY", "RETURN", "REWIND", "SAVE", "SEARCHC", "SEARCHEXTJ", "SEARCHL",
    "SENDVIAUDP", "SET", "SETAFB", "SETALLDATAVAL", "SETAO", "SETDATASEARCH", "SETDATAVAL",
    "SETDO", "SETGO", "SETSYSDATA", "SINGAREA", "SKIPWARN", "SOCKETACCEPT", "SOCKETBIND",
    "SOCKETCLOSE", "SOCKETCONNECT", "SOCKETCREATE", "SOCKETLISTEN", "SOCKETRECEIVE",
    "SOCKETSEND", "SOFTACT", "SOFTDEACT", "SPEEDREFRESH", "SPYSTART", "SPYSTOP", "STARTLOAD",
    "STARTMOVE", "STARTMOVERETRY", "STEPBWDPATH", "STOP", "STOPMOVE", "STOPMOVERESET",
    "STOREPATH", "SYNCMOVEOFF", "SYNCMOVEON", "SYNCMOVEUNDO", "SYSTEMSTOPACTION", "TEST",
    "TPERASE", "TPREADFK", "TPREADNUM", "TPSHOW", "TPWRITE", "TRIGC", "TRIGEQUIP", "TRIGINT",
    "TRIGIO", "TRIGJ", "TRIGL", "TRIGSTOPPROC", "TRYINT", "TUNERESET", "TUNESERVO",
    "UIMSGBOX", "UISHOW", "UNLOAD", "UNPACKRAWBYTES", "VELSET", "WAITAI", "WAITAO",
    "WAITDI", "WAITDO", "WAITGI", "WAITGO", "WAITLOAD", "WAITROB", "WAITSYNCTASK",
    "WAITTESTANDSET", "WAITTIME", "WAITUNTIL", "WAITWOBJ", "WARMSTART", "WORLDACCLIM",
    "WRITE", "WRITEANYBIN", "WRITEBIN", "WRITEBLOCK", "WRITECFGDATA", "WRITERAWBYTES",
    "WRITESTRBIN", "WRITEVAR", "WZBOXDEF", "WZCYLDEF", "WZDISABLE", "WZDOSET", "WZENABLE",
    "WZFREE", "WZHOMEJOINTDEF", "WZLIMJOINTDEF", "WZLIMSUP", "WZSPHDEF",
})


RAPID_FUNCTIONS = frozenset({
    "ABS", "ACOS", "AINPUT", "AND", "AOUTPUT", "ARGNAME", "ASIN", "ATAN", "ATAN2", "BITAND",
    "BITCHECK", "BITLSH", "BITNEG", "BITOR", "BITRSH", "BITXOR", "BYTETOSTR", "CALCJOINTT",
    "CALCROBT", "CALCROTAXISFRAME", "CALCROTAXFRAMEZ", "CDATE", "CJOINTT", "CLKREAD",
    "CORRREAD", "COS", "CPOS", "CROBT", "CSPEEDOVERRIDE", "CTIME", "CTOOL", "CWOBJ",
    "DECTOHEX", "DEFACCFRAME", "DEFDFRAME", "DEFFRAME", "DIM", "DINPUT", "DISTANCE", "DOT",
    "DOUTPUT", "EULERZYX", "EXP", "FILETIME", "FSSIZE", "GETMECUNITNAME", "GETNEXTMECHUNIT",
    "GETNEXTSYM", "GETSYSINFO", "GETTASKNAME", "GETTIME", "GINPUT", "GOUTPUT", "HEXTODEC",
    "ISFILE", "ISMECHUNITACTIVE", "ISPERS", "ISSTOPMOVEACT", "ISSTOPSTATEEVENT", "ISSYSID",
    "ISVAR", "MAXROBSPEED", "MIRPOS", "MODEXIST", "MODTIME", "NONMOTIONMODE", "NORIENT",
    "NUMTOSTR", "OFFS", "OPMODE", "ORIENTZYX", "ORIXMUL", "PFRESTART", "POSEINV", "POSEMULT",
    "POSEVECT", "POW", "PPMOVED", "PRESENT", "PROGMEMFREE", "RAWBYTESLEN", "READBIN",
    "READDIR", "READMOTOR", "READNUM", "READSTR", "READSTRBIN", "READVAR", "RELTOOL",
    "REMAINSPACEINBUF", "ROBOS", "ROUND", "RUNMODE", "SIN", "SOCKETGETSTATUS", "SQRT",
    "STRFIND", "STRLEN", "STRMAP", "STRMATCH", "STRMEMB", "STRORDER", "STRPART", "STRTOBYTE",
    "STRTOVAL", "TAN", "TASKRUNMEC", "TASKRUNROB", "TESTANDSET", "TESTDI", "TESTSIGNREAD",
    "TRUNC", "TYPE", "VALTOSTR", "VECTMAGN",
})


RAPID_TYPES = frozenset({
    "ALIASIO", "BOOL", "BTNRES", "BUTTONDATA", "BYTE", "CAMERADEV", "CFGDOMAIN", "CLOCK",
    "CONFDATA", "CORRDESCR", "DATAPOS", "DIONUM", "DIR", "DNUM", "ERRDOMAIN", "ERRNUM",
    "ERRSTR", "ERRTYPE", "EVENT_TYPE", "EXEC_LEVEL", "EXTJOINT", "HANDLER_TYPE", "ICONDATA",
    "IDENTNO", "INTNUM", "IODEV", "IOUNIT_STATE", "JOINTTARGET", "LISTITEM", "LOADDATA",
    "LOADIDNUM", "LOADSESSION", "MECUNIT", "MOTSETDATA", "NUM", "OPNUM", "ORIENT", "PATHRECID",
    "POS", "POSE", "RAWBYTES", "RESTARTDATA", "RMQHEADER", "RMQMESSAGE", "RMQSLOT",
    "ROBJOINT", "ROBTARGET", "SHAPEDATA", "SIGNALAI", "SIGNALAO", "SIGNALDI", "SIGNALDO",
    "SIGNALGI", "SIGNALGO", "SOCKETDEV", "SOCKETSTATUS", "SPEEDDATA", "STOPPOINTDATA",
    "STRING", "STRINGDIG", "SYMNUM", "SYNCIDENT", "SYSTEMDATA", "TASKID", "TASKS",
    "TESTSIGNAL", "TOOLDATA", "TPNUM", "TRAPDATA", "TRIGGDATA", "TUNETYPE", "UISHOWNUM",
    "WOBJDATA", "WZSTATIONARY", "WZTEMPORARY", "ZONEDATA",
})


RAPID_PREDEFINED = frozenset({
    "TOOL0", "WOBJ0", "LOAD0", "FINE", "VMAX", "V1000", "VROT1", "VROT2", "VROT5",
    "VROT10", "VROT20", "VROT50", "VROT100", "VLIN10", "VLIN20", "VLIN50", "VLIN100",
    "VLIN200", "VLIN500", "VLIN1000", "INPOS20", "INPOS50", "INPOS100", "STOPTIME0_5",
    "STOPTIME1_0", "STOPTIME1_5", "FLLWTIME0_5", "FLLWTIME1_0", "FLLWTIME1_5", "PI",
    "DIFFSPEED", "ERRNO", "INTNO", "ROB_ID", "ROB1", "ROB2", "ROB3", "ROB4", "EOF_BIN",
    "EOF_NUM", "END_OF_LIST", "SPEED_OVR",
})


SPEEDS_MM_S = (5, 10, 20, 30, 40, 50, 60, 80, 100, 150, 200, 300, 400, 500, 600, 800,
               1000, 1500, 2000, 2500, 3000, 4000, 5000, 6000, 7000)


ZONES_MM = (0, 1, 5, 10, 15, 20, 30, 40, 50, 60, 80, 100, 150, 200)  # z0 is 0.3 mm: not exact


# the predefined speed and zone data are global: a user name may not shadow them
PREDEFINED = frozenset({f"V{s}" for s in SPEEDS_MM_S} | {f"Z{z}" for z in ZONES_MM})


RAPID_RULES = NameRules(max_len=32, reserved=RESERVED | PREDEFINED | RAPID_INSTRUCTIONS | RAPID_FUNCTIONS
                        | RAPID_TYPES | RAPID_PREDEFINED, prefix="r")


DATA_ORDER = ("speeddata", "zonedata", "jointtarget", "robtarget")


EXTAX = "[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]"


def cfx_of(branch: ir.Config) -> int:
    """ABB cfx for 6-axis serial arms (see the module docstring; rmot's FLIP is axis 5 < 0).

    ABB's confdata table (Technical reference manual, RAPID data types, confdata; quoted in
    RobotComponents' ABB kinematics and ARTE's compute_configuration): cfx 0..7 =
    4 * (wrist centre behind axis 1) + 2 * (behind the lower arm) + (axis 5 negative).
    """
    return ((4 if branch.shoulder is ir.Shoulder.BACK else 0) + (2 if branch.elbow is ir.Elbow.DOWN else 0)
            + (1 if branch.wrist is ir.Wrist.FLIP else 0))


def num_name(x: float) -> str:
    """A number as part of an identifier: 123.4 -> '123_4', 250.0 -> '250'."""
    return fmt(x, 1).rstrip("0").rstrip(".").replace(".", "_").replace("-", "m")


def pose_text(pose: ir.Pose) -> str:
    """[[x,y,z],[q1,q2,q3,q4]] in mm and a w-first quaternion."""
    return f"[[{fmt_list(position_mm(pose), 3)}],[{fmt_list(pose.quaternion, 6)}]]"


# ----------------------------------------------------------------- runtime logic
#
# Sources (ABB "Technical reference manual - RAPID Instructions, Functions and Data types",
# 3HAC050917-001, and "Technical reference manual - RAPID overview" 3HAC050947-001):
#   * VAR num / VAR bool: program data declared at module level; a VAR's initial value is set
#     only when the module is loaded or reset (RAPID overview, "Variables"), so the declaration
#     carries no value and the `var` statement assigns it where the program runs it (`:=`).
#     rmot's int is a RAPID num (num data type: integers are exact within +-8388608).
#   * FOR counter FROM a TO b DO ... ENDFOR (instruction FOR: "the loop counter is declared
#     automatically", an integer counting by 1); WHILE cond DO ... ENDWHILE; IF cond THEN ...
#     ELSE ... ENDIF; operators AND OR NOT, = <> < <= > >= (RAPID overview, "Expressions":
#     comparisons bind tighter than AND, which binds tighter than OR / XOR / NOT, so a
#     comparison stands bare inside AND/OR and every other compound operand is parenthesised).
#   * Offs(Point, XOffset, YOffset, ZOffset) (function Offs): "add an offset in the object
#     coordinate system to a robot position": the robtarget is written in the move's work
#     object (uframe = the rmot frame, oframe identity), so Offs adds exactly the in-frame step
#     that backends/loops.py found, in mm; orientation and confdata stay the robtarget's.
#   * AInput(Signal) (function AInput): the analog input's current logical value; rmot's
#     `ain[n]` is in volts, so the signal (default name ai<n>) must be configured with its
#     logical value in volts (the I/O configuration's default, logical = physical).
#   * GInput(Signal) (function GInput, RAPID Instructions, Functions and Data types): "reads
#     the value of a group of digital input signals", a signal of type GI configured as
#     several inputs, its value the unsigned integer they form, a num for up to 23 bits
#     (GInputDnum beyond, a dnum rmot does not write: a wider group is refused, E430);
#     rmot's `gin[n]` names the signal from the cell's io line (default gi<n>).
#   * WaitDI / WaitUntil ...\MaxTime:=T\TimeFlag:=flag (instructions WaitDI, WaitUntil): with
#     \TimeFlag, running out of time is not an error: the flag is TRUE and execution goes on,
#     so `IF flag THEN <timeout branch> ENDIF` follows; without \TimeFlag an unhandled
#     ERR_WAIT_MAXTIME stops the program (rmot's plain `timeout T`, base.py).
#   * stop -> EXIT (instruction EXIT: "terminate program execution. Program restart is then
#     blocked"), which ends the task; `Stop` only pauses it (execution continues at the next
#     instruction on restart), so it is not `stop`.

_RAPID_TYPES = {ir.ValueType.INT: "num", ir.ValueType.NUM: "num", ir.ValueType.BOOL: "bool"}


_RAPID_COMPARE = {ir.CompareOp.EQ: "=", ir.CompareOp.NE: "<>", ir.CompareOp.LT: "<",
                  ir.CompareOp.LE: "<=", ir.CompareOp.GT: ">", ir.CompareOp.GE: ">="}


def _offs(ctx: RapidContext, node: ir.Move, role: str, name: str) -> str:
    """`Offs(name, dx, dy, dz)` (mm, work object frame) for a target a vendor loop offsets."""
    offset = ctx.loops.offsets.get((node.uid, role))
    if offset is None:
        return name
    terms = _rt.offset_terms(offset, ctx.loops.counters, 1000.0, lambda v: _rt.trimmed(fmt(v, 6)))
    if terms == ("0", "0", "0"):
        return name
    return f"Offs({name},{','.join(terms)})"


GINPUT_BITS = 23  # GInput reads a GI signal of up to 23 bits into a num (GInputDnum beyond)


def _group(self: RapidBackend, ctx: RapidContext, g: ir.GroupInput, span: object) -> str:
    if g.bits is not None and g.bits > GINPUT_BITS:
        self.unsupported(codes.LOGIC_UNSUPPORTED, f"gin[{g.port}] must be at most {GINPUT_BITS} bits for "
                         f"GInput, a num (got {g.bits} bits)", span)  # type: ignore[arg-type]
    return f"GInput({self._signal(ctx, 'gi', g.port, g.signal, span)})"


def _dialect(self: RapidBackend, ctx: RapidContext, span: object) -> _rt.ExprDialect:
    return _rt.ExprDialect(
        true="TRUE", false="FALSE", and_="AND", or_="OR", not_="NOT ", compare=_RAPID_COMPARE,
        var=lambda v: ctx.names.name(v.name),
        digital=lambda c: (f"DInput({self._signal(ctx, 'di', c.port, c.signal, span)}) "
                           f"= {int(c.value)}"),
        analog=lambda a: f"AInput({self._signal(ctx, 'ai', a.port, a.signal, span)})",
        group=lambda g: _group(self, ctx, g, span),
        # DOutput reads the value of a digital output signal, 0 or 1 (RAPID Instructions,
        # Functions and Data types, "DOutput - Reads the value of a digital output signal")
        output=lambda o: f"DOutput({self._signal(ctx, 'do', o.port, o.signal, span)}) = 1",
        number=lambda v: _rt.trimmed(fmt(v, 6)), compare_binds_tighter=True,
    )


def _expr(self: RapidBackend, e: object, ctx: RapidContext, span: object) -> str:
    return _rt.expr_text(e, _dialect(self, ctx, span))


def _timeout_flag(self: RapidBackend, ctx: RapidContext) -> str:
    name = ctx.names.name("rmot_timeout")
    self._declare(ctx, "var", f"VAR bool {name};")
    return name


def _timed(self: RapidBackend, head: str, timeout: float | None, on_timeout: tuple[ir.Instr, ...],
           ctx: RapidContext) -> list[str]:
    if timeout is None:
        return [head + ";"]
    head += f"\\MaxTime:={fmt(timeout, 3)}"
    if not on_timeout:
        return [head + ";"]
    flag = _timeout_flag(self, ctx)
    return [f"{head}\\TimeFlag:={flag};", f"IF {flag} THEN"] + self.indent(
        self.body(on_timeout, ctx), self.INDENT) + ["ENDIF"]


def rapid_conf(q: Any, branch: ir.Config | None) -> Hashable:
    """The confdata RAPID writes for joints `q` on `branch` (cf1, cf4, cf6, cfx): a vendor
    loop's one robtarget must carry every iteration's."""
    if branch is None or None in (branch.shoulder, branch.elbow, branch.wrist):
        return None
    return (axis_quadrant(q[0]), axis_quadrant(q[3]), axis_quadrant(q[5]), cfx_of(branch))


def rapid_conf_match(first: Any, other: Any) -> bool:
    r"""The template's confdata (written once for every iteration) reaches another iteration's
    when cfx (the IK branch) is equal and cf1, cf4, cf6 differ by at most one quadrant.

    ABB's configuration monitoring (ConfJ\On / ConfL\On, the defaults) selects the branch
    by cfx and checks axes 1, 4 and 6 against the programmed quadrants, stopping when an
    axis would have to turn by more than 90 degrees to reach them (ABB Technical reference
    manual RAPID Instructions, ConfJ / ConfL; summarised in "ABB robot ConfL/ConfJ
    configuration control explained", industrialmonitordirect.com: "generates an error if
    the configuration changes by more than 90 degrees"). A neighbouring quadrant is the
    same turn of the axis (the planner's joints differ from the written quadrant by less
    than 90 degrees beyond its edge); two quadrants apart would be another turn."""
    if first is None or other is None:
        return bool(first == other)
    a, b = first, other  # (cf1, cf4, cf6, cfx)
    return bool(a[3] == b[3] and all(abs(a[i] - b[i]) <= 1 for i in range(3)))
