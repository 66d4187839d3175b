"""The sheet file and the roster: read, checked, every problem reported at its ``file:line:col``.

A sheet file (docs/sheets.md)::

    tutgen_sheet: 1                       # optional: the sheet format version
    title: Tutorial 1
    course: ME4245 Robot Kinematics, Dynamics and Control
    date: 2 February 2026                 # text, printed as written (never today's date)
    problems:
      - p01-composite-inertia.yaml        # a spec, relative to the sheet file
      - spec: p03-cart-pendulum.yaml      # or a spec whose parameters the sheet varies
        vary:
          m1: {range: [1, 5], step: 0.5, unit: kg}
          g: 9.81 m/s^2                   # a value: the same for every variant

``vary`` entries have the form of a spec's ``parameters`` entries (docs/spec-format.md): they replace the
spec's entry of that parameter (keeping its ``latex``, ``description`` and ``dimension``), so the spec file
itself stays as it is. A roster is a CSV file with a header naming ``id`` (and optionally ``name``),
read strictly: an unclosed quote, a stray quote, a field longer than :data:`MAX_ROSTER_FIELD`
characters is an error at its line (never a silently swallowed rest of the file).
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
import stat
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from tutgen.errors import Location, SpecError, SpecErrors
from tutgen.model.marking import Marking
from tutgen.model.system import System
from tutgen.spec.builders.marking import read_marking
from tutgen.spec.expr import did_you_mean
from tutgen.spec.loader import SourceMap, load_yaml_file, load_yaml_text
from tutgen.spec.richtext import RichTextError, parse_rich_text

SHEET_FORMAT_VERSION = 1
SHEET_KEYS = ("tutgen_sheet", "title", "course", "date", "problems", "marking")
PROBLEM_KEYS = ("spec", "vary", "marking")
#: What a variant or a student id may look like: it names a directory.
ID_RE = re.compile(r"[A-Za-z0-9][A-Za-z0-9._-]{0,63}")
#: The longest field (in characters) a roster may hold; the longest roster file (in bytes).
MAX_ROSTER_FIELD = 1000
MAX_ROSTER_BYTES = 16 * 1024 * 1024
#: Ids that cannot name a student's directory: the sheet's own file beside them (``variants/index.csv``)
#: and the names Windows reserves for devices, with or without an extension (``CON``, ``nul.txt``), in
#: any case.
RESERVED_IDS = frozenset({"index.csv"})
WINDOWS_DEVICES = frozenset(
    {"con", "prn", "aux", "nul", *(f"com{i}" for i in range(10)), *(f"lpt{i}" for i in range(10))}
)


@dataclass(frozen=True)
class SheetProblem:
    """One problem of a sheet: its spec (as written and as the sheet varies it) and its base System."""

    number: int  # 1-based, in sheet order
    key: str  # the spec's file stem: names its key and concrete spec files
    path: Path
    text: str  # the spec text with the sheet's ``vary`` entries put in (the spec file's text without)
    system: System  # parameters at their nominal values; ``choices`` where they vary
    marking: Marking | None = None  # what is marked: the problem's ``marking:``, else the sheet's


@dataclass(frozen=True)
class Sheet:
    path: Path
    title: str
    course: str
    date: str
    problems: tuple[SheetProblem, ...]


@dataclass(frozen=True)
class Student:
    id: str
    name: str


def _error(
    smap: SourceMap, keypath: tuple[Any, ...], message: str, hint: str | None = None, key: bool = False
) -> SpecError:
    loc = smap.key_location(keypath) if key else smap.location(keypath)
    return SpecError(loc, message, hint)


def _unknown_key(smap: SourceMap, keypath: tuple[Any, ...], name: str, known: tuple[str, ...], where: str) -> SpecError:
    close = did_you_mean(name, known)
    return _error(
        smap,
        keypath,
        f"unknown key '{name}' in {where}; expected one of: {', '.join(known)}",
        f"did you mean '{close}'?" if close else None,
        key=True,
    )


def _text_field(data: dict[str, Any], smap: SourceMap, key: str, errors: list[SpecError], required: bool) -> str:
    value = data.get(key)
    if value is None:
        if required:
            errors.append(SpecError(Location(smap.path, 1, 1), f"the sheet needs a '{key}'"))
        return ""
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        errors.append(_error(smap, (key,), f"'{key}' must be a text"))
        return ""
    # issue 14: $…$ maths in a sheet's texts, read as a spec's texts are (no declared names: all free)
    text = str(value)
    lead = len(text) - len(text.lstrip())
    try:
        return parse_rich_text(text.strip(), {})
    except RichTextError as exc:
        errors.append(SpecError(smap.expr_location((key,), lead + exc.offset), exc.message, exc.hint))
        return ""


def load_sheet(path: str | Path) -> Sheet:
    """Read a sheet file and every spec it names (with its ``vary`` entries); raise SpecErrors with
    every problem found, in the sheet and in the specs."""
    path = Path(path)
    data, smap = load_yaml_file(path)
    errors: list[SpecError] = []
    if not isinstance(data, dict):
        raise SpecErrors([SpecError(Location(str(path), 1, 1), "expected a mapping (title, course, date, problems)")])
    for name in data:
        if name not in SHEET_KEYS:
            errors.append(_unknown_key(smap, (name,), name, SHEET_KEYS, "the sheet"))
    version = data.get("tutgen_sheet")
    if version is not None and version != SHEET_FORMAT_VERSION:
        errors.append(_error(smap, ("tutgen_sheet",), f"unknown sheet format version {version!r}; expected 1"))
    title = _text_field(data, smap, "title", errors, required=True)
    course = _text_field(data, smap, "course", errors, required=False)
    date = _text_field(data, smap, "date", errors, required=False)
    items = data.get("problems")
    problems: list[SheetProblem] = []
    if not isinstance(items, list) or not items:
        where = ("problems",) if "problems" in data else ()
        errors.append(_error(smap, where, "the sheet needs 'problems': a list of spec files"))
        items = []
    sheet_marking = None
    if data.get("marking") is not None:  # copied into every variant's marking-<problem>.yaml
        sheet_marking = read_marking(data["marking"], smap, ("marking",), errors, path=str(path), source="spec")
    keys: dict[str, int] = {}
    for i, item in enumerate(items):
        problem = _load_problem(path, smap, i, item, errors)
        if problem is None:
            continue
        if isinstance(item, dict) and item.get("marking") is not None:
            where = ("problems", i, "marking")
            own = read_marking(item["marking"], smap, where, errors, path=str(path), source="spec")
            problem = replace(problem, marking=own)
        elif sheet_marking is not None:
            problem = replace(problem, marking=sheet_marking)
        if problem.key in keys:
            errors.append(
                _error(
                    smap,
                    ("problems", i),
                    f"the spec '{problem.key}' is listed twice (also problem {keys[problem.key]})",
                )
            )
            continue
        keys[problem.key] = problem.number
        problems.append(problem)
    if errors:
        raise SpecErrors(errors)
    return Sheet(path, title, course, date, tuple(problems))


def _load_problem(sheet: Path, smap: SourceMap, i: int, item: Any, errors: list[SpecError]) -> SheetProblem | None:
    from tutgen.sheet.variants import parameter_entries, replace_parameters
    from tutgen.spec.validate import validate_spec

    where = ("problems", i)
    vary: dict[str, Any] = {}
    if isinstance(item, dict):
        for name in item:
            if name not in PROBLEM_KEYS:
                errors.append(_unknown_key(smap, (*where, name), name, PROBLEM_KEYS, "a problem"))
        spec = item.get("spec")
        raw_vary = item.get("vary", {})
        if raw_vary is None:
            raw_vary = {}
        if not isinstance(raw_vary, dict):
            errors.append(
                _error(smap, (*where, "vary"), "'vary' must be a mapping: parameter name -> range, choices or value")
            )
            return None
        vary = raw_vary
        spec_where: tuple[Any, ...] = (*where, "spec")
    else:
        spec, spec_where = item, where
    if not isinstance(spec, str) or not spec.strip():
        errors.append(_error(smap, spec_where, "expected the path of a spec file (relative to the sheet)"))
        return None
    spec_path = (sheet.parent / spec.strip()) if not Path(spec.strip()).is_absolute() else Path(spec.strip())
    if not spec_path.is_file():
        errors.append(_error(smap, spec_where, f"no spec file '{spec.strip()}' (looked for {spec_path})"))
        return None
    try:
        data, spec_map = load_yaml_file(spec_path)
    except SpecErrors as exc:
        errors += exc.errors
        return None
    entries = parameter_entries(data)
    if entries is None:  # a malformed spec: its own errors say why
        try:
            validate_spec(data, spec_map)
        except SpecErrors as exc:
            errors += exc.errors
        return None
    text = spec_path.read_text(encoding="utf-8")
    if vary:
        bad = False
        for name, entry in vary.items():
            if name not in entries:
                close = did_you_mean(name, list(entries))
                errors.append(
                    _error(
                        smap,
                        (*where, "vary", name),
                        f"the spec '{spec.strip()}' has no parameter '{name}'"
                        + (f" (its parameters: {', '.join(entries)})" if entries else " (it has no parameters)"),
                        f"did you mean '{close}'?" if close else None,
                        key=True,
                    )
                )
                bad = True
                continue
            merged = _merge(entries[name], entry)
            # check the entry where the sheet wrote it: validate a spec of this one parameter, whose
            # source map is the sheet's, re-rooted at the entry
            local = {
                ("parameters", name, *k[4:]): e
                for k, e in smap._entries.items()
                if tuple(k[:4]) == (*where, "vary", name)
            }
            local[("parameters",)] = smap._entries[(*where, "vary")]
            try:
                validate_spec({"title": "t", "parameters": {name: merged}}, SourceMap(str(sheet), local))
            except SpecErrors as exc:
                errors += exc.errors
                bad = True
            entries[name] = merged
        if bad:
            return None
        text = replace_parameters(text, data, spec_map, entries)
    try:
        system = _validate_text(text, str(spec_path), bool(vary))
    except SpecErrors as exc:
        errors += exc.errors
        return None
    return SheetProblem(i + 1, spec_path.stem, spec_path, text, system)


def _validate_text(text: str, path: str, rewritten: bool) -> System:
    data, smap = load_yaml_text(text, path)
    from tutgen.spec.validate import validate_spec

    try:
        return validate_spec(data, smap)
    except SpecErrors as exc:
        if not rewritten:
            raise
        # locations in the rewritten text would mislead: name the file only
        raise SpecErrors(
            [SpecError(Location(path), e.message + " (with the sheet's 'vary')", e.hint) for e in exc.errors]
        ) from None


def _merge(spec_entry: Any, vary_entry: Any) -> dict[str, Any]:
    """The sheet's entry of a parameter over the spec's: the variation (value, range, choices, step,
    unit) from the sheet; latex, description and dimension kept from the spec unless the sheet sets them."""
    base = dict(spec_entry) if isinstance(spec_entry, dict) else {}
    for key in ("value", "range", "step", "choices", "unit"):
        base.pop(key, None)
    if isinstance(vary_entry, dict):
        base.update(vary_entry)
    elif vary_entry is not None:
        base["value"] = vary_entry
    return base


def load_roster(path: str | Path) -> tuple[Student, ...]:
    """Read a roster: CSV, UTF-8, a header row naming ``id`` and optionally ``name`` (other columns are
    ignored); one student per row. Raise SpecErrors (``file:line:col``) for a missing column, an empty,
    malformed, reserved or repeated id (also one repeated in other case: ``Ada`` and ``ADA`` are one
    directory where case does not count), a malformed row (an unclosed or stray quote) or an over-long
    field. A roster that is not a regular file (a FIFO, a device) is refused without reading it."""
    path = Path(path)
    name = str(path)
    text = _read_roster(path)
    rows, lines, bad = _parse_csv(text, name)
    if bad is not None:
        raise SpecErrors([bad])
    errors: list[SpecError] = []
    if not rows or not any(cell.strip() for cell in rows[0]):
        raise SpecErrors(
            [SpecError(Location(name, 1, 1), "the roster needs a header row with an 'id' column (and 'name')")]
        )
    header = [h.strip().lower() for h in rows[0]]
    if "id" not in header:
        close = did_you_mean("id", header)
        raise SpecErrors(
            [
                SpecError(
                    Location(name, 1, 1),
                    f"the roster's header has no 'id' column (found: {', '.join(h for h in header if h) or 'nothing'})",
                    f"did you mean '{close}'?" if close else "the first row names the columns: id,name",
                )
            ]
        )
    id_col = header.index("id")
    name_col = header.index("name") if "name" in header else None
    students: list[Student] = []
    seen: dict[str, tuple[str, int]] = {}
    for r, row in enumerate(rows[1:], start=1):
        line = lines[r] if r < len(lines) else r + 1
        if not any(cell.strip() for cell in row):
            continue  # a blank line
        col = 1 + sum(len(c) + 1 for c in row[:id_col])
        sid = row[id_col].strip() if id_col < len(row) else ""
        if not sid:
            errors.append(SpecError(Location(name, line, col), "this student has no id"))
            continue
        if not ID_RE.fullmatch(sid) or sid in (".", ".."):
            errors.append(
                SpecError(
                    Location(name, line, col),
                    f"the id '{sid[:40]}' cannot name a directory",
                    "use letters, digits, '.', '_' and '-' (at most 64, starting with a letter or digit)",
                )
            )
            continue
        folded = sid.casefold()
        if folded in RESERVED_IDS or folded.split(".")[0] in WINDOWS_DEVICES or sid.endswith("."):
            errors.append(
                SpecError(
                    Location(name, line, col),
                    f"the id '{sid}' cannot name a student's directory: it is "
                    + ("the name of the sheet's index file" if folded in RESERVED_IDS else "reserved by Windows"),
                    "rename the id (the directory is variants/<id>/)",
                )
            )
            continue
        if folded in seen:
            first, first_line = seen[folded]
            same = "is listed twice" if first == sid else f"is the id '{first}' in other case"
            errors.append(SpecError(Location(name, line, col), f"the id '{sid}' {same} (first on line {first_line})"))
            continue
        seen[folded] = (sid, line)
        student_name = row[name_col].strip() if name_col is not None and name_col < len(row) else ""
        students.append(Student(sid, student_name))
    if not students and not errors:
        errors.append(SpecError(Location(name, 1, 1), "the roster lists no students"))
    if errors:
        raise SpecErrors(errors)
    return tuple(students)


def _read_roster(path: Path) -> str:
    name = str(path)
    try:
        # O_NONBLOCK: a FIFO must not make the open wait for a writer; it is refused just below
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as err:
        raise SpecErrors([SpecError(Location(name), f"cannot read file: {err.strerror or err}")]) from None
    with os.fdopen(fd, "rb") as fh:
        info = os.fstat(fh.fileno())
        if not stat.S_ISREG(info.st_mode):
            raise SpecErrors([SpecError(Location(name), "the roster is not a regular file (a FIFO, a device?)")])
        if info.st_size > MAX_ROSTER_BYTES:
            raise SpecErrors(
                [SpecError(Location(name), f"the roster is larger than {MAX_ROSTER_BYTES // (1024 * 1024)} MiB")]
            )
        data = fh.read(MAX_ROSTER_BYTES + 1)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise SpecErrors([SpecError(Location(name), "the roster is not UTF-8 text")]) from None


def _parse_csv(text: str, name: str) -> tuple[list[list[str]], list[int], SpecError | None]:
    """The rows, the 1-based line on which each starts (quoted fields may span lines), and the first
    error: a malformed row (``strict`` CSV), or a field over :data:`MAX_ROSTER_FIELD` characters."""
    reader = csv.reader(io.StringIO(text, newline=""), strict=True)
    rows: list[list[str]] = []
    starts: list[int] = []
    line = 1
    while True:
        try:
            row = next(reader)
        except StopIteration:
            return rows, starts, None
        except csv.Error as err:
            message = str(err)
            if "field larger than field limit" in message:
                message = f"a field is longer than {MAX_ROSTER_FIELD} characters"
            elif "end of data" in message:
                message = "a quoted field is never closed (a '\"' without its closing '\"')"
            return rows, starts, SpecError(Location(name, line), f"malformed CSV: {message}")
        for c, cell in enumerate(row):
            if len(cell) > MAX_ROSTER_FIELD:
                col = 1 + sum(len(x) + 1 for x in row[:c])
                return (
                    rows,
                    starts,
                    SpecError(
                        Location(name, line, col),
                        f"this field is {len(cell)} characters long; a roster field has at most {MAX_ROSTER_FIELD}",
                    ),
                )
        rows.append(row)
        starts.append(line)
        line = reader.line_num + 1


def json_scalar(value: Any) -> str:
    """A YAML flow scalar for a plain value (JSON is a subset of YAML's flow style)."""
    return json.dumps(value, ensure_ascii=False)
