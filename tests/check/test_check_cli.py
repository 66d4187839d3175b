"""`tutgen check` on the command line: reports, files, exit codes, many files in parallel."""

from __future__ import annotations

import csv
import json
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from typer.testing import CliRunner, Result

import tutgen.engine.pipeline
from tests.check.helpers import TUTORIAL
from tests.conftest import ROOT, solved
from tutgen.check.answers import RESULT_KEYS
from tutgen.cli.main import app
from tutgen.errors import EXIT_CHECK_FAILED, EXIT_INVALID_SPEC, EXIT_OK, EXIT_USAGE

P04 = TUTORIAL / "p04-rp-arm.yaml"
P05 = TUTORIAL / "p05-rr-arm.yaml"
PRINTED = Path(__file__).parent / "answers"
#: The items of the tutorial's problem 5 that its printed answers give (the instructor's marking).
P05_KEY = PRINTED / "p05-key.yaml"
RIGHT = """\
student: Ada
kinetic_energy: m*(r**2*theta_dot**2 + r_dot**2)/2
mass_matrix: [[m*r^2, 0], [0, m]]
equations_of_motion:
  theta: n = m*r**2*theta_ddot + 2*m*r*r_dot*theta_dot + m*g*r*cos(theta)
  r: m*r_ddot - m*r*theta_dot**2 + m*g*sin(theta) - f
potential_energy: m*g*r*sin(theta)
"""
#: The instructor's marking key of these tests: the four items graded, in this order.
KEY = "ask: [kinetic_energy, mass_matrix, equations_of_motion, potential_energy]\n"
WRONG = """\
student: Bob
kinetic_energy: m*(r**2*theta_dot**2 + r_dot**2)/2
mass_matrix: [[m*r^2, 0], [0, 2*m]]
potential_energy: -m*g*r*sin(theta)
"""
INVALID = """\
student: Cy
kinetic_energy: m*(r**2*theta_dot**2 + r_dot**2/2
mas_matrix: 1
"""


@pytest.fixture(autouse=True)
def cached_derive(monkeypatch: pytest.MonkeyPatch) -> None:
    """Serve ``derive`` from the session cache: the command still loads, validates and marks."""
    for spec in (P04, P05):
        solved(str(spec))
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(system.source)[1])


