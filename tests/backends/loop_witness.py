"""Independent witnesses for the emitted vendor loops: tiny interpreters, written
here from the vendors' manuals and NOT from the backends, that run an emitted RAPID module,
KRL module or URScript program's loops, offsets and routine calls, and list every Cartesian
target the program moves to, in the robot base frame, in execution order.

They understand only what the loop programs need: counted loops (RAPID FOR, KRL FOR,
URScript `v = a` + `while v <= b:` + `v = v + 1`), routine calls, the offset arithmetic
(RAPID Offs in the work object, KRL E6POS/FRAME component assignment in $BASE, URScript
pose_add in the base frame) and motion lines; IF blocks (timeout branches) are skipped, as
the plan's main timeline skips them. Arithmetic is evaluated from Python's `ast` with numbers,
names, + - * / and unary minus only (no eval).
"""

from __future__ import annotations

import ast
import math
import re
from collections.abc import Iterator

import numpy as np

Pose = tuple[np.ndarray, np.ndarray]  # (position in metres (3,), rotation matrix (3, 3))


def arith(text: str, env: dict[str, float]) -> float:
    """`text` (numbers, names of `env`, + - * /, parentheses, unary minus) as a number."""

    def ev(node: ast.AST) -> float:
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return float(node.value)
        if isinstance(node, ast.Name):
            return float(env[node.id])
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            return -ev(node.operand) if isinstance(node.op, ast.USub) else ev(node.operand)
        if isinstance(node, ast.BinOp):
            a, b = ev(node.left), ev(node.right)
            ops = {ast.Add: a + b, ast.Sub: a - b, ast.Mult: a * b}
            if isinstance(node.op, ast.Div):
                return a / b
            return ops[type(node.op)]
        raise ValueError(f"not arithmetic: {ast.dump(node)}")

    return ev(ast.parse(text.strip(), mode="eval"))


