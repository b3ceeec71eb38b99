"""The verification Report and its four forms: text (compiler style), JSON, JUnit XML, SARIF.

JSON (version 2; `JSON_SCHEMA` below is the normative description):

    {"version": 2,
     "programs": [{"file": str, "cycle_time_s": float | null,
                   "assumptions": {str: str} | null,
                   "tasks": [{"task": str, "robot": str, "cycle_time_s": float,
                              "moving_s": float, "waiting_s": float, "sync_s": float,
                              "accelerations": str,  # the robot's source; "estimate: ..."
                              "instructions": [{"uid": int, "kind": str, "line": int | null,
                                                "start_s": float, "end_s": float,
                                                "variant": int,
                                                "blend_radius_mm": float}],  # moves only
                              "dynamics": {"model": str, "note": str,          # only with
                                           "joints": [{"joint": int,           # check --dynamics
                                                       "unit": "N·m" | "N",
                                                       "peak_torque": float, "rms_torque": float,
                                                       "peak_power_w": float,
                                                       "rated_torque": float | null,
                                                       "utilisation": float | null}] | null}}],
                   "diagnostics": [{"code": "E300", "severity": "error" | "warning" | "note",
                                    "message": str, "file": str | null,
                                    "line": int | null, "col": int | null,
                                    "end_line": int | null, "end_col": int | null,
                                    "time_s": float | null, "end_time_s": float | null,
                                    "bodies": [str, ...],
                                    "amount": {"value": float, "unit": str} | null}]}]}

Lines and columns are 1-based, end_col exclusive (as rmot.lang.source.Span). Times are
seconds on the program's timeline; amounts are in the unit given (mm, deg/s, N·m, ...).
A program whose cycle time is null did not get through planning. Version 2 added
`assumptions` (the timing model behind the cycle time, rmot.sim.timing_report) and `tasks`
(per task the time moving, waiting and synchronising; per instruction its start and end).
A task's `dynamics` (the one optional key; present only with `rmot check --dynamics`) gives
per joint the peak and RMS torque and the peak power by inverse dynamics on the planned
samples, against the model's rated torque; `joints` is null (and `note` says why) when the
model has no inertia data.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import field
from typing import Any

from rmot.lang.diagnostics import Diagnostic, Severity, render
from rmot.lang.record import record
import re
import os
from pathlib import Path

__all__ = ["JSON_SCHEMA", "Report", "format_json", "format_junit", "format_sarif", "format_text",
           "to_json", "validate_json"]

JSON_VERSION = 2


@record
class Report:
    """What verification found for one program. cycle_times: task name -> seconds."""

    program_file: str
    cycle_times: dict[str, float] = field(default_factory=dict)
    diagnostics: tuple[Diagnostic, ...] = ()
    # where the time goes, per task (rmot.sim.timing_report.timing_json); None: not planned
    tasks: tuple[dict[str, Any], ...] | None = None

    @property
    def errors(self) -> tuple[Diagnostic, ...]:
        return tuple(d for d in self.diagnostics if d.severity is Severity.ERROR)

    @property
    def warnings(self) -> tuple[Diagnostic, ...]:
        return tuple(d for d in self.diagnostics if d.severity is Severity.WARNING)

    @property
    def has_errors(self) -> bool:
        return bool(self.errors)

    @property
    def cycle_time(self) -> float | None:
        """The program's cycle time: its longest task (None if nothing was planned)."""
        return max(self.cycle_times.values()) if self.cycle_times else None

    def summary(self) -> str:
        """One line: file, cycle time per task, counts."""
        if self.cycle_time is None:
            timing = "not planned"
        elif len(self.cycle_times) == 1:
            timing = f"cycle time {self.cycle_time:.3f} s"
        else:
            per_task = ", ".join(f"{k} {v:.3f} s" for k, v in self.cycle_times.items())
            timing = f"cycle time {self.cycle_time:.3f} s ({per_task})"
        e, w = len(self.errors), len(self.warnings)
        verdict = "ok" if e == 0 else "FAILED"
        return f"{self.program_file}: {verdict}: {timing}; {e} error{'s' * (e != 1)}, {w} warning{'s' * (w != 1)}"


