"""A teacher's order of terms and factors: the one printing rule of docs/typesetting.md.

The model keeps the value; only the printed form is ordered. In a product the factors come as

    number · masses · inertias · lengths and other data · g · coordinates · brackets · trigonometric
    factors · rates · accelerations

(``m_2 l_1 l_2 \\sin\\theta_2 \\dot\\theta_1 \\dot\\theta_2``; a bracket of data alone, such as
``(m_1 + m_2)``, goes with the masses in front), and every bracket has a positive leading term, its sign
taken outside (``-g(m_3 + m_4)``, never ``g(-m_3 - m_4)``). An equation of motion is printed as
``Σ_j H_ij q̈_j`` in the order of the coordinates, then the velocity products, then the rest (gravity,
springs), each group's terms collected over what they share with the coordinates, with the applied
inputs on the right of ``=``.
"""

from __future__ import annotations

from enum import IntEnum

import sympy as sp

from tutgen.model.system import System


class Role(IntEnum):
    """Where a factor goes in a printed product (smaller first)."""

    NUMBER = 0
    MASS = 1
    INERTIA = 2
    DATA = 3
    GRAVITY = 4
    COORDINATE = 5
    BRACKET = 6
    TRIG = 7
    RATE = 8
    ACCELERATION = 9


_TRIG = (sp.sin, sp.cos, sp.tan, sp.cot, sp.sec, sp.csc)


def symbol_roles(system: System) -> dict[sp.Basic, Role]:
    """The role of each of a system's symbols, from its kind (coordinate, rate) or its name: a parameter
    named ``m…`` is a mass, ``I…``/``J…`` an inertia, ``g`` the gravity, anything else data."""
    roles: dict[sp.Basic, Role] = {}
    for p in system.parameters:
        name = str(p.symbol)
        if name == "g":
            roles[p.symbol] = Role.GRAVITY
        elif name[:1] == "m" and (len(name) == 1 or not name[1].isalpha() or name[1] == "_"):
            roles[p.symbol] = Role.MASS
        elif name[:1] in ("I", "J"):
            roles[p.symbol] = Role.INERTIA
        else:
            roles[p.symbol] = Role.DATA
    for c in system.coordinates:
        roles[c.q] = Role.COORDINATE
        roles[c.qd] = Role.RATE
        roles[c.qdd] = Role.ACCELERATION
    return roles


def factor_role(factor: sp.Basic, roles: dict[sp.Basic, Role]) -> Role:
    if factor.is_number:
        return Role.NUMBER
    if isinstance(factor, sp.Pow):
        return factor_role(factor.base, roles)
    if isinstance(factor, _TRIG):
        return Role.TRIG
    if isinstance(factor, sp.Add):
        inner = [roles.get(s, Role.DATA) for s in factor.free_symbols]
        return min(inner) if inner and max(inner) < Role.COORDINATE else Role.BRACKET
    return roles.get(factor, Role.DATA)


def positive_lead(expr: sp.Expr) -> tuple[int, sp.Expr]:
    """``(sign, body)`` with ``expr = sign · body`` and ``body`` not starting with a minus."""
    if expr.could_extract_minus_sign():
        return -1, -expr
    return 1, expr


Term = tuple[int, sp.Expr]  # (sign, body): the printed term is ``- body`` when sign is negative


def _collected(terms: list[sp.Expr], coordinate_symbols: set[sp.Basic], rates: list[sp.Basic]) -> list[Term]:
    """Terms gathered over what they share with the coordinates (``a g m_1 \\cos q + a g m_2 \\cos q`` ->
    ``(m_1 + m_2) a g \\cos q``), each coefficient factored with a positive lead; groups with the squares
    of the rates first, then their products, by the order of the coordinates (``rates``)."""
    groups: dict[sp.Expr, list[sp.Expr]] = {}
    for t in terms:
        coeff, rest = sp.S.One, sp.S.One
        for f in sp.Mul.make_args(t):
            if f.free_symbols & coordinate_symbols:
                rest *= f
            else:
                coeff *= f
        groups.setdefault(rest, []).append(coeff)
    order_of = {r: i for i, r in enumerate(rates)}
    out: list[Term] = []
    for rest, coeffs in sorted(groups.items(), key=lambda kv: _rate_key(kv[0], order_of)):
        sign, body = positive_lead(sp.factor_terms(sp.Add(*coeffs)))
        if rest == 1 and isinstance(body, sp.Add):  # terms free of the coordinates share nothing: one by one
            out += [positive_lead(c) for c in coeffs]  # (a sum's sign taken out would need a bracket)
            continue
        out.append((sign, _times(body, rest)))
    return out


def _rate_key(rest: sp.Expr, order_of: dict[sp.Basic, int]) -> tuple[int, tuple[int, ...]]:
    """Squares before products, each by the coordinates' order; terms without rates keep their place."""
    used = sorted(order_of[s] for s in rest.free_symbols if s in order_of)
    return (len(used), tuple(used))


def _times(coeff: sp.Expr, rest: sp.Expr) -> sp.Expr:
    """``coeff · rest`` without sympy distributing a number over a bracket."""
    if rest == 1:
        return coeff
    if isinstance(coeff, sp.Add):
        return sp.Mul(coeff, rest, evaluate=False)
    return coeff * rest


def equation_terms(expr: sp.Expr, system: System) -> list[Term] | None:
    """The terms of an equation of motion's left side in a teacher's order: the accelerations in the
    order of the coordinates (each with its collected coefficient), the velocity products, the rest.
    ``None`` when the expression is not a sum worth ordering."""
    expanded = sp.expand(expr)
    if not isinstance(expanded, sp.Add):
        return None
    coordinates = system.coordinates
    symbols = {s for c in coordinates for s in (c.q, c.qd, c.qdd)}
    ordered: list[Term] = []
    rest = expanded
    for c in coordinates:
        coeff = rest.coeff(c.qdd)
        if coeff == 0:
            continue
        rest = sp.expand(rest - coeff * c.qdd)
        sign, body = positive_lead(sp.factor_terms(coeff))
        ordered.append((sign, _times(body, c.qdd)))
    rates = [c.qd for c in coordinates]
    parts = sp.Add.make_args(rest) if rest != 0 else ()
    velocity = [t for t in parts if t.free_symbols & set(rates)]
    others = [t for t in parts if not t.free_symbols & set(rates)]
    # velocity terms are gathered over their rates (a bracketed coefficient per rate product), the others
    # over everything they share with the coordinates (a trigonometric factor, a spring's stretch)
    ordered += _collected(velocity, set(rates), rates) + _collected(others, symbols, rates)
    if sp.expand(sp.Add(*(sign * body for sign, body in ordered)) - expr) != 0:  # the printed form keeps the value
        return None
    return ordered
