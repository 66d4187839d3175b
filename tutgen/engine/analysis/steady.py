"""Steady motion: the relative equilibria of a system with cyclic coordinates (issue 18, point 3).

A coordinate is cyclic when it appears in none of H, G and Q (its rate may: the spin of a hoop, the
precession of a top). With its rate held at a constant omega, the other coordinates s can stay at rest:
setting q_ddot = 0, q_dot_s = 0 and q_dot_c = omega in the equations of motion H q_ddot + C + G = Q
leaves the rows of s as equations in q_s alone,

    (C + G - Q)_s (q_s; omega) = 0,

solved as the equilibria are (every family; numerically in a box for a numeric spec sympy cannot
solve). Where a root is an acos or asin, the steady state exists only where its argument lies in
[-1, 1]: for the bead on a hoop cos theta = g/(R omega^2), so only where g <= R omega^2.

The row of each cyclic coordinate at the steady state is the generalized force it then needs,
(C + G)_c: zero for a free cyclic coordinate (Q_c = 0), whose conjugate momentum p_c = dL/dq_dot_c is
then conserved; a driven one (Q_c holds an input) gets the input that balances its row.

Stability, from the first-order expansion of the rows of s about the steady state:

- a driven cyclic coordinate keeps its rate (its drive holds it): delta q_dot_c = 0;
- a free one keeps its momentum instead (Routh's reduction): delta p_c = 0, so
  delta q_dot_c = -A_cc^-1 (A_cs delta q_dot_s + P_cs delta q_s), with A = dp_c/dq_dot and
  P = dp_c/dq_s at the steady state, substituted into the rows of s.

Either gives M_r delta q_ddot_s + D_r delta q_dot_s + K_r delta q_s = 0 (D_r holds the gyroscopic
coupling), classified by its eigenvalues (numeric spec) or the sign of K_r (symbolic, D_r = 0).
"""

from __future__ import annotations

import cmath
import random
from dataclasses import dataclass

import sympy as sp
from sympy.core.sorting import default_sort_key

from tutgen.engine.analysis.equilibria import UNSOLVED, existence, input_values, roots
from tutgen.engine.analysis.linear import sign_condition, stiffness_verdict
from tutgen.engine.derivation import Check, Derivation
from tutgen.engine.tidy import tidy
from tutgen.errors import SpecError, SpecErrors
from tutgen.limits import checkpoint
from tutgen.model.system import Coordinate

__all__ = ["SteadyMotion", "SteadyState", "cyclic_coordinates", "steady_motion"]

#: a symbolic reduced model longer than this (sympy's operation count) is not judged by its sign
MAX_OPS = 400

#: a real part this small (relative to the largest eigenvalue) counts as zero
ZERO = 1e-9


@dataclass(frozen=True)
class SteadyState:
    """One steady motion: the other coordinates' values, where it exists, what it needs, its stability.

    ``at`` maps each non-cyclic coordinate to its steady value (0 for one in ``SteadyMotion.free_others``,
    standing for any); ``exists_where`` the inequalities it needs (empty: always); ``required`` each held
    cyclic coordinate's generalized force (C + G)_c there; ``inputs`` an input of a driven row solved so
    that the row balances (tau = b Omega); ``momenta`` each held coordinate's p_c = dL/dq_dot_c there.
    ``mass``, ``damping``, ``stiffness`` are M_r, D_r, K_r of the reduced linear model (see the module).
    """

    at: tuple[tuple[str, sp.Expr], ...]
    exists_where: tuple[sp.Basic, ...]
    required: tuple[tuple[str, sp.Expr], ...]
    inputs: tuple[tuple[sp.Symbol, sp.Expr], ...]
    momenta: tuple[tuple[str, sp.Expr], ...]
    mass: sp.ImmutableMatrix
    damping: sp.ImmutableMatrix
    stiffness: sp.ImmutableMatrix
    verdict: str  # "asymptotically stable", "stable", "unstable", "conditional", "undetermined", "neutral"
    reason: str
    stable_where: tuple[sp.Basic, ...] = ()
    eigenvalues: tuple[complex, ...] | None = None  # numeric spec: of the reduced model, Im >= 0
    # whether it exists at these values: True/False when every condition is a number, else None
    exists: bool | None = True
    # at a pole of the coordinates (a free held coordinate's momentum independent of its rate): then
    # mass and stiffness are those of the rest state, H and d(G - Q)/dq of the others (see _at_pole)
    pole: bool = False


