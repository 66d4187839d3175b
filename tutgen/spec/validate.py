"""Spec data -> :class:`tutgen.model.System`: shape, names, expressions, units and cross-references.

Every problem is collected with its ``file:line:col`` and reported at once (:class:`SpecErrors`).
Expressions go through the whitelist parser of :mod:`tutgen.spec.expr`; nothing here evaluates
user text as code.

Two stages: the shape of the spec (:mod:`tutgen.spec.schema`, its errors translated by
:mod:`tutgen.spec.schema_errors`), then names, expressions, units and cross-references, section by
section (:func:`tutgen.spec.builders.system.build_system`, one builder module per top-level key).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from pydantic import ValidationError

from tutgen.errors import SpecError, SpecErrors
from tutgen.model.system import System
from tutgen.spec import schema as S
from tutgen.spec.builders.context import AXES as AXES
from tutgen.spec.builders.context import RESERVED_NAMES as RESERVED_NAMES
from tutgen.spec.builders.coordinates import MAX_COORDINATES as MAX_COORDINATES
from tutgen.spec.builders.parameters import MAX_CHOICES as MAX_CHOICES
from tutgen.spec.builders.system import build_system
from tutgen.spec.loader import KeyPath, SourceMap, load_yaml_file, load_yaml_text
from tutgen.spec.places import FOUNDATIONS, prune, unit_of
from tutgen.spec.places import NAMED_SECTIONS as NAMED_SECTIONS
from tutgen.spec.schema_errors import translate


def load_system(path: str | Path) -> System:
    """Read, check and convert one spec file."""
    data, smap = load_yaml_file(path)
    return validate_spec(data, smap)


def load_system_text(text: str, path: str = "<spec>") -> System:
    data, smap = load_yaml_text(text, path)
    return validate_spec(data, smap)


def validate_spec(data: Any, smap: SourceMap) -> System:
    """Check a loaded spec and build the model; raise SpecErrors listing every problem.

    Shape errors do not stop the other checks: an object (a body, a joint, ...) whose shape is wrong
    is reported, set aside, and still counts as declared, so that the rest of the spec is checked
    without a second report of the same mistake.
    """
    if not isinstance(data, dict):
        found = "an empty file" if data is None else S.describe(data)
        raise SpecErrors(
            [
                SpecError(
                    smap.location(()),
                    f"expected a mapping of spec keys (title, parameters, bodies, ...), found {found}",
                )
            ]
        )
    errors: list[SpecError] = []
    dropped: set[KeyPath] = set()
    work: dict[str, Any] = data
    for _ in range(3):
        try:
            doc = S.SpecDoc.model_validate(work)
            break
        except ValidationError as exc:
            problems = translate(exc, work, smap)
            errors += [p.error for p in problems]
            units = {unit_of(p.path) for p in problems} - {()}
            dropped |= units
            work = prune(work, units)
    else:  # pragma: no cover - pruning removes every part pydantic complained about
        raise SpecErrors(errors)
    if errors and any(len(u) == 1 and u[0] in FOUNDATIONS for u in dropped):
        raise SpecErrors(errors)
    try:
        system = build_system(doc, data, smap, dropped)
    except SpecErrors as exc:
        raise SpecErrors(errors + exc.errors) from None
    if errors:
        raise SpecErrors(errors)
    return system


__all__ = ["load_system", "load_system_text", "validate_spec"]
