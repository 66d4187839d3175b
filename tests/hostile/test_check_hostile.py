"""Hostile answers files through `tutgen check`: the right verdict for each, and a class run no file can stop.

The files of ``tests/hostile/check/`` are a hostile student's and a careless instructor's attempts from
issue 13 (empty answers, poles everywhere, hidden zeros, tiny scale factors, tolerances set by the
student, one entry answered three ways, expansion bombs, answers without a real value, control
characters in the name). They are marked together, as one class, the way an instructor runs check:
every file must get its own verdict, the summary and the JUnit report must be written and well
formed, the exit status must be the worst file's, and no marking process may be left behind.
"""

from __future__ import annotations

import csv
import json
import os
import tempfile
import time
import xml.etree.ElementTree as ET
from functools import cache
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner, Result

import tutgen.engine.pipeline
from tests.conftest import ROOT, SPECS, solved
from tutgen.cli.main import app
from tutgen.errors import EXIT_CHECK_FAILED, EXIT_INVALID_SPEC, EXIT_USAGE

DATA = ROOT / "tests" / "hostile" / "check"
P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"
P01 = SPECS / "tutorial-1" / "p01-composite-inertia.yaml"


@cache
def p05_bare() -> Path:
    """p05 without its ``marking:`` (the tutorial's items): the class runs below mark with no key at all,
    so the items graded are derived from the spec's ask. Derived as p05 (see ``cached_derive``)."""
    lines = P05.read_text(encoding="utf-8").splitlines(keepends=True)
    bare = Path(tempfile.mkdtemp(prefix="tutgen-hostile-")) / "p05-rr-arm.yaml"
    bare.write_text("".join(ln for ln in lines if not ln.startswith(("marking:", "# what tutgen check marks"))))
    return bare


#: What the spec p05 asks for (its `ask`: everything), so what a file that answers nothing misses.
P05_ASKED = [
    "kinetic_energy",
    "potential_energy",
    "lagrangian",
    "lagrange_terms",
    "mass_matrix",
    "coriolis_vector",
    "gravity_vector",
    "equations_of_motion",
    "christoffel",
]
MISSING_ALL = dict.fromkeys(P05_ASKED, "missing")
#: file -> (file status, {item: status}) for the class run on p05, with no marking key: every item the
#: spec's ask derives is graded, so a file that answers one item right still fails (the others are
#: missing); None: the items are not checked
EXPECTED: dict[str, tuple[str, dict[str, str] | None]] = {
    "empty.yaml": ("fail", MISSING_ALL),
    "only-student.yaml": ("fail", MISSING_ALL),
    "empty-mass-matrix.yaml": ("fail", {"mass_matrix": "missing"}),
    "list-of-empty-mappings.yaml": ("fail", {"mass_matrix": "missing"}),
    "empty-tables.yaml": ("fail", {"christoffel": "missing", "equations_of_motion": "missing"}),
    "pole-everywhere.yaml": ("fail", {"kinetic_energy": "cannot_evaluate"}),
    "hidden-zero-huge.yaml": ("fail", {"kinetic_energy": "cannot_evaluate"}),
    "hidden-zero-moderate.yaml": ("fail", {"kinetic_energy": "wrong"}),
    "hidden-zero-right.yaml": ("fail", {"kinetic_energy": "correct"}),
    "scaled-tiny.yaml": ("fail", {"equations_of_motion": "wrong"}),
    "scaled-moderate.yaml": ("fail", {"equations_of_motion": "correct"}),
    "tolerance-in-answers.yaml": ("invalid", None),
    "item-tolerance.yaml": ("invalid", None),
    "answered-three-times.yaml": ("invalid", None),
    "expansion-bomb.yaml": ("fail", {"kinetic_energy": "wrong"}),
    "oscillating.yaml": ("fail", {"kinetic_energy": "wrong"}),
    "slow-expansion.yaml": ("fail", {"kinetic_energy": "time_limit"}),
    "control-characters.yaml": ("fail", {"kinetic_energy": "correct"}),
}
P01_EXPECTED = {
    "p01-sqrt-of-negative.yaml": "cannot_evaluate",
    "p01-acos-of-two.yaml": "cannot_evaluate",
    "p01-cube-root-of-negative.yaml": "cannot_evaluate",
    "p01-division-by-hidden-zero.yaml": "cannot_evaluate",
    "p01-exp-1000.yaml": "wrong",
}


@pytest.fixture(autouse=True)
def cached_derive(monkeypatch: pytest.MonkeyPatch) -> None:
    """Serve ``derive`` from the session cache: the command still loads, validates and marks."""
    for spec in (P05, P01):
        solved(str(spec))
    same = {str(p05_bare()): str(P05)}
    monkeypatch.setattr(
        tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(same.get(system.source, system.source))[1]
    )


