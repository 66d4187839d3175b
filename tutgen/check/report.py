"""Reports of a check run: a table for the terminal, JSON, JUnit XML, and a per-file summary.

Every function here returns text; the CLI decides where it goes. Output is deterministic (files in
the order given, no durations; JUnit's required ``timestamp`` is the answers file's modification time
and its ``time`` is 0), so reports can be compared between runs.

Everything a student wrote (a name, an answer, a file name) is data: it is stripped of control
characters and escape sequences for the terminal (:func:`tutgen.safetext.terminal_text`), of what
XML 1.0 forbids for JUnit (:func:`tutgen.safetext.xml_text`; the writer escapes markup), and
neutralised for a spreadsheet in the CSV summary (:func:`tutgen.safetext.csv_cell`).
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
import shutil
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from tutgen.check.compare import EntryResult, ItemResult, Status
from tutgen.check.run import CheckRun, FileResult
from tutgen.errors import UsageError
from tutgen.safetext import csv_cell, terminal_text, xml_text
from tutgen.version import __version__

__all__ = [
    "FILE_STATUSES",
    "FORMAT_VERSION",
    "SUMMARY_FIELDS",
    "json_text",
    "plan_reports",
    "render_json",
    "render_junit",
    "render_report",
    "render_summary",
    "render_table",
    "run_to_json",
    "summary_rows",
    "write_reports",
]

#: The version of the layout of the JSON report and the JSON summary (their ``format`` key; additive
#: changes keep it; the schemas are ``tutgen schema --kind check|summary``).
FORMAT_VERSION = 1

#: Columns of the summary (CSV), one row per answers file; also the keys of each JSON summary row.
SUMMARY_FIELDS = (
    "file",
    "student",
    "status",
    "correct",
    "wrong",
    "missing",
    "items",
    "wrong_items",
    "errors",
    "cannot_evaluate",
    "time_limit",
)

_MARKS = {Status.CORRECT: "✓", Status.WRONG: "✗", Status.MISSING: "–", Status.CANNOT_EVALUATE: "?"}
_MARKS[Status.TIME_LIMIT] = "⌛"
_STYLES = {Status.CORRECT: "green", Status.WRONG: "red", Status.MISSING: "yellow", Status.CANNOT_EVALUATE: "magenta"}
_STYLES[Status.TIME_LIMIT] = "magenta"
#: File statuses, in the order the summaries count them.
FILE_STATUSES = ("pass", "fail", "time_limit", "invalid", "error")


# ---------------------------------------------------------------------------------------------
# JSON
# ---------------------------------------------------------------------------------------------


def _entry_json(e: EntryResult) -> dict[str, Any]:
    return {
        "name": e.name,
        "status": e.status.value,
        "how": e.how,
        "feedback": e.feedback,
        "location": e.location,
        "given": e.given,
        "expected": e.expected,
    }


def _item_json(item: ItemResult) -> dict[str, Any]:
    return {
        "name": item.name,
        "status": item.status.value,
        "location": item.location,
        "remarks": list(item.remarks),
        "entries": [_entry_json(e) for e in item.entries],
    }


def _counts(f: FileResult) -> dict[str, int]:
    return {s.value: f.count(s) for s in Status}


def run_to_json(run: CheckRun) -> dict[str, Any]:
    """The whole run as JSON-able data (the structure of ``tutgen check --format json``)."""
    statuses = [f.status for f in run.files]
    return {
        "tutgen": __version__,
        "format": FORMAT_VERSION,
        "spec": run.spec,
        "title": run.title,
        "summary": {"files": len(run.files), **{s: statuses.count(s) for s in FILE_STATUSES}},
        "marking": {"source": run.marking, "asked": list(run.asked), "note": run.marking_note},
        "files": [
            {
                "answers": f.path,
                "student": f.student,
                "status": f.status,
                "counts": _counts(f),
                "errors": list(f.errors),
                "limit": f.limit,
                "items": [_item_json(i) for i in f.items],
            }
            for f in run.files
        ],
    }


#: What ``json.dumps`` leaves raw with ``ensure_ascii=False`` though a terminal or a viewer acts on it:
#: DEL and the C1 controls (U+0080-U+009F, CSI among them), the bidirectional overrides, the line and
#: paragraph separators. Escaped as ``\\uXXXX``: the data is kept, and the JSON means the same.
_JSON_UNSAFE = re.compile("[\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069]")


def json_text(data: Any) -> str:
    """``data`` as indented JSON (UTF-8 text), with every character of :data:`_JSON_UNSAFE` escaped
    (``json.dumps`` escapes only those below U+0020)."""
    text = json.dumps(data, indent=2, ensure_ascii=False)
    return _JSON_UNSAFE.sub(lambda m: f"\\u{ord(m.group()):04x}", text) + "\n"


def render_json(run: CheckRun) -> str:
    return json_text(run_to_json(run))


# ---------------------------------------------------------------------------------------------
# JUnit XML: a test suite per answers file, a test case per answer
# ---------------------------------------------------------------------------------------------


def _details(item: ItemResult) -> str:
    """A failure's text: the entries that are not correct (remarks on the correct ones are not
    failures; they go to the test case's system-out)."""
    return "\n".join(f"{e.name}: {e.status.value}: {e.feedback} ({e.location})" for e in item.problems)


