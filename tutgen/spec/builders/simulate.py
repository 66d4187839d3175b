"""`simulate`: initial conditions, inputs and the interval of `tutgen simulate` (docs/simulate.md)."""

from __future__ import annotations

import difflib

import sympy as sp

from tutgen.model.simulation import DEFAULT_INTERVAL, DEFAULT_SAMPLES, Simulation
from tutgen.spec.builders.context import Context
from tutgen.spec.loader import KeyPath

#: The symbol of time in the expressions of `simulate.inputs` (``t`` is reserved: no spec declares it).
TIME = sp.Symbol("t")


def _hint(name: str, known: list[str]) -> str | None:
    close = difflib.get_close_matches(name, known, n=1)
    return f"did you mean '{close[0]}'?" if close else None


def _constant(ctx: Context, path: KeyPath, value: object, dimension: str | None, what: str) -> sp.Expr | None:
    """A constant: numbers, quantities and parameters; a parameter without a value is an error here."""
    result = ctx.expr(path, value, ctx.params, dimension, what)
    if result is None:
        return None
    unset = sorted(str(s) for s in result.free_symbols if s not in ctx.values)
    if unset:
        ctx.error(
            path,
            f"{what} must be a number; '{value}' uses {', '.join(repr(u) for u in unset)}, which has no value",
            "give the parameter a value in `parameters`",
        )
        return None
    return result


def build_simulate(ctx: Context) -> Simulation | None:
    """The `simulate` section, checked: known coordinates and parameters, constants where constants are
    needed, inputs that name parameters without a value; after the parameters and coordinates."""
    spec = ctx.doc.simulate
    if spec is None:
        return None
    base: KeyPath = ("simulate",)
    places = []
    t_start, t_end = DEFAULT_INTERVAL
    if spec.t is not None:
        if len(spec.t) != 2:
            ctx.error((*base, "t"), f"expected an interval [start, end] of two times, found {len(spec.t)} values")
        else:
            ends = [_constant(ctx, (*base, "t", i), v, "time", "a time") for i, v in enumerate(spec.t)]
            if ends[0] is not None and ends[1] is not None:
                t_start, t_end = (e.xreplace(ctx.values) for e in ends)
                if not t_end > t_start:
                    ctx.error(
                        (*base, "t"),
                        f"the interval must end after it starts; found [{spec.t[0]}, {spec.t[1]}]",
                        "write [start, end] with end > start, e.g. [0, 10]",
                    )
    known = list(ctx.coords)
    initial: dict[str, tuple[tuple[str, sp.Expr], ...]] = {}
    for key in ("q0", "qd0"):
        entries = []
        for name, value in getattr(spec, key).items():
            path: KeyPath = (*base, key, name)
            if name not in ctx.coords:
                ctx.error(
                    path,
                    f"'{key}' names unknown coordinate '{name}' (known: {', '.join(known) or 'none'})",
                    _hint(name, known),
                    key=True,
                )
                continue
            what = "an initial value" if key == "q0" else "an initial rate"
            result = _constant(ctx, path, value, None, what)
            if result is not None:
                entries.append((name, result))
                places.append((f"{key}.{name}", ctx.smap.location(path)))
        initial[key] = tuple(entries)
    inputs = []
    unset = [name for name, symbol in ctx.params.items() if symbol not in ctx.values]
    for name, value in spec.inputs.items():
        path = (*base, "inputs", name)
        if name not in ctx.params:
            ctx.error(
                path,
                f"input '{name}' is not a parameter (parameters without a value: {', '.join(unset) or 'none'})",
                _hint(name, list(ctx.params)),
                key=True,
            )
            continue
        if ctx.params[name] in ctx.values:
            ctx.error(
                path,
                f"input '{name}' is a parameter that has a value; an input gives a value over time to a parameter "
                "that has none",
                f"remove the value of '{name}' in `parameters`, or this input",
                key=True,
            )
            continue
        names = {k: v for k, v in ctx.symbols(coords=True, rates=True).items() if k != name}
        names["t"] = TIME
        result = ctx.expr(path, value, names)
        if result is not None:
            inputs.append((name, result))
            places.append((f"inputs.{name}", ctx.smap.location(path)))
    return Simulation(
        t_start=t_start,
        t_end=t_end,
        q0=initial["q0"],
        qd0=initial["qd0"],
        inputs=tuple(inputs),
        samples=spec.samples if spec.samples is not None else DEFAULT_SAMPLES,
        origin=ctx.smap.key_location(base),
        places=tuple(places),
    )
