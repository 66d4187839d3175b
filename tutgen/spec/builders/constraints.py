"""`constraints` and `independent_coordinates`: holonomic and velocity constraints among the coordinates.

A constraint is an expression that is zero. Written with coordinates only (and parameters) it is a
position (holonomic) constraint f(q) = 0; written with rates it is a velocity constraint, which must be
linear and homogeneous in them, a(q) . q_dot = 0 (the rolling coin). Accelerations are not allowed.
Whether the constraints are independent, and whether the chosen independent coordinates can be kept,
is known only at a state of the system: the engine checks both (tutgen/engine/constraints/).
"""

from __future__ import annotations

import difflib

import sympy as sp

from tutgen.model.system import Constraint, ConstraintKind
from tutgen.spec.builders.context import Context
from tutgen.spec.loader import KeyPath


def build_constraints(ctx: Context) -> list[Constraint]:
    """The constraints, in spec order, each classified as a position or a velocity constraint."""
    out: list[Constraint] = []
    names = ctx.symbols(coords=True, rates=True)
    q = {c.q for c in ctx.coords.values()}
    qd = [c.qd for c in ctx.coords.values()]
    for name, value in ctx.doc.constraints.items():
        path: KeyPath = ("constraints", name)
        ctx.check_name(path, name, "constraint")
        e = ctx.expr(path, value, names)
        if e is None:
            continue
        rates = e.free_symbols & set(qd)
        if not rates:
            if not e.free_symbols & q:
                ctx.error(
                    path,
                    f"constraint '{name}' is '{value}', which uses no coordinate; expected an expression of the "
                    f"coordinates ({', '.join(ctx.coords) or 'none declared'}) that is zero",
                )
                continue
            out.append(Constraint(name, ConstraintKind.POSITION, e, ctx.smap.key_location(path)))
            continue
        poly = sp.Poly(sp.expand(e), *qd)
        if poly.total_degree() > 1 or poly.coeff_monomial(1) != 0:
            ctx.error(
                path,
                f"velocity constraint '{name}' is '{value}', which is not linear and homogeneous in the rates; "
                "expected a sum of NAME_dot terms, each times a function of the coordinates, e.g. "
                "'x_dot - R*phi_dot*cos(theta)'",
            )
            continue
        out.append(Constraint(name, ConstraintKind.VELOCITY, e, ctx.smap.key_location(path)))
    return out


def build_independent_coordinates(ctx: Context, constraints: list[Constraint], loops: int = 0) -> tuple[str, ...]:
    """The coordinates kept when the equations are reduced: as listed, or the first n - m in order (m
    constraints); each must be a declared coordinate, listed once, and there must be n - m of them.

    With ``loops`` loop-closing joints, m is known only from the loop-closure equations (two for a planar
    loop, three otherwise): the engine checks the count, and the default is left to it (empty here)."""
    given = ctx.doc.independent_coordinates
    declared = list(ctx.coords)
    m = len(ctx.doc.constraints)
    if given is None and loops:
        return ()
    if given is None:
        if m and m >= len(declared):
            ctx.error(
                ("constraints",),
                f"{m} constraint(s) on {len(declared)} coordinate(s) leave no motion; expected fewer "
                "constraints than coordinates",
                key=True,
            )
            return ()
        return tuple(declared[: len(declared) - m]) if m else ()
    path: KeyPath = ("independent_coordinates",)
    if not m and not loops:
        ctx.error(path, "`independent_coordinates` is given but there are no `constraints`", key=True)
        return ()
    out: list[str] = []
    ok = True
    for i, name in enumerate(given):
        if name not in ctx.coords:
            close = difflib.get_close_matches(name, declared, n=1)
            ctx.error(
                (*path, i),
                f"independent coordinate '{name}' is not a declared coordinate (declared: {', '.join(declared)})",
                f"did you mean '{close[0]}'?" if close else None,
            )
            ok = False
        elif name in out:
            ctx.error((*path, i), f"independent coordinate '{name}' is listed twice")
            ok = False
        else:
            out.append(name)
    if ok and not loops and len(out) != len(declared) - m:
        ctx.error(
            path,
            f"{len(declared)} coordinates with {m} constraint(s) leave {len(declared) - m} independent "
            f"coordinate(s); found {len(out)} listed ({', '.join(out) or 'none'})",
        )
        ok = False
    return tuple(out) if ok else ()
