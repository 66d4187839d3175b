"""`marking`: what the instructor marks in the answers to this problem (``tutgen check``).

The section has the fields of a marking key file (``tutgen check --key``), and the same reader
(:func:`read_marking`) checks both, every problem located at its ``file:line:col``::

    marking:
      ask: [mass_matrix, christoffel]          # the items graded, in this order
      tolerance: {rel_tol: 0.005}              # every number (optional)
      items:                                   # per item or entry (optional)
        equations_of_motion: {scaling: false}
      significant_figures: 4                   # decimals read as the result rounded (0: off)

Result keys are paths into the ``results`` of ``tutgen solve --format json`` (:func:`parse_key`);
whether this spec has such an entry is known only after the derivation, so ``tutgen check`` checks
that (:func:`tutgen.check.compare.key_problems`). The grammar of keys and tolerances lives here
because a spec holds them now; :mod:`tutgen.check.answers` uses the same.
"""

from __future__ import annotations

import math
import re
from typing import Any

from tutgen.errors import Location, SpecError
from tutgen.model.marking import KeyRule, Marking, Segment, Tolerance
from tutgen.spec.builders.context import Context
from tutgen.spec.expr import did_you_mean
from tutgen.spec.loader import KeyPath, SourceMap

__all__ = [
    "MARKING_FIELDS",
    "RESULT_KEYS",
    "TOLERANCE_KEYS",
    "build_marking",
    "describe_value",
    "marking_data",
    "parse_key",
    "read_marking",
    "tolerance_fields",
]

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
    "steady_motion",
)
#: The keys of a tolerance.
TOLERANCE_KEYS = ("rel_tol", "abs_tol", "rounded")
#: The fields of a marking (a spec's or a sheet's ``marking:``, a key file).
MARKING_FIELDS = ("ask", "tolerance", "items", "significant_figures")
_RULE_FIELDS = ("scaling",)
#: The significant figures a marking may name (as a spec's ``significant_figures``; 0: off).
_FIGURES_RANGE = (0, 15)

_NAME = r"[A-Za-z_][A-Za-z0-9_]*"
_PART_RE = re.compile(rf"(?P<name>{_NAME}|[0-9]+)?(?:\[(?P<index>[^\]]*)\])?")
_INDEX_RE = re.compile(r"\s*[0-9]+\s*(?:,\s*[0-9]+\s*)*")


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


def describe_value(value: Any) -> str:
    """What a YAML value is, for a message: ``an empty value``, ``a list``, ``'abc'``."""
    if value is None:
        return "an empty value"
    if isinstance(value, bool):
        return "true/false"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    return f"'{value}'"


