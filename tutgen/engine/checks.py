"""Checks the engine runs on its own results, so that a wrong answer is reported, never printed.

- The mass matrix H(q) must be positive semi-definite: T = q_dot^T H q_dot / 2 >= 0 for every motion.
  Its eigenvalues are computed numerically at a few random states (random positive values for the
  parameters without one, random angles and positions); semi-definite is allowed, since a coordinate
  that moves no mass gives a singular H (tutorial problem 9).
- The matrix form must reproduce Lagrange's equations as derived term by term, H_dot - 2 C must be
  skew-symmetric and H symmetric (:func:`matrix_form_checks`, exact).
- Every term of every equation of motion must have the same dimension, where the dimensions of all its
  symbols are known (parameters with units or declared dimensions; a coordinate is an angle or a length,
  its velocity that per second, its acceleration that per second squared). An equation with a symbol of
  unknown dimension is not checked.

A failed check is a tutgen bug: :func:`verify` raises :class:`~tutgen.errors.DerivationError` naming the
equation or the matrix.
"""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence

import mpmath
import sympy as sp

from tutgen.engine.derivation import Check, Derivation
from tutgen.engine.kinematics import total_derivative
from tutgen.engine.tidy import is_zero
from tutgen.errors import DerivationError
from tutgen.model.system import System
from tutgen.spec.units import DIMENSIONS, Dimension, DimensionMismatch, dimension_of

__all__ = ["dimension_checks", "mass_matrix_checks", "matrix_form_checks", "verify"]

#: Random states at which H is evaluated.
STATES = 5
#: Relative tolerance on a negative eigenvalue (rounding of a singular H).
TOLERANCE = 1e-12
_SEED = 20261123
_ENERGY = DIMENSIONS["energy"]
_TIME = DIMENSIONS["time"]


def matrix_form_checks(
    system: System,
    h: sp.ImmutableMatrix,
    c_mat: sp.ImmutableMatrix,
    eom: sp.MatrixBase,
    lagrange: Sequence[sp.Expr],
) -> list[Check]:
    """The matrix form against Lagrange's equations (a difference raises: it is a tutgen bug), then
    H_dot - 2 C skew-symmetric and H = H^T, each entry compared exactly (:func:`~tutgen.engine.tidy.is_zero`)."""
    for i, coord in enumerate(system.coordinates):
        zero, _ = is_zero(eom[i] - lagrange[i])
        if not zero:
            raise DerivationError(
                f"internal check failed: the matrix form of the equation for '{coord.name}' differs from "
                "Lagrange's equation; please report this spec as a tutgen bug",
                coord.origin,
            )
    checks = [Check("matrix_form_equals_lagrange", True, "H q_ddot + C + G - Q equals Lagrange's equations")]
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    qdd = [c.qdd for c in system.coordinates]
    n = len(q)
    h_dot = h.applyfunc(lambda e: total_derivative(e, q, qd, qdd))
    skew = h_dot - 2 * c_mat
    ok = all(is_zero(skew[i, j] + skew[j, i])[0] for i in range(n) for j in range(i, n))
    checks.append(Check("skew_symmetry", ok, "H_dot - 2 C is skew-symmetric" if ok else "H_dot - 2 C is NOT skew"))
    checks.append(Check("symmetric_mass_matrix", h == h.T, "H = H^T"))
    return checks


