"""`rmot merge-reports REPORT... -o FILE`: one report from the shards of a CI matrix.

Each runner of an N-way matrix writes its share (`rmot check --shard K/N --format junit|sarif|json`);
a final job merges them. The format is read from the files themselves, and all must agree:

- JUnit XML: every <testcase> in one <testsuite>, ordered by program, counts recomputed.
- SARIF 2.1.0: one run; the rules are the union (by id, sorted) and every result's ruleIndex
  is recomputed; results keep their order within a shard, shards ordered by program.
- rmot JSON (`--format json`): the programs of every report, ordered by file; the version and
  every other top-level member must be equal.

Ordering by program makes the merged file independent of the order the shards are given in
and equal to an unsharded `rmot check` of the programs sorted by path.

Reports are data: XML with a DOCTYPE or entity declaration is refused (no entity expansion),
JSON with NaN/Infinity or nested over 64 levels is refused, a SARIF run is checked for the shape the
merge reads, and a file over 64 MiB is refused before it is read.
Exit codes: 0 merged, 2 an input could not be read or the inputs do not fit together.
"""

from __future__ import annotations

import json
import os
import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import Any

import click

from rmot.compiler.cli import EXIT_INPUT
from rmot.lang.input_file import read_regular
from rmot.compiler.cli import codes
from rmot.lang.diagnostics import Diagnostic, Severity, render
from rmot.lang.atomic import write_text

__all__ = ["MergeError", "merge_documents", "merge_reports"]

MAX_REPORT_BYTES = 64 * 1024 * 1024
_FORBIDDEN_XML = (b"<!DOCTYPE", b"<!ENTITY")


class MergeError(Exception):
    """A report that cannot be merged; `code` is one of rmot.compiler.cli.codes."""

    def __init__(self, code: Any, message: str) -> None:
        super().__init__(message)
        self.code = code


def _codes() -> Any:

    return codes


def _read(path: str) -> bytes:
    codes = _codes()
    try:
        size = os.path.getsize(path)
        if size > MAX_REPORT_BYTES:
            raise MergeError(codes.REPORT_UNREADABLE,
                             f"report '{path}' has {size} bytes, more than the {MAX_REPORT_BYTES} allowed")
        return read_regular(path, MAX_REPORT_BYTES)
    except OSError as exc:
        raise MergeError(codes.REPORT_UNREADABLE, f"cannot read report '{path}': {exc.strerror or exc}") from None


def _reject_constant(name: str) -> Any:
    raise ValueError(f"non-finite number {name}")


def parse_document(path: str, data: bytes) -> tuple[str, Any]:
    """('junit', Element) | ('sarif', dict) | ('json', dict); MergeError otherwise."""
    codes = _codes()
    head = data.lstrip()[:1]
    if head == b"<":
        if any(marker in data for marker in _FORBIDDEN_XML):
            raise MergeError(codes.REPORT_FORMAT, f"report '{path}' declares a DOCTYPE or entities; refused")
        try:
            root = ET.fromstring(data)
        except (ET.ParseError, LookupError, ValueError) as exc:  # LookupError: an encoding Python does not know
            raise MergeError(codes.REPORT_FORMAT, f"report '{path}' is not well-formed XML ({exc})") from None
        if root.tag != "testsuites":
            raise MergeError(codes.REPORT_FORMAT, f"report '{path}' is XML but not JUnit (root <{root.tag}>)")
        return "junit", root
    try:
        doc = json.loads(data.decode("utf-8"), parse_constant=_reject_constant)
    except RecursionError:  # the decoder recurses per level: 200,000 nested arrays
        raise MergeError(codes.REPORT_FORMAT, f"report '{path}' nests JSON values too deeply (an rmot report nests "
                         f"fewer than {MAX_JSON_DEPTH} levels)") from None
    except (UnicodeDecodeError, ValueError) as exc:
        raise MergeError(codes.REPORT_FORMAT,
                         f"report '{path}' is neither JUnit XML nor JSON ({exc.__class__.__name__}: {exc})") from None
    _check_depth(path, doc)
    if isinstance(doc, dict) and doc.get("version") == "2.1.0" and isinstance(doc.get("runs"), list):
        if len(doc["runs"]) != 1 or not isinstance(doc["runs"][0], dict):
            raise MergeError(codes.REPORT_FORMAT, f"report '{path}' is SARIF with {len(doc['runs'])} runs; rmot writes one")
        _check_sarif(path, doc["runs"][0])
        return "sarif", doc
    if isinstance(doc, dict) and isinstance(doc.get("programs"), list) and "version" in doc:
        from rmot.sim.report import JSON_SCHEMA, JSON_VERSION, validate_json  # late: loads numpy only when this runs

        # a report of this version is checked against its schema; another version's (an older
        # rmot's) only when mixed with others (REPORTS_MISMATCH), but its version is a number
        schema = JSON_SCHEMA if doc["version"] == JSON_VERSION else {"properties": {"version": {"type": "integer"}}}
        problems = validate_json(doc, schema)
        if problems:
            more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
            raise MergeError(codes.REPORT_FORMAT, f"report '{path}' is not an rmot check report this version "
                             f"writes: {problems[0][:200]}{more}")
        return "json", doc
    raise MergeError(codes.REPORT_FORMAT, f"report '{path}' is JSON but neither SARIF 2.1.0 nor an rmot check report")