# --------------------------------------------------------------------------- text


GUARANTEE = ("collisions are checked along the whole path, not only at the samples: a contact "
             "deeper than 0.01 mm between two samples cannot be missed (distance bound, see rmot.sim.collide)")


def format_text(reports: Sequence[Report]) -> str:
    """Every diagnostic in compiler style, one summary line per program, then what the
    collision check guarantees (when anything was verified)."""
    from rmot.sim.timing_report import ASSUMPTIONS_LINE  # late: loads numpy only when this runs

    blocks = [render(d) for r in reports for d in r.diagnostics]
    blocks += [r.summary() for r in reports]
    if any(r.cycle_times for r in reports):
        blocks.append(f"note: {GUARANTEE}")
        blocks.append(f"note: {ASSUMPTIONS_LINE}")
        blocks += [f"note: robot '{t['robot']}' calibrated by the cell: {t['accelerations']}"
                   for r in reports for t in (r.tasks or ()) if "(calibration)" in t.get("accelerations", "")]
    return "\n".join(blocks) + "\n"


# --------------------------------------------------------------------------- JSON


_NULL_INT = {"type": ["integer", "null"]}
_NULL_NUM = {"type": ["number", "null"]}

_NUM = {"type": "number"}
_TASK: dict[str, Any] = {
    "type": "object",
    "required": ["task", "robot", "cycle_time_s", "moving_s", "waiting_s", "sync_s", "instructions"],
    "additionalProperties": False,
    "properties": {
        "task": {"type": "string"}, "robot": {"type": "string"}, "cycle_time_s": _NUM,
        "moving_s": _NUM, "waiting_s": _NUM, "sync_s": _NUM, "accelerations": {"type": "string"},
        "instructions": {"type": "array", "items": {
            "type": "object",
            "required": ["uid", "kind", "line", "start_s", "end_s", "variant"],
            "additionalProperties": False,
            "properties": {"uid": {"type": "integer"}, "kind": {"type": "string"}, "line": _NULL_INT,
                           "start_s": _NUM, "end_s": _NUM, "variant": {"type": "integer"},
                           "blend_radius_mm": _NUM},
        }},
    },
}

# A task's optional `dynamics` block (`rmot check --dynamics`; rmot.compiler.design.dynamics_text).
_DYNAMICS: dict[str, Any] = {
    "type": "object",
    "required": ["model", "joints", "note"],
    "additionalProperties": False,
    "properties": {
        "model": {"type": "string"}, "note": {"type": "string"},
        "joints": {"type": ["array", "null"], "items": {
            "type": "object",
            "required": ["joint", "unit", "peak_torque", "rms_torque", "peak_power_w", "rated_torque", "utilisation"],
            "additionalProperties": False,
            "properties": {"joint": {"type": "integer"}, "unit": {"enum": ["N·m", "N"]},
                           "peak_torque": _NUM, "rms_torque": _NUM, "peak_power_w": _NUM,
                           "rated_torque": _NULL_NUM, "utilisation": _NULL_NUM,
                           "rms_utilisation": _NULL_NUM, "suffices": {"type": ["boolean", "null"]}},
        }},
    },
}
_TASK["properties"]["dynamics"] = _DYNAMICS  # optional: not in _TASK["required"]

