"""A robot description as xacro, or with `package://` names: expanded inside the project.

`urdf("vendor/fanuc_m10ia_support/urdf/m10ia.xacro", packages={fanuc_resources:
"vendor/fanuc_resources", fanuc_m10ia_support: "vendor/fanuc_m10ia_support"})` expands the
xacro file with PyPI's `xacro` (the ROS tool, driven without ROS) and hands the URDF to the
loader. Each package is a folder inside the project; `$(find PKG)` and `package://PKG/...`
resolve to it (an unknown package is E542). The expansion treats the files as data:

* every file xacro opens (the top file, each `xacro:include`) must lie inside the project and
  carry no DOCTYPE or entity declaration (no entity expansion), at most MAX_BYTES each;
* `$(env ...)`, `$(optenv ...)` and `$(eval ...)` are refused (E541): the environment is not
  an input, and `$(eval)` is Python;
* `${...}` expressions are evaluated by a small interpreter of arithmetic over the file's
  own properties (numbers, strings, + - * / // % **, comparisons, and/or/not, `a if c else
  b`, `math.*`/`pi`/`radians(...)` style functions, `x.y` and `x['y']` on the file's
  dictionaries): never by Python's eval. Anything else (calling `load_yaml`, attribute
  names starting with `_`, huge powers) is E541.
The URDF is written (atomically) to a folder named by its content hash under the system's
temporary directory, every mesh name made absolute, so the same input gives the same file.
"""

from __future__ import annotations

import ast as pyast
import contextlib
import hashlib
import io
import math
import os
import re
import tempfile
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from rmot.lang import check_codes as codes
from rmot.compiler.passes.context import Reporter
from rmot.compiler.passes.urdf_paths import _inside
from rmot.lang.input_file import NotRegularFile, read_regular
from rmot.lang.source import Span
import xml.dom.minidom
from rmot.lang.atomic import write_text

__all__ = ["MAX_BYTES", "expand_description"]

MAX_BYTES = 8 * 1024 * 1024  # one xacro or URDF file
_LOCK = threading.Lock()  # xacro keeps its state in module globals
_REFUSED_SUBSTITUTIONS = re.compile(r"\$\((env|optenv|eval)\b")
_FUNCTIONS: dict[str, Callable[..., Any]] = {
    **{name: getattr(math, name) for name in ("sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt",
                                              "radians", "degrees", "fabs", "floor", "ceil", "hypot", "exp", "log")},
    "abs": abs, "min": min, "max": max, "float": float, "int": int, "round": round, "str": str, "bool": bool,
}
_ALLOWED_CALLABLES = frozenset(id(f) for f in _FUNCTIONS.values())


class RefusedXacro(Exception):
    """A construct the expansion will not run (its message says which)."""


def expand_description(path: str, packages: dict[str, str], roots: tuple[str, ...], span: Span | None,
                       rep: Reporter) -> str | None:
    """The path of the URDF that `path` (xacro or URDF) expands to, or None after a diagnostic."""
    try:
        try:
            with _LOCK, _sandboxed_xacro(packages, roots) as xacro:
                text = _expand(xacro, path) if path.lower().endswith(".xacro") else _read(path, roots)
            text = _absolute_meshes(text, Path(path).resolve().parent, packages)
        except Exception as exc:  # xacro wraps what our hooks raise: find the hook's own
            raise _own(exc) from None
    except RefusedXacro as exc:
        rep.error(codes.XACRO_REFUSED, f"{os.path.basename(path)} must be plain data to expand (got {exc})", span)
        return None
    except _UnknownPackage as exc:
        rep.error(codes.UNKNOWN_PACKAGE, f"package '{exc}' must be given in urdf(..., packages={{{exc}: \"FOLDER\"}}) "
                  f"(known: {', '.join(sorted(packages)) or 'none'})", span)
        return None
    except Exception as exc:  # xacro raises XacroException, NameError, ... for a defective file
        why = " ".join(str(exc).split())[:300] or type(exc).__name__
        rep.error(codes.XACRO_FAILED, f"{os.path.basename(path)} must expand to a URDF (got: {why})", span)
        return None
    return _write(text, Path(path).stem)


class _UnknownPackage(Exception):
    pass


def _own(exc: BaseException) -> BaseException:
    """The RefusedXacro or _UnknownPackage inside xacro's wrappers (`.exc`, causes), else exc."""
    seen: set[int] = set()
    current: BaseException | None = exc
    while current is not None and id(current) not in seen:
        if isinstance(current, (RefusedXacro, _UnknownPackage)):
            return current
        seen.add(id(current))
        inner = getattr(current, "exc", None)
        current = inner if isinstance(inner, BaseException) else (current.__cause__ or current.__context__)
    return exc


