"""INFORM reads a group input `gin[n]` into a byte variable, `IN Bt IG#(n)` (one group of 8
general inputs, 0..255: DX100/YRC1000 INFORM manual, I/O instructions, IN), and tests the byte
in `JUMP *L IF Bt<op>v`; the import reads the pair back as `gin[n] <op> v`.

Witnesses: a small INFORM interpreter written here from the language's rules (IN fills the byte
with the group's value; `JUMP *L IF` jumps when its comparison holds; labels `*L`), not from the
backend, runs the emitted job for every group value 0..255 and both levels of in[1], against
Python's evaluation of the same IR; the import's reading of the backend's own job is checked
against the condition the program was written with.
"""

from __future__ import annotations

import operator
import re
from pathlib import Path

import pytest
from click.testing import CliRunner
from backend_fixtures import hand_plan, span_at
from test_group_input_backends import COND, INT, PGNO
from test_group_input_backends import _emit as emit_if

from rmot.backends import BACKENDS
from rmot.backends.base import EmitResult
from rmot.backends.readers import read_files
from rmot.backends.readers.model import If, walk
from rmot.backends.readers.writer import SignalMap, program_text
from rmot.compiler.cli import cli
from rmot.lang import ir

_OPS = {"=": operator.eq, "<>": operator.ne, "<": operator.lt, ">": operator.gt, "<=": operator.le, ">=": operator.ge}


def _emit(cond: ir.Condition) -> EmitResult:
    return emit_if("inform", cond)


def _then_runs(job: str, group: int, di1: bool) -> bool:
    """Run the job's instructions: True when its `then` arm (the TIMER) runs."""
    body = job.split("NOP\n")[1].split("\nEND")[0].splitlines()
    labels = {ln: k for k, ln in enumerate(body) if re.fullmatch(r"\*L\d+", ln)}
    byte: dict[str, int] = {}
    k, ran = 0, False
    while k < len(body):
        ln, k = body[k], k + 1
        if m := re.fullmatch(r"IN (B\d+) IG#\(1\)", ln):
            byte[m.group(1)] = group
        elif m := re.fullmatch(r"JUMP (\*L\d+) IF IN#\(1\)=(ON|OFF)", ln):
            k = labels[m.group(1)] if di1 == (m.group(2) == "ON") else k
        elif m := re.fullmatch(r"JUMP (\*L\d+) IF (B\d+)(<>|<=|>=|=|<|>)(\d+)", ln):
            k = labels[m.group(1)] if _OPS[m.group(3)](byte[m.group(2)], int(m.group(4))) else k
        elif ln.startswith("TIMER"):
            ran = True
        else:
            assert ln.startswith(("'", "*L")), ln
    return ran


def test_the_group_reads_as_the_ir_means() -> None:
    result = _emit(COND)
    assert not [d for d in result.diagnostics if d.is_error], result.diagnostics
    job = "\n".join(result.files.values())
    assert "IN B050 IG#(1)" in job, job
    for group in range(256):
        for di1 in (False, True):
            want = group >= 2 and (group < 5 or di1) and group != 3
            assert _then_runs(job, group, di1) == want, (group, di1, job)


@pytest.mark.parametrize(("bits", "said"), [(None, "no width"), (9, "9 bits")])
def test_a_group_wider_than_a_byte_or_of_no_width_is_refused(bits: int | None, said: str) -> None:
    cond = ir.Compare(ir.CompareOp.EQ, ir.GroupInput(port=1, signal="pgno", bits=bits), ir.Const(3, INT))
    errors = [d for d in _emit(cond).diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E430"] and errors[0].span.start.line == 3
    assert "at most 8 bits wide" in errors[0].message and said in errors[0].message


@pytest.mark.parametrize(("op", "value", "rmot"), [
    (ir.CompareOp.EQ, 3, "gin[1] == 3"), (ir.CompareOp.LT, 5, "gin[1] < 5"), (ir.CompareOp.GE, 200, "gin[1] >= 200"),
])
def test_the_import_reads_the_group_test_back(op: ir.CompareOp, value: int, rmot: str, tmp_path: Path) -> None:
    result = _emit(ir.Compare(op, PGNO, ir.Const(value, INT)))
    for name, text in result.files.items():
        (tmp_path / name).write_text(text)
    doc = read_files([str(p) for p in sorted(tmp_path.glob("*.JBI"))])
    assert not doc.diagnostics, doc.diagnostics
    assert [type(s) for r in doc.routines for s in walk(r.body)][:1] == [If]
    text = program_text(doc, SignalMap(), "r1", "cell.rmot")
    assert f"if {rmot} {{" in text and "wait 1 s" in text, text


def test_round_trip_through_a_job(tmp_path: Path) -> None:
    """compile -> INFORM -> `rmot import --cell`: the if on the group input comes back as written."""
    (tmp_path / "cell.rmot").write_text(
        'cell rt_cell {\n  robot r1 = yaskawa_gp8\n  tool t = none tcp pose(x=0mm, y=0mm, z=100mm, q=(1, 0, 0, 0)) '
        'mass 1 kg on r1\n  io gin[1] = "pgno" bits 8\n}\n')
    (tmp_path / "p.rmot").write_text(
        'use cell "cell.rmot"\nprogram p on r1 {\n  target home = joints(0, 10, -10, 0, -30, 0) deg\n  tool t\n'
        "  move joint home speed 50 %\n  if gin[1] == 3 {\n    wait 1 s\n  } else {\n    wait 2 s\n  }\n}\n")
    result = CliRunner().invoke(cli, ["compile", str(tmp_path / "p.rmot"), "--target", "inform", "-o",
                                      str(tmp_path / "out")], catch_exceptions=False)
    assert result.exit_code in (0, 1), result.output
    job = tmp_path / "out" / "inform" / "P.JBI"
    result = CliRunner().invoke(cli, ["import", str(job), "-o", str(tmp_path / "back.rmot"), "--cell",
                                      str(tmp_path / "cell.rmot")], catch_exceptions=False)
    assert result.exit_code == 0 and "0 kept native" in result.output, result.output
    assert "  if gin[1] == 3 {\n    wait 1 s\n  } else {\n    wait 2 s\n  }\n" in (tmp_path / "back.rmot").read_text()


def test_a_group_input_stored_in_a_variable_is_refused() -> None:
    """INFORM compares the byte IG# fills; rmot writes no conversion of it into a D variable."""
    body = (ir.VarDecl(uid=1, name="p", type=INT, init=PGNO, span=span_at(3)),)
    errors = [d for d in BACKENDS["inform"]().emit(hand_plan(body, {}, robot="yaskawa_gp8")).diagnostics if d.is_error]
    assert [d.code.id for d in errors] == ["E430"] and "must be compared with a value" in errors[0].message