def children() -> list[int]:
    """The processes whose parent is this one (marking processes left behind would show here)."""
    mine = str(os.getpid())
    out = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        if stat.rsplit(")", 1)[1].split()[1] == mine:
            out.append(int(entry.name))
    return out


def run(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


def by_file(report: dict[str, Any]) -> dict[str, dict[str, Any]]:
    return {Path(f["answers"]).name: f for f in report["files"]}


def test_check_hostile_class_run(tmp_path: Path) -> None:
    """Every hostile file marked in one class run: its own verdict, every report written, worst exit."""
    files = [DATA / name for name in EXPECTED]
    junit, summary = tmp_path / "junit.xml", tmp_path / "summary.csv"
    before = set(children())
    result = run(
        "check",
        p05_bare(),
        *files,
        "--format",
        "json",
        "--junit",
        junit,
        "--summary",
        summary,
        "--timeout",
        "2",
        "-j",
        "2",
    )
    assert set(children()) <= before, "a marking process was left running"
    assert result.exit_code == EXIT_INVALID_SPEC, result.output  # the worst verdict: invalid files
    assert "Traceback" not in result.output
    report = by_file(json.loads(result.stdout))
    for name, (status, items) in EXPECTED.items():
        marked = report[name]
        assert marked["status"] == status, (name, marked)
        if items is not None:
            assert {i["name"]: i["status"] for i in marked["items"]} == MISSING_ALL | items, name
    # the class summary, one row per file, always written; a student's formula is not a formula
    with summary.open(encoding="utf-8") as fh:
        rows = {Path(r["file"]).name: r for r in csv.DictReader(fh)}
    assert set(rows) == set(EXPECTED)
    assert rows["control-characters.yaml"]["student"] == '\'=HYPERLINK("http://evil")'
    assert rows["empty.yaml"]["missing"] == str(len(P05_ASKED))
    # JUnit: well formed for any input (ElementTree parses it), every asked item a test case
    root = ET.parse(junit).getroot()
    suites = {Path(s.get("name", "")).name: s for s in root.findall("testsuite")}
    assert [c.get("name") for c in suites["empty.yaml"].findall("testcase")] == P05_ASKED
    student = suites["control-characters.yaml"].find("properties/property[@name='student']")
    assert student is not None and student.get("value") == '=HYPERLINK("http://evil")'
    # no marking key: the reports say the items graded were derived, not stated
    assert json.loads(result.stdout)["marking"]["source"] == "derived"
    assert json.loads(result.stdout)["marking"]["asked"] == P05_ASKED


def test_check_hostile_numbers_without_a_real_value() -> None:
    """``sqrt(-1)``, ``acos(2)``, ``(-8)**(1/3)``, ``1/0`` in disguise: "cannot be evaluated", never exit 70."""
    result = run("check", P01, *(DATA / n for n in P01_EXPECTED), "--format", "json")
    assert result.exit_code == EXIT_CHECK_FAILED, result.output
    report = by_file(json.loads(result.stdout))
    assert {n: report[n]["items"][0]["status"] for n in P01_EXPECTED} == P01_EXPECTED


def test_check_hostile_file_time_limit_kills_the_file_not_the_run(tmp_path: Path) -> None:
    """With no per-answer limit, a slow file is stopped at --file-timeout; the next file is still marked."""
    summary = tmp_path / "summary.json"
    files = [DATA / "slow-expansion.yaml", DATA / "hidden-zero-right.yaml"]
    before = set(children())
    start = time.monotonic()
    result = run("check", p05_bare(), *files, "--timeout", "0", "--file-timeout", "1", "--summary", summary, "-j", "1")
    elapsed = time.monotonic() - start
    assert set(children()) <= before, "a marking process was left running"
    assert result.exit_code == EXIT_CHECK_FAILED, result.output
    rows = {Path(r["file"]).name: r for r in json.loads(summary.read_text())["files"]}
    assert rows["slow-expansion.yaml"]["status"] == "time_limit"
    assert rows["slow-expansion.yaml"]["time_limit"] == len(P05_ASKED)  # every asked item: not checked
    assert rows["hidden-zero-right.yaml"]["correct"] == 1  # marked: its one answer is right
    assert elapsed < 60, "the file limit did not stop the slow file"  # 36 s of expansion when unbounded


def test_check_hostile_fifo_is_refused_up_front(tmp_path: Path) -> None:
    fifo = tmp_path / "answers.yaml"
    os.mkfifo(fifo)
    result = run("check", P05, fifo)
    assert result.exit_code == EXIT_USAGE
    assert f"error: {fifo} is a FIFO; give a YAML file" in result.output


def test_check_hostile_terminal_report_has_no_escape_sequences() -> None:
    result = run("check", P05, DATA / "control-characters.yaml")
    assert "\x1b" not in result.stdout and "\x07" not in result.stdout and "\x00" not in result.stdout
    assert '=HYPERLINK("http://evil")' in result.stdout
