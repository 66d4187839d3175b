"""`coordinates`: the generalized coordinates q_i, in order, each with its rate and acceleration symbols;
a driven one (`prescribed:` or `rate:`) with its motion q(t) (docs/spec-format.md#prescribed)."""

from __future__ import annotations

import dataclasses

import sympy as sp

from tutgen.model.system import TIME, Ask, Coordinate
from tutgen.spec import schema as S
from tutgen.spec.builders.context import Context
from tutgen.spec.expr import FUNCTIONS, ExprError, parse_expression
from tutgen.spec.latexname import display_name
from tutgen.spec.names import default_latex
from tutgen.spec.units import DIMENSIONS

#: The most coordinates a spec may have: tutgen derives symbolic equations, which grow fast with n.
MAX_COORDINATES = 12


def build_coordinates(ctx: Context) -> None:
    """Declare every coordinate in ``ctx`` (and the dimension it is declared with)."""
    ctx.check_listed_twice("coordinates")
    names = [*ctx.doc.coordinates, *ctx.dropped_names("coordinates")]
    if len(names) > MAX_COORDINATES:
        extra = names[MAX_COORDINATES]
        ctx.error(
            ctx.name_path("coordinates", extra),
            f"expected at most {MAX_COORDINATES} coordinates, found {len(names)} "
            f"('{extra}' is number {MAX_COORDINATES + 1})",
            "tutgen derives symbolic equations; split the problem, or fix some coordinates",
            key=True,
        )
    for name in ctx.dropped_names("coordinates"):
        if name.isidentifier() and name not in FUNCTIONS and name != "pi":
            ctx.coords[name] = _coordinate(ctx, name, None, None, None)
    for name, spec in ctx.doc.coordinates.items():
        path = ctx.name_path("coordinates", name)
        if not ctx.check_name(path, name, "coordinate"):
            continue
        if name in ctx.params:
            # declared anyway (as a coordinate), so that its uses are not reported too
            ctx.error(path, f"'{name}' is declared both as a parameter and as a coordinate", key=True)
        latex, latex_errors = display_name(name, spec.latex, ctx.smap, (*path, "latex"))
        ctx.errors += latex_errors
        ctx.coords[name] = _coordinate(ctx, name, latex, spec.description, spec.dimension, _motion(ctx, name, spec))
        if spec.dimension == "length":
            ctx.dims[ctx.coords[name].q] = DIMENSIONS["length"]
        elif spec.dimension == "angle":
            ctx.dims[ctx.coords[name].q] = DIMENSIONS["angle"]


def _coordinate(
    ctx: Context,
    name: str,
    latex: str | None,
    description: str | None,
    dimension: str | None,
    prescribed: sp.Expr | None = None,
) -> Coordinate:
    q = sp.Symbol(name, real=True)
    qd = sp.Symbol(f"{name}_dot", real=True)
    qdd = sp.Symbol(f"{name}_ddot", real=True)
    return Coordinate(
        name,
        q,
        qd,
        qdd,
        latex if latex is not None else default_latex(name),
        description,
        dimension,
        ctx.smap.key_location(ctx.name_path("coordinates", name)),
        prescribed=prescribed,
    )


