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

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tutgen.errors import Location, SpecError, SpecErrors
from tutgen.model.marking import DEFAULT_ABS_TOL, DEFAULT_REL_TOL, Segment, Tolerance
from tutgen.spec.builders.marking import RESULT_KEYS, TOLERANCE_KEYS, describe_value, parse_key, tolerance_fields
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

#: Keys of an answers file that are not answers.
RESERVED_KEYS = ("spec", "student", "tolerance")
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
    errors: list[SpecError] = []
    if data is None:  # an empty file answers nothing: every asked item is missing
        data = {}
    if not isinstance(data, dict):
        raise SpecErrors(
            [
                SpecError(
                    smap.location(()), f"expected a mapping of result keys to answers, found {describe_value(data)}"
                )
            ]
        )
    student = spec = None
    tolerance = Tolerance()
    items: list[AnswerItem] = []
    for key, value in data.items():
        keypath: KeyPath = (key,)
        if key in ("spec", "student"):
            if not isinstance(value, str | int | float) or isinstance(value, bool):
                errors.append(
                    SpecError(smap.location(keypath), f"'{key}' must be a text, found {describe_value(value)}")
                )
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
    # the text as loaded (a file, or standard input for `-`), to recover how numbers were written
    lines = tuple(smap.text.splitlines())
    return AnswerSheet(smap.path, student, spec, tolerance, tuple(items), smap, lines, tuple(errors))
