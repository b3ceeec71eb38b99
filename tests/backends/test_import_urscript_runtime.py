"""`rmot import` of URScript variables and the logic on them (lang/REFERENCE.md §12, §14).

Witnesses: a hand-written script (URScript manual: `global`, assignments, `while`, `if`/`elif`/
`else` on variables and `get_standard_digital_in`) whose import must compile with `rmot check`
(the compiler's own type rules); and Python's own parser and evaluator (`ast`), which URScript's
expressions follow operator for operator (`or` < `and` < `not` < comparisons < `+ -` < `* /`),
run on the URScript text and on the imported rmot text over every input level and a range of
variable values: both must give the same truth value.
"""

from __future__ import annotations

import ast
import itertools
import operator
import re
from pathlib import Path

from click.testing import CliRunner

from rmot.backends.readers.model import Cond
from rmot.backends.readers.urscript_logic import condition
from rmot.compiler.cli import cli

HAND = """def prog():
  global takt = 0
  done = False
  level = 0.5
  takt = 0
  while takt < 3 and get_standard_digital_in(1):
    movej([0, -1.57, 1.57, 0, 1.57, 0], a=1.4, v=1.05)
    takt = takt + 1
    level = level * 2
  end
  if (takt == 3 or not get_standard_digital_in(2)):
    set_standard_digital_out(1, True)
    done = True
  elif (level > 1.5):
    set_standard_digital_out(2, True)
  else:
    done = not done
  end
  if done == True:
    sleep(0.5)
  end
end
"""

EXPECTED_BODY = """  var done: bool = off
  var level: num = 0.5
  var takt: int = 0
  while takt < 3 and in[1] == on {
    frame base
    move joint joints(0, -89.954373836, 89.954373836, 0, 89.954373836, 0) deg speed 33.423 % accel 10.027 % zone fine
    takt = takt + 1
    level = level * 2
  }
  if takt == 3 or in[2] == off {
    set out[1] = on
    done = on
  } else {
    if level > 1.5 {
      set out[2] = on
    } else {
      done = not done
    }
  }
  if done {
    wait 0.5 s
  }
}
"""

_OPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
        ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
        ast.Gt: operator.gt, ast.GtE: operator.ge}


def _eval(node: ast.AST, env: dict[str, object]) -> object:
    """Python's meaning of a parsed expression (names from env, no calls but the inputs')."""
    if isinstance(node, ast.Expression):
        return _eval(node.body, env)
    if isinstance(node, ast.BoolOp):
        values = [_eval(v, env) for v in node.values]
        return all(values) if isinstance(node.op, ast.And) else any(values)
    if isinstance(node, ast.UnaryOp):
        value = _eval(node.operand, env)
        return (not value) if isinstance(node.op, ast.Not) else -value  # type: ignore[operator]
    if isinstance(node, ast.BinOp):
        return _OPS[type(node.op)](_eval(node.left, env), _eval(node.right, env))
    if isinstance(node, ast.Compare):
        left, ok = _eval(node.left, env), True
        for op, right_node in zip(node.ops, node.comparators):
            right = _eval(right_node, env)
            ok, left = ok and _OPS[type(op)](left, right), right
        return ok
    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, ast.Name):
        return env[node.id]
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        return env[f"{node.func.id}({_eval(node.args[0], env)})"]
    raise AssertionError(ast.dump(node))


def _rmot_python(text: str) -> str:
    """The imported rmot condition in Python's spelling (rmot's priorities are Python's)."""
    text = re.sub(r"in\[(\d+)\] == on", r"IN\1", text)
    text = re.sub(r"in\[(\d+)\] == off", r"(not IN\1)", text)
    return re.sub(r"\bon\b", "True", re.sub(r"\boff\b", "False", text))


CONDITIONS = [
    "takt == 3 or not get_standard_digital_in(2)",
    "takt < 3 and get_standard_digital_in(1)",
    "not (takt >= 2 and level > 1.5) or get_standard_digital_in(0) == False",
    "done == True and takt + 1 * 2 > level - 0.5",
    "not done or not get_configurable_digital_in(1) and takt != 2",
    "(level * 2 / 4 <= takt) == False",
    "get_digital_in(3) != True or done",
]


