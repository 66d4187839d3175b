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

from dataclasses import dataclass
from enum import IntEnum
from functools import lru_cache

import sympy as sp

from tutgen.model.system import System
from tutgen.render.signs import negative_number
from tutgen.render.size import count_ops  # sympy's count, faster (issue 17)

#: how many distinct expressions the memoised functions below remember: a worked solution asks for the
#: same ones again and again (T in the energies, in L and in Lagrange's terms; H's entries when read off,
#: in H and in its determinant), a sheet's worker for thousands of its variants' expressions (issue 17)
MEMO_SIZE = 1 << 14


def forget() -> None:
    """Empty the memoised functions' tables (tests that count the work done)."""
    for memoised in (ops, arranged, _arranged_terms, _coefficient):
        memoised.cache_clear()


@lru_cache(maxsize=MEMO_SIZE)
def ops(expr: sp.Basic) -> int:
    """``sympy.count_ops(expr)``, remembered (an expression is immutable, and sympy compares and hashes it
    by its structure: ``x + 1.0`` and ``x + 1`` are different keys), counted by render.size.count_ops."""
    return count_ops(expr)


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
        if inner and min(inner) >= Role.RATE:  # a bracket of rates goes with the rates: sin θ (θ̇₁ + θ̇₂)
            return Role.RATE
        return min(inner) if inner and max(inner) < Role.COORDINATE else Role.BRACKET
    return roles.get(factor, Role.DATA)


def positive_lead(expr: sp.Expr) -> tuple[int, sp.Expr]:
    """``(sign, body)`` with ``expr = sign · body`` and ``body`` not starting with a minus."""
    first = expr if expr.is_Number else expr.args[0] if expr.is_Mul else None
    if isinstance(first, (sp.Rational, sp.Float)):  # a finite coefficient: sympy's answer, unasked
        negative = negative_number(first)
    else:
        negative = expr.could_extract_minus_sign()
    if negative:
        return -1, -expr
    return 1, expr


Term = tuple[int, sp.Expr]  # (sign, body): the printed term is ``- body`` when sign is negative


class OrderedSum(sp.Add):
    """A sum whose terms are printed in the order of its arguments (tutgen.render.printer does not sort it):
    built unevaluated, ``OrderedSum(*terms, evaluate=False)``; its value is that of the plain sum."""


def _plus(terms: list[Term]) -> sp.Expr:
    """The terms as one sum that prints in their order (a negative body as ``-1 · body``, unevaluated, so
    that sympy does not distribute the minus over a bracket)."""
    parts = [body if sign > 0 else sp.Mul(sp.S.NegativeOne, body, evaluate=False) for sign, body in terms]
    return parts[0] if len(parts) == 1 else OrderedSum(*parts, evaluate=False)


@dataclass(frozen=True, eq=False)  # compared and hashed by identity: the key of the memoised arrangements
class _Levels:
    """What a term is gathered over, level by level: its rates and accelerations (0), its coordinates (1),
    its data other than masses and inertias (2: lengths, g); what is left are masses, inertias, numbers."""

    roles: dict[sp.Basic, Role]
    accelerations: tuple[sp.Basic, ...]
    rates: tuple[sp.Basic, ...]
    coordinates: tuple[sp.Basic, ...]

    def takes(self, level: int, factor: sp.Basic) -> bool:
        if level == 0:
            return bool(factor.free_symbols & {*self.rates, *self.accelerations})
        if level == 1:
            return bool(factor.free_symbols & set(self.coordinates))
        return factor_role(factor, self.roles) in (Role.DATA, Role.GRAVITY)

    def key(self, level: int, part: sp.Expr) -> tuple[object, ...]:
        """Where a group comes at its level: accelerations by coordinate, then rate products by their
        coordinates' indices (θ̇₁², θ̇₁θ̇₂, θ̇₂², as H's entries are read), then what has no rates; constants
        before the coordinates' functions, those by their first coordinate; data by name, masses last."""
        free = part.free_symbols
        if level == 0:
            if part == 1:
                return (2,)
            acc = [i for i, s in enumerate(self.accelerations) if s in free]
            if acc:
                return (0, tuple(acc))
            used: list[int] = []
            for f in sp.Mul.make_args(part):
                base, exp = f.as_base_exp()
                if base in self.rates and exp.is_Integer:
                    used += [self.rates.index(base)] * int(exp)
                else:
                    used += [i for i, s in enumerate(self.rates) if s in f.free_symbols]
            return (1, tuple(sorted(used)))
        if level == 1:
            if part == 1:
                return (0,)
            first = min((i for i, s in enumerate(self.coordinates) if s in free), default=0)
            return (1, first, ops(part), sp.default_sort_key(part))
        return (1,) if part == 1 else (0, sp.default_sort_key(part))


