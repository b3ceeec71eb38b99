"""`make fuzz FUZZ_MIX=1`'s hostile-file strategies, one input per seed, each replayed through
the command line in the fuzz worker's process:

- mesh: an STL (text or binary), OFF or polygon mesh built and then damaged (counts that lie,
  truncation, NaN/infinite/huge vertices, zero-area triangles, random bytes, a FIFO);
- urdf: examples/urdf_cell/arm6.urdf with attributes set to extremes, elements deleted or
  duplicated, joint types changed, tags cut;
- cache: a small program checked with a cache, one cache entry damaged (bytes flipped, cut,
  swapped with another entry, replaced by a FIFO, a link to /dev/zero or a sparse 4 GiB file),
  checked again: the verdict must be the `--no-cache` one;
- report: a `check --format json|sarif|junit` report mutated (values of other types, deep
  nesting, huge or non-finite numbers, keys removed) and given to `merge-reports`.

An input fails when an exception escapes the command, the output names E550 or a traceback,
or (cache) the verdict differs from the uncached one. `hostile_input(seed)` rebuilds it.
"""

from __future__ import annotations

import json
import os
import random
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

__all__ = ["KINDS", "Hostile", "hostile_input", "run_hostile"]

ROOT = Path(__file__).resolve().parents[2]
ARM6 = ROOT / "examples" / "urdf_cell" / "arm6.urdf"
_EXTREMES = ("nan", "inf", "-inf", "1e308", "-1e308", "0", "-0", "-1", "1e-320", "999999999999", "", "x", "1 2", "NaN NaN NaN")
_SMALL = "program p on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n  move joint joints(20, -10, 10, 0, 90, 0) deg\n}\n"
KINDS = ("mesh", "urdf", "cache", "report")


@dataclass(frozen=True)
class Hostile:
    kind: str
    files: dict[str, str | bytes]
    argv: tuple[str, ...]  # `{d}` is the input's folder
    fifo: str = ""  # a file made a FIFO
    damage: int = 0  # cache: the seed of the damage done between the two runs


def _triangles(rng: random.Random, n: int) -> list[list[tuple[float, float, float]]]:
    return [[(rng.uniform(0, 0.2), rng.uniform(0, 0.2), rng.uniform(0, 0.2)) for _ in range(3)] for _ in range(n)]


def _mesh_text(rng: random.Random, suffix: str) -> str | bytes:
    tris = _triangles(rng, rng.randint(1, 12))
    if rng.random() < 0.2:  # zero area: all corners equal
        tris[0] = [tris[0][0]] * 3
    if suffix == ".stl" and rng.random() < 0.5:  # binary STL, its count sometimes a lie
        import struct

        count = len(tris) if rng.random() < 0.5 else rng.choice((0, len(tris) + 5, 2**31, 2**32 - 1))
        body = b"".join(struct.pack("<12fH", 0, 0, 1, *[c for v in t for c in v], 0) for t in tris)
        return b"\0" * 80 + struct.pack("<I", count) + body[: rng.randint(0, len(body))] if rng.random() < 0.3 else \
            b"\0" * 80 + struct.pack("<I", count) + body
    if suffix == ".stl":
        facets = "".join("facet normal 0 0 1\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in t)
                         + "endloop\nendfacet\n" for t in tris)
        return f"solid t\n{facets}endsolid t\n"
    verts = [v for t in tris for v in t]
    faces = [(3 * i, 3 * i + 1, 3 * i + 2) for i in range(len(tris))]
    nv = len(verts) if rng.random() < 0.6 else rng.choice((0, len(verts) + 3, 10**9))
    nf = len(faces) if rng.random() < 0.6 else rng.choice((0, len(faces) * 2, 10**9))
    head = f"OFF\n{nv} {nf} 0\n" if suffix == ".off" else f"{nv} {nf}\n"
    return head + "".join(f"{x} {y} {z}\n" for x, y, z in verts) + "".join(f"3 {a} {b} {c}\n" for a, b, c in faces)


def _damage_text(rng: random.Random, text: str) -> str:
    """Numbers replaced by extremes, lines deleted, duplicated or cut, a random character."""
    lines = text.splitlines()
    for _ in range(rng.randint(1, 3)):
        if not lines:
            break
        i = rng.randrange(len(lines))
        kind = rng.randrange(5)
        if kind == 0:
            lines[i] = re.sub(r"-?\d+(\.\d+)?(e-?\d+)?", lambda _: rng.choice(_EXTREMES), lines[i], count=rng.randint(1, 3))
        elif kind == 1:
            del lines[i]
        elif kind == 2:
            lines.insert(i, lines[i])
        elif kind == 3:
            lines[i] = lines[i][: rng.randrange(len(lines[i]) + 1)]
        else:
            lines[i] += rng.choice(("\x00", "\ufffd", "}", "{", "<", "&amp;", "\u2028"))
    return "\n".join(lines) + "\n"


