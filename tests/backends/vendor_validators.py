"""Structural validators for emitted controller files, written from the vendors' manuals and
independent of the backends (nothing here imports rmot.backends): each returns a list of
findings ("file:line: rule"), empty when the file passes. Used by test_vendor_validators.py
on every file of every example and every golden file.

Sources (the rule's comment names the section):
  [TP]   FANUC R-30iB/R-30iB Plus Controller Operator's Manual (Basic Operation),
         B-83284EN: ch. 4 "Program structure" (program header, /MN, /POS), 4.3 "Motion
         instructions" (J/L/C, speed units, FINE/CNT 0..100, "C P[i] / : P[j]" circular
         two-line form), 4.5 "Branch instructions" (LBL, JMP, CALL), comments of 32 characters.
  [URS]  Universal Robots, "The URScript Programming Language" e-Series 5.x: 1.1 "Connecting
         to URControl" / 1.3 "Numbers, variables and types" / 1.5 "Flow of control" (def,
         thread, if/elif/else, while, each closed by `end`), Module motion (movej, movel,
         movec: a, v, t, r >= 0, mode), Module interfaces (standard 0..7 / configurable 0..7
         digital I/O).
  [INF]  Yaskawa DX100/DX200 "INFORM" instruction manual and the "Job data format" of the
         offline-teaching interface (/JOB, //NAME, //POS, ///NPOS, Cxxxxx, //INST, ///DATE,
         ///ATTR, ///GROUP1, NOP ... END), MOVJ VJ 0.01..100.00, MOVL V, PL 0..8, circular
         interpolation needs three points, JUMP *label, CALL JOB:, comments 32 characters,
         job names 32 characters (YRC1000), tool files 0..63.
  [KRL]  KUKA KSS 8.x "Operating and Programming Instructions for System Integrators": 10.2
         "Programming motions" (PTP approximated with C_PTP, followed by C_DIS/C_ORI/C_VEL
         when it blends into a CP motion (KUKA mxAutomation manual, PTP); LIN/CIRC with C_DIS, C_ORI,
         C_VEL; $APO.CPTP 1..100 %), 11 "KRL syntax" (DEF ... END, DEFDAT ... ENDDAT, IF ...
         ENDIF, FOR ... ENDFOR, DECL in the .dat, names of at most 24 characters).
  [VAL3] Stäubli VAL3 Reference Manual (s7/s8): 2 "VAL3 language elements" (applications,
         programs begin..end, identifiers of at most 15 characters, if/endIf, while/endWhile,
         for/endFor), motion control (mdesc blend off/joint/Cartesian, leave/reach >= 0),
         SRS project format (.pjx programs and data, one .pgx per program).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

__all__ = ["check_fanuc", "check_inform", "check_krl", "check_urscript", "check_val3"]

NUM = r"-?\d+(?:\.\d+)?"


# --------------------------------------------------------------------------- Fanuc LS

# [TP] HandlingTool V9.40 Operator's Manual 7.3.13: a motion may end with `Offset,PR[i]`; the motion
# option ACC n (acceleration override, 0..150 %: R-30iB Operator's Manual, motion options); the
# option COORD on L and C motions (FANUC Coordinated Motion Function, Setup and Operations Manual,
# "COORD motion option": the follower group moves relative to its leader group, so the program
# needs a second motion group in DEFAULT_GROUP)
_TP_MOTION = re.compile(r"^(J|L) P\[(\d+)(?::[^\]]*)?\] (\d+%|\d+mm/sec|\d+(?:\.\d+)?sec) "
                        r"(FINE|CNT(\d+))(?: ACC(?:[0-9]|[1-9][0-9]|1[0-4][0-9]|150))?( COORD)?(?: Offset,PR\[\d+\])?$")
_TP_CIRC_HEAD = re.compile(r"^C P\[(\d+)(?::[^\]]*)?\]$")
_TP_CIRC_TAIL = re.compile(r"^:\s+P\[(\d+)(?::[^\]]*)?\] (\d+mm/sec|\d+(?:\.\d+)?sec) (FINE|CNT(\d+))( COORD)?$")


def _coord(option: str | None, text: str, where: int) -> list[tuple[int, str]]:
    """COORD needs a leader: a second motion group in DEFAULT_GROUP."""
    groups = re.search(r"DEFAULT_GROUP\t= ([1*,]+);", text)
    if option and (groups is None or groups.group(1).split(",").count("1") < 2):
        return [(where, "a COORD motion needs a leader group: DEFAULT_GROUP must have two groups or more")]
    return []


def check_fanuc(files: dict[str, str]) -> list[str]:
    """Every .ls program of one compile (file name -> text)."""
    out: list[str] = []
    programs = {name[:-3] for name in files if name.endswith(".ls")}
    for name, text in files.items():
        out += [f"{name}:{k}: {msg}" for k, msg in _fanuc_file(name[:-3], text, programs)]
    return out


def _fanuc_file(stem: str, text: str, programs: set[str]) -> list[tuple[int, str]]:
    bad: list[tuple[int, str]] = []
    lines = text.splitlines()
    sections = [k for k, line in enumerate(lines) if line.split(" ")[0] in ("/PROG", "/ATTR", "/MN", "/POS", "/END")]
    heads = [lines[k].split(" ")[0] for k in sections]
    # [TP] ch. 4: /PROG name, /ATTR, /MN, /POS, /END in this order, each once
    if heads != ["/PROG", "/ATTR", "/MN", "/POS", "/END"]:
        return [(1, f"sections must be /PROG /ATTR /MN /POS /END (got {heads})")]
    name = lines[sections[0]].split()[1]
    if name != stem or not re.fullmatch(r"[A-Z][A-Z0-9_]{0,35}", name):
        bad.append((1, f"program name must be the file name, upper case, <= 36 characters (got {name})"))
    mn = lines[sections[2] + 1:sections[3]]
    pos_text = "\n".join(lines[sections[3] + 1:sections[4]])
    line_no, labels, jumps, used_p = 0, [], [], []
    count = re.search(r"LINE_COUNT\t= (\d+);", text)
    k = 0
    while k < len(mn):
        raw, where = mn[k], sections[2] + 2 + k
        m = re.match(r"^\s*(\d+):\s\s(.*)$", raw)
        if m is None:
            bad.append((where, "a /MN line must be 'n:  instruction ;'"))
            k += 1
            continue
        line_no += 1
        if int(m.group(1)) != line_no:
            bad.append((where, f"line numbers must count 1, 2, ... (got {m.group(1)} for {line_no})"))
        body = m.group(2)
        head = _TP_CIRC_HEAD.match(body.rstrip())
        if head is not None or body.rstrip().startswith("C P["):
            # [TP] 4.3 circular: `C P[via]` (no ';') then the continuation `: P[to] speed zone ;`
            if head is None:
                bad.append((where, "a circular line must be 'C P[i]' alone, without ';'"))
            nxt = mn[k + 1].strip() if k + 1 < len(mn) else ""
            tail = _TP_CIRC_TAIL.match(nxt[:-2]) if nxt.endswith(" ;") else None
            if tail is None:
                bad.append((where + 1, "a 'C P[i]' line must be continued by ':  P[j] speed FINE|CNTn ;'"))
            else:
                used_p += [int(head.group(1)) if head else -1, int(tail.group(1))]
                bad += _zone(tail.group(4), where + 1)
                bad += _coord(tail.group(5), text, where + 1)
            k += 2
            continue
        if not body.endswith(" ;"):
            bad.append((where, "an instruction line must end with ' ;'"))
            k += 1
            continue
        instr = body[:-2]
        if instr.startswith("!"):
            if len(instr) - 1 > 32:  # [TP] comments hold 32 characters
                bad.append((where, "a comment must be at most 32 characters"))
        elif instr.startswith(("J ", "L ")):
            motion = _TP_MOTION.match(instr)
            if motion is None:
                bad.append((where, f"a J/L line must be 'J|L P[i] speed FINE|CNTn' (got {instr})"))
            else:
                used_p.append(int(motion.group(2)))
                speed = motion.group(3)
                if speed.endswith("%") and not 1 <= int(speed[:-1]) <= 100:
                    bad.append((where, "a joint speed must be 1..100 %"))
                if speed.endswith("mm/sec") and not 1 <= int(speed[:-6]) <= 2000:
                    bad.append((where, "a linear speed must be 1..2000 mm/sec"))
                bad += _zone(motion.group(5), where)
                if motion.group(6) and motion.group(1) == "J":
                    bad.append((where, "COORD must be on an L or C motion (got a J motion)"))
                bad += _coord(motion.group(6), text, where)
        elif instr.startswith(":"):
            bad.append((where, "a ':' continuation must follow a 'C P[i]' line"))
        else:
            labels += [int(n) for n in re.findall(r"^LBL\[(\d+)\]$", instr)]
            jumps += [int(n) for n in re.findall(r"(?:JMP |TIMEOUT,)LBL\[(\d+)\]", instr)]
            call = re.match(r"^CALL (\w+)$", instr)
            if call and call.group(1) not in programs:
                bad.append((where, f"CALL must name a program of the set (got {call.group(1)})"))
            num = re.match(r"^(UFRAME_NUM|UTOOL_NUM)=(\d+)$", instr)
            if num and not (0 if num.group(1) == "UFRAME_NUM" else 1) <= int(num.group(2)) <= (9 if num.group(1) == "UFRAME_NUM" else 10):
                bad.append((where, f"{num.group(1)} must be a frame the controller has (got {num.group(2)})"))
            payload = re.match(r"^PAYLOAD\[(\d+)\]$", instr)  # R-30iB: payload schedules 1..10
            if instr.startswith("PAYLOAD") and (payload is None or not 1 <= int(payload.group(1)) <= 10):
                bad.append((where, f"PAYLOAD must select a payload schedule 1..10 (got {instr})"))
        k += 1
    if count is None or int(count.group(1)) != line_no:
        bad.append((1, f"LINE_COUNT must equal the number of /MN lines ({line_no})"))
    if len(labels) != len(set(labels)) or not set(jumps) <= set(labels):
        bad.append((1, f"every jump must reach exactly one LBL (labels {labels}, jumps {jumps})"))
    defined = [int(n) for n in re.findall(r"^P\[(\d+)(?::[^\]]*)?\]\{", pos_text, re.M)]
    if defined != list(range(1, len(defined) + 1)) or sorted(set(used_p)) != defined:
        bad.append((1, f"/POS must define P[1..n], each used by /MN (defined {defined}, used {sorted(set(used_p))})"))
    for block in re.findall(r"\{(.*?)\};", pos_text, re.S):
        if not re.search(r"GP1:\s*\n\s*UF : \d+, UT : \d+,", block):
            bad.append((1, "a position must start 'GP1: UF : n, UT : m,'"))
    return bad


def _zone(cnt: str | None, where: int) -> list[tuple[int, str]]:
    if cnt is not None and not 0 <= int(cnt) <= 100:  # [TP] 4.3: CNT 0..100
        return [(where, "CNT must be 0..100")]
    return []


# --------------------------------------------------------------------------- URScript

_UR_OPEN = re.compile(r"^(def \w+\(\):|thread \w+\(\):|if .+:|while .+:)$")
_UR_MIDDLE = re.compile(r"^(elif .+:|else:)$")
_POSE = rf"p\[{NUM}(?:, {NUM}){{5}}\]"
_JOINTS = rf"\[{NUM}(?:, {NUM}){{5}}\]"
_KW = rf"a={NUM}, v={NUM}(?:, t={NUM})?, r=({NUM})"
# [URS] pose_add(p_1, p_2) (a pose expression: p_2 a translation written with loop counters) and
# get_inverse_kin(x, qnear=[6]) (joint positions for movej) are pose / joint-list expressions
_TERM = r"[\w.*+\- ()]+"
_POSE_EXPR = rf"(?:{_POSE}|pose_add\({_POSE}, p\[{_TERM}, {_TERM}, {_TERM}, 0, 0, 0\]\))"
_UR_MOVES = [re.compile(rf"^movej\({_JOINTS}, {_KW}\)$"), re.compile(rf"^movel\({_POSE_EXPR}, {_KW}\)$"),
             re.compile(rf"^movej\(get_inverse_kin\({_POSE_EXPR}, qnear={_JOINTS}\), {_KW}\)$"),
             re.compile(rf"^movec\({_POSE_EXPR}, {_POSE_EXPR}, a={NUM}, v={NUM}, r=({NUM}), mode=[01]\)$")]
# [URS] built-in functions a user `def` must not redefine (a sample of the motion and I/O modules)
_UR_BUILTINS = {"movej", "movel", "movec", "movep", "sleep", "sync", "set_tcp", "set_payload", "popup",
                "halt", "textmsg", "get_steptime", "set_standard_digital_out", "get_standard_digital_in"}


def check_urscript(name: str, text: str) -> list[str]:
    bad: list[str] = []
    lines = text.splitlines()
    stack: list[tuple[str, int]] = []
    defined: list[str] = []
    calls: list[tuple[str, int]] = []
    top_defs = []
    for k, raw in enumerate(lines, start=1):
        line = raw.strip()
        indent = len(raw) - len(raw.lstrip(" "))
        if not line or line.startswith("#"):
            continue
        if indent != 2 * len(stack) - (2 if _UR_MIDDLE.match(line) or line == "end" else 0):
            bad.append(f"{name}:{k}: indentation must follow the block depth")
        if _UR_OPEN.match(line):
            stack.append((line, k))
            d = re.match(r"^(?:def|thread) (\w+)\(\):$", line)
            if d:
                defined.append(d.group(1))
                if len(stack) == 1:
                    top_defs.append(d.group(1))
                if d.group(1) in _UR_BUILTINS:
                    bad.append(f"{name}:{k}: a def must not redefine the built-in {d.group(1)}()")
        elif _UR_MIDDLE.match(line):
            if not stack or not stack[-1][0].startswith("if "):
                bad.append(f"{name}:{k}: elif/else must be inside an if")
        elif line == "end":
            if not stack:
                bad.append(f"{name}:{k}: 'end' closes no block")
            else:
                stack.pop()
        else:
            if line.startswith(("movej(", "movel(", "movec(")):
                m = next((m for rx in _UR_MOVES if (m := rx.match(line))), None)
                if m is None:
                    bad.append(f"{name}:{k}: a motion must be movej([6]) / movel(p[6]) / movec(p[6], p[6]) "
                               "with a, v, [t], r (and mode for movec)")
                elif float(m.group(1)) < 0:
                    bad.append(f"{name}:{k}: the blend radius r must be >= 0")
            for port in re.findall(r"(?:standard|configurable)_digital_(?:out|in)\((-?\d+)", line):
                if not 0 <= int(port) <= 7:
                    bad.append(f"{name}:{k}: digital I/O numbers are 0..7 per group")
            call = re.match(r"^(?:\w+ = run )?(\w+)\(\)$", line)
            if call:
                calls.append((call.group(1), k))
    if stack:
        bad.append(f"{name}: unclosed block '{stack[-1][0]}' from line {stack[-1][1]}")
    for fn, k in calls:
        if fn not in defined[: len(defined)] and fn not in _UR_BUILTINS:
            bad.append(f"{name}:{k}: {fn}() must be defined before it is called")
    # [URS] 1.1: a script sent to the controller runs its top level: one program def, then its call
    code = [ln.strip() for ln in lines if ln.strip() and not ln.strip().startswith("#")]
    if len(top_defs) != 1 or not code or code[-1] != f"{top_defs[0]}()":
        bad.append(f"{name}: the script must define one program and end by calling it")
    return bad


# --------------------------------------------------------------------------- INFORM

def check_inform(files: dict[str, str]) -> list[str]:
    jobs = {n[:-4] for n in files if n.endswith(".JBI")}
    out: list[str] = []
    for name, text in files.items():
        out += [f"{name}:{k}: {msg}" for k, msg in _inform_job(name[:-4], text, jobs)]
    return out


def _inform_job(stem: str, text: str, jobs: set[str]) -> list[tuple[int, str]]:
    bad: list[tuple[int, str]] = []
    lines = text.splitlines()
    if lines[:1] != ["/JOB"] or len(lines) < 2 or lines[1] != f"//NAME {stem}":
        return [(1, "a job starts '/JOB', '//NAME <file name>'")]
    if not re.fullmatch(r"[A-Z0-9_]{1,32}", stem):
        bad.append((2, "a job name is at most 32 characters of A-Z, 0-9, _"))
    try:
        pos, inst = lines.index("//POS"), lines.index("//INST")
    except ValueError:
        return bad + [(1, "a job has //POS and //INST sections")]
    # [INF] job data format: ///NPOS C,BC,EC,P,BP,EX counts; position variables as `Pnnnn=`;
    # base (BC) and station (EC) positions in pulses, one integer per axis
    npos = re.fullmatch(r"///NPOS (\d+),(\d+),(\d+),(\d+),0,0", lines[pos + 1])
    cs = [(k, ln) for k, ln in enumerate(lines[pos + 2:inst], start=pos + 3) if ln.startswith("C")]
    ps = [(k, ln) for k, ln in enumerate(lines[pos + 2:inst], start=pos + 3) if ln.startswith("P")]
    axis_lines = {kind: [(k, ln) for k, ln in enumerate(lines[pos + 2:inst], start=pos + 3) if ln.startswith(kind)]
                  for kind in ("BC", "EC")}
    counts = [len(cs), len(axis_lines["BC"]), len(axis_lines["EC"]), len(ps)]
    if npos is None or [int(g) for g in npos.groups()] != counts:
        bad.append((pos + 2, f"///NPOS must count the positions, base and station positions and "
                             f"position variables ({','.join(map(str, counts))},0,0)"))
    # the data form in effect at each line: ///PULSE or ///RECTAN (the last one before it); a
    # base axis (BC) under ///RECTAN is a traveling axis in mm (NX100 specifications, target
    # position "mm for traveling axis"), a station axis (EC) is always whole pulses
    form = {k: "" for k in range(pos + 3, inst + 1)}
    for k, ln in enumerate(lines[pos + 2:inst], start=pos + 3):
        form[k] = ln[3:] if ln in ("///PULSE", "///RECTAN") else form.get(k - 1, "")
    for kind, found in axis_lines.items():
        for i, (k, ln) in enumerate(found):
            mm = kind == "BC" and form[k] == "RECTAN"
            if not re.fullmatch(rf"{kind}{i:05d}=" + (r"-?\d+\.\d{3}" if mm else r"-?\d+(,-?\d+)*"), ln):
                bad.append((k, f"{kind} positions are {kind}00000.. in order, "
                               f"{'mm with 3 decimals (///RECTAN)' if mm else 'whole pulses'} (got {ln})"))
    for k, ln in ps:
        if not re.fullmatch(r"P\d{4}=" + ",".join([NUM] * 6), ln):
            bad.append((k, f"a position variable is Pnnnn=X,Y,Z,Rx,Ry,Rz (got {ln})"))
    for i, (k, ln) in enumerate(cs):
        if not re.fullmatch(rf"C{i:05d}=" + ",".join([NUM] * 6), ln):
            bad.append((k, f"positions are C00000.. in order, each X,Y,Z,Rx,Ry,Rz (got {ln})"))
    for k, ln in enumerate(lines[pos + 2:inst], start=pos + 3):
        if ln.startswith("///"):
            m = re.fullmatch(r"///(TOOL|USER|POSTYPE|RECTAN|RCONF|PULSE)(?: (.*))?", ln)
            if m is None:
                bad.append((k, f"unknown position attribute {ln}"))
            elif m.group(1) == "TOOL" and not 0 <= int(m.group(2)) <= 63:
                bad.append((k, "tool files are 0..63"))
            elif m.group(1) == "USER" and not 1 <= int(m.group(2)) <= 63:
                bad.append((k, "user frames are 1..63"))
            elif m.group(1) == "POSTYPE" and m.group(2) not in ("ROBOT", "USER", "BASE", "PULSE"):
                bad.append((k, "POSTYPE is ROBOT, USER, BASE or PULSE"))
            elif m.group(1) == "RCONF" and not re.fullmatch(r"[01](,[01]){7}", m.group(2) or ""):
                bad.append((k, "RCONF has 8 flags of 0/1"))
    station = lines[inst + 5:inst + 6] == ["///GROUP2 ST1"]  # a station: its own control group
    head = lines[inst + 1:inst + 5] + lines[inst + 5 + station:inst + 6 + station]
    groups = {"///GROUP1 RB1": False, "///GROUP1 RB1,BS1": True}  # the robot, with its base axis
    if not (len(head) == 5 and head[0].startswith("///DATE ") and head[1].startswith("///COMM")
            and head[2].startswith("///ATTR") and head[3] in groups and head[4] == "NOP"):
        bad.append((inst + 1, "//INST is followed by ///DATE, ///COMM, ///ATTR, ///GROUP1 RB1[,BS1], [///GROUP2 ST1], NOP"))
    elif (axis_lines["BC"] and not groups[head[3]]) or (axis_lines["EC"] and not station):
        bad.append((inst + 4, "BC positions need ///GROUP1 RB1,BS1 and EC positions ///GROUP2 ST1"))
    if lines[-1] != "END":
        bad.append((len(lines), "a job ends with END"))
    body = list(enumerate(lines[inst + 6 + station:-1], start=inst + 7 + station))
    names = {f"C{i:05d}" for i in range(len(cs))} | {f"{kind}{i:05d}" for kind, found in axis_lines.items() for i in range(len(found))}
    used: set[str] = set()
    labels = [ln for _, ln in body if re.fullmatch(r"\*L\d+", ln)]
    run = 0  # consecutive MOVC lines
    for k, ln in body + [(len(lines), "END")]:
        if ln.startswith(("MOVC ", "SMOVC ")):
            run += 1
        else:
            if 0 < run < 2:
                bad.append((k - 1, "circular interpolation needs its points on consecutive MOVC lines"))
            run = 0
        if ln.startswith("'"):
            if len(ln) > 32:
                bad.append((k, "a comment is at most 32 characters"))
            continue
        for c in re.findall(r"\b(?:B|E)?C\d{5}\b", ln):
            used.add(c)
            if c not in names:
                bad.append((k, f"{c} is not a position of the job"))
        # ACC=/DEC= 20..100 % (YRC1000 INFORM manual, MOVJ/MOVL tags); a robot move with its base
        # axis (BCnnnnn when GROUP1 has BS1) and the station group's move `+MOVJ ECnnnnn VJ=v`
        # A coordinated move, the robot the slave of the station: `SMOVL|SMOVC ... +MOVJ ECnnnnn`
        # with no speed on the station's part, under ///GROUP2 ST1 (a job a DX200 saved,
        # rpiRobotics/dx200_motion_progam_exec example_inform/R1-S1-SAMPLE.JBI @ 57e6205e:
        # `SMOVL C00003 V=11.0  +MOVJ EC00003` beside `MOVL C00002 V=11.0  +MOVJ EC00002 VJ=0.78`).
        base = " BC\\d{5}" if groups.get(head[3]) else ""
        slave = ln.startswith(("SMOVL ", "SMOVC "))
        plus = r" \+MOVJ EC\d{5}" + ("" if slave else r" VJ=(?:[\d.]+)") if station else ""
        m = re.match(r"^MOV([JLC]) C\d{5}" + base + r" (VJ|V)=([\d.]+)(?: PL=(\d+))?"
                     r"(?: ACC=(?:[2-9][0-9]|100) DEC=(?:[2-9][0-9]|100))?(?: FPT)?" + plus + "$", ln[slave:])
        if ln.startswith(("MOV", "SMOV")) and (m is None or (slave and not station)):
            bad.append((k, f"a motion is '[S]MOVJ|MOVL|MOVC Cnnnnn VJ=|V= [PL=n] [FPT]', SMOVL/SMOVC with "
                           f"'+MOVJ ECnnnnn' of a ///GROUP2 ST1 station (got {ln})"))
        elif m:
            if (m.group(1) == "J") != (m.group(2) == "VJ"):
                bad.append((k, "MOVJ takes VJ=, MOVL/MOVC take V="))
            if m.group(2) == "VJ" and not 0.01 <= float(m.group(3)) <= 100.0:
                bad.append((k, "VJ is 0.01..100.00 %"))
            if m.group(2) == "V" and not 0.1 <= float(m.group(3)) <= 1500.0:
                bad.append((k, "V is 0.1..1500.0 mm/s"))
            if m.group(4) is not None and not 0 <= int(m.group(4)) <= 8:
                bad.append((k, "PL is 0..8"))
        for target in re.findall(r"JUMP (\*L\d+)", ln):
            if labels.count(target) != 1:
                bad.append((k, f"{target} must be defined once"))
        call = re.match(r"^CALL JOB:(\w+)$", ln)
        if call and call.group(1) not in jobs:
            bad.append((k, f"CALL JOB:{call.group(1)} names no job of the set"))
    bad += [(pos + 2, f"{c} is defined but no instruction uses it") for c in sorted(names - used)]
    return bad


# --------------------------------------------------------------------------- VAL3

_VAL3_NS = {"p": "http://www.staubli.com/robotics/VAL3/Project/3",
            "g": "http://www.staubli.com/robotics/VAL3/Program/2",
            "d": "http://www.staubli.com/robotics/VAL3/Data/2"}


def check_val3(files: dict[str, str]) -> list[str]:
    """One application folder: `app/app.pjx`, `app/app.dtx`, `app/<program>.pgx`."""
    bad: list[str] = []
    apps = {name.split("/")[0] for name in files}
    for app in sorted(apps):
        mine = {n.split("/", 1)[1]: t for n, t in files.items() if n.startswith(app + "/")}
        try:
            project = ET.fromstring(mine[f"{app}.pjx"])
            data = ET.fromstring(mine[f"{app}.dtx"])
        except (KeyError, ET.ParseError) as exc:
            bad.append(f"{app}: the application needs a well-formed {app}.pjx and {app}.dtx ({exc})")
            continue
        listed = {p.get("file") for p in project.iter(f"{{{_VAL3_NS['p']}}}Program")}
        present = {n for n in mine if n.endswith(".pgx")}
        if listed != present or not {"start.pgx", "stop.pgx"} <= present:
            bad.append(f"{app}: the project must list exactly its .pgx files, start and stop included")
        sizes = {d.get("name"): int(d.get("size", "0")) for d in data.iter(f"{{{_VAL3_NS['d']}}}Data")}
        for d in data.iter(f"{{{_VAL3_NS['d']}}}Data"):
            if len(d.get("name", "")) > 15:
                bad.append(f"{app}.dtx: identifier {d.get('name')} is longer than 15 characters")
            if d.get("type") == "mdesc":
                for v in d:
                    if v.get("blend") not in ("off", "joint", "Cartesian") or float(v.get("leave", "-1")) < 0 \
                            or float(v.get("reach", "-1")) < 0 or min(float(v.get(a, "0")) for a in ("accel", "vel", "decel")) <= 0:
                        bad.append(f"{app}.dtx: mdesc {v.attrib} must have blend off|joint|Cartesian, "
                                   "leave/reach >= 0 and positive accel/vel/decel")
        programs = {n[:-4] for n in present}
        for pname in sorted(present):
            try:
                root = ET.fromstring(mine[pname])
            except ET.ParseError as exc:
                bad.append(f"{app}/{pname}: not well-formed XML ({exc})")
                continue
            progs = list(root.iter(f"{{{_VAL3_NS['g']}}}Program"))
            if len(progs) != 1 or progs[0].get("name") != pname[:-4] or len(pname[:-4]) > 15:
                bad.append(f"{app}/{pname}: one Program named like its file, at most 15 characters")
                continue
            code_el = progs[0].find(f"{{{_VAL3_NS['g']}}}Code")
            code = (code_el.text or "") if code_el is not None else ""
            bad += [f"{app}/{pname}: {m}" for m in _val3_code(code, programs, sizes)]
    return bad


def _val3_code(code: str, programs: set[str], sizes: dict[str | None, int]) -> list[str]:
    bad: list[str] = []
    lines = [ln.strip() for ln in code.strip().splitlines()]
    if not lines or lines[0] != "begin" or lines[-1] != "end":
        return ["code must be 'begin' ... 'end'"]
    stack: list[str] = []
    pairs = {"if": "endIf", "while": "endWhile", "for": "endFor"}
    for ln in lines[1:-1]:
        if ln.startswith("//"):
            continue
        word = ln.split(" ")[0].split("(")[0]
        if word in pairs:
            stack.append(pairs[word])
        elif word in pairs.values():
            if not stack or stack.pop() != word:
                bad.append(f"'{word}' closes no matching block")
        elif word == "else" and (not stack or stack[-1] != "endIf"):
            bad.append("'else' outside an if")
        call = re.match(r"^call (\w+)\(\)$", ln)
        if call and call.group(1) not in programs:
            bad.append(f"call {call.group(1)}() names no program of the application")
        for array, index in re.findall(r"\b(pTarget|jTarget|mSpeed|dIn|dOut|aOut)\[(\d+)\]", ln):
            if int(index) >= sizes.get(array, 0):
                bad.append(f"{array}[{index}] is beyond the declared size {sizes.get(array, 0)}")
    if stack:
        bad.append(f"unclosed block (missing {stack[-1]})")
    return bad


# --------------------------------------------------------------------------- KRL

_KRL_SYSTEM = {"$NULLFRAME", "HOME"}


def check_krl(files: dict[str, str], *, kss_exact_ptp: bool = False) -> list[str]:
    """A module's .src and .dat (file name -> text), structural rules of [KRL]; `kss_exact_ptp`:
    the controller runs KSS >= 8.2, where a PTP may also be approximated with C_DIS."""
    bad: list[str] = []
    for name, text in files.items():
        if not name.endswith(".src"):
            continue
        stem = name[:-4]
        dat = files.get(f"{stem}.dat", "")
        declared = set(re.findall(r"^\s*DECL \w+ (\w+)=", dat, re.M))
        if not re.search(rf"^DEFDAT {re.escape(stem)}$", dat, re.M) or not dat.rstrip().endswith("ENDDAT"):
            bad.append(f"{stem}.dat: must be DEFDAT {stem} ... ENDDAT")
        lines = text.splitlines()
        defs = [m for ln in lines if (m := re.match(r"^DEF (\w+)\((.*)\)$", ln.strip()))]
        routines = {m.group(1) for m in defs}
        if not defs or defs[0].group(1) != stem:
            bad.append(f"{name}: the first DEF must be the module's name")
        stack: list[str] = []
        pairs = {"DEF": "END", "IF": "ENDIF", "FOR": "ENDFOR", "WHILE": "ENDWHILE", "LOOP": "ENDLOOP"}
        for k, raw in enumerate(lines, start=1):
            ln = raw.split(";", 1)[0].strip()
            if not ln or ln.startswith("&"):
                continue
            word = ln.split(" ")[0].split("(")[0]
            if word in pairs and not (word == "IF" and "THEN" not in ln):
                stack.append(pairs[word])
            elif word in pairs.values():
                if not stack or stack.pop() != word:
                    bad.append(f"{name}:{k}: {word} closes no matching block")
            elif word == "ELSE" and (not stack or stack[-1] != "ENDIF"):
                bad.append(f"{name}:{k}: ELSE outside an IF")
            for ident in re.findall(r"\b\w+\b", ln):
                if len(ident) > 24 and not ident.isdigit():
                    bad.append(f"{name}:{k}: identifier {ident} is longer than 24 characters")
            motion = re.match(r"^(PTP|LIN|CIRC) (\w+)(?:,(\w+))?(?: (C_\w+(?: C_\w+)?))?$", ln)
            if word in ("PTP", "LIN", "CIRC"):
                if motion is None:
                    bad.append(f"{name}:{k}: a motion is 'PTP|LIN p [C_..]' or 'CIRC aux,p [C_..]'")
                    continue
                kind, first, second, apo = motion.groups()
                if (kind == "CIRC") != (second is not None):
                    bad.append(f"{name}:{k}: CIRC takes an auxiliary and an end point, PTP/LIN one point")
                ptp_forms = ("C_PTP", "C_PTP C_DIS", "C_PTP C_ORI", "C_PTP C_VEL")  # PTP->CP: mxAutomation
                if kss_exact_ptp:  # KSS >= 8.2: PTP approximated by distance (System Integrators, "Approximate positioning")
                    ptp_forms += ("C_DIS",)
                if apo is not None and apo not in (ptp_forms if kind == "PTP" else ("C_DIS", "C_ORI", "C_VEL")):
                    bad.append(f"{name}:{k}: {kind} cannot be approximated with {apo}")
                for point in filter(None, (first, second)):
                    if point not in declared and point.upper() not in _KRL_SYSTEM:
                        bad.append(f"{name}:{k}: {point} is not declared in {stem}.dat")
            cptp = re.match(r"^\$APO\.CPTP=(\S+)$", ln)
            if cptp and not 1 <= float(cptp.group(1)) <= 100:
                bad.append(f"{name}:{k}: $APO.CPTP is 1..100 %")
            call = re.match(r"^(\w+)\((.*)\)$", ln)
            if call and word not in pairs and word not in ("PULSE", "WAIT") and call.group(1) not in routines:
                bad.append(f"{name}:{k}: {call.group(1)}() is no routine of the module")
        if stack:
            bad.append(f"{name}: unclosed block (missing {stack[-1]})")
    return bad
