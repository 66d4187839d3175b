"""`gravity`: the gravitational acceleration, as a vector or as `g` along a `direction`."""

from __future__ import annotations

import sympy as sp

from tutgen.spec.builders.context import Context
from tutgen.spec.loader import KeyPath


def build_gravity(ctx: Context) -> sp.ImmutableMatrix | None:
    """The gravity vector in the world frame; None without gravity (or after reporting a problem)."""
    spec = ctx.doc.gravity
    if spec is None:
        return None
    path: KeyPath = ("gravity",)
    names = ctx.symbols()
    if spec.vector is not None:
        if spec.g is not None or spec.direction is not None:
            extra = "g" if spec.g is not None else "direction"
            ctx.error(
                (*path, extra),
                f"gravity gives both `vector` and `{extra}`; expected a vector, or `g` with `direction`",
                key=True,
            )
            return None
        # the shorthand `gravity: [0, -g, 0]` is the vector itself
        vpath = path if isinstance(ctx.written(path), list) else (*path, "vector")
        return ctx.vector(vpath, spec.vector, names, "acceleration")
    if spec.g is None or spec.direction is None:
        found = (
            "`g` without `direction`"
            if spec.g is not None
            else "`direction` without `g`"
            if spec.direction is not None
            else "neither"
        )
        ctx.error(
            path,
            f"gravity needs a `vector`, or `g` and `direction` (e.g. {{g: g, direction: -y}}); found {found}",
            key=True,
        )
        return None
    g = ctx.expr((*path, "g"), spec.g, names, "acceleration", "gravity")
    direction = ctx.axis((*path, "direction"), spec.direction, {})
    if g is None or direction is None:
        return None
    return sp.ImmutableMatrix([g * d for d in direction])
