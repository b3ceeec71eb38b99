"""Every emitted file of every shipped example and every golden file through a validator
that is not the backend's own code: rapidchecker (RAPID), krllint (KRL, PyPI), and the
structural validators of vendor_validators.py written from the Fanuc, UR, Yaskawa and
Stäubli manuals (Fanuc LS, URScript, INFORM, VAL3). Each validator is also shown to reject
the defect it exists for, so none of these tests can pass vacuously."""

from __future__ import annotations

import warnings
from argparse import Namespace
from collections import defaultdict
from pathlib import Path

import pytest
from backend_fixtures import GOLDEN, ROOT, example_plans
from vendor_validators import check_fanuc, check_inform, check_krl, check_urscript, check_val3

from rmot.backends import BACKENDS
from rmot.backends import controllers

EXAMPLES = tuple(sorted(p.stem for p in (ROOT / "examples").glob("*.rmot")))
VENDORS = controllers()


def rapid_findings(files: dict[str, str]) -> list[str]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from rapidchecker.cli import check_file
    return [f"{name}: {e}" for name, text in files.items() for e in check_file(text)]


# krllint's layout rule wants DEF bodies at column 0 and 3-space blocks (its house style, not
# KRL syntax); every other rule (keyword/type case — which also catches identifiers that are
# keywords —, whitespace, tabs) must pass
KRLLINT_LAYOUT = ["bad-indentation", "bad-indented-inline-form"]


def krl_findings(files: dict[str, str], tmp: Path) -> list[str]:
    from krllint.linter import Linter
    from krllint.reporter import BaseReporter

    found: list[str] = []

    class Collect(BaseReporter):  # type: ignore[misc]
        def report(self, message) -> None:  # type: ignore[no-untyped-def]
            super().report(message)
            found.append(f"{self._current_file}: {message.line_number}:{message.column} {message.code}")

        def start_file(self, filename) -> None:  # type: ignore[no-untyped-def]
            self._current_file = filename

        def finalize_file(self) -> None:
            pass

        def finalize(self) -> None:
            pass

        def handle_new_file(self) -> None:
            pass

        handle_convention = handle_refactor = handle_warning = handle_error = handle_fatal = \
            lambda self, message: None

    config = Namespace(INDENT_CHAR=" ", INDENT_SIZE=2, DISABLE=KRLLINT_LAYOUT, REPORTER=Collect)
    paths = []
    for name, text in files.items():
        path = tmp / name
        path.write_text(text, encoding="utf-8")
        paths.append(str(path))
    Linter(cli_args=Namespace(target=paths, fix=False, generate_config=False, config=None), config=config).lint()
    return found


def findings(vendor: str, files: dict[str, str], tmp: Path) -> list[str]:
    if vendor == "rapid":
        return rapid_findings(files)
    if vendor == "krl":
        return krl_findings(files, tmp) + check_krl(files)
    if vendor == "fanuc":
        return check_fanuc(files)
    if vendor == "urscript":
        return [f for name, text in files.items() for f in check_urscript(name, text)]
    if vendor == "inform":
        return check_inform(files)
    return check_val3(files)


# Examples that drive external axes (lang/REFERENCE.md §15), and the vendors that refuse them
# with E607: URScript and VAL3 have no external axes. INFORM writes them (the examples declare
# each axis' pulse scale): its validator checks the BC/EC positions, NPOS and the groups.
EXTERNAL_AXES_EXAMPLES = {"weld_positioner", "track_tending"}
REFUSE_EXTERNAL_AXES = {"urscript", "val3"}
# Examples with coordinated motion (a seam in a frame the positioner turns during the move), and the
# vendors that refuse it with E607 at that move: none (INFORM writes it as SMOVL/SMOVC).
COORDINATED_EXAMPLES = {"weld_positioner"}
REFUSE_COORDINATED: set[str] = set()


@pytest.mark.parametrize("vendor", VENDORS)
@pytest.mark.parametrize("example", EXAMPLES)
def test_every_example_file_passes_the_independent_validator(example: str, vendor: str, tmp_path: Path) -> None:
    result = BACKENDS[vendor]().emit(example_plans((example,))[example])
    if (example in EXTERNAL_AXES_EXAMPLES and vendor in REFUSE_EXTERNAL_AXES) or \
            (example in COORDINATED_EXAMPLES and vendor in REFUSE_COORDINATED):
        assert {d.code.id for d in result.diagnostics if d.is_error} == {"E607"}
        return
    assert not result.has_errors, [d.message for d in result.diagnostics if d.is_error]
    assert findings(vendor, result.files, tmp_path) == []