@dataclass(frozen=True)
class SteadyMotion:
    """The steady motions of a system at the given rates of its cyclic coordinates.

    ``cyclic`` is every cyclic coordinate; ``rates`` those held, with their rate (the spec's
    `analysis.steady`, else every cyclic coordinate at its own rate symbol); ``free`` those of
    ``rates`` with Q_c = 0 (momentum held; the others are driven, rate held); ``others`` the rest, of
    which ``free_others`` appear in no row (they may rest anywhere); ``residual`` the rows of ``others``
    at the steady rates, each = 0; ``method`` as for the equilibria ("symbolic", "numeric", "none").
    """

    cyclic: tuple[str, ...]
    rates: tuple[tuple[str, sp.Expr], ...]
    free: tuple[str, ...]
    others: tuple[str, ...]
    free_others: tuple[str, ...]
    residual: sp.ImmutableMatrix
    states: tuple[SteadyState, ...]
    method: str
    remark: str | None
    check: Check

    @property
    def held(self) -> str:
        """What the stability analysis holds constant: "momentum" (every held coordinate free), "rate"
        (every one driven) or "mixed"."""
        if len(self.free) == len(self.rates):
            return "momentum"
        return "rate" if not self.free else "mixed"


def _where_found(d: Derivation, q: sp.Symbol) -> list[str]:
    """Which of H, G and Q contain the coordinate ``q``."""
    found = []
    for label, m in (("H", d.mass_matrix), ("G", d.gravity_vector), ("Q", d.generalized_forces)):
        if m is not None and m.has(q):
            found.append(label)
    return found


def cyclic_coordinates(d: Derivation) -> tuple[Coordinate, ...]:
    """The coordinates that appear in none of H, G and Q, in the spec's order."""
    return tuple(c for c in d.system.coordinates if not _where_found(d, c.q))


def _held(d: Derivation) -> tuple[tuple[Coordinate, sp.Expr], ...]:
    """The held cyclic coordinates with their rates; a spec error at each named one that is not cyclic,
    saying which of H, G and Q contain it."""
    s = d.system
    by_name = {c.name: c for c in s.coordinates}
    named = s.analysis.steady if s.analysis is not None else None
    if named is None:
        return tuple((c, c.qd) for c in cyclic_coordinates(d))
    assert s.analysis is not None
    errors = []
    for name, _ in named:
        found = _where_found(d, by_name[name].q)
        if found:
            errors.append(
                SpecError(
                    s.analysis.place(f"steady.{name}"),
                    f"'{name}' is not a cyclic coordinate: {' and '.join(found)} "
                    f"contain{'s' if len(found) == 1 else ''} {name}; a steady rate is given only to a "
                    "coordinate absent from H, G and Q",
                    _cyclic_hint(d),
                )
            )
    if errors:
        raise SpecErrors(errors)
    return tuple((by_name[name], rate) for name, rate in named)


def _cyclic_hint(d: Derivation) -> str:
    names = [c.name for c in cyclic_coordinates(d)]
    return f"the cyclic coordinates are: {', '.join(names)}" if names else "this system has no cyclic coordinate"


def _forces_at(d: Derivation) -> sp.ImmutableMatrix:
    """Q with the spec's `analysis.inputs` at their values (the other inputs still symbols)."""
    n = len(d.system.coordinates)
    q_vec = d.generalized_forces if d.generalized_forces is not None else sp.ImmutableMatrix.zeros(n, 1)
    given = dict(d.system.analysis.inputs) if d.system.analysis is not None else {}
    return sp.ImmutableMatrix(q_vec.xreplace(given))


def _momenta(d: Derivation, held: list[Coordinate]) -> sp.Matrix:
    """p_c = dL/dq_dot_c of each held coordinate (H q_dot when the route has no L)."""
    s = d.system
    if d.lagrangian is not None:
        return sp.Matrix([sp.diff(d.lagrangian, c.qd) for c in held])
    assert d.mass_matrix is not None
    rows = [s.coordinates.index(c) for c in held]
    qd = sp.Matrix([c.qd for c in s.coordinates])
    return sp.Matrix([(d.mass_matrix[i, :] * qd)[0] for i in rows])