def _mesh(rng: random.Random) -> Hostile:
    suffix = rng.choice((".stl", ".off", ".mesh"))
    body = _mesh_text(rng, suffix)
    if isinstance(body, str) and rng.random() < 0.7:
        body = _damage_text(rng, body)
    elif isinstance(body, bytes) and rng.random() < 0.3:
        body = bytes(rng.randrange(256) for _ in range(rng.randint(0, 400)))
    scale = rng.choice(("", "", ", scale=1000", ", scale=1e-9", ", scale=0.001"))
    program = (f'cell c {{\n  robot r1 = abb_irb1600\n  fixture f = mesh("part{suffix}"{scale}) at pose(x=800mm, z=400mm)\n}}\n'
               + _SMALL)
    fifo = f"part{suffix}" if rng.random() < 0.03 else ""
    return Hostile("mesh", {"p.rmot": program, f"part{suffix}": body}, ("check", "{d}/p.rmot"), fifo)


def _urdf(rng: random.Random) -> Hostile:
    text = ARM6.read_text(encoding="utf-8")
    for _ in range(rng.randint(1, 4)):
        kind = rng.randrange(4)
        if kind == 0:  # an attribute's value set to an extreme
            attrs = list(re.finditer(r'(\w+)="([^"]*)"', text))
            if attrs:
                m = rng.choice(attrs)
                text = text[: m.start(2)] + rng.choice(_EXTREMES) + text[m.end(2):]
        elif kind == 1:  # an element deleted or duplicated
            elems = list(re.finditer(r"<(\w+)[^<>]*/>", text))
            if elems:
                m = rng.choice(elems)
                text = text[: m.start()] + (m.group(0) * 2 if rng.random() < 0.5 else "") + text[m.end():]
        elif kind == 2:  # a joint type changed
            text = re.sub(r'type="(revolute|fixed|continuous|prismatic)"',
                          lambda _: f'type="{rng.choice(("revolute", "fixed", "continuous", "prismatic", "floating", "planar", "x"))}"',
                          text, count=rng.randint(1, 3))
        elif text:  # cut somewhere
            text = text[: rng.randrange(len(text))]
    program = 'cell c {\n  robot r1 = urdf("arm.urdf")\n}\nprogram p on r1 {\n  wait 1 s\n  move joint joints(0, 10, 10, 0, 10, 0) deg\n}\n'
    return Hostile("urdf", {"p.rmot": program, "arm.urdf": text}, ("check", "{d}/p.rmot"))


def _cache(rng: random.Random, seed: int) -> Hostile:
    return Hostile("cache", {"p.rmot": _SMALL}, ("check", "{d}/p.rmot"), damage=seed)


def _report(rng: random.Random) -> Hostile:
    fmt = rng.choice(("json", "sarif", "junit"))
    return Hostile("report", {"p.rmot": _SMALL}, ("merge-reports", "{d}/r." + ("xml" if fmt == "junit" else fmt)),
                   damage=rng.randrange(1 << 30))


