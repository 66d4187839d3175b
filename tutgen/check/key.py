"""The instructor's marking key: which items are asked, and the tolerances and rules of each.

Tolerances belong to the instructor, never to the student: an answers file that sets one is
refused (:mod:`tutgen.check.answers`). The key is a YAML file given as ``tutgen check --key KEY``::

    ask: [kinetic_energy, mass_matrix, equations_of_motion]   # the items graded (optional)
    tolerance: {rel_tol: 0.005}                               # every number (optional)
    items:                                                    # per item or entry (optional)
      inertia_tensor[1,1]: {rel_tol: 0.01, rounded: true}
      equations_of_motion: {scaling: false}

A rule given for a key applies to every entry under it; the most specific rule wins, then the key's
``tolerance``, then the defaults. ``scaling: false`` accepts an equation of motion only as written
or with its terms moved across the ``=``, not multiplied by a constant factor.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from tutgen.check.answers import RESULT_KEYS, TOLERANCE_KEYS, Segment, Tolerance, parse_key, tolerance_fields
from tutgen.errors import Location, SpecError, SpecErrors
from tutgen.spec.expr import did_you_mean
from tutgen.spec.loader import load_yaml_file

__all__ = ["KeyRule", "MarkingKey", "read_key"]

_KEY_FIELDS = ("ask", "tolerance", "items")
_RULE_FIELDS = (*TOLERANCE_KEYS, "scaling")


@dataclass(frozen=True)
class KeyRule:
    """The rule of one key entry: a tolerance and whether equations may be scaled."""

    key: str
    segments: tuple[Segment, ...]
    tolerance: Tolerance = field(default_factory=Tolerance)
    scaling: bool | None = None
    location: Location = field(default_factory=lambda: Location("<key>"))


@dataclass(frozen=True)
class MarkingKey:
    """A marking key (the default: nothing asked beyond what is answered, default tolerances)."""

    path: str | None = None
    ask: tuple[tuple[str, tuple[Segment, ...], Location], ...] | None = None  # (key, segments, location)
    tolerance: Tolerance = field(default_factory=Tolerance)
    rules: tuple[KeyRule, ...] = field(default_factory=tuple)


def _segments(key: Any, where: str, loc: Location, errors: list[SpecError]) -> tuple[Segment, ...] | None:
    try:
        segments = parse_key(str(key))
    except ValueError as exc:
        errors.append(SpecError(loc, f"cannot read the {where} '{key}': {exc}"))
        return None
    head = str(segments[0])
    if head not in RESULT_KEYS:
        close = did_you_mean(head, RESULT_KEYS)
        errors.append(
            SpecError(loc, f"unknown result '{head}' in the {where}", f"did you mean '{close}'?" if close else None)
        )
        return None
    return segments


def read_key(path: str | Path) -> MarkingKey:
    """Read a marking key; every problem is raised at once as SpecErrors (file:line:col)."""
    data, smap = load_yaml_file(path)
    errors: list[SpecError] = []
    if data is None:
        data = {}
    if not isinstance(data, dict):
        raise SpecErrors([SpecError(smap.location(()), "a marking key is a mapping with ask, tolerance, items")])
    ask = None
    tolerance = Tolerance()
    rules: list[KeyRule] = []
    for name, value in data.items():
        if name not in _KEY_FIELDS:
            close = did_you_mean(str(name), _KEY_FIELDS)
            errors.append(
                SpecError(
                    smap.key_location((name,)),
                    f"unknown key '{name}' in a marking key; expected one of: {', '.join(_KEY_FIELDS)}",
                    f"did you mean '{close}'?" if close else None,
                )
            )
        elif name == "ask":
            if not isinstance(value, list) or not value:
                errors.append(SpecError(smap.location(("ask",)), "'ask' is a non-empty list of result keys"))
                continue
            asked = []
            for i, key in enumerate(value):
                loc = smap.location(("ask", i))
                segs = _segments(key, "asked item", loc, errors)
                if segs is not None:
                    asked.append((str(key), segs, loc))
            ask = tuple(asked)
        elif name == "tolerance":
            if not isinstance(value, dict):
                errors.append(
                    SpecError(smap.location(("tolerance",)), "'tolerance' is a mapping such as {rel_tol: 0.01}")
                )
                continue
            tolerance, _ = tolerance_fields(value, ("tolerance",), smap, errors, allowed=())
        else:
            if not isinstance(value, dict):
                errors.append(SpecError(smap.location(("items",)), "'items' maps result keys to rules"))
                continue
            for key, rule in value.items():
                loc = smap.key_location(("items", key))
                segs = _segments(key, "item", loc, errors)
                if not isinstance(rule, dict):
                    errors.append(
                        SpecError(smap.location(("items", key)), "a rule is a mapping such as {rel_tol: 0.01}")
                    )
                    continue
                tol, extra = tolerance_fields(rule, ("items", key), smap, errors, allowed=("scaling",))
                scaling = extra.get("scaling")
                if scaling is not None and not isinstance(scaling, bool):
                    errors.append(SpecError(smap.location(("items", key, "scaling")), "'scaling' is true or false"))
                    scaling = None
                if segs is not None:
                    rules.append(KeyRule(str(key), segs, tol, scaling, loc))
    if errors:
        raise SpecErrors(errors)
    return MarkingKey(str(path), ask, tolerance, tuple(rules))
