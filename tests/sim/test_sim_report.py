"""Report formats (text, JSON + schema, JUnit, SARIF) and the `rmot check` command."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest
from click.testing import CliRunner
from simkit import PROGRAM_PATH, arm3, box, cell, make_plan, source, task_plan

from rmot.compiler.cli import check_cmd
from rmot.sim.report import JSON_SCHEMA, Report, format_json, format_junit, format_sarif, format_text, to_json, validate_json
from rmot.sim.verification import verify_with


def _colliding_report() -> Report:
    file = source()
    c = cell([("r1", (0, 0, 0))], fixtures=[box("post", (0.05, 0.05, 0.05), (0.0, 0.0, 1.2))])
    tp = task_plan("main", "r1", [(0, -1, 0), (0, -1, 0.2), (0, 1, 0.2)], [0.5, 1.0], file)
    return verify_with(make_plan(c, [tp], file), robots={"r1": arm3("r1", vmax=10, amax=100)}, clearance=0.01)


def _clean_report() -> Report:
    return Report("clean.rmot", {"main": 1.5}, ())


@pytest.fixture(scope="module")
def reports() -> list[Report]:
    return [_colliding_report(), _clean_report()]


class TestJson:
    def test_validates_against_schema(self, reports) -> None:
        """The JSON report validates against JSON_SCHEMA, with the documented fields."""
        doc = json.loads(format_json(reports))
        assert validate_json(doc) == []
        assert doc["version"] == 2
        first = doc["programs"][0]
        assert first["assumptions"]["motion_model"].startswith("acceleration-limited")
        assert first["file"] == PROGRAM_PATH and first["cycle_time_s"] == pytest.approx(1.5)
        hit = next(d for d in first["diagnostics"] if d["code"] == "E300")
        assert hit["line"] == 3 and hit["bodies"] == ["r1/link3", "post"]
        assert hit["amount"]["unit"] == "mm" and hit["time_s"] <= hit["end_time_s"]

    def test_validator_rejects_bad_documents(self, reports) -> None:
        """The schema check is real: missing keys, wrong types and extra keys are reported."""
        doc = to_json(reports)
        del doc["programs"][0]["diagnostics"][0]["line"]
        doc["programs"][1]["cycle_time_s"] = "1.5"
        doc["extra"] = 1
        errors = validate_json(doc)
        assert len(errors) == 3
        assert any("line" in e for e in errors) and any("cycle_time_s" in e for e in errors)

    def test_schema_is_itself_json(self) -> None:
        """The schema round-trips through json (it can be published as a file)."""
        assert json.loads(json.dumps(JSON_SCHEMA)) == JSON_SCHEMA

    def test_deterministic(self) -> None:
        """Two runs on the same plan give byte-identical JSON."""
        assert format_json([_colliding_report()]) == format_json([_colliding_report()])


class TestJunitSarifText:
    def test_junit_structure(self, reports) -> None:
        """One testcase per program, one failure per error finding."""
        root = ET.fromstring(format_junit(reports))
        cases = root.findall("./testsuite/testcase")
        assert [c.get("name") for c in cases] == [PROGRAM_PATH, "clean.rmot"]
        assert len(cases[0].findall("failure")) == len(reports[0].errors) >= 1
        assert cases[1].findall("failure") == []
        assert root.get("failures") == str(len(reports[0].errors))

    def test_sarif_structure(self, reports) -> None:
        """SARIF 2.1.0 with a rule per code and a located result per diagnostic."""
        doc = json.loads(format_sarif(reports))
        assert doc["version"] == "2.1.0"
        run = doc["runs"][0]
        rules = [r["id"] for r in run["tool"]["driver"]["rules"]]
        results = run["results"]
        assert len(results) == len(reports[0].diagnostics)
        for r in results:
            assert rules[r["ruleIndex"]] == r["ruleId"]
            assert r["level"] in ("error", "warning", "note")
            region = r["locations"][0]["physicalLocation"]["region"]
            assert region["startLine"] >= 1
        assert "E300" in rules

    def test_text_has_carets_and_summary(self, reports) -> None:
        """Compiler-style diagnostics with the source line, then one summary line per program."""
        text = format_text(reports)
        assert f"{PROGRAM_PATH}:3:3: error[E300]:" in text
        assert "   |   ^~~~" in text
        lines = text.strip().splitlines()
        assert lines[-4].startswith(f"{PROGRAM_PATH}: FAILED: cycle time 1.500 s")
        assert lines[-3] == "clean.rmot: ok: cycle time 1.500 s; 0 errors, 0 warnings"
        assert lines[-2].startswith("note: collisions are checked along the whole path")
        assert lines[-1].startswith("note: timing: acceleration-limited")  # the cycle time's assumptions


class TestCheckCommand:
    @pytest.fixture()
    def fake_pipeline(self, monkeypatch, tmp_path):
        """Stand-ins for the front end + planner: files named bad* are input errors."""
        outcomes = {"dirty.rmot": _colliding_report(), "clean.rmot": _clean_report()}

        def fake_check_one(path, cell=None, project_root=None, clearance=None, images=None):
            name = path.rsplit("/", 1)[-1]
            if name.startswith("bad"):
                return check_cmd.CheckOutcome(Report(path, {}, ()), True)
            return check_cmd.CheckOutcome(outcomes[name], False)

        monkeypatch.setattr(check_cmd, "check_one", fake_check_one)
        return tmp_path

    def test_exit_codes(self, fake_pipeline) -> None:
        """0 clean, 1 with error findings, 2 with an input error or a bad option."""
        run = CliRunner().invoke
        assert run(check_cmd.check, ["clean.rmot"]).exit_code == 0
        assert run(check_cmd.check, ["clean.rmot", "dirty.rmot"]).exit_code == 1
        assert run(check_cmd.check, ["dirty.rmot", "bad.rmot"]).exit_code == 2
        assert run(check_cmd.check, ["clean.rmot", "--clearance", "10"]).exit_code == 2
        assert run(check_cmd.check, []).exit_code == 2

    def test_jobs_keep_input_order(self, fake_pipeline) -> None:
        """--jobs 2 gives the same bytes as a serial run, programs in input order."""
        run = CliRunner().invoke
        serial = run(check_cmd.check, ["dirty.rmot", "clean.rmot", "--format", "json"])
        parallel = run(check_cmd.check, ["dirty.rmot", "clean.rmot", "--format", "json", "--jobs", "2"])
        assert serial.output == parallel.output
        assert [p["file"] for p in json.loads(serial.output)["programs"]] == [PROGRAM_PATH, "clean.rmot"]

    def test_output_file(self, fake_pipeline) -> None:
        """-o writes the report to a file (and nothing to stdout)."""
        out = fake_pipeline / "report.xml"
        result = CliRunner().invoke(check_cmd.check, ["clean.rmot", "--format", "junit", "-o", str(out)])
        assert result.exit_code == 0 and result.output == ""
        assert ET.parse(out).getroot().tag == "testsuites"


def test_guarantee_text_matches_the_tolerance() -> None:
    """The guarantee printed in reports states the tolerance the collision check uses."""
    from rmot.sim.collide import CONTACT_TOL
    from rmot.sim.report import GUARANTEE

    assert f"deeper than {CONTACT_TOL * 1000:g} mm" in GUARANTEE


def test_parse_length() -> None:
    """--clearance takes a length with a unit."""
    assert check_cmd.parse_length("10mm") == pytest.approx(0.01)
    assert check_cmd.parse_length("1.5 cm") == pytest.approx(0.015)
    assert check_cmd.parse_length("0.02m") == pytest.approx(0.02)
    with pytest.raises(ValueError, match="unit"):
        check_cmd.parse_length("10")


def test_missing_program_is_input_error(tmp_path) -> None:
    """A program path that does not exist is the front end's E501, exit code 2."""
    result = CliRunner().invoke(check_cmd.check, [str(tmp_path / "nope.rmot")])
    assert result.exit_code == 2
    assert "error[E501]: file" in result.output and "must be readable" in result.output
