"""What an LMS export holds of one problem of one variant: plain data, built in the sheet's workers.

A question's *parts* are the graded items of the variant's marking key (its ``ask``), taken from the
answer key's results (``tutgen solve --format json``) and cut where an LMS input can hold one answer:
a number, an expression, a list of them or a matrix. A mapping is cut into its entries
(``positions.cart``); a list of per-coordinate records (``lagrange_terms``) into one part per
coordinate and field (``lagrange_terms[x].dL_dq``), the ``coordinate`` name being the label, not an
answer. Texts that are not answers (a part's ``shape``, Newton–Euler's ``method`` and ``remarks``,
booleans) are left out.

A part is *numeric* when every entry is a number (a JSON number); it then carries the instructor's
tolerance of each entry (:func:`entry_tolerance`); otherwise it is *symbolic*.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

#: Keys of the results whose values are labels or remarks, never answers.
NOT_ANSWERS = frozenset({"coordinate", "shape", "method", "remarks", "agrees_with_lagrange"})

#: The check's default tolerances (docs/check.md), used when the marking key says nothing and its
#: significant figures are 0 (decimals exact).
DEFAULT_REL_TOL = 1e-9
DEFAULT_ABS_TOL = 1e-12


@dataclass(frozen=True)
class Part:
    """One answer of a question: ``path`` into the answers file (keys, and coordinate names for a
    per-coordinate list), ``value`` as in the answer key (a number, an expression string, a list or a
    list of rows), and for a numeric part the absolute tolerance of each entry (same shape)."""

    path: tuple[str, ...]
    value: Any
    numeric: bool
    tolerance: Any = None

    @property
    def label(self) -> str:
        return label_of(self.path)

    @property
    def shape(self) -> str:
        """``scalar``, ``list`` or ``matrix``."""
        if not isinstance(self.value, list):
            return "scalar"
        return "matrix" if self.value and all(isinstance(r, list) for r in self.value) else "list"


@dataclass(frozen=True)
class LmsQuestion:
    """One problem of one variant, as an LMS question: Markdown texts (maths between ``$``), the
    figure as ``(file name, SVG text)``, and the graded parts."""

    problem: str  # the spec's key, e.g. p03-cart-pendulum
    number: int
    variant: str  # the variant's id (v001, a student's id), or "nominal"
    label: str  # the variant's label ("Variant 1", a student's name), or ""
    title: str
    question_md: str
    feedback_md: str
    figure: tuple[str, str] | None
    parts: tuple[Part, ...]

    @property
    def ident(self) -> str:
        return f"{self.problem}--{self.variant}"


def entry_tolerance(value: float, rule: Mapping[str, Any], figures: int) -> float:
    """The absolute tolerance an LMS applies to a numeric entry, matching ``tutgen check``: the marking
    key's ``rel_tol``/``abs_tol`` when it states them (``max(abs_tol, rel_tol·|r|)``); else half a unit
    of the last of the significant figures the variant's solution prints, so that the value printed
    there is right; else (figures 0, decimals exact) the check's own tight defaults."""
    r = abs(float(value))
    if "rel_tol" in rule or "abs_tol" in rule:
        return max(float(rule.get("abs_tol", DEFAULT_ABS_TOL)), float(rule.get("rel_tol", 0.0)) * r)
    if figures > 0 and r > 0:
        return 0.5 * 10.0 ** (math.floor(math.log10(r)) - figures + 1)
    return max(DEFAULT_ABS_TOL, DEFAULT_REL_TOL * r)


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _is_answer_leaf(v: Any) -> bool:
    """A number, an expression, or a (nested) list of them: one LMS input."""
    if isinstance(v, list):
        return bool(v) and all(_is_answer_leaf(e) and not (isinstance(e, list) and _depth(e) > 1) for e in v)
    return _is_number(v) or isinstance(v, str)


def _depth(v: Any) -> int:
    return 1 + max((_depth(e) for e in v), default=0) if isinstance(v, list) else 0


def _numbers(v: Any) -> bool:
    return all(_numbers(e) for e in v) if isinstance(v, list) else _is_number(v)


def _walk(path: tuple[str, ...], value: Any) -> Iterator[tuple[tuple[str, ...], Any]]:
    if isinstance(value, bool) or value is None:
        return
    if isinstance(value, dict):
        for k, v in value.items():
            if k not in NOT_ANSWERS:
                yield from _walk((*path, str(k)), v)
    elif isinstance(value, list) and value and all(isinstance(e, dict) and "coordinate" in e for e in value):
        for record in value:
            yield from _walk((*path, f"[{record['coordinate']}]"), record)
    elif _is_answer_leaf(value):
        yield path, value


def rule_for(path: tuple[str, ...], marking: Mapping[str, Any]) -> Mapping[str, Any]:
    """The marking key's rule for a part: the most specific ``items`` entry naming it or a key above it,
    then the key's ``tolerance``."""
    items = marking.get("items") or {}
    for n in range(len(path), 0, -1):
        rule = items.get(".".join(path[:n]))
        if rule and ("rel_tol" in rule or "abs_tol" in rule):
            return rule
    return marking.get("tolerance") or {}


def parts_of(results: Mapping[str, Any], marking: Mapping[str, Any]) -> tuple[Part, ...]:
    """The graded parts of one variant's results (the JSON ``results``) under its marking key (the
    mapping of ``marking-<problem>.yaml``): its ``ask`` items, in its order."""
    figures = int(marking.get("significant_figures", 0) or 0)
    parts: list[Part] = []
    for key in marking.get("ask") or list(results):
        if key not in results:
            continue
        for path, leaf in _walk((key,), results[key]):
            if _numbers(leaf):
                rule = rule_for(path, marking)
                tol = _map(leaf, lambda x, rule=rule: entry_tolerance(x, rule, figures))
                parts.append(Part(path, leaf, True, tol))
            else:
                parts.append(Part(path, leaf, False))
    return tuple(parts)


def _map(v: Any, f: Any) -> Any:
    return [_map(e, f) for e in v] if isinstance(v, list) else f(v)


def label_of(path: Sequence[str]) -> str:
    """A part's name as docs/check.md writes keys: ``positions.cart``, ``lagrange_terms[x].dL_dq``."""
    return "".join(p if p.startswith("[") or i == 0 else f".{p}" for i, p in enumerate(path))


def path_of(label: str) -> tuple[str, ...]:
    """The inverse of :func:`label_of`."""
    return tuple(p for p in re.split(r"\.|(?=\[)", label) if p)


def answers_from(values: Mapping[tuple[str, ...], Any]) -> dict[str, Any]:
    """An answers file's mapping (docs/check.md) from answers by part path, nested as the results are;
    a ``[x]`` step is the record of coordinate x in a per-coordinate list, in the order first met."""
    out: dict[str, Any] = {}
    for path, value in values.items():
        target: Any = out
        for i, step in enumerate(path[:-1]):
            nxt = path[i + 1]
            if nxt.startswith("["):
                target = target.setdefault(step, [])
            elif step.startswith("["):
                name = step[1:-1]
                record = next((r for r in target if r.get("coordinate") == name), None)
                if record is None:
                    record = {"coordinate": name}
                    target.append(record)
                target = record
            else:
                target = target.setdefault(step, {})
        target[path[-1]] = value
    return out
