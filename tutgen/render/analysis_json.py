"""The JSON of issue 18's analysis: ``results.equilibria`` and ``results.linearization``
(docs/json-output.md#equilibria-and-linearization). Values as the rest of ``results``: numbers for
numbers, expressions in the spec grammar; complex numbers as ``[re, im]``."""

from __future__ import annotations

from typing import Any

from tutgen.engine.analysis import LinearModel
from tutgen.engine.analysis.equilibria import existence
from tutgen.engine.derivation import Derivation
from tutgen.render.jsonout import expr_text, matrix, value, vector

__all__ = ["analysis_results"]


def _complex(z: complex) -> list[float]:
    return [z.real + 0.0, z.imag + 0.0]


def _at(values: tuple[tuple[str, Any], ...], num: Any) -> dict[str, Any]:
    return {name: value(num(v)) for name, v in values}


def _relations(relations: Any) -> list[str]:
    """Inequalities in the spec grammar, e.g. ``g > R*omega**2``."""
    return [f"{expr_text(w.lhs)} {w.rel_op} {expr_text(w.rhs)}" for w in relations]


def _linear(m: LinearModel, num: Any) -> dict[str, Any]:
    out: dict[str, Any] = {
        "about": _at(m.about, num),
        "inputs": [str(u) for u in m.inputs],
        "mass_matrix": matrix(num(m.mass)),
        "damping_matrix": matrix(num(m.damping)),
        "stiffness_matrix": matrix(num(m.stiffness)),
        "input_matrix": matrix(num(m.input_matrix)),
        "state_matrix": matrix(num(m.state_matrix)),
        "state_input_matrix": matrix(num(m.state_input)),
        "stability": m.verdict,
        "reason": m.reason,
    }
    if m.characteristic is not None:
        out["characteristic_polynomial"] = value(num(m.characteristic))
    if m.conditions:
        out["stiffness_minors"] = [value(num(c)) for c in m.conditions]
    if m.stable_where:
        out["stable_where"] = _relations(m.stable_where)
    if m.modes is not None:
        out["modes"] = [
            {
                "eigenvalue": _complex(mode.eigenvalue),
                "natural_frequency": mode.natural_frequency,  # rad/s
                "frequency_hz": mode.frequency_hz,
                "damping_ratio": mode.damping_ratio,
                "shape": [_complex(x) for x in mode.shape],
            }
            for mode in m.modes
        ]
    return out


def analysis_results(d: Derivation) -> dict[str, Any]:
    """The keys ``equilibria`` and ``linearization`` of ``results``, those that were derived."""
    a = d.analysis
    if a is None:
        return {}
    num = d.numeric
    out: dict[str, Any] = {}
    if a.equilibria is not None:
        eq = a.equilibria
        out["equilibria"] = {
            "residual": vector(num(eq.residual)),
            "method": eq.method,
            "free_coordinates": list(eq.free),
            "solutions": [
                {
                    "at": _at(sol, num),
                    "stability": m.verdict,
                    "reason": m.reason,
                    **({"exists_where": _relations([x for _, v in sol for x in existence(v)])} if exists else {}),
                    **({"stable_where": _relations(m.stable_where)} if m.stable_where else {}),
                }
                for sol, m in zip(eq.solutions, a.classified, strict=False)
                for exists in [any(existence(v) for _, v in sol)]
            ],
            **({"remark": eq.remark} if eq.remark else {}),
        }
    if a.linear:
        out["linearization"] = [_linear(m, num) for m in a.linear]
    return out
