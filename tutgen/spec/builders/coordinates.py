"""`coordinates`: the generalized coordinates q_i, in order, each with its rate and acceleration symbols."""

from __future__ import annotations

import dataclasses

import sympy as sp

from tutgen.model.system import Coordinate
from tutgen.spec.builders.context import Context
from tutgen.spec.expr import FUNCTIONS
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
        ctx.coords[name] = _coordinate(ctx, name, latex, spec.description, spec.dimension)
        if spec.dimension == "length":
            ctx.dims[ctx.coords[name].q] = DIMENSIONS["length"]
        elif spec.dimension == "angle":
            ctx.dims[ctx.coords[name].q] = DIMENSIONS["angle"]


def _coordinate(
    ctx: Context, name: str, latex: str | None, description: str | None, dimension: str | None
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
    )


def coordinates_with_dimensions(ctx: Context) -> dict[str, Coordinate]:
    """The coordinates with their SI dimension, which is known only once the joints have been built
    (a revolute joint makes its coordinate an angle, a prismatic one a length)."""
    return {n: dataclasses.replace(c, si_dimension=ctx.dims.get(c.q)) for n, c in ctx.coords.items()}
