"""Variants: which value each varying parameter takes, and the concrete spec that fixes them.

Sampling is a pure function of (seed, problem key, variant id, parameter name): the SHA-256 of those,
read as an integer, indexes the parameter's allowed values. No global random state, no ``hash()``: the
same seed gives the same variants on every machine, in every process, whatever the number of workers.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import sympy as sp

from tutgen.model.system import Parameter, System
from tutgen.spec.loader import SourceMap


@dataclass(frozen=True)
class Variant:
    """One variant of a sheet: an id (``v001`` or a student's id) and a label for its header."""

    id: str
    label: str


def variant_ids(count: int) -> tuple[Variant, ...]:
    width = max(3, len(str(count)))
    return tuple(Variant(f"v{i:0{width}d}", f"Variant {i}") for i in range(1, count + 1))


def pick(seed: int, problem: str, variant: str, parameter: str, count: int) -> int:
    """The index (0 <= i < count) of the value ``parameter`` of ``problem`` takes in ``variant``."""
    text = "\x00".join(("tutgen-sheet-1", str(seed), problem, variant, parameter))
    return int.from_bytes(hashlib.sha256(text.encode("utf-8")).digest()[:16], "big") % count


def sample(system: System, problem: str, variant: str, seed: int) -> dict[str, sp.Expr]:
    """The value (exact, SI) of each parameter of ``system`` that has a choice of values."""
    return {
        p.name: p.choices[pick(seed, problem, variant, p.name, len(p.choices))]
        for p in system.parameters
        if p.choices is not None and len(p.choices) > 1
    }


def with_values(system: System, values: Mapping[str, sp.Expr]) -> System:
    """The system with these parameter values (and no choices left: every parameter fixed)."""
    import dataclasses

    params = tuple(
        dataclasses.replace(p, value=values.get(p.name, p.value), choices=None) if p.choices is not None else p
        for p in system.parameters
    )
    return dataclasses.replace(system, parameters=params)


def changes_structure(system: System, values: Mapping[str, sp.Expr]) -> bool:
    """Whether substituting ``values`` into the derivation of ``system`` could differ from deriving the
    concrete spec afresh, so the variant must be derived on its own.

    The derivation is symbolic in the parameters, and the symbols' assumptions are fixed from all the
    allowed values, so substitution is exact, except where a value is zero or negative: a zero can make
    terms, bodies or whole rows vanish (a singular mass matrix, a coordinate that no longer moves
    anything), and the engine's checks (H positive semi-definite) depend on the signs.
    """
    return any(not v.is_positive for v in values.values())


# --- numbers as written ---------------------------------------------------------------------


def quantity_text(p: Parameter, value: sp.Expr) -> str:
    """The value as a spec writes it: ``3.5 kg``, ``0.5`` or an expression."""
    from tutgen.spec.units import decimal_text, in_unit

    number = in_unit(value, p.unit)
    if number.is_Rational:
        text = decimal_text(number)
        if p.unit and "/" not in text:
            return f"{text} {p.unit}"
        if not p.unit:
            return text
    return str(value)  # a number that has no decimal form: SI, as an expression


# --- the spec text ---------------------------------------------------------------------------


def parameter_entries(data: Any) -> dict[str, Any] | None:
    """A spec's ``parameters`` as a mapping name -> entry (None for a spec without any), or None when the
    section is malformed (the validator reports it)."""
    if not isinstance(data, dict):
        return None
    section = data.get("parameters")
    if section is None:
        return {}
    if isinstance(section, list):
        if not all(isinstance(n, str) for n in section):
            return None
        return {n: None for n in section}
    if isinstance(section, dict):
        return dict(section)
    return None


def _entry_text(entry: Any) -> str:
    if entry is None:
        return ""
    if isinstance(entry, dict):
        if not entry:
            return " {}"
        return " {" + ", ".join(f"{k}: {_flow(v)}" for k, v in entry.items()) + "}"
    return " " + _flow(entry)


def _flow(value: Any) -> str:
    if isinstance(value, list):
        return "[" + ", ".join(_flow(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {_flow(v)}" for k, v in value.items()) + "}"
    return json.dumps(value, ensure_ascii=False)


def parameters_block(entries: Mapping[str, Any]) -> str:
    lines = ["parameters:"]
    for name, entry in entries.items():
        lines.append(f"  {name}:{_entry_text(entry)}")
    return "\n".join(lines) + "\n" if entries else "parameters: {}\n"


def replace_parameters(text: str, data: dict[str, Any], smap: SourceMap, entries: Mapping[str, Any]) -> str:
    """The spec text with its ``parameters`` section replaced by ``entries`` (block style); the rest of
    the text (comments too) is kept as written. A spec written in flow style as a whole is written out
    again as JSON (YAML's flow subset), without its comments."""
    block = parameters_block(entries)
    lines = text.splitlines(keepends=True)
    if lines and not lines[-1].endswith("\n"):
        lines[-1] += "\n"
    tops = [(smap.key_location((k,)), k) for k in data]
    if any(loc.col != 1 for loc, _ in tops):
        whole = dict(data)
        whole["parameters"] = {k: (v if v is not None else {}) for k, v in entries.items()}
        return json.dumps(whole, ensure_ascii=False, indent=2) + "\n"
    if "parameters" not in data:
        # before the first section after the title, or at the end
        after = [loc.line for loc, k in tops if k not in ("tutgen", "title", "statement")]
        at = min(after) - 1 if after else len(lines)
        return "".join(lines[:at]) + block + "".join(lines[at:])
    start = smap.key_location(("parameters",)).line
    later = sorted(loc.line for loc, _ in tops if loc.line > start)
    end = later[0] - 1 if later else len(lines)  # 0-based index of the next section's key line
    # comment lines right above the next section belong to it
    while end > start and lines[end - 1].lstrip().startswith("#"):
        end -= 1
    return "".join(lines[: start - 1]) + block + "".join(lines[end:])


def concrete_entries(text_entries: Mapping[str, Any], system: System, values: Mapping[str, sp.Expr]) -> dict[str, Any]:
    """The parameter entries of a variant's concrete spec: every varying parameter fixed to its value."""
    out: dict[str, Any] = {}
    by_name = {p.name: p for p in system.parameters}
    for name, entry in text_entries.items():
        p = by_name.get(name)
        if p is None or p.choices is None:
            out[name] = entry
            continue
        kept = {
            k: v
            for k, v in (entry.items() if isinstance(entry, dict) else ())
            if k in ("latex", "description", "dimension")
        }
        fixed = values.get(name, p.value)
        assert fixed is not None
        out[name] = {"value": quantity_text(p, fixed), **kept}
    return out


def concrete_spec(problem_text: str, path: str, system: System, values: Mapping[str, sp.Expr]) -> str:
    """The concrete spec of a variant: the problem's spec text with every varying parameter fixed."""
    if all(p.choices is None for p in system.parameters):
        return problem_text  # nothing varies: the spec as written
    data, smap = _parsed(problem_text, path)
    entries = parameter_entries(data) or {}
    return replace_parameters(problem_text, data, smap, concrete_entries(entries, system, values))


@lru_cache(maxsize=64)
def _parsed(problem_text: str, path: str) -> tuple[dict[str, Any], SourceMap]:
    """The problem's spec, read once per process for all its variants (nothing here changes what it
    returns: :func:`replace_parameters` and :func:`parameter_entries` copy what they change)."""
    from tutgen.spec.loader import load_yaml_text

    return load_yaml_text(problem_text, path)