def _cleared(rel: sp.Basic, rates: list[sp.Expr]) -> sp.Basic:
    """g/(R omega^2) <= 1 as g <= R omega^2: a positive denominator multiplied out (its sign judged with
    the rates taken positive where the relation is even in them)."""
    if not isinstance(rel, (sp.LessThan, sp.GreaterThan)):
        return rel
    lhs, rhs = rel.lhs, rel.rhs
    num, den = sp.fraction(sp.together(lhs - rhs))
    if _is_positive(den, rates):
        diff = sp.expand(num)
    elif _is_positive(-den, rates):
        diff = sp.expand(-num)
    else:
        return rel
    terms = sp.Add.make_args(diff)
    right = sp.Add(*[-t for t in terms if t.could_extract_minus_sign()])
    left = sp.Add(*[t for t in terms if not t.could_extract_minus_sign()])
    op = sp.LessThan if isinstance(rel, sp.LessThan) else sp.GreaterThan
    return op(left, right, evaluate=False)


def _is_positive(expr: sp.Expr, rates: list[sp.Expr]) -> bool:
    if expr.is_positive:
        return True
    symbols = [r for r in rates if isinstance(r, sp.Symbol)]
    if not symbols:
        return False
    flipped = expr.xreplace({r: -r for r in symbols})
    if sp.expand(flipped - expr) != 0:
        return False
    positive = {r: sp.Dummy(r.name, positive=True) for r in symbols}
    return bool(expr.xreplace(positive).is_positive)


def _shortest(v: sp.Expr) -> sp.Expr:
    """The shorter of the factored and the tidied form (Routh's reduction leaves a fraction)."""
    # no simplify: at an acos root the entries are algebraic (sin(acos x) = sqrt(1 - x^2)), and simplify
    # spends minutes on a top's; cancel and factor are exact and quick
    factored = sp.factor(sp.cancel(sp.together(sp.expand(v))))
    tidied = tidy(factored)
    return _signs(factored) if sp.count_ops(factored) < sp.count_ops(tidied) else tidied


def _negative_heavy(f: sp.Expr) -> bool:
    terms = sp.Add.make_args(f)
    return isinstance(f, sp.Add) and sum(t.could_extract_minus_sign() for t in terms) * 2 >= len(terms)


def _signs(v: sp.Expr) -> sp.Expr:
    """A fraction's factors with mostly negative terms turned over in pairs, one above and one below the
    line, so that m (g - R w^2) / (2 m g^2 - M R^2 w^4) reads m (R w^2 - g) / (M R^2 w^4 - 2 m g^2)."""
    num, den = sp.fraction(v)
    if den == 1:
        return v
    top, bottom = list(sp.Mul.make_args(num)), list(sp.Mul.make_args(den))
    below = [i for i, f in enumerate(bottom) if _negative_heavy(f)]
    above = [i for i, f in enumerate(top) if _negative_heavy(f)]
    for i, j in zip(below, above, strict=False):
        bottom[i], top[j] = sp.expand(-bottom[i]), sp.expand(-top[j])
    out = sp.Mul(sp.Mul(*top), sp.Pow(sp.Mul(*bottom), -1))
    return out if sp.expand(out - v) == 0 or sp.cancel(out - v) == 0 else v