def hostile_input(seed: int) -> Hostile:
    rng = random.Random(seed)
    kind = KINDS[(seed // 4) % len(KINDS)]
    if kind == "mesh":
        return _mesh(rng)
    if kind == "urdf":
        return _urdf(rng)
    if kind == "cache":
        return _cache(rng, seed)
    return _report(rng)


# ----------------------------------------------------------------------------- running
def _cli(argv: list[str], cache: str) -> tuple[int, str, BaseException | None]:
    from click.testing import CliRunner

    from rmot.compiler.cli import cli

    old = os.environ.get("RMOT_CACHE_DIR")
    os.environ["RMOT_CACHE_DIR"] = cache
    try:
        result = CliRunner().invoke(cli, argv, catch_exceptions=True)
    finally:
        if old is None:
            os.environ.pop("RMOT_CACHE_DIR", None)
        else:
            os.environ["RMOT_CACHE_DIR"] = old
    exc = result.exception if not isinstance(result.exception, SystemExit) else None
    return result.exit_code, result.output, exc


def _problem(code: int, output: str, exc: BaseException | None) -> str | None:
    if exc is not None:
        return f"traceback: {exc.__class__.__name__}: {str(exc)[:200]}"
    if "E550" in output or "Traceback" in output:
        line = next((x for x in output.splitlines() if "E550" in x or "Traceback" in x), "")
        return f"traceback: {line[:240]}"
    return None


def _damage_entry(rng: random.Random, cache: Path) -> str:
    """One cache entry damaged; what was done, for the failure's description."""
    entries = sorted(p for p in cache.rglob("*") if p.is_file() and p.name != "secret" and not p.name.startswith("."))
    if not entries:
        return "no entry"
    path = rng.choice(entries)
    data = path.read_bytes()
    how = rng.choice(("flip", "cut", "swap", "fifo", "dev_zero", "sparse", "junk", "empty"))
    path.unlink()
    if how == "flip" and data:
        i = rng.randrange(len(data))
        path.write_bytes(data[:i] + bytes([data[i] ^ (1 << rng.randrange(8))]) + data[i + 1:])
    elif how == "cut":
        path.write_bytes(data[: rng.randrange(len(data) + 1)])
    elif how == "swap":
        other = rng.choice(entries)
        path.write_bytes(other.read_bytes() if other.exists() else data[::-1])
    elif how == "fifo":
        os.mkfifo(path)
    elif how == "dev_zero":
        path.symlink_to("/dev/zero")
    elif how == "sparse":
        with open(path, "wb") as f:
            f.truncate(4 << 30)
    elif how == "junk":
        path.write_bytes(b"rmot-sealed/1\n" + bytes(rng.randrange(256) for _ in range(200)))
    else:
        path.write_bytes(b"")
    return f"{how} {path.relative_to(cache)}"


def _mutate_json(rng: random.Random, doc: object, depth: int = 0) -> object:
    """`doc` with one value somewhere replaced by a value of another type or an extreme."""
    hostile: list[Callable[[], object]] = [
        lambda: None, lambda: 5, lambda: "x", lambda: [], lambda: {}, lambda: 1e308, lambda: -1,
        lambda: "\x00\u2028", lambda: [[[[[]]]]], lambda: {"$t": 1}, lambda: "9" * 400]
    if isinstance(doc, dict) and doc and (depth < 6 and rng.random() < 0.8):
        key = rng.choice(sorted(doc))
        if rng.random() < 0.15:
            return {k: v for k, v in doc.items() if k != key}
        return {**doc, key: _mutate_json(rng, doc[key], depth + 1)}
    if isinstance(doc, list) and doc and (depth < 6 and rng.random() < 0.8):
        i = rng.randrange(len(doc))
        return [*doc[:i], _mutate_json(rng, doc[i], depth + 1), *doc[i + 1:]]
    return rng.choice(hostile)()


def _report_text(rng: random.Random, fmt: str, clean: str) -> str:
    if fmt == "xml":
        text = _damage_text(rng, clean)
        if rng.random() < 0.2:
            text = "<a>" * 100_000 + "</a>" * 100_000
        return text
    doc = json.loads(clean)
    for _ in range(rng.randint(1, 3)):
        doc = _mutate_json(rng, doc)
    text = json.dumps(doc)
    if rng.random() < 0.1:
        text = text.replace("1e+308", "NaN", 1).replace("-1", "-Infinity", 1)
    if rng.random() < 0.05:
        text = "[" * 100_000 + "]" * 100_000
    return text


_VERDICTS: dict[str, tuple[int, str]] = {}  # program text -> (exit code, stdout) of --no-cache
_REPORTS: dict[str, str] = {}  # format -> a clean report of _SMALL


def run_hostile(seed: int, proj: str, cache_root: str) -> str:
    """One hostile input; 'ok exit=N files=0' or the failure."""
    h = hostile_input(seed)
    rng = random.Random(seed * 7919 + 1)
    for name, body in h.files.items():
        path = Path(proj) / name
        if isinstance(body, bytes):
            path.write_bytes(body)
        else:
            path.write_text(body, encoding="utf-8", errors="surrogatepass")
    if h.fifo:
        (Path(proj) / h.fifo).unlink()
        os.mkfifo(Path(proj) / h.fifo)
    argv = [a.format(d=proj) for a in h.argv]
    if h.kind == "cache":
        return _run_cache(rng, argv, proj, cache_root)
    if h.kind == "report":
        fmt = argv[-1].rsplit(".", 1)[1]
        if fmt not in _REPORTS:
            out = str(Path(proj) / f"clean.{fmt}")
            _cli(["check", argv[-1].rsplit("/", 1)[0] + "/p.rmot", "--no-cache", "--format",
                  "junit" if fmt == "xml" else fmt, "-o", out], cache_root)
            _REPORTS[fmt] = Path(out).read_text(encoding="utf-8")
        Path(argv[-1]).write_text(_report_text(rng, fmt, _REPORTS[fmt]), encoding="utf-8", errors="surrogatepass")
    code, output, exc = _cli(argv, os.path.join(cache_root, "shared"))
    return _problem(code, output, exc) or f"ok exit={code} files=0"


def _run_cache(rng: random.Random, argv: list[str], proj: str, cache_root: str) -> str:
    text = Path(argv[1]).read_text(encoding="utf-8")
    if text not in _VERDICTS:
        code, output, exc = _cli([*argv, "--no-cache"], os.path.join(cache_root, "none"))
        _VERDICTS[text] = (code, output.replace(proj, "{d}"))
    cache = Path(cache_root) / f"c{rng.randrange(1 << 30)}"
    try:
        first = _cli(argv, str(cache))
        problem = _problem(*first)
        if problem:
            return problem
        what = _damage_entry(rng, cache)
        code, output, exc = _cli(argv, str(cache))
        problem = _problem(code, output, exc)
        if problem:
            return f"{problem} (after {what})"
        if (code, output.replace(proj, "{d}")) != _VERDICTS[text]:
            return f"verdict: exit {code} after {what}, {_VERDICTS[text][0]} without the cache"
        return f"ok exit={code} files=0"
    finally:
        import shutil

        shutil.rmtree(cache, ignore_errors=True)
