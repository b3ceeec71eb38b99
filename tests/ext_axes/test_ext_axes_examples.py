"""The two external-axes examples through the real command line: each checks clean (exit 0,
no error or warning, only the W603 note) at about its cycle time, and compiles for RAPID, KRL
and Fanuc TP with only the documented warnings (W411, W415, W416), and for INFORM with the pulse
scales the examples declare (W450, W604 too; weld_positioner's coordinated seam is E607 there);
URScript and VAL3 refuse it with E607 and write nothing for it (lang/REFERENCE.md §15).

(The examples drive external axes, which two of the six controllers and both data formats
refuse, so they are not in test_shipped_examples.py's every-vendor list.)"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from rmot.compiler.cli import cli

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# example -> approximate cycle time (s) from `rmot check`; +-25 % as for the other examples
CYCLE = {"weld_positioner.rmot": 56.0, "track_tending.rmot": 15.4}


def _run(*args: str) -> Result:
    return CliRunner().invoke(cli, list(args))


@pytest.mark.parametrize("name", sorted(CYCLE))
def test_checks_clean(name: str) -> None:
    result = _run("check", str(EXAMPLES / name), "--format", "json")
    assert result.exit_code == 0, result.output
    report = json.loads(result.stdout)["programs"][0]
    # only the note that the pairs the axes move are checked sample by sample (W603)
    assert [(d["code"], d["severity"]) for d in report["diagnostics"]] == [("W603", "note")]
    assert report["cycle_time_s"] == pytest.approx(CYCLE[name], rel=0.25)


@pytest.mark.parametrize("name", sorted(CYCLE))
def test_compiles_for_rapid_krl_fanuc_and_the_others_refuse(name: str, tmp_path: Path) -> None:
    ok = _run("compile", str(EXAMPLES / name), "--target", "rapid", "--target", "krl", "--target", "fanuc",
              "-o", str(tmp_path / "a"))
    assert ok.exit_code == 0, ok.stderr
    # W415 a KUKA arm for ABB or Fanuc; W416 Fanuc UTOOL/UFRAME written by the program, W411 the
    # tool's mass for the Fanuc payload schedule (both explained in pick_place.rmot)
    assert set(re.findall(r"warning\[(W\d+)\]", ok.stderr)) <= {"W411", "W415", "W416"}
    assert {p.name for p in (tmp_path / "a").iterdir()} == {"rapid", "krl", "fanuc", ".rmot.output"}
    informed = _run("compile", str(EXAMPLES / name), "--target", "inform", "-o", str(tmp_path / "i"))
    if name == "weld_positioner.rmot":  # its seam is coordinated motion, which INFORM refuses at the first arc
        assert informed.exit_code != 0 and re.search(r"weld_positioner.rmot:64:3: error\[E607\]: .*coordinated circular",
                                                     informed.stderr), informed.stderr
        return
    assert informed.exit_code == 0, informed.stderr
    # W450 joint targets as Cartesian + RCONF, W604 the station's own VJ (weld_positioner)
    assert set(re.findall(r"warning\[(W\d+)\]", informed.stderr)) <= {"W411", "W415", "W450", "W604"}
    for vendor in ("urscript", "val3"):
        refused = _run("compile", str(EXAMPLES / name), "--target", vendor, "-o", str(tmp_path / vendor))
        assert refused.exit_code != 0 and "error[E607]" in refused.stderr, refused.stderr
        assert not (tmp_path / vendor / vendor).exists()