def textbook(v: sp.Expr) -> sp.Expr:
    """``v`` in the form a textbook prints, its value unchanged: a factor pair (a - b)(a + b) as
    a^2 - b^2, the terms of each sum that share a monomial collected over it ((M + 2 m) Omega^4 R^2 +
    6 m g^2, not M Omega^4 R^2 + 2 m Omega^4 R^2 + 6 m g^2), and a negative coefficient turned into a
    factor of mostly negative terms (m R (g - Omega^2 R), not -m R (-g + Omega^2 R))."""
    if not isinstance(v, sp.Expr) or v.is_number or sp.count_ops(v) > 300:
        return v
    if isinstance(v, sp.Add) and sp.fraction(sp.together(v))[1] != 1:
        # m R^2 w^2 - m g^2/w^2 over its common denominator: m (R^2 w^4 - g^2)/w^2
        over = sp.factor(sp.together(v))
        if not isinstance(over, sp.Add) and sp.count_ops(over) <= sp.count_ops(v) + 2:
            return textbook(over)
    if isinstance(v, sp.Add):
        out = _collected(v)
    else:
        num, den = sp.fraction(v)
        top, bottom = _paired(list(sp.Mul.make_args(num))), _paired(list(sp.Mul.make_args(den)))
        top, bottom = [_collected(f) for f in top], [_collected(f) for f in bottom]
        coefficient = [f for f in top if f.is_number]
        if coefficient and sp.Mul(*coefficient).is_negative:
            heavy = next((i for i, f in enumerate(top) if _negative_heavy(f)), None)
            if heavy is not None:
                top = [-f if f.is_number else f for f in top]
                top[heavy] = _collected(sp.expand(-top[heavy]))
        out = sp.Mul(*top) / sp.Mul(*bottom) if bottom else sp.Mul(*top)
    try:
        same = sp.cancel(sp.together(out - v)) == 0
    except (sp.PolynomialError, TypeError):
        same = False
    return out if same else v


def _paired(factors: list[sp.Expr]) -> list[sp.Expr]:
    """Factors with each pair of sums whose product has two terms ((a - b)(a + b)) multiplied out."""
    out = list(factors)
    i = 0
    while i < len(out):
        j = i + 1
        while j < len(out):
            a, b = out[i], out[j]
            if isinstance(a, sp.Add) and isinstance(b, sp.Add) and len(sp.Add.make_args(sp.expand(a * b))) == 2:
                out[i] = sp.expand(a * b)
                del out[j]
                continue
            j += 1
        i += 1
    return out


def _collected(f: sp.Expr) -> sp.Expr:
    """A sum with the terms that share a monomial collected over it, when what is left of each is a
    parameter or a number (M + 2 m): the largest such group first, greedily."""
    if not isinstance(f, sp.Add):
        return f
    terms = list(sp.Add.make_args(f))
    best: tuple[int, int, sp.Expr, list[sp.Expr]] | None = None
    for i in range(len(terms)):
        for j in range(i + 1, len(terms)):
            g = sp.gcd(terms[i], terms[j])
            if g.is_number:
                continue
            group = [t for t in terms if _is_simple(t / g)]
            if len(group) >= 2 and len(group) < len(terms) + (0 if len(terms) > 2 else 1):
                score = (len(group), int(sp.Poly(g).total_degree()) if g.is_polynomial() else 0)
                if best is None or score > best[:2]:
                    best = (*score, g, group)
    if best is None:
        return f
    _, _, g, group = best
    rest = [t for t in terms if t not in group]
    inner = sp.Add(*[sp.cancel(t / g) for t in group])
    if len(sp.Add.make_args(inner)) < 2:
        return f
    return sp.Add(sp.Mul(inner, g), _collected(sp.Add(*rest)) if rest else sp.Integer(0))


def _is_simple(q: sp.Expr) -> bool:
    """A number times at most one symbol to the first power (m, 2 m, M/2): what collects into M + 2 m."""
    q = sp.cancel(q)
    _, rest = q.as_coeff_Mul()
    return rest == 1 or (isinstance(rest, sp.Symbol))


class _Singular(Exception):
    """The free coordinates' momenta do not depend on their rates here (A_cc singular: a pole of the
    coordinates, such as theta = 0 of a spherical pendulum)."""


