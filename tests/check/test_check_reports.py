"""Reports for any input: JUnit valid against the common JUnit schema, CSV cells no spreadsheet runs,
terminal text without escape sequences."""

from __future__ import annotations

import csv
import io
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import xmlschema

from tests.check.helpers import mark_text, tutorial
from tutgen.check.report import render_json, render_junit, render_summary, render_table
from tutgen.check.run import CheckRun, FileResult

SCHEMA = Path(__file__).parent / "junit.xsd"
#: a student's name with every class of hostile character: a formula, CSI and OSC escapes, BEL, NUL,
#: a vertical tab, a C1 control, a bidirectional override, XML markup
NAME = '=HYPERLINK("http://x")\x1b[2J\x1b]0;title\x07\x00\x0b\x9b31m\u202eAda <b>&'


@pytest.fixture(scope="module")
def run() -> CheckRun:
    ref = tutorial(4)
    marked = mark_text(ref, "kinetic_energy: m*r_dot**2\nmass_matrix: {}\n")
    assert not marked.errors, marked.errors
    hostile = FileResult(marked.path, NAME, marked.items)
    invalid = FileResult("bad\x1b[31m.yaml", None, (), ("bad.yaml:1:1: error: \x00broken\x1b[0m",))
    limited = FileResult("slow.yaml", None, (), limit="time limit: 1 s per file")
    return CheckRun(ref.spec, "title \x07", (hostile, invalid, limited))


def test_reports_junit_is_valid_against_the_junit_schema(run: CheckRun) -> None:
    text = render_junit(run)
    xmlschema.XMLSchema(SCHEMA).validate(text)  # raises on the first violation
    root = ET.fromstring(text)
    suite = root.findall("testsuite")[0]
    assert suite.get("timestamp") and suite.get("time") == "0"
    student = suite.find("properties/property[@name='student']")
    assert student is not None and student.get("value") == '=HYPERLINK("http://x")Ada <b>&'
    assert [c.get("name") for c in suite.findall("testcase")] == ["kinetic_energy", "mass_matrix"]
    assert [f.get("type") for f in suite.findall("testcase/failure")] == ["wrong", "missing"]


def test_reports_junit_schema_catches_a_bad_report() -> None:
    """The schema test can fail: a test case without a name, a text timestamp, are refused."""
    schema = xmlschema.XMLSchema(SCHEMA)
    assert not schema.is_valid('<testsuites><testsuite name="a" tests="1"><testcase/></testsuite></testsuites>')
    assert not schema.is_valid('<testsuites><testsuite name="a" tests="0" timestamp="today"/></testsuites>')


def test_reports_csv_cells_are_not_formulas(run: CheckRun) -> None:
    rows = list(csv.DictReader(io.StringIO(render_summary(run, "csv"))))
    assert rows[0]["student"] == '\'=HYPERLINK("http://x")Ada <b>&'
    assert all(not cell.startswith(("=", "+", "-", "@", "\t")) for row in rows for cell in row.values())
    assert [r["status"] for r in rows] == ["fail", "invalid", "time_limit"]


def test_reports_terminal_text_has_no_control_characters(run: CheckRun) -> None:
    text = render_table(run)
    assert not any(c in text for c in "\x1b\x07\x00\x0b\x9b\u202e")
    assert "3 files: 0 pass, 1 fail, 1 invalid, 1 time limit" in text


@pytest.mark.parametrize(
    "render", [render_json, lambda r: render_summary(r, "json")], ids=["check-json", "summary-json"]
)
def test_reports_json_escapes_c1_controls_and_keeps_the_data(run: CheckRun, render: object) -> None:
    """json.dumps escapes only what is below U+0020: a C1 control (CSI, U+009B) or a bidirectional
    override would reach a terminal that shows the JSON. They are escaped; the data is unchanged."""
    text = render(run)  # type: ignore[operator]
    assert not any(c in text for c in "\x1b\x07\x00\x0b\x9b\u202e\x7f")
    assert "\\u009b" in text and "\\u202e" in text
    data = json.loads(text)
    assert data["files"][0]["student"] == NAME