def tolerance_fields(
    data: dict[str, Any], keypath: KeyPath, smap: SourceMap, errors: list[SpecError], *, allowed: tuple[str, ...]
) -> tuple[Tolerance, dict[str, Any]]:
    """The tolerance fields of ``data`` (of a marking), and the other keys in ``allowed`` with their
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
                    SpecError(
                        smap.location(path), f"'{key}' must be a number (e.g. 0.01), found {describe_value(value)}"
                    )
                )
                continue
            elif value < 0:
                errors.append(SpecError(smap.location(path), f"'{key}' must not be negative, found {value}"))
                continue
            fields[key] = value if key == "rounded" else float(value)
        elif key in allowed:
            extra[key] = value
        else:
            close = did_you_mean(str(key), (*allowed, *TOLERANCE_KEYS))
            errors.append(
                SpecError(
                    smap.key_location(path),
                    f"unknown key '{key}' in a tolerance; expected one of: {', '.join((*allowed, *TOLERANCE_KEYS))}",
                    f"did you mean '{close}'?" if close else None,
                )
            )
    return Tolerance(**fields), extra


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


def read_marking(
    data: Any, smap: SourceMap, base: KeyPath, errors: list[SpecError], *, path: str | None = None, source: str = "key"
) -> Marking:
    """Read a marking (a mapping with :data:`MARKING_FIELDS`) found at ``base`` in a YAML file; every
    problem goes to ``errors`` at its place."""
    what = "a marking key" if not base else f"'{base[-1]}'"
    if data is None:
        data = {}
    if not isinstance(data, dict):
        errors.append(
            SpecError(
                smap.location(base),
                f"{what} is a mapping with {', '.join(MARKING_FIELDS)}; found {describe_value(data)}",
            )
        )
        return Marking(path, source=source)
    ask = None
    tolerance = Tolerance()
    rules: list[KeyRule] = []
    figures: int | None = None
    for name, value in data.items():
        at = (*base, name)
        if name not in MARKING_FIELDS:
            close = did_you_mean(str(name), MARKING_FIELDS)
            errors.append(
                SpecError(
                    smap.key_location(at),
                    f"unknown key '{name}' in {what}; expected one of: {', '.join(MARKING_FIELDS)}",
                    f"did you mean '{close}'?" if close else None,
                )
            )
        elif name == "ask":
            if not isinstance(value, list) or not value:
                errors.append(SpecError(smap.location(at), "'ask' is a non-empty list of result keys"))
                continue
            asked = []
            for i, key in enumerate(value):
                loc = smap.location((*at, i))
                segs = _segments(key, "asked item", loc, errors)
                if segs is not None:
                    asked.append((str(key), segs, loc))
            ask = tuple(asked)
        elif name == "tolerance":
            if not isinstance(value, dict):
                errors.append(SpecError(smap.location(at), "'tolerance' is a mapping such as {rel_tol: 0.01}"))
                continue
            tolerance, _ = tolerance_fields(value, at, smap, errors, allowed=())
        elif name == "significant_figures":
            lo, hi = _FIGURES_RANGE
            if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
                errors.append(
                    SpecError(
                        smap.location(at),
                        f"'significant_figures' is a whole number from {lo} to {hi} "
                        f"(0: decimals are exact), found {describe_value(value)}",
                    )
                )
                continue
            figures = value
        else:
            if not isinstance(value, dict):
                errors.append(SpecError(smap.location(at), "'items' maps result keys to rules"))
                continue
            for key, rule in value.items():
                loc = smap.key_location((*at, key))
                segs = _segments(key, "item", loc, errors)
                if not isinstance(rule, dict):
                    errors.append(SpecError(smap.location((*at, key)), "a rule is a mapping such as {rel_tol: 0.01}"))
                    continue
                tol, extra = tolerance_fields(rule, (*at, key), smap, errors, allowed=_RULE_FIELDS)
                scaling = extra.get("scaling")
                if scaling is not None and not isinstance(scaling, bool):
                    errors.append(SpecError(smap.location((*at, key, "scaling")), "'scaling' is true or false"))
                    scaling = None
                if segs is not None:
                    rules.append(KeyRule(str(key), segs, tol, scaling, loc))
    return Marking(path, ask, tolerance, tuple(rules), figures, source)


def build_marking(ctx: Context) -> Marking | None:
    """The spec's ``marking:`` section (None when it has none)."""
    if ctx.doc.marking is None:  # none, or set aside for a shape error (already reported)
        return None
    return read_marking(ctx.doc.marking, ctx.smap, ("marking",), ctx.errors, path=ctx.smap.path, source="spec")


def marking_data(marking: Marking) -> dict[str, Any]:
    """A marking as the YAML mapping :func:`read_marking` reads (what a sheet writes for a variant)."""
    out: dict[str, Any] = {}
    if marking.ask is not None:
        out["ask"] = [key for key, _, _ in marking.ask]
    tolerance = _tolerance_data(marking.tolerance)
    if tolerance:
        out["tolerance"] = tolerance
    if marking.rules:
        items = {}
        for rule in marking.rules:
            items[rule.key] = _tolerance_data(rule.tolerance) | (
                {} if rule.scaling is None else {"scaling": rule.scaling}
            )
        out["items"] = items
    if marking.significant_figures is not None:
        out["significant_figures"] = marking.significant_figures
    return out


def _tolerance_data(tolerance: Tolerance) -> dict[str, Any]:
    fields = {"rel_tol": tolerance.rel_tol, "abs_tol": tolerance.abs_tol, "rounded": tolerance.rounded}
    return {k: v for k, v in fields.items() if v is not None}