def _reduced(
    d: Derivation,
    point: dict[sp.Basic, sp.Expr],
    others: list[Coordinate],
    free: list[Coordinate],
) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
    """M_r, D_r, K_r of the rows of ``others`` about the steady state ``point``: a driven held rate
    kept (its columns dropped), a free one's momentum kept (Routh's reduction, see the module)."""
    s = d.system
    assert d.equations_of_motion is not None
    if not others:
        empty = sp.ImmutableMatrix.zeros(0, 0)
        return empty, empty, empty
    rows = [s.coordinates.index(c) for c in others]
    e = sp.Matrix([d.equations_of_motion[i] for i in rows])

    # formed at a general value of the others (trigonometric rational functions, quick to cancel), and
    # only then at the steady value, which may be an acos of a long argument
    qs = [c.q for c in others]
    general = {k: v for k, v in point.items() if k not in qs}
    steady = {k: v for k, v in point.items() if k in qs}
    motion = {x for c in s.coordinates for x in (c.qd, c.qdd)}
    rates = {k: v for k, v in general.items() if k in motion}
    e = e.xreplace({k: v for k, v in general.items() if k not in motion})

    def at(m: sp.Matrix) -> sp.Matrix:
        return m.xreplace(rates)

    m_ss = at(e.jacobian([c.qdd for c in others]))
    d_ss = at(e.jacobian([c.qd for c in others]))
    k_ss = at(e.jacobian(qs))
    if free:
        m_sf = at(e.jacobian([c.qdd for c in free]))
        d_sf = at(e.jacobian([c.qd for c in free]))
        p = _momenta(d, free).xreplace({k: v for k, v in general.items() if k not in rates})
        a_fs = at(p.jacobian([c.qd for c in others]))
        a_ff = at(p.jacobian([c.qd for c in free]))
        p_fs = at(p.jacobian(qs))
        det = sp.cancel(sp.expand(a_ff.det()))
        if _short(det.xreplace(steady)) == 0:
            raise _Singular
        x = a_ff.inv()
        m_ss = m_ss - m_sf * x * a_fs
        d_ss = d_ss - m_sf * x * p_fs - d_sf * x * a_fs
        k_ss = k_ss - d_sf * x * p_fs

    def clean(m: sp.Matrix) -> sp.ImmutableMatrix:
        return sp.ImmutableMatrix(m.applyfunc(lambda v: textbook(_short(sp.factor(sp.cancel(v)).xreplace(steady)))))

    return clean(m_ss), clean(d_ss), clean(k_ss)


def _short(v: sp.Expr) -> sp.Expr:
    """:func:`_shortest` where the expression is short enough to simplify quickly; else as it is."""
    return _shortest(v) if sp.count_ops(v) <= 200 else v


def _eigen_verdict(values: list[complex], damping: sp.Matrix, stiffness: sp.Matrix) -> tuple[str, str]:
    scale = max([1.0] + [abs(v) for v in values])
    worst = max(v.real for v in values)
    if worst > ZERO * scale:
        return "unstable", f"an eigenvalue has a positive real part ({worst:.4g} per second): a small disturbance grows"
    if any(abs(v) <= ZERO * scale for v in values):
        return "undetermined", "an eigenvalue is 0: the linear model has a neutral direction and does not decide"
    if all(v.real < -ZERO * scale for v in values):
        return "asymptotically stable", "every eigenvalue has a negative real part: small motions die away"
    return "stable", "every eigenvalue is imaginary: the small motions about the steady state are oscillations"


def _inside(exists: tuple[sp.Basic, ...]) -> dict[sp.Symbol, sp.Expr] | None:
    """A substitution that puts the parameters strictly inside where a steady state exists: for each
    condition p <= rhs with p a positive symbol, p = rhs/(1 + y), y > 0 (None when a condition has
    another form)."""
    out: dict[sp.Symbol, sp.Expr] = {}
    for i, rel in enumerate(exists):
        if not isinstance(rel, sp.LessThan) or not isinstance(rel.lhs, sp.Symbol) or not rel.lhs.is_positive:
            return None
        if rel.lhs in out or rel.rhs.has(rel.lhs):
            return None
        out[rel.lhs] = rel.rhs / (1 + sp.Dummy(f"y{i}", positive=True))
    return out


