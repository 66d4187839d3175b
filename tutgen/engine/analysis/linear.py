"""The linear model about an equilibrium q0: M dq_ddot + D dq_dot + K dq = B du, and its state space.

With e(q, q_dot, q_ddot, u) = H q_ddot + C + G - Q (each entry = 0, the equations of motion), a first-
order expansion about the rest state (q0, 0, 0, u0) gives, entry by entry,

    M = de/dq_ddot = H(q0),  D = de/dq_dot,  K = de/dq,  B = -de/du = dQ/du,

all at the rest state. C is quadratic in the rates, so D holds the dampers and any force that is linear
in the rates (a gyroscopic part appears as the skew part of D); K holds gravity's and the springs'
stiffness and the circulatory part of Q (its skew part). The state x = [dq, dq_dot] then obeys
x_dot = A x + B_x u with A = [[0, I], [-M^-1 K, -M^-1 D]] and B_x = [[0], [M^-1 B]].

For a numeric spec the eigenvalues of A give the natural frequencies (|lambda|, rad/s and Hz), the damping
ratios (-Re lambda / |lambda|) and the mode shapes; the verdict on stability follows from them, or, for a
symbolic spec without damping, from the sign of K (Lagrange-Dirichlet: K positive definite is stable; a
negative direction of K unstable).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import sympy as sp

from tutgen.engine.analysis.equilibria import input_values
from tutgen.engine.derivation import Check, Derivation
from tutgen.engine.tidy import tidy
from tutgen.limits import checkpoint

__all__ = ["SINGULAR_MASS", "LinearModel", "Mode", "is_singular", "linearize", "stiffness_verdict"]

#: a real part this small (relative to the largest eigenvalue) counts as zero
ZERO = 1e-9


@dataclass(frozen=True)
class Mode:
    """One eigenvalue of A (of a complex pair, the one with Im >= 0), with what it means."""

    eigenvalue: complex
    natural_frequency: float  # |lambda|, rad/s
    frequency_hz: float  # |lambda| / 2 pi
    damping_ratio: float | None  # -Re lambda / |lambda|, None for lambda = 0
    shape: tuple[complex, ...]  # dq of the eigenvector, largest entry 1


@dataclass(frozen=True)
class LinearModel:
    """A linear model about one equilibrium (see the module's docstring)."""

    about: tuple[tuple[str, sp.Expr], ...]
    inputs: tuple[sp.Symbol, ...]
    mass: sp.ImmutableMatrix
    damping: sp.ImmutableMatrix
    stiffness: sp.ImmutableMatrix
    input_matrix: sp.ImmutableMatrix
    state_matrix: sp.ImmutableMatrix
    state_input: sp.ImmutableMatrix
    characteristic: sp.Expr | None  # det(M s^2 + D s + K), for up to 3 coordinates
    modes: tuple[Mode, ...] | None  # numeric specs
    # "asymptotically stable", "stable", "unstable", "conditional" (stable where ``stable_where`` holds)
    # or "undetermined" (the linear model does not decide)
    verdict: str
    reason: str
    conditions: tuple[sp.Expr, ...] = ()  # symbolic: the leading minors of K, each > 0 for stability
    # symbolic and undecided: each minor > 0 with its positive factors taken out (g - R omega^2 > 0)
    stable_where: tuple[sp.Basic, ...] = ()
    check: Check | None = None


#: the variable of the characteristic polynomial
S = sp.Symbol("s")

#: the reason given when M = H(q0) is singular at the equilibrium
SINGULAR_MASS = (
    "M is singular here (its determinant vanishes): the coordinates are singular at this configuration, as Euler "
    "angles are at their pole, so the linear model cannot be solved for the accelerations and has no "
    "state-space form; it does not decide stability (coordinates that are regular here would)"
)


#: an entry of A with more operations than this is brought to lowest terms and factored, not simplified:
#: ``simplify`` of a symbolic 4-link arm's M^-1 K ran for minutes (every smaller entry is simplified as before)
SIMPLIFY_OPS = 400


def _simplest(x: sp.Expr) -> sp.Expr:
    if sp.count_ops(x) > SIMPLIFY_OPS:
        return tidy(sp.factor(sp.cancel(x)))
    return tidy(sp.simplify(x))


def is_singular(mass: sp.Matrix) -> bool:
    """Whether M = H(q0) is singular: its determinant is identically zero (the parameters symbolic)."""
    if mass.shape[0] == 0:
        return False
    det = mass.det(method="berkowitz")
    return bool(sp.expand(det) == 0 or tidy(sp.simplify(det)) == 0)


def linearize(d: Derivation, about: tuple[tuple[str, sp.Expr], ...]) -> LinearModel:
    """The linear model of a derivation about ``about`` (every coordinate's value at the equilibrium)."""
    checkpoint("linearization")
    s = d.system
    assert d.equations_of_motion is not None
    q = [c.q for c in s.coordinates]
    qd = [c.qd for c in s.coordinates]
    qdd = [c.qdd for c in s.coordinates]
    u0 = input_values(d)
    inputs = tuple(sym for sym, _ in (s.analysis.inputs if s.analysis is not None else ()))
    rest: dict[sp.Basic, sp.Expr] = {qi: v for qi, (_, v) in zip(q, about, strict=True)}
    rest.update({x: sp.Integer(0) for x in (*qd, *qdd)})
    rest.update(u0)
    e = sp.Matrix(d.equations_of_motion)

    def at_rest(m: sp.Matrix) -> sp.ImmutableMatrix:
        return sp.ImmutableMatrix(m.xreplace(rest).applyfunc(lambda x: tidy(sp.simplify(x))))

    n = len(q)
    mass = at_rest(e.jacobian(qdd))
    damping = at_rest(e.jacobian(qd))
    stiffness = at_rest(e.jacobian(q))
    b = at_rest(-e.jacobian(list(inputs))) if inputs else sp.ImmutableMatrix(sp.zeros(n, 0))
    singular = is_singular(mass)
    if singular:  # no state space: M dq_ddot cannot be solved for dq_ddot (the top's H at its pole, theta = 0)
        a = bx = sp.ImmutableMatrix(sp.zeros(0, 0))
    else:
        minv = mass.inv()  # DomainMatrix: each entry in lowest terms (LU left a 4-link arm nested fractions)
        a = sp.Matrix(sp.BlockMatrix([[sp.zeros(n), sp.eye(n)], [-minv * stiffness, -minv * damping]]))
        a = sp.ImmutableMatrix(a.applyfunc(_simplest))
        bx = sp.ImmutableMatrix(sp.Matrix.vstack(sp.zeros(n, b.shape[1]), minv * b).applyfunc(tidy)) if inputs else b
    characteristic = None
    if n <= 3:
        characteristic = tidy(sp.factor(sp.expand((mass * S**2 + damping * S + stiffness).det(method="berkowitz"))))
    numeric = not (a.free_symbols - set(d.values))
    modes = _modes(d, a, n) if numeric and not singular else None
    conditions: tuple[sp.Expr, ...] = ()
    where: tuple[sp.Basic, ...] = ()
    if singular:
        verdict, reason = "undetermined", SINGULAR_MASS
    elif modes is not None:
        verdict, reason = _eigen_verdict(d, modes, damping, stiffness)
    else:
        verdict, reason, conditions = stiffness_verdict(damping, stiffness)
        if verdict == "undetermined" and conditions:
            where = tuple(c for c in (sign_condition(m) for m in conditions) if c is not sp.true)
            if where and sp.false not in where:
                verdict = "conditional"
    return LinearModel(
        about=about,
        inputs=inputs,
        mass=mass,
        damping=damping,
        stiffness=stiffness,
        input_matrix=b,
        state_matrix=a,
        state_input=bx,
        characteristic=characteristic,
        modes=modes,
        verdict=verdict,
        reason=reason,
        conditions=conditions,
        stable_where=where,
        check=_finite_difference_check(d, rest, mass, damping, stiffness),
    )


def sign_condition(expr: sp.Expr) -> sp.Basic:
    """``expr > 0`` with the factors known to be positive (parameters, even powers) taken out:
    m R (g - R omega^2) > 0 is g - R omega^2 > 0. sympy's true or false when the sign is known."""
    expr = sp.factor(expr)
    factors = sp.Mul.make_args(expr)
    kept = [f for f in factors if not f.is_positive]
    sign = 1
    rest = []
    for f in kept:
        if f.is_negative:
            sign = -sign
        else:
            rest.append(f)
    body = sp.Mul(*rest)
    if sign < 0:
        body = -body
    if body.is_positive:
        return sp.true
    if body.is_nonpositive:
        return sp.false
    body = sp.expand(body)
    # the negative terms on the right: g > R omega^2, not -R omega^2 + g > 0
    terms = sp.Add.make_args(body)
    right = sp.Add(*[-t for t in terms if t.could_extract_minus_sign()])
    left = sp.Add(*[t for t in terms if not t.could_extract_minus_sign()])
    return sp.StrictGreaterThan(left, right, evaluate=False)


def _minors(k: sp.Matrix) -> list[sp.Expr]:
    return [tidy(sp.factor(k[:i, :i].det(method="berkowitz"))) for i in range(1, k.shape[0] + 1)]


def stiffness_verdict(damping: sp.Matrix, stiffness: sp.Matrix) -> tuple[str, str, tuple[sp.Expr, ...]]:
    """Stability from the sign of K when the eigenvalues are not numbers: a conservative system (no D,
    K symmetric) is stable when K is positive definite (Lagrange-Dirichlet: U has a strict minimum) and
    unstable when K has a negative direction. Returns (verdict, reason, the leading minors of K)."""
    k = sp.Matrix(stiffness)
    if (k - k.T).applyfunc(sp.simplify) != sp.zeros(*k.shape) or sp.Matrix(damping) != sp.zeros(*k.shape):
        return "undetermined", "the system has damping or non-conservative stiffness: the eigenvalues decide", ()
    minors = _minors(k)
    if all(m.is_positive for m in minors):
        return "stable", "K is positive definite (every leading minor > 0): U has a strict minimum there", tuple(minors)
    if any(m.is_negative for m in minors) or any(k[i, i].is_negative for i in range(k.shape[0])):
        return "unstable", "K is not positive semi-definite: U decreases along some direction", tuple(minors)
    if all(m.is_nonnegative for m in minors) and any(m.is_zero for m in minors):
        return "undetermined", "K is singular: the linear model has a neutral direction", tuple(minors)
    return "undetermined", "the sign of K depends on the parameters: stable where K is positive definite", tuple(minors)


def _modes(d: Derivation, a: sp.Matrix, n: int) -> tuple[Mode, ...]:
    """The eigenvalues of A (numpy), one of each complex pair, slowest decay first."""
    import numpy as np

    values, vectors = np.linalg.eig(np.array(d.numeric(a).evalf(17).tolist(), dtype=float))
    scale = max(1.0, float(np.max(np.abs(values)))) if len(values) else 1.0
    modes: list[Mode] = []
    for lam, vec in zip(values, vectors.T, strict=True):
        if lam.imag < -ZERO * scale:
            continue
        lam = complex(round(lam.real, 12), round(lam.imag, 12) if abs(lam.imag) > ZERO * scale else 0.0)
        dq = vec[:n]
        big = dq[int(np.argmax(np.abs(dq)))] if np.max(np.abs(dq)) > 0 else 1.0
        shape = tuple(complex(round((x / big).real, 12), round((x / big).imag, 12)) + 0j for x in dq)
        w = abs(lam)
        zeta = (-lam.real / w) + 0.0 if w > ZERO * scale else None  # + 0.0: no -0.0
        modes.append(Mode(lam, w, w / (2 * math.pi), zeta, shape))
    modes.sort(key=lambda m: (-m.eigenvalue.real, m.natural_frequency, m.eigenvalue.imag))
    return tuple(modes)


def _eigen_verdict(d: Derivation, modes: tuple[Mode, ...], damping: sp.Matrix, stiffness: sp.Matrix) -> tuple[str, str]:
    """Stability from the eigenvalues of A. A coordinate whose row and column of K are zero (one the
    rest state does not fix: a cart without a spring) contributes the eigenvalue 0 twice; it is named as
    neutral, and the verdict is on the others."""
    scale = max([1.0] + [abs(m.eigenvalue) for m in modes])
    worst = max(m.eigenvalue.real for m in modes)
    if worst > ZERO * scale:
        return "unstable", f"an eigenvalue has a positive real part ({worst:.4g} per second): a small disturbance grows"
    k = sp.Matrix(d.numeric(stiffness))
    c = sp.Matrix(d.numeric(damping))
    n = k.shape[0]
    neutral = [i for i in range(n) if all(k[i, j] == 0 and k[j, i] == 0 for j in range(n))]
    zero = [m for m in modes if abs(m.eigenvalue) <= ZERO * scale]
    names = [d.system.coordinates[i].name for i in neutral]
    # quoted, so a worked solution typesets the names (tutgen/render/wording.py)
    along = f"neutral along {', '.join(repr(x) for x in names)}, which may rest anywhere; " if neutral else ""
    if len(zero) > 2 * len(neutral) or (zero and not neutral):
        return "undetermined", "an eigenvalue is 0: the linear model has a neutral direction and does not decide"
    rest = [m for m in modes if abs(m.eigenvalue) > ZERO * scale]
    if all(m.eigenvalue.real < -ZERO * scale for m in rest):
        if not neutral:
            return "asymptotically stable", "every eigenvalue has a negative real part: small motions die away"
        return "stable", along + "the other eigenvalues have negative real parts: small motions die away"
    keep = [i for i in range(n) if i not in neutral]
    kr = k.extract(keep, keep)
    if c == sp.zeros(n, n) and kr == kr.T and all(m.is_positive for m in _minors(kr)):
        if not neutral:
            return "stable", "the eigenvalues are imaginary and K is positive definite: undamped small oscillations"
        # K itself is only semi-definite then (the neutral rows and columns are zero)
        return "stable", along + (
            "the other eigenvalues are imaginary and K is positive definite in the other coordinates: undamped "
            "small oscillations"
        )
    return "undetermined", "eigenvalues lie on the imaginary axis: the linear model does not decide"


def _finite_difference_check(
    d: Derivation, rest: dict[sp.Basic, sp.Expr], mass: sp.Matrix, damping: sp.Matrix, stiffness: sp.Matrix
) -> Check:
    """The linear model against central finite differences of the nonlinear equations at the rest state,
    parameters without a value at fixed positive numbers (M, D, K entry by entry)."""
    s = d.system
    q = [c.q for c in s.coordinates]
    qd = [c.qd for c in s.coordinates]
    qdd = [c.qdd for c in s.coordinates]
    assert d.equations_of_motion is not None
    e = sp.Matrix(d.equations_of_motion)
    point = {k: v for k, v in rest.items()}
    others = sorted(
        (e.free_symbols | mass.free_symbols | stiffness.free_symbols) - set(q) - set(qd) - set(qdd) - set(d.values),
        key=str,
    )
    variables = [*q, *qd, *qdd]
    held = {k: v for k, v in point.items() if k not in variables}  # the inputs at their values
    # parameters without a value at fixed positive numbers where the equilibrium exists (a bead's
    # cos theta = g/(R omega^2) needs R omega^2 >= g): the first of a fixed list of sets that gives it real
    fill: dict[sp.Symbol, sp.Rational] = {}
    x0: list[float] | None = None
    for pattern in _FILLS:
        fill = {sym: pattern(i) for i, sym in enumerate(others) if sym not in point}
        values = [complex(sp.N(d.numeric(point.get(v, 0)).xreplace(fill))) for v in variables]
        if all(abs(z.imag) <= 1e-12 * max(1.0, abs(z)) for z in values):
            x0 = [z.real for z in values]
            break
    if x0 is None:
        return Check(
            "linearization_matches_finite_differences",
            True,
            "M, D and K of the linear model not checked against central differences: the equilibrium is not "
            "real at any of the test values of the parameters",
        )
    ev = d.numeric(e.xreplace(held)).xreplace(fill)
    f = sp.lambdify([variables], list(ev), "math")
    h = 1e-6
    worst = 0.0
    n = len(q)
    for blockno, block in enumerate((stiffness, damping, mass)):
        expected = sp.Matrix(d.numeric(block)).xreplace(fill)
        for j in range(n):
            plus, minus = list(x0), list(x0)
            plus[blockno * n + j] += h
            minus[blockno * n + j] -= h
            fp, fm = f(plus), f(minus)
            for i in range(n):
                fd = (fp[i] - fm[i]) / (2 * h)
                want = float(sp.N(expected[i, j]))
                worst = max(worst, abs(fd - want) / max(1.0, abs(want)))
    passed = worst < 1e-5
    # the worst difference itself is not printed: its last digits vary with the platform's floating point
    return Check(
        "linearization_matches_finite_differences",
        passed,
        "M, D and K of the linear model equal central differences of the equations of motion at the "
        f"equilibrium ({'to' if passed else 'not to'} 5 significant figures)",
    )


#: the test values of parameters without a value, tried in turn (the first as before: 7/5, 2, 13/5, ...)
_FILLS = (
    lambda i: sp.Rational(7 + 3 * i, 5),
    lambda i: sp.Rational(7 + 3 * i, 5) * (4 if i % 2 else sp.Rational(1, 4)),
    lambda i: sp.Rational(7 + 3 * i, 5) * (sp.Rational(1, 4) if i % 2 else 4),
    lambda i: sp.Rational(40 - 3 * i, 5) if i < 12 else sp.Rational(1, 2),
)


def complex_text(z: complex, digits: int = 4) -> str:
    """A complex number as text: ``-0.5 + 3.1 i``, ``2.0``, ``3.1 i``."""
    re, im = z.real, z.imag
    if abs(im) == 0:
        return f"{re:.{digits}g}"
    sign = "-" if im < 0 else "+"
    if abs(re) == 0:
        return f"{'-' if im < 0 else ''}{abs(im):.{digits}g} i"
    return f"{re:.{digits}g} {sign} {abs(im):.{digits}g} i"
