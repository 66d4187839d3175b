"""Equilibria: the rest configurations G(q) = Q(q, 0), with the inputs at their given (or zero) values.

At rest q_dot = q_ddot = 0, so the equations of motion H q_ddot + C + G - Q = 0 reduce to the residual
r(q) = G(q) - Q(q, 0): the generalized forces of gravity and springs balanced by the applied ones (a
damper's force vanishes at rest). Its roots are found symbolically where sympy can (every family of
solutions of one period, e.g. theta = 0 and theta = pi, each + 2 k pi for an angle); when sympy cannot
and the spec is numeric, numerically, all roots in a stated box. A coordinate the residual does not
contain can rest anywhere: the equilibria are not isolated along it, which is reported, not an error.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.core.sorting import default_sort_key

from tutgen.engine.derivation import Derivation
from tutgen.engine.tidy import tidy
from tutgen.errors import SpecError, SpecErrors
from tutgen.limits import checkpoint

__all__ = ["BOX", "Equilibria", "check_given", "find_equilibria", "input_values", "rest_residual", "roots"]

#: the box searched for the roots of a numeric spec that sympy cannot solve: angles over one turn,
#: other coordinates (lengths, SI) within +- BOX
BOX = 10.0


@dataclass(frozen=True)
class Equilibria:
    """The rest configurations of a system.

    ``residual`` is G(q) - Q(q, 0) (parameters symbolic, inputs at their values); ``solutions`` each map
    every coordinate name to its value (a coordinate in ``free`` to 0, standing for any value);
    ``method`` says how they were found: "symbolic" (sympy's solve, every family), "numeric" (all
    roots found in the box, floats) or "none" (no equilibrium found).
    """

    residual: sp.ImmutableMatrix
    solutions: tuple[tuple[tuple[str, sp.Expr], ...], ...]
    free: tuple[str, ...]
    method: str
    remark: str | None = None


def input_values(d: Derivation) -> dict[sp.Symbol, sp.Expr]:
    """The inputs at the equilibrium: the spec's `analysis.inputs`, and 0 for every parameter without a
    value that appears in Q and is a force (a load's symbol: ``real``, not ``positive``) the spec did not
    name: an equilibrium is taken with the pushes off unless the spec says otherwise."""
    given = dict(d.system.analysis.inputs) if d.system.analysis is not None else {}
    q_vec = d.generalized_forces if d.generalized_forces is not None else sp.ImmutableMatrix([])
    values = d.values
    for s in sorted(q_vec.free_symbols, key=default_sort_key):
        is_parameter = any(p.symbol == s for p in d.system.parameters)
        if is_parameter and s not in values and s not in given and s.is_positive is not True:
            given[s] = sp.Integer(0)
    return given


def rest_residual(d: Derivation) -> sp.ImmutableMatrix:
    """G(q) - Q(q, 0): the equations of motion at rest, inputs at their values."""
    assert d.equations_of_motion is not None
    s = d.system
    rest: dict[sp.Basic, sp.Expr] = {c.qd: sp.Integer(0) for c in s.coordinates}
    rest.update({c.qdd: sp.Integer(0) for c in s.coordinates})
    rest.update(input_values(d))
    return sp.ImmutableMatrix([tidy(sp.expand(e.xreplace(rest))) for e in d.equations_of_motion])


def check_given(d: Derivation, residual: sp.ImmutableMatrix) -> None:
    """The spec's `analysis.about` must be an equilibrium: a spec error at it, saying by how much G and
    Q differ there, if it is not."""
    a = d.system.analysis
    if a is None or a.about is None:
        return
    at = {c.q: v for c, (_, v) in zip(d.system.coordinates, a.about, strict=True)}
    off = [sp.simplify(d.numeric(e.xreplace(at))) for e in residual]
    bad = [(c, e) for c, e in zip(d.system.coordinates, off, strict=True) if e != 0]
    if not bad:
        return
    where = ", ".join(f"{c.name} = {v}" for c, (_, v) in zip(d.system.coordinates, a.about, strict=True))
    by = "; ".join(f"(G - Q)_{c.name} = {sp.N(e, 4) if e.is_number else e}" for c, e in bad)
    raise SpecErrors(
        [
            SpecError(
                a.place("about"),
                f"'about' is not an equilibrium: at {where}, G(q) - Q(q, 0) is not 0: {by}",
                "an equilibrium balances gravity and the springs (G) with the applied forces (Q); ask for "
                "`equilibria` to see where they balance",
            )
        ]
    )


def _angle(d: Derivation, name: str) -> bool:
    c = next(c for c in d.system.coordinates if c.name == name)
    return c.dimension == "angle"


def _canonical(d: Derivation, name: str, v: sp.Expr) -> sp.Expr:
    """An angle's value in (-pi, pi] where it is a number (the family is v + 2 k pi)."""
    if _angle(d, name) and v.is_number and v.is_real:
        w = sp.nsimplify(v) if isinstance(v, sp.Float) else v
        shifted = w - 2 * sp.pi * sp.floor((w + sp.pi) / (2 * sp.pi))
        if shifted == -sp.pi:
            shifted = sp.pi
        return shifted if not isinstance(v, sp.Float) else sp.Float(shifted, 15)
    return v


#: what :func:`roots` says when it could not solve (reported as the method "none", with the remark)
UNSOLVED = "unsolved"
UNSOLVED_REMARK = (
    "sympy finds no closed form for these equations, and the parameters have no values to search for the "
    "roots numerically; give the parameters values, or name an equilibrium with `about`"
)


def find_equilibria(d: Derivation) -> Equilibria:
    """Every equilibrium of a derivation (see the module's docstring)."""
    checkpoint("equilibria")
    residual = rest_residual(d)
    check_given(d, residual)
    coords = d.system.coordinates
    present = [c for c in coords if any(e.has(c.q) for e in residual)]
    free = tuple(c.name for c in coords if c not in present)
    equations = [e for e in residual if e != 0]
    if not present:
        remark = None if not equations else "G - Q does not vanish at rest anywhere: there is no equilibrium"
        solutions: tuple[tuple[tuple[str, sp.Expr], ...], ...] = ()
        if not equations:
            solutions = (tuple((c.name, sp.Integer(0)) for c in coords),)
        return Equilibria(residual, solutions, free, "symbolic" if not equations else "none", remark)
    out, method = roots(d, residual, present, coords)
    if method == UNSOLVED:
        return Equilibria(residual, (), free, "none", UNSOLVED_REMARK)
    if not out:
        return Equilibria(residual, (), free, "none", "no equilibrium was found")
    return Equilibria(residual, tuple(out), free, method)


def _solve_one(equation: sp.Expr, x: sp.Symbol) -> list[sp.Expr] | None:
    """The roots of one equation in one unknown, factor by factor, every family of one period: a factor
    in cos(x) alone gives +- acos(c), one in sin(x) alone asin(s) and pi - asin(s) (sympy's own solve
    returns half-angle forms and drops roots such as pi for these); other factors go to sympy."""
    c, s = sp.Dummy("c"), sp.Dummy("s")
    roots: list[sp.Expr] = []
    try:
        factors = sp.factor_list(sp.factor(equation))[1]
    except sp.PolynomialError:  # not a polynomial in its atoms (a spring's sqrt((d + x)^2)/|d + x|): numeric roots
        return None
    for factor, _ in factors:
        if not factor.has(x):
            continue
        if factor.has(sp.tan):
            factor = sp.together(factor.rewrite(sp.sin)).as_numer_denom()[0]
        in_cos = factor.xreplace({sp.cos(x): c})
        in_sin = factor.xreplace({sp.sin(x): s})
        try:
            if not in_cos.has(x):
                for v in sp.solve(in_cos, c):
                    roots += [sp.acos(v)] if sp.acos(v) in (0, sp.pi) else [sp.acos(v), -sp.acos(v)]
            elif not in_sin.has(x):
                for v in sp.solve(in_sin, s):
                    roots += [sp.asin(v)] if sp.asin(v) == sp.pi / 2 else [sp.asin(v), sp.pi - sp.asin(v)]
            else:
                trig = {f: sp.Dummy() for f in factor.atoms(sp.sin, sp.cos) if f.has(x)}
                if trig and factor.xreplace(trig).has(x):
                    return None  # x both inside and outside sin/cos (x - 2 sin x): no closed form, and
                    # sympy's solve spends many seconds finding that out
                roots += sp.solve(factor, x)
        except (NotImplementedError, ValueError, TypeError):
            return None
    return [r for r in roots if r.is_real is not False]


def _solve_symbolic(equations: list[sp.Expr], unknowns: list[sp.Symbol]) -> list[dict[sp.Symbol, sp.Expr]] | None:
    """Every real solution, or None when sympy cannot solve the system. Equations in one unknown each
    (decoupled, the common case) are solved one by one (:func:`_solve_one`) and combined; a coupled
    system goes to sympy's solve whole."""
    alone = {u: [e for e in equations if e.free_symbols & set(unknowns) == {u}] for u in unknowns}
    if all(alone.values()) and sum(len(v) for v in alone.values()) == len(equations):
        choices: list[list[dict[sp.Symbol, sp.Expr]]] = []
        for u, eqs in alone.items():
            roots = _solve_one(eqs[0], u)
            if roots is None:
                return None
            roots = [r for r in roots if all(sp.simplify(e.subs(u, r)) == 0 for e in eqs[1:])]
            choices.append([{u: r} for r in roots])
        out: list[dict[sp.Symbol, sp.Expr]] = [{}]
        for options in choices:
            out = [{**a, **b} for a in out for b in options]
        return out
    try:
        sols = sp.solve(equations, unknowns, dict=True)
    except (NotImplementedError, ValueError, TypeError):
        return None
    out = []
    for sol in sols:
        if any(u not in sol for u in unknowns):
            return None  # a family sympy leaves partly unsolved: not a list of equilibria
        if any(v.is_real is False for v in sol.values()):
            continue
        out.append(sol)
    return out


def existence(value: sp.Expr) -> tuple[sp.Basic, ...]:
    """Where a symbolic equilibrium exists: the argument of each acos or asin in it must lie in [-1, 1]
    (only the bound that can fail, for an argument of known sign), e.g. g/(R omega^2) <= 1."""
    out: list[sp.Basic] = []
    for f in sorted(value.atoms(sp.acos, sp.asin), key=default_sort_key):
        arg = f.args[0]
        if arg.is_number:
            continue
        if arg.is_nonnegative:
            out.append(sp.Le(arg, 1))
        elif arg.is_nonpositive:
            out.append(sp.Ge(arg, -1))
        else:
            out += [sp.Ge(arg, -1), sp.Le(arg, 1)]
    return tuple(dict.fromkeys(out))


def _solve_numeric(d: Derivation, residual: sp.ImmutableMatrix, present: list) -> list[dict[sp.Symbol, sp.Expr]]:
    """All roots found in the box from a grid of starting points (scipy's root), rounded and deduplicated."""
    import numpy as np
    from scipy.optimize import root

    q = [c.q for c in present]
    rows = [d.numeric(e) for e in residual if e != 0]
    f = sp.lambdify([q], rows, "numpy")
    jac = sp.lambdify([q], sp.Matrix(rows).jacobian(q), "numpy")
    spans = [(-np.pi, np.pi) if c.dimension == "angle" else (-BOX, BOX) for c in present]
    grids = np.meshgrid(*[np.linspace(lo, hi, 9) for lo, hi in spans])
    roots: list[np.ndarray] = []
    for start in np.stack([g.ravel() for g in grids], axis=1):
        sol = root(lambda x: np.asarray(f(x), dtype=float), start, jac=lambda x: np.asarray(jac(x), dtype=float))
        if not sol.success or np.max(np.abs(f(sol.x))) > 1e-9:
            continue
        x = sol.x.copy()
        for i, c in enumerate(present):
            if c.dimension == "angle":
                x[i] = (x[i] + np.pi) % (2 * np.pi) - np.pi
        inside = all(lo - 1e-9 <= xi <= hi + 1e-9 for xi, (lo, hi) in zip(x, spans, strict=True))
        if inside and not any(np.allclose(x, r, atol=1e-7) for r in roots):
            roots.append(x)
    return [{qi: sp.Float(round(float(xi), 12), 15) for qi, xi in zip(q, r, strict=True)} for r in roots]


def roots(
    d: Derivation, residual: sp.ImmutableMatrix, present: list, shown: list | None = None
) -> tuple[list[tuple[tuple[str, sp.Expr], ...]], str]:
    """The roots of ``residual`` in the coordinates ``present`` (every family, symbolically where sympy
    can, else numerically in the box when everything is a number), each as (name, value) pairs of
    ``shown`` (default ``present``) in order, 0 for a coordinate solved for by none of them, an angle's
    value in (-pi, pi]; with how they were found ("symbolic", "numeric" or "none"). Shared with the
    equilibria (:func:`find_equilibria`) and steady motion (tutgen.engine.analysis.steady)."""
    equations = [e for e in residual if e != 0]
    found = _solve_symbolic(equations, [c.q for c in present])
    method = "symbolic"
    if found is None and not (residual.free_symbols - {c.q for c in d.system.coordinates} - set(d.values)):
        found = _solve_numeric(d, residual, present)
        method = "numeric"
    if found is None:  # sympy has no closed form, and the parameters have no values for a numeric search
        return [], UNSOLVED
    if not found:
        return [], "none"
    out: list[tuple[tuple[str, sp.Expr], ...]] = []
    seen: set[tuple[str, ...]] = set()
    for sol in found:
        values = tuple(
            (c.name, _canonical(d, c.name, tidy(sp.sympify(sol.get(c.q, sp.Integer(0))))))
            for c in (present if shown is None else shown)
        )
        key = tuple(sp.srepr(v) for _, v in values)
        if key not in seen:
            seen.add(key)
            out.append(values)
    out.sort(key=lambda vs: [default_sort_key(v) for _, v in vs])
    return out, method