JSON_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "$id": "https://rmot.dev/schemas/check-report-2.json",
    "title": "rmot check report, version 2",
    "type": "object",
    "required": ["version", "programs"],
    "additionalProperties": False,
    "properties": {
        "version": {"const": JSON_VERSION},
        "programs": {
            "type": "array",
            "items": {
                "type": "object",
                "required": ["file", "cycle_time_s", "assumptions", "tasks", "diagnostics"],
                "additionalProperties": False,
                "properties": {
                    "file": {"type": "string"},
                    "cycle_time_s": _NULL_NUM,
                    "assumptions": {"type": ["object", "null"]},
                    "tasks": {"type": "array", "items": _TASK},
                    "diagnostics": {
                        "type": "array",
                        "items": {
                            "type": "object",
                            "required": ["code", "severity", "message", "file", "line", "col", "end_line",
                                         "end_col", "time_s", "end_time_s", "bodies", "amount"],
                            "additionalProperties": False,
                            "properties": {
                                "code": {"type": "string", "pattern": "^[EW][0-9]{3}$"},
                                "severity": {"enum": ["error", "warning", "note"]},
                                "message": {"type": "string"},
                                "file": {"type": ["string", "null"]},
                                "line": _NULL_INT, "col": _NULL_INT,
                                "end_line": _NULL_INT, "end_col": _NULL_INT,
                                "time_s": _NULL_NUM, "end_time_s": _NULL_NUM,
                                "bodies": {"type": "array", "items": {"type": "string"}},
                                "amount": {
                                    "type": ["object", "null"],
                                    "required": ["value", "unit"],
                                    "additionalProperties": False,
                                    "properties": {"value": {"type": "number"}, "unit": {"type": "string"}},
                                },
                            },
                        },
                    },
                },
            },
        },
    },
}


def _round(x: float | None, digits: int = 6) -> float | None:
    return None if x is None else round(float(x), digits)


def diagnostic_json(d: Diagnostic) -> dict[str, Any]:
    span = d.span
    return {
        "code": d.code.id,
        "severity": d.severity.value,
        "message": d.message,
        "file": span.path if span else None,
        "line": span.start.line if span else None,
        "col": span.start.col if span else None,
        "end_line": span.end.line if span else None,
        "end_col": span.end.col if span else None,
        "time_s": _round(d.time_s),
        "end_time_s": _round(d.end_time_s),
        "bodies": list(d.bodies),
        "amount": {"value": float(d.amount.value), "unit": d.amount.unit} if d.amount else None,
    }


def to_json(reports: Sequence[Report]) -> dict[str, Any]:
    return {
        "version": JSON_VERSION,
        "programs": [
            {"file": r.program_file, "cycle_time_s": _round(r.cycle_time),
             "assumptions": _assumptions() if r.cycle_times else None,
             "tasks": list(r.tasks or ()),
             "diagnostics": [diagnostic_json(d) for d in r.diagnostics]}
            for r in reports
        ],
    }


def _assumptions() -> dict[str, str]:
    from rmot.sim.timing_report import ASSUMPTIONS  # late: loads numpy only when this runs

    return dict(ASSUMPTIONS)


def format_json(reports: Sequence[Report]) -> str:
    return json.dumps(to_json(reports), indent=2, ensure_ascii=False) + "\n"


_TYPES: dict[str, type | tuple[type, ...]] = {"object": dict, "array": list, "string": str, "integer": int, "number": (int, float),
          "null": type(None), "boolean": bool}


def validate_json(doc: Any, schema: dict[str, Any] = JSON_SCHEMA, where: str = "$") -> list[str]:
    """The subset of JSON Schema that JSON_SCHEMA uses: type, const, enum, pattern, required,
    properties, additionalProperties: false, items. Returns the violations (empty = valid)."""

    errors: list[str] = []
    if "type" in schema:
        types = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        ok = any(isinstance(doc, _TYPES[t]) and not (t in ("integer", "number") and isinstance(doc, bool)) for t in types)
        if not ok:
            return [f"{where}: must be of type {'/'.join(types)} (got {type(doc).__name__})"]
    if "const" in schema and doc != schema["const"]:
        errors.append(f"{where}: must be {schema['const']!r} (got {doc!r})")
    if "enum" in schema and doc not in schema["enum"]:
        errors.append(f"{where}: must be one of {schema['enum']} (got {doc!r})")
    if "pattern" in schema and isinstance(doc, str) and not re.search(schema["pattern"], doc):
        errors.append(f"{where}: must match {schema['pattern']} (got {doc!r})")
    if isinstance(doc, dict):
        for key in schema.get("required", []):
            if key not in doc:
                errors.append(f"{where}: must have key '{key}'")
        props = schema.get("properties", {})
        for key, value in doc.items():
            if key in props:
                errors += validate_json(value, props[key], f"{where}.{key}")
            elif schema.get("additionalProperties") is False:
                errors.append(f"{where}: must not have key '{key}'")
    if isinstance(doc, list) and "items" in schema:
        for i, item in enumerate(doc):
            errors += validate_json(item, schema["items"], f"{where}[{i}]")
    return errors