def _remarks(item: ItemResult) -> list[str]:
    """The remarks of an item: its own, and (when it is not correct) those of its correct entries,
    each named, so that they never read as part of what is wrong."""
    if item.status is Status.CORRECT:
        return list(item.remarks)
    return [f"{e.name}: correct: {e.feedback}" for e in item.entries if e.status is Status.CORRECT and e.feedback]


def _line_of(location: str) -> str | None:
    parts = location.rsplit(":", 2)
    return parts[1] if len(parts) == 3 and parts[1].isdigit() else None


def _timestamp(path: str) -> str:
    """JUnit's ``timestamp`` of a suite: the answers file's modification time (UTC, to the second),
    so that the same files give the same report; the epoch when the file cannot be read."""
    try:
        seconds = int(os.stat(path).st_mtime)
    except (OSError, ValueError, OverflowError):
        seconds = 0
    return datetime.fromtimestamp(seconds, UTC).strftime("%Y-%m-%dT%H:%M:%S")


def _xml(text: str) -> str:
    """Text for JUnit: no escape sequences or control characters (a CI page shows it, as a terminal
    would), and only what XML 1.0 allows; ElementTree escapes the markup."""
    return xml_text(terminal_text(text))


def _element(parent: ET.Element, tag: str, attrs: dict[str, str] | None = None, text: str | None = None) -> ET.Element:
    """A sub-element whose attributes and text are made safe with :func:`_xml`."""
    node = ET.SubElement(parent, tag, {k: _xml(v) for k, v in (attrs or {}).items()})
    if text is not None:
        node.text = _xml(text)
    return node


def render_junit(run: CheckRun) -> str:
    """JUnit XML (the common "Jenkins"/Ant dialect, valid against its schema): one ``testsuite`` per
    answers file, one ``testcase`` per item (every asked item, answered or not); a wrong, missing,
    unevaluable or timed-out item is a ``failure``, an invalid file or a bug an ``error``."""
    root = ET.Element("testsuites", name=_xml(f"tutgen check {run.spec}"))
    total = failures = errors = 0
    for f in run.files:
        stem = f.path.rsplit("/", 1)[-1].removesuffix(".yaml").removesuffix(".yml")
        suite = _element(root, "testsuite", {"name": f.path, "timestamp": _timestamp(f.path), "time": "0"})
        props = _element(suite, "properties")
        _element(props, "property", {"name": "spec", "value": run.spec})
        if f.student:
            _element(props, "property", {"name": "student", "value": f.student})
        _element(props, "property", {"name": "marking", "value": run.marking_note or f"stated ({run.marking})"})
        n = fails = errs = 0
        if f.errors:
            case = _element(suite, "testcase", {"classname": stem, "name": "answers file", "file": f.path, "time": "0"})
            kind = "internal" if f.internal else "invalid"
            _element(case, "error", {"type": kind, "message": f.errors[0].split("\n")[0]}, "\n".join(f.errors))
            n, errs = 1, 1
        for item in f.items:
            attrs = {"classname": stem, "name": item.name, "file": f.path, "time": "0"}
            line = _line_of(item.location)
            if line:
                attrs["line"] = line
            case = _element(suite, "testcase", attrs)
            n += 1
            if item.status is not Status.CORRECT:
                fails += 1
                first = item.problems[0]
                message = f"{first.name}: {first.feedback}"
                _element(case, "failure", {"type": item.status.value, "message": message}, _details(item))
            if _remarks(item):
                _element(case, "system-out", None, "\n".join(_remarks(item)))
        for name, value in (("tests", n), ("failures", fails), ("errors", errs), ("skipped", 0)):
            suite.set(name, str(value))
        total, failures, errors = total + n, failures + fails, errors + errs
    root.set("tests", str(total))
    root.set("failures", str(failures))
    root.set("errors", str(errors))
    root.set("time", "0")
    ET.indent(root)
    return '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


