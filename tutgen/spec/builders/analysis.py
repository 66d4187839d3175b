"""`analysis`: the equilibrium and the inputs of `ask: [equilibria, linearization]`, the rates of
`ask: [steady_motion]`."""

from __future__ import annotations

import difflib
from collections.abc import Mapping

import sympy as sp

from tutgen.errors import Location
from tutgen.model.analysis import Analysis
from tutgen.spec.builders.context import Context
from tutgen.spec.loader import KeyPath


def _hint(name: str, known: list[str]) -> str | None:
    close = difflib.get_close_matches(name, known, n=1)
    return f"did you mean '{close[0]}'?" if close else None


def build_analysis(ctx: Context) -> Analysis | None:
    """The `analysis` section, checked: known coordinates, values that are constants (numbers and
    parameters), inputs that name parameters without a value; after the parameters and coordinates.
    Whether ``about`` is an equilibrium is known only once G and Q are derived
    (tutgen.engine.analysis reports it at ``about``)."""
    spec = ctx.doc.analysis
    if spec is None:
        return None
    base: KeyPath = ("analysis",)
    places = []
    about: tuple[tuple[str, sp.Expr], ...] | None = None
    if spec.about is not None:
        given: dict[str, sp.Expr] = {}
        for name, result, path in _per_coordinate(ctx, "about", spec.about, "an equilibrium value"):
            given[name] = result
            places.append((f"about.{name}", ctx.smap.location(path)))
        places.append(("about", ctx.smap.key_location((*base, "about"))))
        about = tuple((c, given.get(c, sp.Integer(0))) for c in ctx.coords)
    inputs = []
    unset = [name for name, symbol in ctx.params.items() if symbol not in ctx.values]
    for name, value in spec.inputs.items():
        path = (*base, "inputs", name)
        if name not in ctx.params or ctx.params[name] in ctx.values:
            what = "is not a parameter" if name not in ctx.params else "is a parameter that has a value"
            ctx.error(
                path,
                f"input '{name}' {what}; an input is a parameter without a value (those: {', '.join(unset) or 'none'})",
                _hint(name, unset),
                key=True,
            )
            continue
        names = {k: v for k, v in ctx.params.items() if k != name}
        result = ctx.expr(path, value, names, None, "an input's value at the equilibrium")
        if result is not None:
            inputs.append((ctx.params[name], result))
            places.append((f"inputs.{name}", ctx.smap.location(path)))
    steady = _steady(ctx, spec.steady, places) if spec.steady is not None else None
    return Analysis(
        about=about, inputs=tuple(inputs), origin=ctx.smap.key_location(base), places=tuple(places), steady=steady
    )


def _steady(
    ctx: Context, spec: dict[str, object], places: list[tuple[str, Location]]
) -> tuple[tuple[str, sp.Expr], ...]:
    """`steady`: known coordinates, each with a constant rate (numbers and parameters). Whether each is
    cyclic is known only once H, G and Q are derived (tutgen.engine.analysis.steady reports it at
    ``steady.<name>``)."""
    out: list[tuple[str, sp.Expr]] = []
    for name, result, path in _per_coordinate(ctx, "steady", spec, "a steady rate"):
        out.append((name, result))
        places.append((f"steady.{name}", ctx.smap.key_location(path)))
    places.append(("steady", ctx.smap.key_location(("analysis", "steady"))))
    return tuple(out)


def _per_coordinate(
    ctx: Context, key: str, spec: Mapping[str, object], what: str
) -> list[tuple[str, sp.Expr, KeyPath]]:
    """``analysis.<key>``: a value per known coordinate (numbers and parameters), each as (name, value,
    its key path); an unknown coordinate or a value that does not parse is reported and left out."""
    known = list(ctx.coords)
    out: list[tuple[str, sp.Expr, KeyPath]] = []
    for name, value in spec.items():
        path: KeyPath = ("analysis", key, name)
        if name not in ctx.coords:
            ctx.error(
                path,
                f"'{key}' names unknown coordinate '{name}' (known: {', '.join(known) or 'none'})",
                _hint(name, known),
                key=True,
            )
            continue
        result = ctx.expr(path, value, ctx.params, None, what)
        if result is not None:
            out.append((name, result, path))
    return out