# Policy: an rmot report nests 7 levels (SARIF: runs, results, locations, physicalLocation,
# region); 64 leaves room for any member a reader adds and keeps the merge's own recursion
# (json.dumps with indent recurses once per level) far from Python's limit.
MAX_JSON_DEPTH = 64


def _check_depth(path: str, doc: Any) -> None:
    """MergeError when a value of `doc` nests more than MAX_JSON_DEPTH levels (checked without recursion)."""
    stack = [(doc, 1)]
    while stack:
        value, depth = stack.pop()
        if depth > MAX_JSON_DEPTH:
            raise MergeError(_codes().REPORT_FORMAT, f"report '{path}' nests JSON values more than {MAX_JSON_DEPTH} "
                             "levels deep (an rmot report nests fewer)")
        children = value.values() if isinstance(value, dict) else value if isinstance(value, list) else ()
        stack.extend((child, depth + 1) for child in children)


def _check_sarif(path: str, run: dict[str, Any]) -> None:
    """MergeError naming the first member of a SARIF run that does not have the shape the merge reads."""
    def fail(where: str, wanted: str, got: Any) -> None:
        raise MergeError(_codes().REPORT_FORMAT, f"report '{path}': SARIF member {where} must be {wanted} "
                         f"(got {type(got).__name__} {json.dumps(got)[:40]})")

    tool = run.get("tool", {})
    if not isinstance(tool, dict):
        fail("runs[0].tool", "an object", tool)
    driver = tool.get("driver", {})
    if not isinstance(driver, dict):
        fail("runs[0].tool.driver", "an object", driver)
    for name, items in (("tool.driver.rules", driver.get("rules", [])), ("results", run.get("results", []))):
        if not isinstance(items, list):
            fail(f"runs[0].{name}", "an array", items)
        key = "id" if name.endswith("rules") else "ruleId"
        for k, item in enumerate(items):
            if not isinstance(item, dict) or not isinstance(item.get(key), str):
                fail(f"runs[0].{name}[{k}]", f"an object with a string '{key}'", item)
            locations = item.get("locations", [])
            if not isinstance(locations, list) or not all(isinstance(loc, dict) for loc in locations):
                fail(f"runs[0].{name}[{k}].locations", "an array of objects", locations)


# --------------------------------------------------------------------------- JUnit


def _merge_junit(roots: list[ET.Element]) -> str:
    cases = [case for root in roots for suite in root.iter("testsuite") for case in suite.findall("testcase")]
    cases.sort(key=lambda c: c.get("name", ""))
    failures = sum(len(c.findall("failure")) for c in cases)
    suites = ET.Element("testsuites", name="rmot check", tests=str(len(cases)), failures=str(failures))
    suite = ET.SubElement(suites, "testsuite", name="rmot check", tests=str(len(cases)),
                          failures=str(failures), errors="0", skipped="0")
    suite.extend(cases)
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


# --------------------------------------------------------------------------- SARIF


def _first_uri(doc: dict[str, Any]) -> str:
    for result in doc["runs"][0].get("results", []):
        for loc in result.get("locations", []):
            physical = loc.get("physicalLocation")
            artifact = physical.get("artifactLocation") if isinstance(physical, dict) else None
            uri = artifact.get("uri") if isinstance(artifact, dict) else None
            if isinstance(uri, str):
                return uri
    return ""