# ---------------------------------------------------------------------------------------------
# Summary: one row per answers file (CSV or JSON)
# ---------------------------------------------------------------------------------------------


def summary_rows(run: CheckRun) -> list[dict[str, Any]]:
    rows = []
    for f in run.files:
        counts = _counts(f)
        rows.append(
            {
                "file": f.path,
                "student": f.student or "",
                "status": f.status,
                "correct": counts["correct"],
                "wrong": counts["wrong"],
                "missing": counts["missing"],
                "items": len(f.items),
                "wrong_items": "; ".join(i.name for i in f.items if i.status is not Status.CORRECT),
                "errors": len(f.errors),
                "cannot_evaluate": counts["cannot_evaluate"],
                "time_limit": counts["time_limit"],
            }
        )
    return rows


def render_summary(run: CheckRun, fmt: str) -> str:
    """The summary as ``csv`` or ``json`` text."""
    rows = summary_rows(run)
    if fmt == "json":
        return json_text({"format": FORMAT_VERSION, "spec": run.spec, "files": rows})
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=SUMMARY_FIELDS, lineterminator="\n")
    writer.writeheader()
    # every text cell is neutralised for spreadsheets (a student called "=HYPERLINK(...)"); numbers stay numbers
    writer.writerows({k: csv_cell(v) if isinstance(v, str) else v for k, v in row.items()} for row in rows)
    return buffer.getvalue()


# ---------------------------------------------------------------------------------------------
# The terminal table (rich)
# ---------------------------------------------------------------------------------------------


def _item_details(item: ItemResult) -> str:
    """The details cell of an item's row: what is not correct, how numeric equalities were decided,
    and (for a correct item) its remarks. A wrong item's correct entries get rows of their own."""
    lines = []
    for e in item.entries:
        name = "" if e.name == item.name else f"{e.name}: "
        if e.status is not Status.CORRECT:
            lines.append(f"{name}{e.feedback}  [{e.location}]")
        elif e.how.startswith("numeric") and item.status is Status.CORRECT:
            lines.append(f"{name}{e.how}")
    if item.status is Status.CORRECT:
        lines += item.remarks
    return "\n".join(lines)


def _errors(n: int) -> str:
    return "1 error" if n == 1 else f"{n} errors"