def _split(term: sp.Expr, level: int, levels: _Levels) -> tuple[sp.Expr, sp.Expr]:
    """(the part of a product the level gathers over, the coefficient)."""
    part, coeff = sp.S.One, sp.S.One
    for f in sp.Mul.make_args(term):
        if levels.takes(level, f):
            part *= f
        else:
            coeff *= f
    return part, coeff


def _arrange(terms: list[sp.Expr], level: int, levels: _Levels) -> list[Term]:
    """Terms (of an expanded sum) gathered over what they share at ``level`` and the levels below, each
    group's coefficient one bracket with a positive lead, groups in the level's order."""
    if level > 2:  # masses, inertias and numbers: each term on its own
        return sorted((positive_lead(t) for t in terms), key=lambda t: sp.default_sort_key(t[1]))
    groups: dict[sp.Expr, list[sp.Expr]] = {}
    for t in terms:
        part, coeff = _split(t, level, levels)
        groups.setdefault(part, []).append(coeff)
    out: list[Term] = []
    for part in sorted(groups, key=lambda p: levels.key(level, p)):
        coeffs = groups[part]
        if part == 1:
            out += _arrange(coeffs, level + 1, levels)
            continue
        sign, body = _coefficient(tuple(coeffs), level + 1, levels)
        out.append((sign, _times(body, part)))
    return out


@lru_cache(maxsize=MEMO_SIZE)
def _coefficient(coeffs: tuple[sp.Expr, ...], level: int, levels: _Levels) -> Term:
    """A group's coefficient: the common factor in front, the rest arranged from ``level`` on, with a
    positive lead (``-(m_3 + m_4) g``, ``(m_1 + m_2) a_1^2 + m_2 a_2^2``). Remembered: the sums of a
    worked solution share their groups (T in L, L's terms in Lagrange's), six calls in seven repeat one.
    :class:`_Unkept` when the printed coefficient would not keep the value of the sum of ``coeffs``."""
    if len(coeffs) == 1 and coeffs[0].is_Atom:  # a lone number or symbol: nothing to factor (factor_terms'
        return positive_lead(coeffs[0])  # own first test), nor to arrange
    given = sp.Add(*coeffs)
    sign, body = _factored(given, level, levels)
    # the printed coefficient keeps the value (factor_terms, trigsimp and decimals may not): its expansion
    # is the sum's (the cheap test, which nearly always decides), or the two differ by zero (numbers of
    # other kinds, 0.5 and 1/2, cancel). Tested here, once per group (the groups repeat), rather than on
    # the whole arranged sum: the groups' terms are the sum's, so the sum keeps its value when each does
    printed = expanded_form(sign * body)
    if printed != given and expanded_form(printed - given) != 0:
        raise _Unkept
    return sign, body


def _factored(given: sp.Expr, level: int, levels: _Levels) -> Term:
    """:func:`_coefficient`, untested: the common factor of the sum ``given`` in front, the rest arranged
    from ``level`` on, with a positive lead."""
    total = sp.factor_terms(given)
    if _has_pythagoras(total):  # expanding may show sin² x + cos² x (a moment balance's l² θ̈ terms)
        total = sp.factor_terms(sp.trigsimp(total))
    common, inner = sp.S.One, total
    if isinstance(total, sp.Mul):
        adds = [f for f in total.args if isinstance(f, sp.Add)]
        if len(adds) == 1:
            inner = adds[0]
            common = sp.Mul(*(f for f in total.args if f is not inner))
    if not isinstance(inner, sp.Add):
        return positive_lead(total)
    arranged = _arrange(list(sp.Add.make_args(inner)), level, levels)
    sign, common = positive_lead(common)
    if arranged and arranged[0][0] < 0:
        sign, arranged = -sign, [(-s, b) for s, b in arranged]
    return sign, _times(common, _plus(arranged)) if common != 1 else _plus(arranged)


class _Unkept(Exception):
    """A group's arranged coefficient that does not keep its value: the sum is not arranged."""


def _has_pythagoras(expr: sp.Expr) -> bool:
    """Whether ``sin(x)**2`` and ``cos(x)**2`` of one argument both occur (cheap, before a trigsimp)."""
    squares = [p for p in expr.atoms(sp.Pow) if p.exp == 2 and isinstance(p.base, (sp.sin, sp.cos))]
    sines = {p.base.args[0] for p in squares if isinstance(p.base, sp.sin)}
    return any(isinstance(p.base, sp.cos) and p.base.args[0] in sines for p in squares)


def _times(coeff: sp.Expr, rest: sp.Expr) -> sp.Expr:
    """``coeff · rest`` without sympy distributing a number over a bracket."""
    if rest == 1:
        return coeff
    if coeff == 1:
        return rest
    if isinstance(coeff, sp.Add) or isinstance(rest, sp.Add):
        return sp.Mul(coeff, rest, evaluate=False)
    return coeff * rest


