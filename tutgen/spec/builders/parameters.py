"""`parameters`: the named quantities of a problem, symbolic or with a value, unit and allowed values."""

from __future__ import annotations

import re

import sympy as sp

from tutgen.model.system import Parameter
from tutgen.spec import schema as S
from tutgen.spec.builders.context import Context
from tutgen.spec.builders.words import expected_dimension, found_dimension
from tutgen.spec.expr import FUNCTIONS, ExprError, number_to_rational
from tutgen.spec.latexname import display_name
from tutgen.spec.loader import KeyPath
from tutgen.spec.units import DIMENSIONS, Dimension, parse_quantity, parse_unit

#: The most values a parameter's ``range`` may allow (variants of a tutorial sheet).
MAX_CHOICES = 10_000


def build_parameters(ctx: Context) -> list[Parameter]:
    """Declare every parameter in ``ctx`` (its symbol and dimension) and return them in spec order."""
    parameters: list[Parameter] = []
    ctx.check_listed_twice("parameters")
    # parameters that appear in forces are plain real numbers; the rest (masses, lengths,
    # stiffnesses, g) are positive, which lets sqrt(l**2) become l
    force_text = " ".join(str(v) for v in ctx.doc.generalized_forces.values())
    for load in ctx.doc.loads.values():
        force_text += " " + " ".join(str(v) for v in (load.force or []) + (load.torque or []))
    for name in ctx.dropped_names("parameters"):
        if name.isidentifier() and name not in FUNCTIONS and name != "pi":
            ctx.params[name] = sp.Symbol(name, real=True)
            ctx.dims[ctx.params[name]] = None
    for name, spec in ctx.doc.parameters.items():
        path = ctx.name_path("parameters", name)
        if not ctx.check_name(path, name, "parameter"):
            continue
        is_force = _mentions(force_text, name)
        symbol = sp.Symbol(name, real=True) if is_force else sp.Symbol(name, positive=True)
        value: sp.Expr | None = None
        unit: str | None = None
        dim: Dimension | None = DIMENSIONS[spec.dimension] if spec.dimension else None
        # declared before its value is checked: a bad value is one error, not one per use
        ctx.params[name] = symbol
        ctx.dims[symbol] = dim
        if spec.value is not None:
            vpath = (*path, "value") if ctx.smap.has((*path, "value")) else path
            if isinstance(spec.value, str):
                try:
                    quantity = parse_quantity(spec.value)
                except ExprError as exc:
                    ctx.expr_error(vpath, exc)
                    continue
                if quantity is not None:
                    if spec.dimension is not None and dim is not None and quantity.dimension != dim:
                        ctx.error(
                            vpath,
                            f"parameter '{name}' is declared as {expected_dimension(spec.dimension)}, "
                            f"but its value '{spec.value}' is {found_dimension(quantity.dimension)}",
                        )
                        continue
                    value, unit, dim = quantity.value, quantity.unit, quantity.dimension
                    ctx.dims[symbol] = dim
            if value is None:
                value = ctx.expr(vpath, spec.value, {})
                if value is None:
                    continue
        choices: tuple[sp.Expr, ...] | None = None
        if spec.range is not None or spec.choices is not None or spec.step is not None:
            allowed = _choices(ctx, path, name, spec, dim)
            if allowed is None:
                continue
            choices, range_unit, dim = allowed
            unit = range_unit or unit
            ctx.dims[symbol] = dim
            if value is None:
                value = choices[(len(choices) - 1) // 2] if spec.range is not None else choices[0]
            elif value not in choices:
                ctx.error((*path, "value"), f"the value of parameter '{name}' is not one of its allowed values")
                continue
        if value is not None and symbol.is_positive and not all(v.is_positive for v in (choices or (value,))):
            # a zero or negative value: the symbol must not be assumed positive, or
            # sqrt(a**2) would become a before the value is put in
            dims = ctx.dims.pop(symbol)
            symbol = sp.Symbol(name, real=True)
            ctx.params[name] = symbol
            ctx.dims[symbol] = dims
        latex, latex_errors = display_name(name, spec.latex, ctx.smap, (*path, "latex"))
        ctx.errors += latex_errors
        where = ctx.smap.key_location(path)
        parameters.append(
            Parameter(name, symbol, value, latex, spec.description, unit, where, ctx.dims.get(symbol), choices)
        )
    ctx.values = {p.symbol: p.value for p in parameters if p.value is not None}
    return parameters


def _choices(
    ctx: Context, path: KeyPath, name: str, spec: S.ParameterSpec, declared: Dimension | None
) -> tuple[tuple[sp.Expr, ...], str | None, Dimension | None] | None:
    """The allowed values (exact, SI) of a parameter with a ``range`` or ``choices`` (variants of a
    tutorial sheet), its unit as written and its dimension; None after reporting an error."""
    if spec.range is not None and spec.choices is not None:
        ctx.error((*path, "choices"), f"parameter '{name}' has both a range and choices; give one of them")
        return None
    if spec.step is not None and spec.range is None:
        ctx.error((*path, "step"), f"parameter '{name}' has a step but no range", "write range: [lo, hi]")
        return None
    factor: sp.Expr = sp.Integer(1)
    dim = declared
    if spec.unit is not None:
        upath = (*path, "unit")
        try:
            factor, udim = parse_unit(spec.unit)
        except ExprError as exc:
            ctx.expr_error(upath, exc)
            return None
        if declared is not None and udim != declared and spec.dimension is not None:
            ctx.error(
                upath,
                f"parameter '{name}' is declared as {expected_dimension(spec.dimension)}, "
                f"but its unit '{spec.unit}' is {found_dimension(udim)}",
            )
            return None
        dim = udim
    key = "range" if spec.range is not None else "choices"
    try:
        if spec.range is not None:
            lo, hi = (number_to_rational(v) for v in spec.range)
            if hi < lo:
                ctx.error((*path, key), f"the range of parameter '{name}' goes down: write [lo, hi] with lo <= hi")
                return None
            step = number_to_rational(spec.step) if spec.step is not None else (hi - lo) / 10
            if hi == lo:
                step = sp.Integer(1)
            if step <= 0:
                ctx.error((*path, "step"), f"the step of parameter '{name}' must be positive")
                return None
            count = int(sp.floor((hi - lo) / step)) + 1
            if count > MAX_CHOICES:
                ctx.error(
                    (*path, "step"),
                    f"the range of parameter '{name}' has {count} values; the limit is {MAX_CHOICES}",
                    "use a larger step",
                )
                return None
            numbers = [lo + k * step for k in range(count)]
        else:
            assert spec.choices is not None
            numbers = [number_to_rational(v) for v in spec.choices]
            for i, n in enumerate(numbers):
                if n in numbers[:i]:
                    ctx.error((*path, key, i), f"choice {spec.choices[i]} of parameter '{name}' is listed twice")
                    return None
    except ExprError as exc:
        ctx.error((*path, key), f"parameter '{name}': {exc.message}")
        return None
    return tuple(n * factor for n in numbers), spec.unit, dim


def _mentions(text: str, name: str) -> bool:
    """Whether ``name`` appears in ``text`` as a whole word."""
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", text) is not None