def quat_matrix(w: float, x: float, y: float, z: float) -> np.ndarray:
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def rot(axis: int, deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    if axis == 0:
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == 1:
        return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rotvec_matrix(rx: float, ry: float, rz: float) -> np.ndarray:
    """Rodrigues: UR's rotation vector (axis * angle)."""
    angle = math.sqrt(rx * rx + ry * ry + rz * rz)
    if angle < 1e-15:
        return np.eye(3)
    k = np.array([rx, ry, rz]) / angle
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def compose(a: Pose, b: Pose) -> Pose:
    return (a[0] + a[1] @ b[0], a[1] @ b[1])


def _block_end(lines: list[str], i: int, opens: re.Pattern[str], closes: re.Pattern[str]) -> int:
    """Index of the line closing the block opened at lines[i]."""
    depth = 0
    for j in range(i, len(lines)):
        if opens.match(lines[j]):
            depth += 1
        elif closes.match(lines[j]):
            depth -= 1
            if depth == 0:
                return j
    raise ValueError(f"unclosed block at line {i}: {lines[i]}")


# --------------------------------------------------------------------------- RAPID


def rapid_targets(text: str) -> list[Pose]:
    """ABB RAPID (Technical reference manual: FOR, Offs, robtarget, wobjdata, MoveJ/MoveL)."""
    lines = [ln.split("!", 1)[0].strip() for ln in text.splitlines()]
    lines = [ln for ln in lines if ln]
    num = r"[-0-9.E+]+"
    points: dict[str, Pose] = {}
    wobjs: dict[str, Pose] = {}
    for ln in lines:
        m = re.match(
            rf"CONST robtarget (\w+):=\[\[({num}),({num}),({num})\],"
            rf"\[({num}),({num}),({num}),({num})\]",
            ln,
        )
        if m:
            v = [float(g) for g in m.groups()[1:]]
            points[m.group(1)] = (np.array(v[:3]) / 1000.0, quat_matrix(*v[3:]))
        m = re.match(
            rf'TASK PERS wobjdata (\w+):=\[FALSE,TRUE,"",\[\[({num}),({num}),({num})\],'
            rf"\[({num}),({num}),({num}),({num})\]\]",
            ln,
        )
        if m:
            v = [float(g) for g in m.groups()[1:]]
            wobjs[m.group(1)] = (np.array(v[:3]) / 1000.0, quat_matrix(*v[3:]))
    procs: dict[str, list[str]] = {}
    for i, ln in enumerate(lines):
        m = re.match(r"PROC (\w+)\(\)", ln)
        if m:
            procs[m.group(1)] = lines[i + 1 : lines.index("ENDPROC", i)]
    out: list[Pose] = []
    opens, closes = re.compile(r"^(FOR|IF|WHILE) "), re.compile(r"^(ENDFOR|ENDIF|ENDWHILE)$")

    def run(body: list[str], env: dict[str, float]) -> None:
        i = 0
        while i < len(body):
            ln = body[i]
            m = re.match(r"FOR (\w+) FROM (-?\d+) TO (-?\d+) DO", ln)
            if m:
                end = _block_end(body, i, opens, closes)
                for v in range(int(m.group(2)), int(m.group(3)) + 1):
                    run(body[i + 1 : end], {**env, m.group(1): v})
                i = end + 1
                continue
            if opens.match(ln):  # IF (timeout branches) and WHILE: not on the main timeline here
                i = _block_end(body, i, opens, closes) + 1
                continue
            m = re.match(
                r"Move[JL] (Offs\((\w+),([^,]+),([^,]+),(.+?)\)|(\w+)), \w.*?(?:\\WObj:=(\w+))?;$",
                ln,
            )
            if m:
                name = m.group(2) or m.group(6)
                pos, r = points[name]
                if m.group(2):
                    pos = pos + np.array([arith(m.group(k), env) for k in (3, 4, 5)]) / 1000.0
                frame = wobjs[m.group(7)] if m.group(7) else (np.zeros(3), np.eye(3))
                out.append(compose(frame, (pos, r)))
            m = re.match(r"(\w+);$", ln)
            if m and m.group(1) in procs:
                run(procs[m.group(1)], env)
            i += 1

    run(procs["main"], {})
    return out


# --------------------------------------------------------------------------- KRL


def _krl_pose(text: str) -> Pose:
    v = dict(re.findall(r"([XYZABC]) (-?[0-9.]+)", text))
    r = (
        rot(2, float(v["A"])) @ rot(1, float(v["B"])) @ rot(0, float(v["C"]))
    )  # KSS: Rz(A) Ry(B) Rx(C)
    return np.array([float(v["X"]), float(v["Y"]), float(v["Z"])]) / 1000.0, r


def krl_targets(src: str, dat: str) -> list[Pose]:
    """KUKA KRL (KSS 8.x: FOR/ENDFOR, structure components, $BASE, PTP/LIN)."""
    data: dict[str, Pose] = {}
    for m in re.finditer(r"DECL (?:E6POS|FRAME|POS) (\w+)=\{([^}]*)\}", dat):
        data[m.group(1)] = _krl_pose(m.group(2))
    lines = [ln.split(";", 1)[0].strip() for ln in src.splitlines()]
    lines = [ln for ln in lines if ln and not ln.startswith("&")]
    routines: dict[str, list[str]] = {}
    for i, ln in enumerate(lines):
        m = re.match(r"DEF (\w+)\(", ln)
        if m:
            routines[m.group(1)] = lines[i + 1 : lines.index("END", i)]
    main = next(iter(routines))
    out: list[Pose] = []
    state = {"base": (np.zeros(3), np.eye(3))}
    work: dict[str, list[float]] = {}
    opens, closes = re.compile(r"^(FOR|IF|WHILE) "), re.compile(r"^(ENDFOR|ENDIF|ENDWHILE)$")

    def run(body: list[str], env: dict[str, float]) -> None:
        i = 0
        while i < len(body):
            ln = body[i]
            m = re.match(r"FOR (\w+)=(-?\d+) TO (-?\d+)$", ln)
            if m:
                end = _block_end(body, i, opens, closes)
                for v in range(int(m.group(2)), int(m.group(3)) + 1):
                    run(body[i + 1 : end], {**env, m.group(1): v})
                i = end + 1
                continue
            if opens.match(ln):
                i = _block_end(body, i, opens, closes) + 1
                continue
            m = re.match(r"\$BASE=(\$?\w+)$", ln)
            if m:
                state["base"] = (
                    (np.zeros(3), np.eye(3)) if m.group(1) == "$NULLFRAME" else data[m.group(1)]
                )
            m = re.match(r"(\w+)=(\w+)$", ln)
            if m and m.group(2) in data:
                work[m.group(1)] = list(data[m.group(2)][0])
                data[m.group(1)] = data[m.group(2)]
            m = re.match(r"(\w+)\.([XYZ])=(\w+)\.([XYZ])([+-].*)$", ln)
            if m:
                k = "XYZ".index(m.group(2))
                pos = data[m.group(1)][0].copy()
                pos[k] = data[m.group(3)][0][k] + arith(m.group(5), env) / 1000.0
                data[m.group(1)] = (pos, data[m.group(1)][1])
            m = re.match(r"(PTP|LIN) (\w+)", ln)
            if m and m.group(2) in data:
                out.append(compose(state["base"], data[m.group(2)]))
            m = re.match(r"(\w+)\(\)$", ln)
            if m and m.group(1) in routines:
                run(routines[m.group(1)], env)
            i += 1

    run(routines[main], {})
    return out


# --------------------------------------------------------------------------- URScript


def ur_targets(text: str) -> list[Pose | None]:
    """Universal Robots URScript (while/end, def, pose_add, movel/movej(get_inverse_kin));
    a movej to joint values (no pose written) is listed as None."""
    lines = [ln.split("#", 1)[0].rstrip() for ln in text.splitlines()]
    lines = [ln for ln in lines if ln.strip()]
    stripped = [ln.strip() for ln in lines]
    opens, closes = re.compile(r"^(def |while |if |thread ).*:$"), re.compile(r"^end$")
    defs: dict[str, list[str]] = {}
    for i, ln in enumerate(stripped):
        m = re.match(r"def (\w+)\(\):$", ln)
        if m:
            defs[m.group(1)] = stripped[i + 1 : _block_end(stripped, i, opens, closes)]
    program = next(iter(defs))
    num = r"-?[0-9.]+"
    pose_rx = re.compile(rf"p\[({num}), ({num}), ({num}), ({num}), ({num}), ({num})\]")
    out: list[Pose | None] = []

    def pose_of(expr: str, env: dict[str, float]) -> Pose:
        m = re.match(r"pose_add\((p\[[^\]]*\]), p\[([^,]+), ([^,]+), ([^,]+), 0, 0, 0\]\)", expr)
        base = pose_rx.match(m.group(1) if m else expr)
        assert base is not None, expr
        v = [float(g) for g in base.groups()]
        pos = np.array(v[:3])
        if m:
            pos = pos + np.array([arith(m.group(k), env) for k in (2, 3, 4)])
        return pos, rotvec_matrix(*v[3:])

    def run(body: list[str], env: dict[str, float]) -> None:
        i = 0
        while i < len(body):
            ln = body[i]
            if opens.match(ln):
                end = _block_end(body, i, opens, closes)
                m = re.match(r"while (\w+) <= (-?\d+):$", ln)
                if m:  # a counted loop: the counter steps inside the body
                    while env[m.group(1)] <= int(m.group(2)):
                        run(body[i + 1 : end], env)
                i = end + 1
                continue
            m = re.match(r"(\w+) = (.+)$", ln)
            if m and not m.group(2).startswith("run "):
                try:
                    env[m.group(1)] = arith(m.group(2), env)
                except (ValueError, KeyError):
                    pass
            m = re.match(r"movel\((.*), a=", ln) or re.match(
                r"movej\(get_inverse_kin\((.*), qnear=", ln
            )
            if m:
                out.append(pose_of(m.group(1), env))
            elif re.match(r"movej\(\[", ln):
                out.append(None)
            m = re.match(r"(\w+)\(\)$", ln)
            if m and m.group(1) in defs:
                run(defs[m.group(1)], env)
            i += 1

    run(defs[program], {})
    return out


def iter_pairs(a: list[Pose], b: list[Pose]) -> Iterator[tuple[int, Pose, Pose]]:
    for k, (x, y) in enumerate(zip(a, b, strict=True)):
        yield k, x, y