def _read(path: str, roots: tuple[str, ...]) -> str:
    """A file's text, once it is known to be inside the project, small, and entity-free."""
    resolved = Path(path).resolve()
    if not any(_inside(resolved, Path(r)) for r in roots):
        raise RefusedXacro(f"an include outside the project: {path}")
    try:
        data = read_regular(resolved, MAX_BYTES)
    except NotRegularFile as exc:
        raise RefusedXacro(f"not a regular file of at most {MAX_BYTES // (1024 * 1024)} MiB ({exc.strerror}): {path}") from None
    if re.search(rb"<!(DOCTYPE|ENTITY)", data):
        raise RefusedXacro(f"a DOCTYPE or entity declaration in {os.path.basename(path)}")
    text = data.decode("utf-8")
    found = _REFUSED_SUBSTITUTIONS.search(text)
    if found:
        raise RefusedXacro(f"$({found.group(1)} ...) in {os.path.basename(path)}: the environment and Python are no inputs")
    return text


@contextlib.contextmanager
def _sandboxed_xacro(packages: dict[str, str], roots: tuple[str, ...]) -> Iterator[Any]:
    """xacro with `find` from `packages`, files read through `_read`, `${}` through `_evaluate`."""

    import xacro  # late: xacro is heavy or optional, loaded only where used
    from xacro import substitution_args  # late: xacro is heavy or optional, loaded only where used

    def find(pkg: str) -> str:
        if pkg not in packages:
            raise _UnknownPackage(pkg)
        return packages[pkg]

    def parse(inp: Any, filename: str | None = None) -> Any:
        if inp is None:
            assert filename is not None
            return xml.dom.minidom.parseString(_read(filename, roots))
        return xml.dom.minidom.parseString(inp if isinstance(inp, str) else inp.read())

    saved = (xacro.safe_eval, xacro.parse, substitution_args._eval_find)
    xacro.safe_eval, xacro.parse, substitution_args._eval_find = _evaluate, parse, find
    try:
        yield xacro
    finally:
        xacro.safe_eval, xacro.parse, substitution_args._eval_find = saved


def _expand(xacro: Any, path: str) -> str:
    with contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        xacro.init_stacks(path)
        doc = xacro.parse(None, path)
        xacro.process_doc(doc)
    return str(doc.toxml())


def _evaluate(expr: str, symbols: Any, local: Any = None) -> Any:
    """A `${...}` expression over the file's properties (module doc), without Python's eval."""
    tree = pyast.parse(expr.strip(), mode="eval")

    def lookup(name: str) -> Any:
        if name.startswith("_"):
            raise RefusedXacro(f"the name '{name}'")
        for table in (local, symbols):
            if table is not None and name in table:
                return table[name]
        if name in _FUNCTIONS:
            return _FUNCTIONS[name]
        if name == "pi":
            return math.pi
        raise NameError(f"name '{name}' is not defined")

    return _Interpreter(lookup).visit(tree.body)