def mass_matrix_checks(derivation: Derivation) -> list[Check]:
    """H(q) is positive semi-definite at ``STATES`` random states (numeric eigenvalues, 30 digits).

    Parameters with numeric values keep them; the others get random values in [0.5, 2] (parameters are
    positive unless they are forces, which H does not contain); coordinates random values in [-3, 3].

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> from tutgen.engine.pipeline import derive
    >>> pendulum = load_system_text('''
    ... tutgen: 1
    ... title: pendulum
    ... parameters: [m, l, g]
    ... coordinates: [theta]
    ... gravity: [0, -g, 0]
    ... bodies: {bob: {mass: m, com: [0, -l, 0]}}
    ... joints: {pivot: {type: revolute, parent: ground, child: bob, axis: z, coordinate: theta}}
    ... ''')
    >>> mass_matrix_checks(derive(pendulum, "lagrange"))[0].passed
    True
    """
    h = derivation.mass_matrix
    if h is None or h.shape[0] == 0:
        return []
    system = derivation.system
    name = "positive_semidefinite_mass_matrix"
    h = h.subs(system.values) if system.values else h
    symbols = sorted(h.free_symbols, key=sp.default_sort_key)
    coords = {c.q for c in system.coordinates}
    rng = random.Random(_SEED)
    evaluate = sp.lambdify(symbols, h, modules="mpmath")
    lowest: mpmath.mpf | None = None
    with mpmath.workdps(30):
        for _ in range(STATES):
            state = [rng.uniform(-3, 3) if s in coords else rng.uniform(0.5, 2) for s in symbols]
            try:
                values = mpmath.matrix(evaluate(*state))
                values = (values + values.T) / 2
                eigenvalues = mpmath.eigsy(values, eigvals_only=True)
            except (ArithmeticError, TypeError, ValueError) as exc:  # e.g. a division by zero at this state
                return [Check(name, True, f"not checked: H could not be evaluated numerically ({exc})")]
            eig = [mpmath.mpf(e) for e in eigenvalues]
            scale = max([mpmath.mpf(1), *(abs(e) for e in eig)])
            if min(eig) < -TOLERANCE * scale:
                where = ", ".join(f"{s} = {v:.3f}" for s, v in zip(symbols, state, strict=True))
                detail = f"the mass matrix H has the negative eigenvalue {mpmath.nstr(min(eig), 6)}"
                return [Check(name, False, detail + (f" at {where}" if where else ""))]
            lowest = min(eig) if lowest is None else min(lowest, min(eig))
    kind = "semi-definite (singular somewhere)" if lowest is not None and lowest <= TOLERANCE else "definite"
    return [Check(name, True, f"H is positive {kind} at {STATES} random states")]


def symbol_dimensions(system: System) -> dict[sp.Symbol, Dimension | None]:
    """The dimension of every parameter, coordinate, velocity and acceleration symbol (None: unknown)."""
    dims: dict[sp.Symbol, Dimension | None] = {p.symbol: p.dimension for p in system.parameters}
    for c in system.coordinates:
        d = c.si_dimension
        dims[c.q] = d
        dims[c.qd] = d / _TIME if d is not None else None
        dims[c.qdd] = d / _TIME**2 if d is not None else None
    return dims


def _numbers_unknown(expr: sp.Expr) -> sp.Expr:
    """Numbers other than 1 and -1 become symbols of unknown dimension (never a mismatch).

    A value given in the spec with a unit (``15 kg``, ``0.45 m``) reaches the equations as a bare SI
    number, so a number may carry any dimension; exponents keep their numbers.
    """
    if expr.is_Number:
        return expr if expr in (sp.Integer(1), sp.Integer(-1)) else sp.Dummy()
    if not expr.args or isinstance(expr, sp.Symbol):
        return expr
    if isinstance(expr, sp.Pow):
        return sp.Pow(_numbers_unknown(expr.base), expr.exp, evaluate=False)
    return expr.func(*(_numbers_unknown(a) for a in expr.args), evaluate=False)


def _equation_check(
    name: str, expr: sp.Expr, coordinate_dim: Dimension | None, dims: Mapping[sp.Symbol, Dimension | None]
) -> tuple[bool | None, str]:
    """(True, detail) consistent, (None, why) not checked, (False, what differs) inconsistent."""
    if any(dims.get(s) is None for s in expr.free_symbols):
        unknown = sorted(str(s) for s in expr.free_symbols if dims.get(s) is None)
        return None, f"'{name}': not checked (unknown dimension of {', '.join(unknown)})"
    expected = _ENERGY / coordinate_dim if coordinate_dim is not None else None
    first: tuple[sp.Expr, Dimension] | None = None
    for term in sp.Add.make_args(expr):
        if term.is_number:
            continue  # a number may stand for any value in SI units
        try:
            dim = dimension_of(_numbers_unknown(term), dims)
        except DimensionMismatch as exc:
            return False, f"in the equation for '{name}', the term {sp.sstr(term)} is inconsistent: {exc}"
        if dim is None:
            continue
        if first is None:
            first = (term, dim)
            if expected is not None and dim != expected:
                return False, (
                    f"in the equation for '{name}', the term {sp.sstr(term)} has the dimension {dim}, "
                    f"expected {expected} (a generalized force for a coordinate of dimension {coordinate_dim})"
                )
        elif dim != first[1]:
            return False, (
                f"in the equation for '{name}', the term {sp.sstr(term)} has the dimension {dim} but the term "
                f"{sp.sstr(first[0])} has {first[1]}"
            )
    return True, f"'{name}': every term is {first[1] if first else expected}"