def run(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


def answers(tmp_path: Path, **files: str) -> list[Path]:
    (tmp_path / "key.yaml").write_text(KEY, encoding="utf-8")
    paths = []
    for name, text in files.items():
        path = tmp_path / f"{name}.yaml"
        path.write_text(text, encoding="utf-8")
        paths.append(path)
    return paths


def test_check_cli_all_correct_exits_0(tmp_path: Path) -> None:
    (right,) = answers(tmp_path, right=RIGHT)
    result = run("check", P04, right, "--key", tmp_path / "key.yaml")
    assert result.exit_code == EXIT_OK, result.output
    assert "✓ correct" in result.stdout
    assert "kinetic_energy" in result.stdout and "equations_of_motion" in result.stdout
    assert "4 correct, 0 wrong, 0 missing" in result.stdout
    assert "no marking key" not in result.stdout
    assert "equations_of_motion[1]: the terms are on the other side of '='" in result.stdout
    assert result.stderr == ""


def test_check_cli_wrong_exits_1_and_names_the_entry(tmp_path: Path) -> None:
    (wrong,) = answers(tmp_path, wrong=WRONG)
    result = run("check", P04, wrong)
    assert result.exit_code == EXIT_CHECK_FAILED
    assert "mass_matrix[2,2]: off by a factor 2" in result.stdout
    assert "wrong sign" in result.stdout


def test_check_cli_invalid_answers_exit_3_with_locations(tmp_path: Path) -> None:
    (invalid,) = answers(tmp_path, invalid=INVALID)
    result = run("check", P04, invalid)
    assert result.exit_code == EXIT_INVALID_SPEC  # a key that is no result makes the file invalid
    assert result.stderr.splitlines() == [
        f"{invalid}:3:1: error: unknown result 'mas_matrix'; expected one of: " + ", ".join(RESULT_KEYS),
        "  hint: did you mean 'mass_matrix'?",
    ]
    assert "Traceback" not in result.output


def test_check_cli_invalid_spec_exits_3(tmp_path: Path) -> None:
    spec = tmp_path / "spec.yaml"
    spec.write_text("tutgen: 1\ntitle: x\ncoordinates: [q]\nbodies: {b: {mass: m}}\n", encoding="utf-8")
    (right,) = answers(tmp_path, right=RIGHT)
    result = run("check", spec, right)
    assert result.exit_code == EXIT_INVALID_SPEC
    assert str(spec) in result.stderr and "error:" in result.stderr
    assert "Traceback" not in result.output


@pytest.mark.parametrize(
    "args",
    [
        pytest.param(("check",), id="no-arguments"),
        pytest.param(("check", P04), id="no-answers"),
        pytest.param(("check", P04, "{answers}", "--summary", "{tmp}/summary.txt"), id="summary-extension"),
        pytest.param(("check", P04, "{answers}", "--junit", "{answers}"), id="report-onto-answers"),
        pytest.param(("check", P04, "{answers}", "--jobs", "0"), id="zero-jobs"),
    ],
)
def test_check_cli_usage_errors_exit_2(tmp_path: Path, args: tuple) -> None:
    (right,) = answers(tmp_path, right=RIGHT)
    result = run(*(str(a).format(answers=right, tmp=tmp_path) for a in args))
    assert result.exit_code == EXIT_USAGE, result.output
    assert "Traceback" not in result.output
    assert right.read_text(encoding="utf-8") == RIGHT


def test_check_cli_json_report(tmp_path: Path) -> None:
    (wrong,) = answers(tmp_path, wrong=WRONG)
    result = run("check", P04, wrong, "--format", "json", "--key", tmp_path / "key.yaml")
    assert result.exit_code == EXIT_CHECK_FAILED
    doc = json.loads(result.stdout)
    assert doc["summary"] == {"files": 1, "pass": 0, "fail": 1, "time_limit": 0, "invalid": 0, "error": 0}
    assert doc["marking"] == {"source": "key", "asked": KEY[6:-2].split(", "), "note": ""}
    (f,) = doc["files"]
    assert (f["student"], f["status"], f["counts"]) == (
        "Bob",
        "fail",
        {"correct": 1, "wrong": 2, "missing": 1, "cannot_evaluate": 0, "time_limit": 0},
    )
    matrix = next(i for i in f["items"] if i["name"] == "mass_matrix")
    entry = next(e for e in matrix["entries"] if e["name"] == "mass_matrix[2,2]")
    assert entry == {
        "name": "mass_matrix[2,2]",
        "status": "wrong",
        "how": "",
        "feedback": "off by a factor 2 (yours is 2 times the correct expression)",
        "location": f"{wrong}:3:31",
        "given": "2*m",
        "expected": "m",
    }


def test_check_cli_junit_and_summary_for_a_class(tmp_path: Path) -> None:
    paths = answers(tmp_path, right=RIGHT, wrong=WRONG, invalid=INVALID)
    junit, summary = tmp_path / "report.xml", tmp_path / "summary.csv"
    key = tmp_path / "key.yaml"
    result = run("check", P04, *paths, "--junit", junit, "--summary", summary, "--jobs", "2", "--key", key)
    assert result.exit_code == EXIT_INVALID_SPEC  # an invalid file outranks wrong answers
    assert "3 files: 1 pass, 1 fail, 1 invalid" in result.stdout
    root = ET.parse(junit).getroot()
    assert (root.tag, root.get("tests"), root.get("failures"), root.get("errors")) == ("testsuites", "9", "3", "1")
    suites = root.findall("testsuite")
    assert [s.get("name") for s in suites] == [str(p) for p in paths]
    cases = {c.get("name"): c for c in suites[1].findall("testcase")}
    assert list(cases) == ["kinetic_energy", "mass_matrix", "equations_of_motion", "potential_energy"]
    failure = cases["mass_matrix"].find("failure")
    assert failure is not None and failure.get("type") == "wrong"
    assert failure.get("message") == "mass_matrix[2,2]: off by a factor 2 (yours is 2 times the correct expression)"
    assert suites[2].find("testcase/error") is not None
    with summary.open(encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert [(r["student"], r["status"], r["correct"], r["wrong"], r["wrong_items"]) for r in rows] == [
        ("Ada", "pass", "4", "0", ""),
        ("Bob", "fail", "1", "2", "mass_matrix; equations_of_motion; potential_energy"),
        ("", "invalid", "0", "0", ""),
    ]


def test_check_cli_parallel_output_does_not_depend_on_workers(tmp_path: Path) -> None:
    """Many files in worker processes: results in input order, the same as marking in one process."""
    paths = []
    for i, name in enumerate([PRINTED / "p05-printed.yaml"] * 3):
        copy = tmp_path / f"student{i:02d}.yaml"
        shutil.copy(name, copy)
        paths.append(copy)
    paths += answers(tmp_path, zz_invalid=INVALID.replace("m*(r**2*theta_dot**2 + r_dot**2/2", "m1"))
    one = run("check", P05, *paths, "--format", "json", "-j", "1", "--summary", tmp_path / "one.json", "--key", P05_KEY)
    two = run("check", P05, *paths, "--format", "json", "-j", "2", "--summary", tmp_path / "two.json", "--key", P05_KEY)
    assert one.exit_code == two.exit_code == EXIT_INVALID_SPEC
    assert one.stdout == two.stdout
    assert (tmp_path / "one.json").read_text() == (tmp_path / "two.json").read_text()
    rows = json.loads((tmp_path / "two.json").read_text())["files"]
    assert [r["file"] for r in rows] == [str(p) for p in paths]
    assert {r["wrong_items"] for r in rows[:-1]} == {"lagrange_terms"}


def test_check_cli_tutorial_printed_answers_in_ci(tmp_path: Path) -> None:
    """The CI use: the tutorial's printed answers, a JUnit report naming the typo."""
    junit = tmp_path / "junit.xml"
    result = run("check", P05, PRINTED / "p05-printed.yaml", "--junit", junit, "--key", P05_KEY)
    assert result.exit_code == EXIT_CHECK_FAILED
    failures = ET.parse(junit).getroot().findall(".//failure")
    assert [f.get("message", "").split(":")[0] for f in failures] == ["lagrange_terms[2].dL_dq"]


def test_check_cli_help_mentions_exit_codes() -> None:
    result = run("check", "--help")
    assert result.exit_code == 0
    assert "Exit codes: 0 every answer correct, 1 an answer wrong or missing" in result.stdout
    assert (ROOT / "docs" / "check.md").exists()


def test_check_cli_without_a_key_grades_the_items_the_spec_asks(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """No marking key: one right answer is not a pass. The items graded are derived from the spec's
    ask, and the report says so, so that an instructor does not take the grade for theirs."""
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(str(P04))[1])
    spec = tmp_path / "p04.yaml"  # p04 without its marking: (the tutorial's), so nothing states the items
    spec.write_text(_p04_bare(), encoding="utf-8")
    (one,) = answers(tmp_path, one="kinetic_energy: m*(r**2*theta_dot**2 + r_dot**2)/2\n")
    result = run("check", spec, one, "--junit", tmp_path / "junit.xml")
    assert result.exit_code == EXIT_CHECK_FAILED, result.output
    assert "1 correct, 0 wrong, 9 missing" in result.stdout
    assert "no marking key: 10 items graded, derived from the spec's ask" in result.stdout.replace("\n", " ")
    root = ET.parse(tmp_path / "junit.xml").getroot()
    assert root.get("tests") == "10" and root.get("failures") == "9"
    note = root.find("testsuite/properties/property[@name='marking']")
    assert note is not None and note.get("value", "").startswith("no marking key: 10 items graded")


def _p04_bare() -> str:
    """p04's text without its editor line and its ``marking:`` (and the comment above it): the system
    alone, its lines numbered as the tests below expect."""
    lines = P04.read_text(encoding="utf-8").splitlines(keepends=True)
    drop = ("# yaml-language-server:", "marking:", "# what tutgen check marks")
    return "".join(ln for ln in lines if not ln.startswith(drop))


def _p04_copy(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, extra: str) -> Path:
    """A copy of p04 (bare) with ``extra`` YAML at its end, derived as p04 (the same system)."""
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(str(P04))[1])
    spec = tmp_path / "p04.yaml"
    spec.write_text(_p04_bare() + extra, encoding="utf-8")
    return spec


def test_check_cli_spec_marking_states_the_items(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A spec's ``marking:`` is the instructor's: its ask is graded, with no "no marking key" note."""
    spec = _p04_copy(tmp_path, monkeypatch, "marking:\n  ask: [kinetic_energy]\n")
    (one,) = answers(tmp_path, one="kinetic_energy: m*(r**2*theta_dot**2 + r_dot**2)/2\n")
    result = run("check", spec, one, "--format", "json")
    assert result.exit_code == EXIT_OK, result.output
    doc = json.loads(result.stdout)
    assert doc["marking"] == {"source": "spec", "asked": ["kinetic_energy"], "note": ""}
    assert [i["name"] for i in doc["files"][0]["items"]] == ["kinetic_energy"]


def test_check_cli_spec_marking_errors_are_located(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    line = _p04_bare().count("\n") + 2
    spec = _p04_copy(tmp_path, monkeypatch, "marking:\n  ask: [H, 'mass_matrix[3,3]']\n  toleranse: {}\n")
    (one,) = answers(tmp_path, one="kinetic_energy: 1\n")
    result = run("check", spec, one)
    assert result.exit_code == EXIT_INVALID_SPEC, result.output
    assert f"{spec}:{line}:9: error: unknown result 'H' in the asked item" in result.stderr
    assert f"{spec}:{line + 1}:3: error: unknown key 'toleranse' in 'marking'" in result.stderr
    assert "hint: did you mean 'tolerance'?" in result.stderr