def golden_sets() -> list[tuple[str, str, dict[str, str]]]:
    """(vendor, group, files): golden files grouped by the example they come from."""
    out = []
    for vendor in VENDORS:
        groups: dict[str, dict[str, str]] = defaultdict(dict)
        for path in sorted((GOLDEN / vendor).glob("*")):
            parts = path.name.split("__")
            if vendor == "val3":
                group, name = ("__".join(parts[:-2]), "/".join(parts[-2:]))
            else:
                group, name = ("__".join(parts[:-1]), parts[-1])
            groups[group][name] = path.read_text(encoding="utf-8")
        out += [(vendor, group or "-", files) for group, files in sorted(groups.items())]
    return out


@pytest.mark.parametrize(("vendor", "group", "files"), golden_sets(), ids=lambda v: v if isinstance(v, str) else "")
def test_every_golden_file_passes_the_independent_validator(vendor: str, group: str, files: dict[str, str],
                                                            tmp_path: Path) -> None:
    assert findings(vendor, files, tmp_path) == []


# --------------------------------------------------------------------------- the validators can fail

FANUC_ARC_TERMINATED = """/PROG  A
/ATTR
LINE_COUNT\t= 2;
/MN
   1:  J P[1] 100% FINE ;
   2:  C P[2] ;
    :  P[3] 100mm/sec FINE ;
/POS
P[1]{
   GP1:
\tUF : 0, UT : 1,
};
P[2]{
   GP1:
\tUF : 0, UT : 1,
};
P[3]{
   GP1:
\tUF : 0, UT : 1,
};
/END
"""


def test_fanuc_validator_rejects_a_terminated_circular_line() -> None:
    assert any("without ';'" in f for f in check_fanuc({"A.ls": FANUC_ARC_TERMINATED}))
    fixed = FANUC_ARC_TERMINATED.replace("C P[2] ;", "C P[2]")
    assert check_fanuc({"A.ls": fixed}) == []


def test_urscript_validator_rejects_a_script_that_never_calls_its_program() -> None:
    text = "def prog():\n  movel(p[0, 0, 0.5, 0, 3.14, 0], a=1.2, v=0.25, r=0)\nend\n"
    assert any("end by calling it" in f for f in check_urscript("prog.script", text))
    assert check_urscript("prog.script", text + "prog()\n") == []
    shadow = "def prog():\n  def movel():\n    sleep(0.1)\n  end\n  movel()\nend\nprog()\n"
    assert any("built-in movel" in f for f in check_urscript("prog.script", shadow))


def test_inform_validator_rejects_an_unknown_job_and_a_bad_position() -> None:
    job = ("/JOB\n//NAME A\n//POS\n///NPOS 1,0,0,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
           "///RCONF 0,0,0,0,0,0,0,0\nC00000=1,2,3,4,5,6\n//INST\n///DATE 2000/01/01 00:00\n///COMM a\n"
           "///ATTR SC,RW\n///GROUP1 RB1\nNOP\nMOVL C00000 V=100.0 PL=0\nCALL JOB:B\nEND\n")
    assert any("names no job" in f for f in check_inform({"A.JBI": job}))
    assert check_inform({"A.JBI": job.replace("CALL JOB:B\n", "")}) == []
    assert any("not a position" in f for f in check_inform({"A.JBI": job.replace("CALL JOB:B", "MOVL C00001 V=1.0")}))