def _bare_numbers(system: System) -> bool:
    """True when a physical quantity of the spec is a plain number (a literal, or a value with a unit,
    converted to SI): its dimension is lost, so a dimensional check of the equations would be wrong."""
    values: list[object] = []
    for body in system.bodies:
        if body.position is not None:
            values += list(body.position)
        for part in body.parts:
            values += [part.mass, part.density, *part.at]
            for _, dim in part.dimensions:
                values += list(dim) if isinstance(dim, tuple) else [dim]
            if part.inertia is not None:
                values += list(part.inertia)
    for joint in system.joints:
        values += [*joint.origin_offset, joint.offset]
    for spring in system.springs:
        values += [spring.stiffness, spring.free_length]
    values += [d.coefficient for d in system.dampers]
    for load in system.loads:
        values += [*(load.force or ()), *(load.torque or ()), *load.at]
    values += [v for _, v in system.generalized_forces]
    values += list(system.gravity) if system.gravity is not None else []
    return any(isinstance(v, sp.Expr) and v.is_number and v != 0 for v in values)


def _dimension_results(system: System, derivation: Derivation) -> list[tuple[int, bool | None, str]]:
    eom = derivation.equations_of_motion
    if eom is None:
        return []
    if _bare_numbers(system):
        return [(i, None, "a quantity is a bare number") for i in range(len(system.coordinates))]
    dims = symbol_dimensions(system)
    return [(i, *_equation_check(c.name, eom[i], c.si_dimension, dims)) for i, c in enumerate(system.coordinates)]


def dimension_checks(system: System, derivation: Derivation) -> list[Check]:
    """Every term of every equation of motion has the same dimension (energy over the coordinate's).

    One check, ``dimensional_consistency``: failed for the first equation with two terms that differ;
    otherwise passed, naming the equations that could not be checked (a symbol of unknown dimension).
    """
    results = _dimension_results(system, derivation)
    if not results:
        return []
    name = "dimensional_consistency"
    for _, ok, detail in results:
        if ok is False:
            return [Check(name, False, detail)]
    checked = [system.coordinates[i].name for i, ok, _ in results if ok]
    skipped = [system.coordinates[i].name for i, ok, _ in results if ok is None]
    if not checked:
        return [Check(name, True, "dimensions not checked: some quantities have no units, or are plain numbers")]
    detail = "every term agrees in the equations for " + ", ".join(f"'{c}'" for c in checked)
    if skipped:
        detail += "; not checked (symbols without units): " + ", ".join(f"'{c}'" for c in skipped)
    return [Check(name, True, detail)]


def verify(system: System, derivation: Derivation) -> list[Check]:
    """Both kinds of checks; raise :class:`DerivationError` at the first failed one, naming it."""
    checks = mass_matrix_checks(derivation)
    for check in checks:
        if not check.passed:
            h_symbols = derivation.mass_matrix.free_symbols if derivation.mass_matrix is not None else set()
            negative = [p for p in system.parameters if p.value is not None and p.value.is_negative]
            negative = [p for p in negative if p.symbol in h_symbols] or negative
            if negative:
                given = ", ".join(f"{p.name} = {sp.sstr(p.value)}" for p in negative)
                raise DerivationError(
                    f"{check.detail}: the kinetic energy could be negative; a mass or inertia must not be "
                    f"negative (given: {given})",
                    negative[0].origin,
                )
            raise DerivationError(
                f"internal check failed: {check.detail}, so the kinetic energy could be negative; "
                "please report this spec as a tutgen bug",
                system.origin,
            )
    for i, ok, detail in _dimension_results(system, derivation):
        if ok is False:
            raise DerivationError(
                f"internal check failed: {detail}; please report this spec as a tutgen bug",
                system.coordinates[i].origin,
            )
    return checks + dimension_checks(system, derivation)
