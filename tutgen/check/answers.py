"""Reading an answers file: safe YAML in, typed items with locations out.

An answers file is a mapping from result keys of ``tutgen solve --format json`` (its ``results``)
to answers in the same form: expressions as strings in the spec grammar, numbers, lists, tables.
Two keys are not results: ``spec`` (the spec the answers are for; informational) and ``student``
(a name for the reports). ``tolerance`` (and ``rel_tol``, ``abs_tol``, ``rounded``) are refused:
tolerances are the instructor's (:mod:`tutgen.check.key`). The
format is documented in docs/check.md.

A key is a path into the results (:func:`parse_key`): ``mass_matrix``, ``mass_matrix[1,2]``,
``christoffel[1,1,2]``, ``bodies.body.inertia_tensor``, ``lagrange_terms[2].dL_dq`` or
``lagrange_terms.theta2.dL_dq``; indices are 1-based, as in the reports.

This module reads the file only; whether a key exists for a given spec, and whether an answer is
right, is :mod:`tutgen.check.compare`'s business. Every problem found here is collected and raised
once as :class:`~tutgen.errors.SpecErrors` (exit code 3).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tutgen.errors import Location, SpecError, SpecErrors
from tutgen.spec.expr import did_you_mean
from tutgen.spec.loader import KeyPath, SourceMap, load_yaml_file

__all__ = [
    "DEFAULT_ABS_TOL",
    "DEFAULT_REL_TOL",
    "MSG_NO_TOLERANCE",
    "RESERVED_KEYS",
    "RESULT_KEYS",
    "TOLERANCE_KEYS",
    "AnswerItem",
    "AnswerSheet",
    "Segment",
    "Tolerance",
    "is_tolerance_form",
    "parse_key",
    "read_answers",
    "tolerance_fields",
    "unknown_key_error",
]

#: Default relative tolerance of a numeric answer (tutgen's numbers are exact or 12+ digits).
DEFAULT_REL_TOL = 1e-9
#: Default absolute tolerance of a numeric answer (what "zero" means for a number).
DEFAULT_ABS_TOL = 1e-12

#: The keys of ``results`` in tutgen's JSON output (tutgen/render/jsonout.py), in its order.
RESULT_KEYS = (
    "bodies",
    "mass",
    "center_of_mass",
    "inertia_tensor",
    "principal_moments",
    "positions",
    "velocities",
    "angular_velocities",
    "speeds_squared",
    "body_kinetic_energies",
    "kinetic_energy",
    "potential_energy",
    "lagrangian",
    "lagrange_terms",
    "generalized_forces",
    "mass_matrix",
    "coriolis_vector",
    "coriolis_matrix",
    "gravity_vector",
    "mass_matrix_determinant",
    "equations_of_motion",
    "christoffel",
    "christoffel_first_kind",
    "newton_euler",
)
#: Keys of an answers file that are not answers.
RESERVED_KEYS = ("spec", "student", "tolerance")
#: The keys of a tolerance (file-wide under ``tolerance:``, or per answer next to ``value:``).
TOLERANCE_KEYS = ("rel_tol", "abs_tol", "rounded")
#: The textbook letters people write for results, and the result key each one means.
_LETTERS = {
    "H": "mass_matrix",
    "M": "mass_matrix",
    "C": "coriolis_vector",
    "G": "gravity_vector",
    "T": "kinetic_energy",
    "U": "potential_energy",
    "V": "potential_energy",
    "L": "lagrangian",
    "Q": "generalized_forces",
    "tau": "generalized_forces",
    "J": "inertia_tensor",
    "I": "inertia_tensor",
    "eom": "equations_of_motion",
    "h": "christoffel",
    "c": "christoffel_first_kind",
}

#: One step of a key path: a name (a result key, a body, a coordinate) or a group of 1-based indices.
Segment = str | tuple[int, ...]

_NAME = r"[A-Za-z_][A-Za-z0-9_]*"
_PART_RE = re.compile(rf"(?P<name>{_NAME}|[0-9]+)?(?:\[(?P<index>[^\]]*)\])?")
_INDEX_RE = re.compile(r"\s*[0-9]+\s*(?:,\s*[0-9]+\s*)*")


@dataclass(frozen=True)
class Tolerance:
    """How close a numeric answer must be. A field left None takes the file's, then the default.

    A number ``a`` is right when ``|a - r| <= max(abs_tol, rel_tol * |r|)`` for the result ``r``.
    With ``rounded`` a number written as a literal must instead be ``r`` rounded half-up to the
    significant figures the literal shows (``3.46e-3`` for 3.4676e-3 is wrong: it rounds to 3.47e-3).
    """

    rel_tol: float | None = None
    abs_tol: float | None = None
    rounded: bool | None = None

    def over(self, base: Tolerance) -> Tolerance:
        """This tolerance, with the fields it leaves open taken from ``base``."""
        return Tolerance(
            self.rel_tol if self.rel_tol is not None else base.rel_tol,
            self.abs_tol if self.abs_tol is not None else base.abs_tol,
            self.rounded if self.rounded is not None else base.rounded,
        )

    @property
    def is_set(self) -> bool:
        return self.rel_tol is not None or self.abs_tol is not None or self.rounded is not None

    @property
    def rel(self) -> float:
        return DEFAULT_REL_TOL if self.rel_tol is None else self.rel_tol

    @property
    def abs(self) -> float:
        return DEFAULT_ABS_TOL if self.abs_tol is None else self.abs_tol


@dataclass(frozen=True)
class AnswerItem:
    """One top-level answer: the key as written, its parsed path, its value and where it was written."""

    key: str
    segments: tuple[Segment, ...]
    value: Any
    keypath: KeyPath  # of the value in the file's data
    location: Location  # of the key


@dataclass(frozen=True)
class AnswerSheet:
    """An answers file, read and checked for shape (not yet against a spec)."""

    path: str
    student: str | None
    spec: str | None
    tolerance: Tolerance
    items: tuple[AnswerItem, ...]
    source: SourceMap
    lines: tuple[str, ...]  # the file's text, to recover how numbers were written
    errors: tuple[SpecError, ...] = ()  # problems found so far; raised with those found when marking

    def location(self, keypath: KeyPath) -> Location:
        return self.source.location(keypath)

    def raw_number(self, keypath: KeyPath, value: float | int) -> str | None:
        """The number at ``keypath`` as it was written (``1.0e-2``, not ``0.01``), if it can be found."""
        loc = self.source.location(keypath)
        if not 0 < loc.line <= len(self.lines) or loc.col <= 0:
            return None
        match = _NUMBER_RE.match(self.lines[loc.line - 1], loc.col - 1)
        if match is None:
            return None
        try:
            same = float(match.group()) == float(value)
        except (ValueError, OverflowError):
            return None
        return match.group() if same else None


_NUMBER_RE = re.compile(r"[-+]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")


def parse_key(key: str) -> tuple[Segment, ...]:
    """The path a key names: dotted names and 1-based index groups.

    ``mass_matrix[1,2]`` is ``("mass_matrix", (1, 2))``; ``lagrange_terms.2.dL_dq`` and
    ``lagrange_terms[2].dL_dq`` are both ``("lagrange_terms", (2,), "dL_dq")``. Raises
    ``ValueError`` with a message for a key that is not of this shape.
    """
    if not key or key != key.strip():
        raise ValueError("a key is a result name such as 'mass_matrix' or 'mass_matrix[1,2]'")
    segments: list[Segment] = []
    for part in key.split("."):
        match = _PART_RE.fullmatch(part)
        if not part or match is None or (match.group("name") is None and match.group("index") is None):
            raise ValueError(f"'{part}' is not a name or an index (write e.g. 'mass_matrix[1,2]')")
        name, index = match.group("name"), match.group("index")
        if name is not None:
            if name.isdigit():
                segments.append((int(name),))
            else:
                segments.append(name)
        if index is not None:
            if not _INDEX_RE.fullmatch(index):
                raise ValueError(f"'[{index}]' is not an index: write whole numbers from 1, e.g. '[1,2]'")
            segments.append(tuple(int(i) for i in index.split(",")))
    for seg in segments:
        if isinstance(seg, tuple) and min(seg) < 1:
            raise ValueError("indices start at 1, as in the reports: the first entry is [1]")
    if not isinstance(segments[0], str):
        raise ValueError("a key starts with a result name, e.g. 'mass_matrix[1,2]'")
    return tuple(segments)


def tolerance_fields(
    data: dict[str, Any], keypath: KeyPath, smap: SourceMap, errors: list[SpecError], *, allowed: tuple[str, ...]
) -> tuple[Tolerance, dict[str, Any]]:
    """The tolerance fields of ``data`` (of a marking key), and the other keys in ``allowed`` with their
    values; problems go to ``errors``."""
    fields: dict[str, Any] = {}
    extra: dict[str, Any] = {}
    for key, value in data.items():
        path = (*keypath, key)
        if key in TOLERANCE_KEYS:
            if key == "rounded":
                if not isinstance(value, bool):
                    errors.append(SpecError(smap.location(path), f"'rounded' must be true or false, found {value!r}"))
                    continue
            elif isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
                errors.append(
                    SpecError(smap.location(path), f"'{key}' must be a number (e.g. 0.01), found {_describe(value)}")
                )
                continue
            elif value < 0:
                errors.append(SpecError(smap.location(path), f"'{key}' must not be negative, found {value}"))
                continue
            fields[key] = value if key == "rounded" else float(value)
        elif key in allowed:
            extra[key] = value
        else:
            close = did_you_mean(key, (*allowed, *TOLERANCE_KEYS))
            errors.append(
                SpecError(
                    smap.key_location(path),
                    f"unknown key '{key}' in a tolerance; expected one of: {', '.join((*allowed, *TOLERANCE_KEYS))}",
                    f"did you mean '{close}'?" if close else None,
                )
            )
    return Tolerance(**fields), extra


def _describe(value: Any) -> str:
    if value is None:
        return "an empty value"
    if isinstance(value, bool):
        return "true/false"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    return f"'{value}'"


def is_tolerance_form(value: Any) -> bool:
    """Whether ``value`` is ``{value: ..., rel_tol: ..., ...}``: an answer with its own tolerance."""
    return isinstance(value, dict) and "value" in value and all(k == "value" or k in TOLERANCE_KEYS for k in value)


#: Why an answers file may not set a tolerance.
MSG_NO_TOLERANCE = (
    "an answers file may not set '{key}': tolerances are the instructor's (the marking key, tutgen check --key)"
)


def unknown_key_error(key: str, location: Location) -> SpecError:
    """The error for a top-level key that is neither a result key nor a reserved one."""
    close = _LETTERS.get(key) or did_you_mean(key, (*RESULT_KEYS, *RESERVED_KEYS))
    hint = f"did you mean '{close}'?" if close else "keys are those of `tutgen solve SPEC --format json` (results)"
    return SpecError(location, f"unknown result '{key}'; expected one of: {', '.join(RESULT_KEYS)}", hint)


def read_answers(path: str | Path) -> AnswerSheet:
    """Read an answers file and check its shape.

    Checks the YAML (safely, with the spec loader), the reserved keys and the grammar of every key.
    A file that is not YAML or not a mapping raises SpecErrors at once; other problems are kept in
    ``errors``, to be raised together with those found when the values are read against a spec
    (:func:`tutgen.check.compare.check_sheet`), so that every problem is reported at once.
    """
    data, smap = load_yaml_file(path)
    name = str(path)
    errors: list[SpecError] = []
    if data is None:  # an empty file answers nothing: every asked item is missing
        data = {}
    if not isinstance(data, dict):
        raise SpecErrors(
            [SpecError(smap.location(()), f"expected a mapping of result keys to answers, found {_describe(data)}")]
        )
    student = spec = None
    tolerance = Tolerance()
    items: list[AnswerItem] = []
    for key, value in data.items():
        keypath: KeyPath = (key,)
        if key in ("spec", "student"):
            if not isinstance(value, str | int | float) or isinstance(value, bool):
                errors.append(SpecError(smap.location(keypath), f"'{key}' must be a text, found {_describe(value)}"))
            elif key == "spec":
                spec = str(value)
            else:
                student = str(value)
            continue
        if key == "tolerance" or key in TOLERANCE_KEYS:
            errors.append(SpecError(smap.key_location(keypath), MSG_NO_TOLERANCE.format(key=key)))
            continue
        try:
            segments = parse_key(key)
        except ValueError as exc:
            errors.append(SpecError(smap.key_location(keypath), f"cannot read the key '{key}': {exc}"))
            continue
        head = segments[0]
        assert isinstance(head, str)
        if head not in RESULT_KEYS:
            errors.append(unknown_key_error(head, smap.key_location(keypath)))
            continue
        items.append(AnswerItem(key, segments, value, keypath, smap.key_location(keypath)))
    try:
        text = Path(path).read_text(encoding="utf-8-sig", errors="replace")
    except OSError:  # pragma: no cover - it was just read
        text = ""
    return AnswerSheet(name, student, spec, tolerance, tuple(items), smap, tuple(text.splitlines()), tuple(errors))