def _verdict(
    d: Derivation, mass: sp.Matrix, damping: sp.Matrix, stiffness: sp.Matrix, exists: tuple[sp.Basic, ...] = ()
) -> tuple[str, str, tuple[sp.Basic, ...], tuple[complex, ...] | None]:
    """The stability of the reduced model: eigenvalues of a numeric one, the sign of K_r otherwise."""
    n = mass.shape[0]
    if n == 0:
        return "neutral", "every coordinate is cyclic: nothing is left to disturb but the rates themselves", (), None
    numeric = [d.numeric(m) for m in (mass, damping, stiffness)]
    if not any(m.free_symbols for m in numeric):
        import numpy as np

        mi = numeric[0].inv()
        a = sp.Matrix(sp.BlockMatrix([[sp.zeros(n), sp.eye(n)], [-mi * numeric[2], -mi * numeric[1]]]))
        values = np.linalg.eigvals(np.array(a.evalf(17).tolist(), dtype=complex))
        scale = max([1.0] + [abs(v) for v in values])
        kept = sorted(
            (
                complex(round(v.real, 12) + 0.0, round(v.imag, 12) + 0.0 if abs(v.imag) > ZERO * scale else 0.0)
                for v in values
                if v.imag >= -ZERO * scale
            ),
            key=lambda z: (-z.real, z.imag),
        )
        verdict, reason = _eigen_verdict(kept, numeric[1], numeric[2])
        return verdict, reason, (), tuple(kept)
    if sum(sp.count_ops(x) for x in (*damping, *stiffness)) > MAX_OPS:
        return (
            "undetermined",
            "the reduced K is too long to judge by its sign: give the parameters values for the eigenvalues",
            (),
            None,
        )
    verdict, reason, minors = stiffness_verdict(damping, stiffness)
    where: tuple[sp.Basic, ...] = ()
    inside = _inside(exists) if exists else None
    if verdict == "undetermined" and minors and inside:
        signs = [sign_condition(sp.factor(sp.together(m.xreplace(inside)))) for m in minors]
        if all(x is sp.true for x in signs):
            why = "the reduced K is positive definite wherever this steady motion exists (strictly)"
            return "stable", why, (), None
        if signs[0] is sp.false or any(x is sp.false for x in signs[::2]):
            return "unstable", "the reduced K has a negative direction wherever this steady motion exists", (), None
    if verdict == "undetermined" and minors:
        where = tuple(c for c in (sign_condition(m) for m in minors) if c is not sp.true)
        if where and sp.false not in where:
            verdict = "conditional"
    return verdict, reason, where, None


def steady_motion(d: Derivation) -> SteadyMotion:
    """The steady motions of a derivation (see the module's docstring)."""
    checkpoint("steady motion")
    s = d.system
    assert d.equations_of_motion is not None
    held = _held(d)
    held_coords = [c for c, _ in held]
    forces = _forces_at(d)
    free = [c for c in held_coords if forces[s.coordinates.index(c)] == 0]
    others = [c for c in s.coordinates if c not in held_coords]
    rates = {c.qd: r for c, r in held}
    base: dict[sp.Basic, sp.Expr] = {c.qdd: sp.Integer(0) for c in s.coordinates}
    base.update({c.qd: sp.Integer(0) for c in others})
    base.update(rates)
    zeroed = input_values(d)
    eom = d.equations_of_motion
    rows = [s.coordinates.index(c) for c in others]
    residual = sp.ImmutableMatrix([tidy(sp.expand(eom[i].xreplace(base).xreplace(zeroed))) for i in rows])
    present = [c for c in others if residual.has(c.q)]
    free_others = tuple(c.name for c in others if c not in present)
    remark = None
    if present:
        # sin(2 theta) back to 2 sin(theta) cos(theta): each factor then in cos or sin alone (acos roots,
        # every family), not sympy's half-angle atan forms
        solutions, method = roots(d, sp.ImmutableMatrix(residual.applyfunc(sp.expand_trig)), present)
        method = "none" if method == UNSOLVED else method  # the JSON's methods: symbolic, numeric, none
        if not solutions:
            remark = "no steady state was found at these rates"
    elif any(e != 0 for e in residual):
        solutions, method = [], "none"
        remark = "the rows of the other coordinates do not vanish at these rates: there is no steady state"
    else:
        solutions, method = [()], "symbolic"
    rate_list = list(rates.values())
    states = []
    for sol in solutions:
        given = dict(sol)
        at = tuple((c.name, given.get(c.name, sp.Integer(0))) for c in others)
        point = dict(base)
        point.update({c.q: v for c, (_, v) in zip(others, at, strict=True)})
        states.append(_state(d, at, point, others, held, free, rate_list, zeroed))
    check = _check(d, tuple(states), base, others, held)
    return SteadyMotion(
        cyclic=tuple(c.name for c in cyclic_coordinates(d)),
        rates=tuple((c.name, r) for c, r in held),
        free=tuple(c.name for c in free),
        others=tuple(c.name for c in others),
        free_others=free_others,
        residual=residual,
        states=tuple(states),
        method=method,
        remark=remark,
        check=check,
    )