def _motion(ctx: Context, name: str, spec: S.CoordinateSpec) -> sp.Expr | None:
    """A driven coordinate's motion q(t): `prescribed` (a function of t and the parameters) or
    `initial + rate*t` (constants); None for a degree of freedom or when the spec is wrong here."""
    base = (*ctx.name_path("coordinates", name),)
    if spec.prescribed is not None and spec.rate is not None:
        ctx.error(
            (*base, "rate"),
            f"coordinate '{name}' gives both `prescribed` and `rate`; expected one of them",
            f"`rate: w` is `prescribed: w*t`; keep one (e.g. `prescribed: {spec.prescribed}`)",
            key=True,
        )
        return None
    if spec.initial is not None and spec.rate is None:
        ctx.error(
            (*base, "initial"),
            f"coordinate '{name}' gives `initial` without `rate`; `initial` is the value at t = 0 of a coordinate "
            "driven at a constant `rate`",
            "add `rate:`, or write the whole motion in `prescribed:` (e.g. `prescribed: phi0 + omega*t`)"
            if spec.prescribed is None
            else f"write the value at t = 0 into `prescribed: {spec.prescribed}`, and remove `initial`",
            key=True,
        )
        return None
    if spec.rate is not None:
        rate = ctx.expr((*base, "rate"), spec.rate, ctx.params)
        initial = ctx.expr((*base, "initial"), spec.initial, ctx.params) if spec.initial is not None else sp.Integer(0)
        if rate is None or initial is None:
            return None
        return initial + rate * TIME
    if spec.prescribed is None:
        return None
    path = (*base, "prescribed")
    try:
        return parse_expression(spec.prescribed, {**ctx.params, "t": TIME})
    except ExprError as exc:
        ctx.expr_error(path, exc, _motion_hint(ctx, exc.message))
        return None


def _motion_hint(ctx: Context, message: str) -> str | None:
    """Why a name is unknown in a prescribed motion: it may use only the time t and the parameters."""
    if not message.startswith("unknown name '"):
        return None
    name = message.split("'")[1]
    base = name.removesuffix("_ddot").removesuffix("_dot")
    if base in ctx.coords or base in ctx.doc.coordinates:
        return (
            f"'{name}' belongs to a coordinate; a prescribed motion is a function of the time t and the parameters only"
        )
    return f"declare '{name}' in `parameters`; a prescribed motion may use the time t and the parameters"


def check_prescribed(ctx: Context) -> None:
    """What a driven coordinate rules out, once every section is built: nothing left free, the
    constraints' reduction (it chooses its own independent coordinates), the analysis at rest and the
    simulation (both need a system without explicit time)."""
    driven = [c for c in ctx.coords.values() if c.prescribed is not None]
    if not driven:
        return
    if len(driven) == len(ctx.coords):
        ctx.error(
            ("coordinates",),
            f"every coordinate is prescribed ({', '.join(c.name for c in driven)}): nothing is left free to have "
            "equations of motion",
            "leave at least one coordinate without `prescribed`/`rate`",
            key=True,
        )
    for key in ("constraints", "independent_coordinates"):
        if getattr(ctx.doc, key):
            ctx.error(
                (key,),
                f"`{key}` with a prescribed coordinate ('{driven[0].name}') is not supported; expected either "
                "constraints or prescribed coordinates",
                "write the driven motion into the constraint, or drop the constraint",
                key=True,
            )
    if ctx.doc.simulate is not None:
        ctx.error(
            ("simulate",),
            f"`simulate` with a prescribed coordinate ('{driven[0].name}') is not supported yet: the simulation "
            "integrates every coordinate as free",
            f"remove `simulate`, or make '{driven[0].name}' free",
            key=True,
        )
    refused = {Ask.EQUILIBRIA: "rest configurations", Ask.LINEARIZATION: "linear models about a rest configuration"}
    for i, item in enumerate(ctx.doc.ask or []):
        if (a := Ask(item)) in refused:
            what = refused[a]
            ctx.error(
                ("ask", i),
                f"`{item}` does not apply with a prescribed coordinate ('{driven[0].name}'): the equations of the "
                f"others depend on the time t, and tutgen derives {what} only for a system without explicit time",
                f"remove `{item}` from `ask`, or make '{driven[0].name}' free",
            )


def coordinates_with_dimensions(ctx: Context) -> dict[str, Coordinate]:
    """The coordinates with their SI dimension, which is known only once the joints have been built
    (a revolute joint makes its coordinate an angle, a prismatic one a length)."""
    return {n: dataclasses.replace(c, si_dimension=ctx.dims.get(c.q)) for n, c in ctx.coords.items()}