def render_table(run: CheckRun, *, color: bool = False, width: int = 120) -> str:
    """A readable report: one table of answers for a single file; one row per file for several."""
    from rich.console import Console
    from rich.table import Table
    from rich.text import Text as RichText

    def Text(text: str, style: str = "") -> RichText:
        return RichText(terminal_text(text), style=style)

    buffer = io.StringIO()
    console = Console(
        file=buffer, width=width, force_terminal=color, color_system="standard" if color else None, highlight=False
    )
    if len(run.files) == 1:
        f = run.files[0]
        if f.errors:
            console.print(Text(f"{f.path}: invalid answers file ({_errors(len(f.errors))}, listed on stderr)"))
            return buffer.getvalue()
        who = f" ({f.student})" if f.student else ""
        table = Table(title=Text(f"{f.path}{who}: answers to {run.spec}"), title_justify="left")
        table.add_column("", no_wrap=True)
        table.add_column("answer", overflow="fold")
        table.add_column("details", overflow="fold")
        for item in f.items:
            mark = Text(_MARKS[item.status] + " " + item.status.value, style=_STYLES[item.status])
            table.add_row(mark, Text(item.name), Text(_item_details(item)))
            if item.status is not Status.CORRECT:  # a correct entry's remark is not part of what is wrong
                ok = Text(_MARKS[Status.CORRECT] + " " + Status.CORRECT.value, style=_STYLES[Status.CORRECT])
                for e in item.entries:
                    if e.status is Status.CORRECT and (e.feedback or e.how.startswith("numeric")):
                        table.add_row(ok, Text(e.name), Text(e.feedback or e.how))
        console.print(table)
        c = _counts(f)
        extra = "".join(f", {c[s]} {s.replace('_', ' ')}" for s in ("cannot_evaluate", "time_limit") if c[s])
        console.print(f"{c['correct']} correct, {c['wrong']} wrong, {c['missing']} missing{extra}")
        if f.limit:
            console.print(Text(f"{f.path}: stopped before the end ({f.limit})"))
        if run.marking_note:
            console.print(Text(run.marking_note))
        return buffer.getvalue()
    table = Table(title=Text(f"answers to {run.spec}"), title_justify="left")
    for name in ("file", "student", "result", "correct", "wrong", "missing", "not correct"):
        table.add_column(name, overflow="fold", justify="right" if name in ("correct", "wrong", "missing") else "left")
    for f in run.files:
        style = {"pass": "green", "fail": "red"}.get(f.status, "magenta")
        c = _counts(f)
        not_correct = "; ".join(i.name for i in f.items if i.status is not Status.CORRECT)
        if f.errors:
            not_correct = f"invalid file: {_errors(len(f.errors))} (on stderr)"
        if f.limit:
            not_correct = f"stopped: {f.limit}"
        table.add_row(
            Text(f.path),
            Text(f.student or ""),
            Text(f.status, style=style),
            str(c["correct"]),
            str(c["wrong"]),
            str(c["missing"]),
            Text(not_correct),
        )
    console.print(table)
    statuses = [f.status for f in run.files]
    extra = "".join(f", {statuses.count(s)} {s.replace('_', ' ')}" for s in ("time_limit", "error") if s in statuses)
    console.print(
        f"{len(run.files)} files: {statuses.count('pass')} pass, {statuses.count('fail')} fail, "
        f"{statuses.count('invalid')} invalid{extra}"
    )
    if run.marking_note:
        console.print(Text(run.marking_note))
    return buffer.getvalue()


# ---------------------------------------------------------------------------------------------
# Report files
# ---------------------------------------------------------------------------------------------

#: Summary formats by file extension.
SUMMARY_FORMATS = {".csv": "csv", ".json": "json"}


def plan_reports(
    spec: Path, answers: Sequence[Path], *, junit: Path | None, summary: Path | None
) -> list[tuple[Path, str]]:
    """The report files to write, as (path, kind); checked before any marking is done.

    Raises UsageError for a summary that is neither .csv nor .json, two reports onto one file, or a
    report that would overwrite the spec or an answers file. Other existing files are replaced.
    """
    targets: list[tuple[Path, str]] = []
    if junit is not None:
        targets.append((junit, "junit"))
    if summary is not None:
        kind = SUMMARY_FORMATS.get(summary.suffix.lower())
        if kind is None:
            raise UsageError(f"--summary {summary}: the file name must end in .csv or .json")
        targets.append((summary, kind))
    inputs = {p.resolve() for p in (spec, *answers)}
    for path, _ in targets:
        if path.resolve() in inputs:
            raise UsageError(f"refusing to overwrite the input file {path} with a report; choose another name")
        if path.is_dir():
            raise UsageError(f"{path} is a directory; give a file name for the report")
    if len(targets) == 2 and targets[0][0].resolve() == targets[1][0].resolve():
        raise UsageError("--junit and --summary name the same file")
    return targets


def write_reports(run: CheckRun, targets: list[tuple[Path, str]]) -> None:
    """Write each planned report file (through a temporary file and a rename)."""
    from tutgen.api import write_outputs

    texts = [render_junit(run) if kind == "junit" else render_summary(run, kind) for _, kind in targets]
    write_outputs([path for path, _ in targets], texts)


def render_report(run: CheckRun, fmt: str, *, color: bool = False) -> str:
    """The report for stdout: ``table`` or ``json``."""
    if fmt == "json":
        return render_json(run)
    width = shutil.get_terminal_size((120, 24)).columns if color else 120
    return render_table(run, color=color, width=width)