def levels_of(system: System) -> _Levels:
    coordinates = system.coordinates
    return _Levels(
        symbol_roles(system),
        tuple(c.qdd for c in coordinates),
        tuple(c.qd for c in coordinates),
        tuple(c.q for c in coordinates),
    )


def arranged_terms(expr: sp.Expr, levels: _Levels) -> list[Term] | None:
    """The terms of a sum in a teacher's order (docs/typesetting.md): the accelerations in the order of
    the coordinates, each with its collected coefficient; the rate products; the rest, gathered over the
    coordinates' functions (a trigonometric factor, a spring's stretch), then over the data (``(m_1 +
    m_2) a_1^2``). ``None`` when the expression is not a sum worth ordering or the arranged terms would
    not keep its value."""
    found = _arranged_terms(expr, levels)
    return list(found) if found is not None else None


def already_expanded(expr: sp.Expr) -> bool:
    """Whether ``sympy.expand(expr)`` is ``expr`` itself, read off its form (issue 17: four in five of the
    sums a sheet arranges are, and ``expand`` walks a sum once per hint to find nothing to do): a sum of
    products of numbers, symbols, powers of a symbol, and sines and cosines (and their integer powers)
    of a sum of symbols with rational coefficients. None of expand's default hints changes any of these
    (no product over a sum, no power of a sum or of a product, no exponent that is a sum, no ``exp`` or
    ``log``); ``False`` for anything else, which ``expand`` then decides (tests/render/test_order.py)."""
    for term in sp.Add.make_args(expr):
        for factor in sp.Mul.make_args(term):
            if factor.is_Number or factor.is_Symbol:
                continue
            if factor.is_Pow:
                base, exp = factor.args
                if (base.is_Symbol and exp.is_Rational) or (exp.is_Integer and _trig_of_linear(base)):
                    continue
                return False
            if not _trig_of_linear(factor):
                return False
    return True


def expanded_form(expr: sp.Expr) -> sp.Expr:
    """``sympy.expand(expr)``, without its walks when ``expr`` is :func:`already_expanded`."""
    return expr if already_expanded(expr) else sp.expand(expr)


def _trig_of_linear(f: sp.Basic) -> bool:
    """``sin`` or ``cos`` of a sum of symbols with rational coefficients (``q_1 + 2 q_2``)."""
    if not isinstance(f, (sp.sin, sp.cos)):
        return False
    for t in sp.Add.make_args(f.args[0]):
        if not (
            t.is_Symbol
            or t.is_Rational
            or (t.is_Mul and len(t.args) == 2 and t.args[0].is_Rational and t.args[1].is_Symbol)
        ):
            return False
    return True


@lru_cache(maxsize=MEMO_SIZE)
def _arranged_terms(expr: sp.Expr, levels: _Levels) -> tuple[Term, ...] | None:
    """:func:`arranged_terms`, remembered per expression and printer (``levels``)."""
    expanded = expanded_form(expr)
    if not isinstance(expanded, sp.Add):
        return None
    try:  # the printed form keeps the value: each group's coefficient is tested (_coefficient); the
        # rest is exact (a term split into its part and coefficient, a sign taken out)
        return tuple(_arrange(list(sp.Add.make_args(expanded)), 0, levels))
    except _Unkept:
        return None


@lru_cache(maxsize=MEMO_SIZE)
def arranged(expr: sp.Expr, levels: _Levels) -> sp.Expr:
    """``expr`` as a sum that prints in a teacher's order, or ``expr`` itself when that is much longer:
    an arranged form that has a quarter more operations than the model's (``m_2 (l_1 + l_2 \\cos q)^2`` expanded)
    is not used."""
    found = arranged_terms(expr, levels)
    result = _plus(found) if found else expr
    if found and ops(result) > 1.25 * ops(expr) + 2:
        result = expr
    squares = _perfect_squares(expr, levels)
    if squares is not None and ops(squares) < ops(result):
        return squares
    return result


#: a mass's coefficient with more generators than this (symbols and functions of the coordinates) is not
#: factored in search of a square: sympy's ``factor`` grows fast with them (one coefficient of the symbolic
#: PUMA's U, 53 generators: 5 s), and a square a teacher writes has a few (p08's: 4, the top's: 6)
SQUARE_GENERATORS = 24


def _generators(expr: sp.Expr) -> int:
    return len(expr.free_symbols | expr.atoms(sp.Function))


