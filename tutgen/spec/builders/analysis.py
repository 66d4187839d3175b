"""`analysis`: the equilibrium and the inputs of `ask: [equilibria, linearization]`, the rates of
`ask: [steady_motion]`."""

from __future__ import annotations

import difflib

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
    known = list(ctx.coords)
    if spec.about is not None:
        given: dict[str, sp.Expr] = {}
        for name, value in spec.about.items():
            path: KeyPath = (*base, "about", name)
            if name not in ctx.coords:
                ctx.error(
                    path,
                    f"'about' names unknown coordinate '{name}' (known: {', '.join(known) or 'none'})",
                    _hint(name, known),
                    key=True,
                )
                continue
            result = ctx.expr(path, value, ctx.params, None, "an equilibrium value")
            if result is not None:
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
    known = list(ctx.coords)
    out: list[tuple[str, sp.Expr]] = []
    for name, value in spec.items():
        path: KeyPath = ("analysis", "steady", name)
        if name not in ctx.coords:
            ctx.error(
                path,
                f"'steady' names unknown coordinate '{name}' (known: {', '.join(known) or 'none'})",
                _hint(name, known),
                key=True,
            )
            continue
        result = ctx.expr(path, value, ctx.params, None, "a steady rate")
        if result is not None:
            out.append((name, result))
            places.append((f"steady.{name}", ctx.smap.key_location(path)))
    places.append(("steady", ctx.smap.key_location(("analysis", "steady"))))
    return tuple(out)