def test_conditions_mean_what_urscript_means() -> None:
    names = {"TAKT": ("takt", "int"), "LEVEL": ("level", "num"), "DONE": ("done", "bool")}
    for text in CONDITIONS:
        found = condition(text, names)
        assert found is not None, text
        leaves = [c for c in found.parts if isinstance(c, Cond)]
        assert len(leaves) == len(found.parts)
        rmot = _rmot_python(found.text.format(*(f"in[{c.signal}] == {'on' if c.on else 'off'}" for c in leaves)))
        for takt, level, done, *ins in itertools.product(range(5), (0.0, 0.5, 1.5, 2.25), (False, True),
                                                          (False, True), (False, True), (False, True), (False, True)):
            inputs = dict(zip((0, 1, 2, 3), ins))
            env: dict[str, object] = {"takt": takt, "level": level, "done": done, "True": True, "False": False}
            env |= {f"get_standard_digital_in({n})": v for n, v in inputs.items()}
            env |= {f"get_digital_in({n})": v for n, v in inputs.items()}
            env |= {"get_configurable_digital_in(1)": ins[2]}
            rmot_env: dict[str, object] = {"takt": takt, "level": level, "done": done}
            rmot_env |= {f"IN{n}": v for n, v in inputs.items()} | {"IN9": ins[2]}
            want = _eval(ast.parse(text, mode="eval"), env)
            got = _eval(ast.parse(rmot, mode="eval"), rmot_env)
            assert bool(want) == bool(got), (text, rmot, takt, level, done, ins)


def test_refused_where_meaning_differs() -> None:
    names = {"N": ("n", "int"), "B": ("b", "bool")}
    for text in ("not n == 1", "1 < n < 3", "n % 2 == 0", "n / 2 == 1", "b == true", "b and sp[0] > 1",
                 "n == 1 AND b"):
        assert condition(text, names) is None, text


def _imported(tmp_path: Path, text: str) -> tuple[str, str]:
    src = tmp_path / "prog.script"
    src.write_text(text)
    out = tmp_path / "prog.rmot"
    result = CliRunner().invoke(cli, ["import", str(src), "-o", str(out)])
    assert result.exit_code == 0, result.output
    return out.read_text(), result.output


def test_hand_written_script_imports_and_checks(tmp_path: Path) -> None:
    text, _ = _imported(tmp_path, HAND)
    assert text.split("program prog on r1 {\n", 1)[1] == EXPECTED_BODY
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "prog.rmot")])
    assert result.exit_code == 0, result.output


def test_variables_a_thread_or_a_turn_carries_stay_native(tmp_path: Path) -> None:
    # `count` carries from one turn of the outermost loop to the next (the one-cycle reading would
    # reset it); `flag` is set by a thread: both stay native, with W510 at their lines
    script = """count = 0
flag = False
thread watch():
  flag = True
end
run watch()
while (True):
  count = count + 1
  if (count == 5):
    set_standard_digital_out(1, True)
  end
  if (flag):
    set_standard_digital_out(2, True)
  end
end
"""
    text, output = _imported(tmp_path, script)
    assert "var " not in text
    assert 'native urscript "if (count == 5):"' in text and 'native urscript "if (flag):"' in text
    assert re.search(r"prog\.script:9:\d+: warning\[W510\]", output)


def test_variable_reset_at_the_top_of_each_turn_is_read(tmp_path: Path) -> None:
    script = """while (True):
  n = 0
  while n < 2 and get_standard_digital_in(0):
    sleep(0.1)
    n = n + 1
  end
end
"""
    text, _ = _imported(tmp_path, script)
    assert "var n: int = 0\n" in text and "while n < 2 and in[0] == on {" in text and "n = n + 1" in text


def test_a_keyword_name_stays_native(tmp_path: Path) -> None:
    # `speed` is an rmot keyword: renaming it would part it from native lines reading `speed`
    script = """speed = 0
while speed < 2:
  speed = speed + 0.5
  sleep(0.1)
end
"""
    text, output = _imported(tmp_path, script)
    assert "var " not in text and 'native urscript "while speed < 2:"' in text
    assert "W510" in output


def test_a_variable_a_urcap_installation_sets_stays_native(tmp_path: Path) -> None:
    script = """def prog():
  # begin: URCap Installation Node
  #   Source: Gripper, 1.0.0, Vendor
  thread grip_watch():
    ready = True
  end
  # end: URCap Installation Node
  ready = False
  if (ready):
    set_standard_digital_out(1, True)
  end
end
"""
    text, _ = _imported(tmp_path, script)
    assert "var " not in text and 'native urscript "if (ready):"' in text


def test_hostile_conditions_stay_native(tmp_path: Path) -> None:
    # thousands of nested `not (`: no internal error, the condition stays native (W510)
    for test in ("not (" * 3000 + "b" + ")" * 3000, "not " * 5000 + "b"):
        text, output = _imported(tmp_path, f"def p():\n  b = False\n  if {test}:\n    sleep(1)\n  end\nend\n")
        assert "native urscript" in text and "W510" in output