def _square_degree(coefficient: sp.Expr, coordinates: set[sp.Symbol]) -> bool:
    """Whether some generator in the coordinates has degree 2 or more in ``coefficient``, the polynomial:
    a square ``f**2`` with a generator ``g`` of the coordinates in ``f`` has degree ``2 deg_g f`` in ``g``
    and so has every multiple of it, so without one there is no such square (a planar chain's H: every
    cosine of a joint-angle sum to the first power). A power that is not a positive integer, or a
    coordinate inside one, is ``True``: the square-free decomposition decides."""
    for term in sp.Add.make_args(coefficient):
        for factor in sp.Mul.make_args(term):
            if not factor.free_symbols & coordinates:
                continue
            _, exp = factor.as_base_exp()  # exp(q) is (E, q): a power that is no integer
            if not (exp.is_Integer and exp > 0) or exp >= 2:
                return True
    return False


def _may_hold_square(coefficient: sp.Expr, levels: _Levels) -> bool:
    """Whether ``sp.factor(coefficient)`` can hold a square of a function of the coordinates: its
    square-free decomposition (gcd-based, cheap) has a part of multiplicity 2 in them. ``factor``'s
    multivariate Hensel lifting is what costs (a planar 5-link chain's H coefficients ran for minutes, all
    square-free); a coefficient without such a part is not factored, which prints it exactly as before.
    When the decomposition cannot be taken, ``True``: the old path decides."""
    coordinates = set(levels.coordinates)
    if not _square_degree(coefficient, coordinates):
        return False
    try:
        _, parts = sp.sqf_list(coefficient)
    except sp.PolynomialError:
        try:
            _, parts = sp.sqf_list(sp.numer(sp.together(coefficient)))
        except (sp.PolynomialError, NotImplementedError):
            return True
    except NotImplementedError:
        return True
    return any(k == 2 and part.free_symbols & coordinates for part, k in parts)


def _perfect_squares(expr: sp.Expr, levels: _Levels) -> sp.Expr | None:
    """A configuration-dependent sum with a mass's coefficient a perfect square, printed as the square
    (p08's ``m_1 l_1^2 + m_2 (l_1 + l_2 \\cos\\theta_2)^2``, not its three expanded terms): the terms
    gathered over their masses, in the masses' order, each mass's coefficient factored; ``None`` when
    no coefficient is a square of a sum of the coordinates' functions, the expression has rates (an
    energy or an equation of motion keeps the order of its rates), or the form would change the value."""
    free = expr.free_symbols
    if free & {*levels.rates, *levels.accelerations} or not free & set(levels.coordinates):
        return None
    expanded = expanded_form(expr)
    if not isinstance(expanded, sp.Add):
        return None
    groups: dict[sp.Expr, list[sp.Expr]] = {}
    for t in sp.Add.make_args(expanded):
        mass = sp.Mul(*(f for f in sp.Mul.make_args(t) if factor_role(f, levels.roles) is Role.MASS))
        groups.setdefault(mass, []).append(t / mass)
    terms: list[Term] = []
    found = False
    if all(mass == 1 for mass in groups):  # no mass to gather over (a sheet's variant: every mass a number)
        return None
    for mass in sorted(groups, key=lambda m: (m == 1, sp.default_sort_key(m))):
        coefficient = sp.Add(*groups[mass])
        if mass == 1:  # what no mass multiplies is never printed as a square: its terms as they are
            terms += _arrange([c for c in sp.Add.make_args(expanded_form(coefficient))], 0, levels)
            continue
        try:
            factored = (
                sp.factor(coefficient)
                if _generators(coefficient) <= SQUARE_GENERATORS and _may_hold_square(coefficient, levels)
                else coefficient
            )
        except (sp.PolynomialError, NotImplementedError):
            factored = coefficient
        sign, body = positive_lead(factored)
        square = next(
            (
                f
                for f in sp.Mul.make_args(body)
                if isinstance(f, sp.Pow)
                and f.exp == 2
                and isinstance(f.base, sp.Add)
                and f.base.free_symbols & set(levels.coordinates)
            ),
            None,
        )
        if square is not None:
            found = True
            rest = body / square
            _, base = positive_lead(square.base)  # (-a - b)^2 = (a + b)^2
            inner = arranged(base, levels) if isinstance(base, sp.Add) else base
            terms.append((sign, _times(mass * rest, sp.Pow(inner, 2, evaluate=False))))
        else:
            terms += _arrange([mass * c for c in sp.Add.make_args(expanded_form(coefficient))], 0, levels)
    if not found:
        return None
    result = _plus(terms)
    if sp.expand(result - expr) != 0:  # the printed form keeps the value
        return None
    return result


def equation_terms(expr: sp.Expr, system: System) -> list[Term] | None:
    """The terms of an equation of motion's left side in a teacher's order (:func:`arranged_terms`)."""
    return arranged_terms(expr, levels_of(system))