# --------------------------------------------------------------------------- JUnit


def format_junit(reports: Sequence[Report]) -> str:
    """One testcase per program (time = cycle time), one <failure> per error diagnostic;
    warnings go to the testcase's <system-out>."""
    import xml.etree.ElementTree as ET  # here, not at the top: only JUnit output needs it  # late: loads xml only when this runs

    failures = sum(len(r.errors) for r in reports)
    suites = ET.Element("testsuites", name="rmot check", tests=str(len(reports)), failures=str(failures))
    suite = ET.SubElement(suites, "testsuite", name="rmot check", tests=str(len(reports)),
                          failures=str(failures), errors="0", skipped="0")
    for r in reports:
        case = ET.SubElement(suite, "testcase", classname="rmot.check", name=r.program_file,
                             time=f"{r.cycle_time or 0.0:.3f}")
        for d in r.errors:
            failure = ET.SubElement(case, "failure", message=d.message, type=d.code.id)
            failure.text = render(d)
        if r.warnings:
            out = ET.SubElement(case, "system-out")
            out.text = "\n".join(render(d) for d in r.warnings)
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


# --------------------------------------------------------------------------- SARIF


SARIF_SCHEMA_URI = "https://json.schemastore.org/sarif-2.1.0.json"


def format_sarif(reports: Sequence[Report]) -> str:
    """SARIF 2.1.0: one run, a rule per code used, a result per diagnostic."""
    diags = [d for r in reports for d in r.diagnostics]
    codes = sorted({d.code.id: d.code for d in diags}.values(), key=lambda c: c.id)
    rule_index = {c.id: i for i, c in enumerate(codes)}
    results = []
    for r in reports:
        for d in r.diagnostics:
            result: dict[str, Any] = {
                "ruleId": d.code.id,
                "ruleIndex": rule_index[d.code.id],
                "level": {"error": "error", "warning": "warning", "note": "note"}[d.severity.value],
                "message": {"text": d.message},
                "locations": [_sarif_location(d, r.program_file)],
            }
            props = {k: v for k, v in diagnostic_json(d).items() if k in ("time_s", "end_time_s", "bodies", "amount") and v not in (None, [])}
            if props:
                result["properties"] = props
            results.append(result)
    doc = {
        "$schema": SARIF_SCHEMA_URI,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {
                "name": "rmot",
                "informationUri": "https://rmot.dev",
                "rules": [{"id": c.id, "name": c.name, "shortDescription": {"text": c.summary}} for c in codes],
            }},
            "results": results,
            "properties": {"collisionGuarantee": GUARANTEE},
        }],
    }
    return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"


def _sarif_location(d: Diagnostic, program_file: str) -> dict[str, Any]:
    if d.span is None:
        return {"physicalLocation": {"artifactLocation": {"uri": _uri(program_file)}}}
    s = d.span
    region = {"startLine": s.start.line, "startColumn": s.start.col, "endLine": s.end.line, "endColumn": s.end.col}
    return {"physicalLocation": {"artifactLocation": {"uri": _uri(s.path)}, "region": region}}


def _uri(path: str) -> str:
    """Code-scanning tools want paths relative to the checkout: relative to the working
    directory when the file is inside it, else an absolute file:// URI."""

    absolute = Path(os.path.abspath(path))
    try:
        return absolute.relative_to(Path.cwd()).as_posix()
    except ValueError:
        return absolute.as_uri()