def _state(
    d: Derivation,
    at: tuple[tuple[str, sp.Expr], ...],
    point: dict[sp.Basic, sp.Expr],
    others: list[Coordinate],
    held: tuple[tuple[Coordinate, sp.Expr], ...],
    free: list[Coordinate],
    rates: list[sp.Expr],
    zeroed: dict[sp.Symbol, sp.Expr],
) -> SteadyState:
    s = d.system
    assert d.equations_of_motion is not None
    forces = _forces_at(d)
    exists = tuple(dict.fromkeys(_cleared(x, rates) for _, v in at for x in existence(v)))
    required = []
    inputs = []
    for c, _ in held:
        i = s.coordinates.index(c)
        row = d.equations_of_motion[i] + forces[i]  # (H q_ddot + C + G)_c
        required.append((c.name, _shortest(row.xreplace(point))))
        unknown = sorted((forces[i].free_symbols & set(zeroed)) - set(d.values), key=default_sort_key)
        if len(unknown) == 1:
            u = unknown[0]
            balance = (d.equations_of_motion[i]).xreplace(point).xreplace({k: v for k, v in zeroed.items() if k != u})
            solved = sp.solve(balance, u)
            if len(solved) == 1:
                inputs.append((u, _shortest(solved[0])))
    p = _momenta(d, [c for c, _ in held]) if held else sp.Matrix([])
    momenta = tuple((c.name, textbook(_shortest(p[k].xreplace(point)))) for k, (c, _) in enumerate(held))
    point_inputs = dict(point)
    point_inputs.update(zeroed)
    decided = [d.numeric(x) for x in exists]
    known: bool | None = True
    if any(x is sp.false for x in decided):
        known = False
    elif any(x is not sp.true for x in decided):
        known = None
    if known is False:
        n = len(others)
        zero = sp.ImmutableMatrix.zeros(n, n)
        return SteadyState(
            at,
            exists,
            tuple(required),
            tuple(inputs),
            momenta,
            zero,
            zero,
            zero,
            "none",
            "it does not exist at these values",
            exists=False,
        )
    pole = False
    try:
        mass, damping, stiffness = _reduced(d, point_inputs, others, free)
        verdict, reason, where, eigen = _verdict(d, mass, damping, stiffness, exists)
    except _Singular:
        mass, damping, stiffness, verdict, reason, where, eigen = _at_pole(d, at, point_inputs, others, free, momenta)
        pole = True
    return SteadyState(
        at=at,
        exists_where=exists,
        required=tuple(required),
        inputs=tuple(inputs),
        momenta=momenta,
        mass=mass,
        damping=damping,
        stiffness=stiffness,
        verdict=verdict,
        reason=reason,
        stable_where=where,
        eigenvalues=eigen,
        exists=known,
        pole=pole,
    )