def test_inform_validator_rejects_axis_positions_the_header_or_groups_do_not_state() -> None:
    job = ("/JOB\n//NAME A\n//POS\n///NPOS 1,1,1,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
           "///RCONF 0,0,0,0,0,0,0,0\nC00000=1,2,3,4,5,6\n///POSTYPE PULSE\n///PULSE\nBC00000=120000\n"
           "EC00000=0,90000\n//INST\n///DATE 2000/01/01 00:00\n///COMM a\n///ATTR SC,RW\n"
           "///GROUP1 RB1,BS1\n///GROUP2 ST1\nNOP\nMOVL C00000 BC00000 V=100.0 PL=0 +MOVJ EC00000 VJ=50.00\nEND\n")
    assert check_inform({"A.JBI": job}) == []
    assert any("///NPOS must count" in f for f in check_inform({"A.JBI": job.replace("NPOS 1,1,1", "NPOS 1,0,1")}))
    assert any("EC00001 is not a position" in f for f in check_inform({"A.JBI": job.replace("+MOVJ EC00000", "+MOVJ EC00001")}))
    assert any("need ///GROUP1 RB1,BS1" in f for f in check_inform({"A.JBI": job.replace("RB1,BS1", "RB1")}))
    assert any("whole pulses" in f for f in check_inform({"A.JBI": job.replace("BC00000=120000", "BC00000=12.5")}))
    unused = job.replace("EC00000=0,90000\n", "EC00000=0,90000\nEC00001=0,0\n").replace("NPOS 1,1,1", "NPOS 1,1,2")
    assert any("EC00001 is defined but no instruction uses it" in f for f in check_inform({"A.JBI": unused}))


def test_inform_validator_reads_a_track_in_mm_only_under_rectan() -> None:
    """A base axis written in mm (a traveling axis without its pulse scale) stands right after
    the C positions, before ///PULSE; a station axis stays whole pulses."""
    job = ("/JOB\n//NAME A\n//POS\n///NPOS 1,1,1,0,0,0\n///TOOL 0\n///POSTYPE ROBOT\n///RECTAN\n"
           "///RCONF 0,0,0,0,0,0,0,0\nC00000=1,2,3,4,5,6\nBC00000=1200.000\n///POSTYPE PULSE\n///PULSE\n"
           "EC00000=0,90000\n//INST\n///DATE 2000/01/01 00:00\n///COMM a\n///ATTR SC,RW\n"
           "///GROUP1 RB1,BS1\n///GROUP2 ST1\nNOP\nMOVL C00000 BC00000 V=100.0 PL=0 +MOVJ EC00000 VJ=50.00\nEND\n")
    assert check_inform({"A.JBI": job}) == []
    under_pulse = job.replace("BC00000=1200.000\n///POSTYPE PULSE\n///PULSE\n", "///POSTYPE PULSE\n///PULSE\nBC00000=1200.000\n")
    assert any("whole pulses" in f for f in check_inform({"A.JBI": under_pulse}))
    assert any("mm with 3 decimals" in f for f in check_inform({"A.JBI": job.replace("=1200.000", "=1200")}))
    assert any("whole pulses" in f for f in check_inform({"A.JBI": job.replace("EC00000=0,90000", "EC00000=0.000,9.000")}))


def test_val3_validator_rejects_an_index_beyond_the_data_and_an_unlisted_program() -> None:
    plan = example_plans(("inspect",))["inspect"]
    files = BACKENDS["val3"]().emit(plan).files
    assert check_val3(files) == []
    start = next(n for n in files if n.endswith("/start.pgx"))
    broken = {**files, start: files[start].replace("begin\n", "begin\n  movej(jTarget[999], flange, mSpeed[0])\n", 1)}
    assert any("jTarget[999]" in f for f in check_val3(broken))
    extra = {**files, start.replace("start", "orphan"): files[start]}
    assert any("list exactly its .pgx" in f for f in check_val3(extra))


def test_krllint_flags_a_keyword_used_as_a_name(tmp_path: Path) -> None:
    src = "DEF a( )\n  PTP start\nEND\n"
    assert any("wrong-case-keyword" in f for f in krl_findings({"a.src": src}, tmp_path))
    assert krl_findings({"a.src": "DEF a( )\n  PTP home\nEND\n"}, tmp_path) == []


def test_krl_validator_rejects_c_dis_on_ptp_and_undeclared_points() -> None:
    dat = "&ACCESS RVP\nDEFDAT a\n  DECL E6POS p={X 1}\nENDDAT\n"
    src = "&ACCESS RVP\nDEF a( )\n  PTP p C_DIS\n  LIN q\nEND\n"
    found = check_krl({"a.src": src, "a.dat": dat})
    assert any("PTP cannot be approximated with C_DIS" in f for f in found)
    assert any("q is not declared" in f for f in found)
    good = "&ACCESS RVP\nDEF a( )\n  $APO.CPTP=20\n  PTP p C_PTP\n  LIN p C_DIS\nEND\n"
    assert check_krl({"a.src": good, "a.dat": dat}) == []