def _merge_sarif(docs: list[dict[str, Any]]) -> str:
    codes = _codes()
    rules: dict[str, dict[str, Any]] = {}
    for doc in docs:
        for rule in doc["runs"][0].get("tool", {}).get("driver", {}).get("rules", []):
            known = rules.setdefault(rule["id"], rule)
            if known != rule:
                raise MergeError(codes.REPORTS_MISMATCH,
                                 f"rule {rule['id']} is described differently in two reports (different rmot versions?)")
    order = sorted(rules)
    index = {rule_id: k for k, rule_id in enumerate(order)}
    results = []
    for doc in sorted(docs, key=_first_uri):
        for result in doc["runs"][0].get("results", []):
            if result["ruleId"] not in index:
                raise MergeError(codes.REPORT_FORMAT, f"a SARIF result has rule {result['ruleId'][:40]!r}, which no report's "
                                 "tool.driver.rules describes")
            results.append({**result, "ruleIndex": index[result["ruleId"]]})
    run0 = docs[0]["runs"][0]
    tool0 = run0.get("tool", {})  # optional members, as _check_sarif reads them
    driver = {**tool0.get("driver", {}), "rules": [rules[r] for r in order]}
    run = {**run0, "tool": {**tool0, "driver": driver}, "results": results}
    merged = {**docs[0], "runs": [run]}
    return json.dumps(merged, indent=2, ensure_ascii=False) + "\n"


# --------------------------------------------------------------------------- rmot JSON


def _merge_json(docs: list[dict[str, Any]]) -> str:
    codes = _codes()
    base = {k: v for k, v in docs[0].items() if k != "programs"}
    for doc in docs[1:]:
        other = {k: v for k, v in doc.items() if k != "programs"}
        if other != base:
            differing = sorted(k for k in set(base) | set(other) if base.get(k) != other.get(k))
            raise MergeError(codes.REPORTS_MISMATCH, f"reports differ in {', '.join(differing)}; "
                             "they were written by different rmot versions or options")
    programs = [p for doc in docs for p in doc["programs"]]
    programs.sort(key=lambda p: str(p.get("file", "")) if isinstance(p, dict) else "")
    return json.dumps({**docs[0], "programs": programs}, indent=2, ensure_ascii=False) + "\n"


_MERGERS: dict[str, Callable[[list[Any]], str]] = {"junit": _merge_junit, "sarif": _merge_sarif, "json": _merge_json}


def merge_documents(parsed: list[tuple[str, str, Any]]) -> tuple[str, str]:
    """[(path, format, document)] -> (format, merged text)."""
    codes = _codes()
    formats = {fmt for _, fmt, _ in parsed}
    if len(formats) != 1:
        listing = ", ".join(f"{path} ({fmt})" for path, fmt, _ in parsed)
        raise MergeError(codes.REPORTS_MISMATCH, f"reports must all have one format; got {listing}")
    fmt = formats.pop()
    return fmt, _MERGERS[fmt]([doc for _, _, doc in parsed])


def merge_reports(paths: list[str]) -> tuple[str, str]:
    parsed = []
    for path in paths:
        fmt, doc = parse_document(path, _read(path))
        parsed.append((path, fmt, doc))
    return merge_documents(parsed)


@click.command("merge-reports")
@click.argument("reports", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None, help="Write the merged report to FILE.")
def merge_reports_cmd(reports: tuple[str, ...], output: str | None) -> None:
    """Merge the JUnit, SARIF or JSON reports of `rmot check --shard K/N` runs into one."""

    try:
        _, text = merge_reports(list(reports))
        if output:
            _write_atomic(output, text)
        else:
            click.echo(text, nl=False)
    except MergeError as exc:
        click.echo(render(Diagnostic(exc.code, Severity.ERROR, str(exc), None)), err=True)
        click.get_current_context().exit(EXIT_INPUT)


def _write_atomic(path: str, text: str) -> None:
    """The one atomic writer (lang/atomic.py); a failure is a MergeError (REPORT_UNWRITABLE)."""

    try:
        write_text(path, text)
    except OSError as exc:
        raise MergeError(_codes().REPORT_UNWRITABLE, f"cannot write '{path}': {exc.strerror or exc}") from None