class _Interpreter:
    """Evaluates the allowed node kinds of a Python expression tree; refuses every other."""

    _BIN: dict[type, Callable[[Any, Any], Any]] = {
        pyast.Add: lambda a, b: a + b, pyast.Sub: lambda a, b: a - b, pyast.Mult: lambda a, b: a * b,
        pyast.Div: lambda a, b: a / b, pyast.FloorDiv: lambda a, b: a // b, pyast.Mod: lambda a, b: a % b,
        pyast.Pow: lambda a, b: a ** b,
    }
    _CMP: dict[type, Callable[[Any, Any], bool]] = {
        pyast.Eq: lambda a, b: a == b, pyast.NotEq: lambda a, b: a != b, pyast.Lt: lambda a, b: a < b,
        pyast.LtE: lambda a, b: a <= b, pyast.Gt: lambda a, b: a > b, pyast.GtE: lambda a, b: a >= b,
    }

    def __init__(self, lookup: Callable[[str], Any]) -> None:
        self.lookup = lookup

    def visit(self, node: pyast.AST) -> Any:
        method = getattr(self, f"visit_{type(node).__name__}", None)
        if method is None:
            raise RefusedXacro(f"an expression part '{type(node).__name__}'")
        return method(node)

    def visit_Constant(self, node: pyast.Constant) -> Any:
        if not isinstance(node.value, (int, float, str, bool)) and node.value is not None:
            raise RefusedXacro(f"the constant {node.value!r}")
        return node.value

    def visit_Name(self, node: pyast.Name) -> Any:
        return self.lookup(node.id)

    def visit_BinOp(self, node: pyast.BinOp) -> Any:
        a, b = self.visit(node.left), self.visit(node.right)
        numbers = all(isinstance(x, (int, float)) for x in (a, b))
        strings = isinstance(node.op, pyast.Add) and all(isinstance(x, str) for x in (a, b))
        if not (numbers or strings) or type(node.op) not in self._BIN:
            raise RefusedXacro(f"{type(a).__name__} {type(node.op).__name__} {type(b).__name__}")
        if isinstance(node.op, pyast.Pow) and (abs(b) > 64 or abs(a) > 1e6):
            raise RefusedXacro("a power beyond 1e6 ** 64")
        return self._BIN[type(node.op)](a, b)

    def visit_UnaryOp(self, node: pyast.UnaryOp) -> Any:
        value = self.visit(node.operand)
        if isinstance(node.op, pyast.Not):
            return not value
        if not isinstance(value, (int, float)) or not isinstance(node.op, (pyast.USub, pyast.UAdd)):
            raise RefusedXacro(f"the operator {type(node.op).__name__}")
        return -value if isinstance(node.op, pyast.USub) else value

    def visit_BoolOp(self, node: pyast.BoolOp) -> Any:
        value = self.visit(node.values[0])
        for item in node.values[1:]:
            if (isinstance(node.op, pyast.And) and not value) or (isinstance(node.op, pyast.Or) and value):
                return value
            value = self.visit(item)
        return value

    def visit_Compare(self, node: pyast.Compare) -> Any:
        left = self.visit(node.left)
        for op, right_node in zip(node.ops, node.comparators):
            right = self.visit(right_node)
            if type(op) not in self._CMP:
                raise RefusedXacro(f"the comparison {type(op).__name__}")
            if not self._CMP[type(op)](left, right):
                return False
            left = right
        return True

    def visit_IfExp(self, node: pyast.IfExp) -> Any:
        return self.visit(node.body) if self.visit(node.test) else self.visit(node.orelse)

    def visit_Attribute(self, node: pyast.Attribute) -> Any:
        base = self.visit(node.value)
        if node.attr.startswith("_") or not isinstance(base, dict) or node.attr not in base:
            if node.attr in _FUNCTIONS and isinstance(base, dict):  # xacro's `math.` namespace
                return _FUNCTIONS[node.attr]
            if node.attr == "pi" and isinstance(base, dict):
                return math.pi
            raise RefusedXacro(f"the attribute '.{node.attr}'")
        return base[node.attr]

    def visit_Subscript(self, node: pyast.Subscript) -> Any:
        base, key = self.visit(node.value), self.visit(node.slice)
        if isinstance(base, dict) and isinstance(key, (int, str)):
            return base[key]
        if isinstance(base, (list, tuple, str)) and isinstance(key, int):
            return base[key]
        raise RefusedXacro("an index into something that is not the file's data")

    def visit_Call(self, node: pyast.Call) -> Any:
        func = self.visit(node.func)
        if id(func) not in _ALLOWED_CALLABLES or node.keywords:
            raise RefusedXacro("a call of anything but a math function")
        args = [self.visit(a) for a in node.args]
        if not all(isinstance(a, (int, float, str, bool)) for a in args):
            raise RefusedXacro("a math function of something that is not a number")
        return func(*args)


def _absolute_meshes(text: str, folder: Path, packages: dict[str, str]) -> str:
    """Every mesh name made absolute: package://PKG/rest from `packages`, relative names from
    the described file's folder; names outside the project are judged by urdf_paths later."""
    def absolute(match: re.Match[str]) -> str:
        name = match.group(2)
        if name.startswith("package://"):
            pkg, _, rest = name[len("package://"):].partition("/")
            if pkg not in packages:
                if packages:
                    raise _UnknownPackage(pkg)
                return match.group(0)  # no packages given: urdf_paths searches the ancestors
            name = os.path.join(packages[pkg], rest)
        elif not name.startswith("file://") and not os.path.isabs(name):
            name = str(folder / name)
        return f"{match.group(1)}{_xml_attr(name)}{match.group(3)}"

    return re.sub(r'(<mesh\b[^>]*?\bfilename=")([^"]*)(")', absolute, text)


def _xml_attr(text: str) -> str:
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")


def _write(text: str, stem: str) -> str:

    digest = hashlib.sha256(text.encode("utf-8")).hexdigest()[:20]
    folder = Path(tempfile.gettempdir()) / f"rmot-descriptions-{os.getuid()}" / digest
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / ((re.sub(r"[^A-Za-z0-9_.-]", "_", stem) or "robot") + ".urdf")
    if not target.is_file() or target.read_text(encoding="utf-8") != text:
        write_text(str(target), text)
    return str(target)

