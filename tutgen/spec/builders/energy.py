"""`energy`: the kinetic and potential energy given directly, as expressions of the coordinates."""

from __future__ import annotations

import sympy as sp

from tutgen.spec.builders.context import Context


def build_energy(ctx: Context, bodies: set[str]) -> tuple[sp.Expr | None, sp.Expr | None]:
    """The kinetic and potential energy given in `energy` (None, None without it, or after a problem).

    ``bodies`` are the declared bodies: a spec gives its energies, or the bodies they come from.
    """
    spec = ctx.doc.energy
    # keys set aside for shape errors (or unknown ones, perhaps a misspelt `bodies`) may be what
    # is missing here: guess nothing about them
    unsure = bool(
        ctx.dropped_keys
        - {"tutgen", "title", "statement", "gravity", "ask", "methods", "significant_figures", "marking", "simulate"}
    )
    has_bodies = bool(ctx.doc.bodies or ctx.doc.joints or bodies or ctx.doc.arm)
    has_bodies |= bool(ctx.dropped_names("joints"))
    if spec is None:
        if ctx.coords and not has_bodies and not unsure:
            ctx.error(
                ("coordinates",),
                "the spec has `coordinates` but no `bodies` and no `energy`; expected one of them, to say what moves",
                key=True,
            )
        return None, None
    if has_bodies:
        given = "`bodies`" if ctx.doc.bodies or bodies else "`joints`"
        given = "`arm`" if ctx.doc.arm is not None else given
        ctx.error(
            ("energy",),
            f"the spec gives both `energy` and {given}; expected the energy, or the bodies, not both",
            key=True,
        )
        return None, None
    if not ctx.coords:
        if not unsure:
            ctx.error(
                ("energy",),
                "`energy` needs `coordinates` (the q_i that T and U depend on); found none",
                key=True,
            )
        return None, None
    t = ctx.expr(("energy", "kinetic"), spec.kinetic, ctx.symbols(coords=True, rates=True))
    if t is not None:
        t = _check_quadratic(ctx, t)
    if ctx.doc.gravity is not None:
        ctx.error(
            ("gravity",),
            "`gravity` has no effect when the energies are given; expected its potential energy in "
            "`energy.potential` (e.g. m*g*h), found a `gravity` section",
            key=True,
        )
    u = (
        ctx.expr(("energy", "potential"), spec.potential, ctx.symbols(coords=True))
        if spec.potential is not None
        else sp.Integer(0)
    )
    return t, u


def _check_quadratic(ctx: Context, t: sp.Expr) -> sp.Expr | None:
    """T must be a quadratic form in the velocities: T = q_dot^T H(q) q_dot / 2."""
    rates = [c.qd for c in ctx.coords.values()]
    expanded = sp.expand(t)
    bad = []
    for term in sp.Add.make_args(expanded):
        powers = term.as_powers_dict()
        degree = sum(powers.get(r, 0) for r in rates)
        if degree != 2 or any(not sp.sympify(powers.get(r, 0)).is_Integer for r in rates):
            bad.append(term)
    if bad:
        shown = ", ".join(sp.sstr(b) for b in bad[:3]) + (", ..." if len(bad) > 3 else "")
        ctx.error(
            ("energy", "kinetic"),
            "expected the kinetic energy as a quadratic form in the velocities, T = q_dot^T H(q) q_dot / 2 "
            f"(every term of degree 2 in the NAME_dot), found the term{'s' if len(bad) > 1 else ''} {shown}",
        )
        return None
    return t