def _at_pole(
    d: Derivation,
    at: tuple[tuple[str, sp.Expr], ...],
    point: dict[sp.Basic, sp.Expr],
    others: list[Coordinate],
    free: list[Coordinate],
    momenta: tuple[tuple[str, sp.Expr], ...],
) -> tuple[
    sp.ImmutableMatrix,
    sp.ImmutableMatrix,
    sp.ImmutableMatrix,
    str,
    str,
    tuple[sp.Basic, ...],
    tuple[complex, ...] | None,
]:
    """The verdict at a pole of the coordinates, where Routh's reduction does not exist (A_cc = 0).

    There the free held coordinate is undefined (the azimuth on the axis of a spherical pendulum): its
    momentum is 0 whatever its rate, and the rate means nothing. When every held momentum is 0 there,
    nothing spins and the steady motion is the rest state on the axis, an equilibrium: decided as one,
    by M = H and K = d(G - Q)/dq of the others at rest (the polar angle is the distance from the axis,
    so its stiffness is the stiffness in every direction about the axis). When something spins (a
    sleeping top) that needs coordinates regular on the axis, which are not formed: said so."""
    s = d.system
    names = ", ".join(c.name for c in free)
    where = " and ".join(f"{n} = {_plain(v)}" for n, v in at)
    singular = (
        f"the coordinates are singular at {where}: on that axis {names} is undefined, the momentum of {names} "
        "is 0 whatever its rate, and the rate means nothing"
    )
    n = len(others)
    zero = sp.ImmutableMatrix.zeros(n, n)
    if any(sp.simplify(v) != 0 for _, v in momenta):
        reason = (
            f"{singular}. This steady motion is the body spinning about its own axis; its stability needs "
            "coordinates that are regular on the axis (the sleeping top's criterion), which this analysis "
            "does not form"
        )
        return zero, zero, zero, "undetermined", reason, (), None
    assert d.equations_of_motion is not None
    rows = [s.coordinates.index(c) for c in others]
    e = sp.Matrix([d.equations_of_motion[i] for i in rows])
    rest = {k: v for k, v in point.items() if k not in {c.q for c in others}}
    rest.update({c.qd: sp.Integer(0) for c in s.coordinates})
    steady = {c.q: v for c, (_, v) in zip(others, at, strict=True)}

    def at_rest(m: sp.Matrix) -> sp.ImmutableMatrix:
        return sp.ImmutableMatrix(m.xreplace(rest).xreplace(steady).applyfunc(lambda v: _short(sp.factor(v))))

    mass = at_rest(e.jacobian([c.qdd for c in others]))
    stiffness = at_rest(e.jacobian([c.q for c in others]))
    verdict, why, stable_where, eigen = _verdict(d, mass, zero, stiffness)
    rest_state = (
        f"{singular}. This steady motion is the system at rest on the axis (turning about the axis moves "
        "nothing there), an equilibrium, decided as one: the stiffness K of the others at rest is the same "
        "in every direction about the axis"
    )
    if verdict == "stable":
        reason = f"{rest_state}, and it is positive: U has a strict minimum there"
    elif verdict == "unstable":
        reason = f"{rest_state}, and it is negative: U has a maximum there"
    else:
        reason = f"{rest_state}; {why}"
    return mass, zero, stiffness, verdict, reason, stable_where, eigen


def _plain(v: sp.Expr) -> str:
    """A steady value for a sentence: pi for a float of pi, the spec grammar otherwise."""
    if v.is_Float and abs(float(v) - float(sp.pi)) < 1e-12:
        return "pi"
    return str(v)


def _check(
    d: Derivation,
    states: tuple[SteadyState, ...],
    base: dict[sp.Basic, sp.Expr],
    others: list[Coordinate],
    held: tuple[tuple[Coordinate, sp.Expr], ...],
) -> Check:
    """Each steady motion in the full nonlinear equations of motion, numerically (complex arithmetic,
    so a state outside where it exists still checks): the rows of the other coordinates vanish and each
    held row equals the generalized force it needs, parameters without a value at random positive
    numbers."""
    s = d.system
    assert d.equations_of_motion is not None
    forces = _forces_at(d)
    zeroed = input_values(d)
    rng = random.Random(18)
    worst = 0.0
    for st in states:
        if st.exists is False:
            continue
        point = dict(base)
        point.update({c.q: v for c, (_, v) in zip(others, st.at, strict=True)})
        required = dict(st.required)
        rows = []
        for i, c in enumerate(s.coordinates):
            full = d.equations_of_motion[i].xreplace(point)  # H q_ddot + C + G - Q
            if c.name in required:
                full = full + forces[i].xreplace(point) - required[c.name]
            rows.append(d.numeric(full.xreplace(zeroed)))
        symbols = sorted(set().union(*[r.free_symbols for r in rows]), key=default_sort_key)
        fill = {x: sp.Rational(rng.randint(700, 1900), 1000) for x in symbols}
        for r in rows:
            v = complex(sp.N(r.xreplace(fill), 30))
            if cmath.isnan(v):
                continue
            worst = max(worst, abs(v))
    passed = worst < 1e-9
    return Check(
        "steady_motion_satisfies_equations",
        passed,
        "each steady motion satisfies the full equations of motion: the other coordinates' rows vanish and "
        f"each held coordinate's row is the generalized force it needs ({'to' if passed else 'not to'} 1e-9)",
    )
