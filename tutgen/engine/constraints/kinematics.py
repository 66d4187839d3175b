"""The constraints' kinematics: the Jacobian A, the velocity analysis q_dot = T q_dot_i, the position
analysis of the dependent coordinates, and the checks that need a consistent state.

Conventions. The constraints are m equations among the n coordinates, in spec order:

- a position (holonomic) constraint f_k(q) = 0 contributes the row A_k = df_k/dq, and, differentiated,
  A_k q_dot = 0;
- a velocity (nonholonomic) constraint a_k(q) . q_dot = 0 contributes its coefficients as the row A_k.

Either way A q_dot = 0, and once more differentiated A q_ddot + b = 0 with b = (d(A q_dot)/dq) q_dot, the
acceleration analysis. The coordinates are split into the independent q_i (the spec's
``independent_coordinates``) and the dependent q_d; with A = [A_i | A_d] (columns in that split),
q_dot_d = B q_dot_i with B = -A_d^-1 A_i, and q_dot = T q_dot_i, where T's row of an independent
coordinate is a unit row and that of a dependent one the row of B.

The numeric checks work at consistent states: random values of the parameters without one (in
[0.5, 2]) and of the independent coordinates (in [-1.5, 1.5], then in [-pi, pi] if too few close there),
the dependent ones then solved from the position constraints (:func:`damped_gauss_newton` from a few
starting points). The random numbers are seeded, so the same spec gives the same states and the same
messages.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from itertools import combinations

import mpmath
import sympy as sp

from tutgen.engine.constraints.positions import LoopAnalysis, loop_analysis
from tutgen.engine.tidy import tidy
from tutgen.errors import DerivationError
from tutgen.model.system import Constraint, ConstraintKind, System

__all__ = [
    "ConstraintKinematics",
    "State",
    "consistent_states",
    "constraint_kinematics",
    "damped_gauss_newton",
    "solve_positions",
]

_SEED = 20261202
#: how many random draws of the independent coordinates are tried before a position constraint is said
#: to hold at no configuration, and the starting points of each solve
_DRAWS = 8
#: the half-widths of the ranges the independent coordinates are drawn from, in turn (see consistent_states)
_SPREADS = (1.5, float(mpmath.pi))
_STARTS = (0.3, -0.7, 1.3, 2.5, -2.0)
#: a singular value below this (relative to the largest) makes A rank-deficient
_RANK_TOLERANCE = 1e-9
#: |f(q)| below this is a root of the position constraints (at 30 digits)
_ROOT_TOLERANCE = mpmath.mpf("1e-25")


@dataclass(frozen=True)
class State:
    """A consistent state: a value for every parameter without one, every coordinate and every rate."""

    values: dict[sp.Symbol, mpmath.mpf]


@dataclass(frozen=True)
class ConstraintKinematics:
    """The constraints' kinematics (see the module's conventions); indices are into the coordinates."""

    constraints: tuple[Constraint, ...]  # the spec's, after the loop-closure equations of its loop joints
    functions: tuple[sp.Expr, ...]  # f_k(q) of a position constraint, a_k(q) . q_dot of a velocity one
    jacobian: sp.ImmutableMatrix  # A, m x n
    bias: sp.ImmutableMatrix  # b, m x 1: A q_ddot + b = 0
    independent: tuple[int, ...]
    dependent: tuple[int, ...]
    velocity_ratios: sp.ImmutableMatrix  # B, m x n_i: q_dot_d = B q_dot_i
    determinant: sp.Expr  # det A_d: zero at the singular (dead-point) configurations of this choice
    velocity_map: sp.ImmutableMatrix  # T, n x n_i: q_dot = T q_dot_i
    # the position analysis: each dependent coordinate solved from the position constraints, by
    # branch (one branch when they are linear in q_d); empty when not solved in closed form
    positions: tuple[tuple[tuple[int, sp.Expr], ...], ...]
    rates: dict[sp.Symbol, sp.Expr]  # q_dot_d -> B q_dot_i
    is_holonomic: bool  # every constraint is a position constraint
    # a loop's closed-form position analysis with its two branches (tutgen/engine/constraints/positions.py),
    # when the position constraints are not linear in q_d but are one planar loop's
    loop: LoopAnalysis | None = None


def _free_values(system: System, rng: random.Random) -> dict[sp.Symbol, mpmath.mpf]:
    return {
        # a value may be irrational (30 deg is pi/6): evaluated, not converted
        p.symbol: mpmath.mpf(sp.N(p.value, 30)) if p.value is not None else mpmath.mpf(rng.uniform(0.5, 2))
        for p in system.parameters
    }


def _numeric(expr: sp.Expr, values: dict[sp.Symbol, mpmath.mpf]) -> sp.Expr:
    return expr.subs(values)


def _position_unknowns(
    system: System,
    functions: Sequence[sp.Expr],
    dependent: Sequence[int],
    constraints: Sequence[Constraint] | None = None,
) -> tuple[list[sp.Expr], list[sp.Symbol], list[sp.Symbol]]:
    """The position constraints (``constraints``, default the system's, with their ``functions``), the
    coordinates solved from them (the dependent ones they use first, then any other they use: a singular
    choice of independent coordinates is found after, at a consistent state), and the other symbols they
    use, sorted."""
    coords = system.coordinates
    cons = system.constraints if constraints is None else constraints
    position = [f for f, c in zip(functions, cons, strict=True) if c.kind is ConstraintKind.POSITION]
    used = [c.q for c in coords if any(c.q in f.free_symbols for f in position)]
    dep = {coords[i].q for i in dependent}
    fixed = sorted(used, key=lambda s: s not in dep)[: len(position)]
    others = sorted(set().union(*(f.free_symbols for f in position)) - set(fixed), key=sp.default_sort_key)
    return position, fixed, others


#: the compiled solver of each ConstraintKinematics solve_positions has seen (kept with it, so that its
#: id is not reused while the entry lives): a simulation solves the same loop at every initial state
_SOLVERS: dict[int, tuple[ConstraintKinematics, _Solver | None, list[sp.Symbol], list[sp.Symbol]]] = {}


def solve_positions(
    system: System,
    ck: ConstraintKinematics,
    values: Mapping[sp.Symbol, float],
    start: Mapping[sp.Symbol, float] | None = None,
) -> dict[sp.Symbol, float] | None:
    """The dependent coordinates that satisfy the position constraints, numerically.

    Parameters
    ==========

    system : the spec's system (``Derivation.system``) or the constrained one (with its loop-closure
        equations, as :func:`~tutgen.engine.constraints.loops.with_loop_closures` returns it): only its
        coordinates are read
    ck : the constraints' kinematics (``Derivation.constraints.kinematics``)
    values : a number for every parameter and independent coordinate the position constraints use
    start : where to start from, for the coordinates solved (missing ones start at 0); the root found is
        the one :func:`damped_gauss_newton` reaches from there, the branch nearest ``start`` in practice.
        Without it a few fixed starting points are tried in turn.

    Returns
    =======

    The value of every coordinate solved from the position constraints (the dependent ones they use), or
    ``None`` when no root is found (the loop does not close at these numbers). Empty when the spec has no
    position constraints.
    """
    hit = _SOLVERS.get(id(ck))
    if hit is None or hit[0] is not ck:
        position, fixed, others = _position_unknowns(system, ck.functions, ck.dependent, ck.constraints)
        hit = (ck, _Solver(position, fixed, others) if position else None, fixed, others)
        while len(_SOLVERS) >= 16:
            _SOLVERS.pop(next(iter(_SOLVERS)))
        _SOLVERS[id(ck)] = hit
    _ck, solver, fixed, others = hit
    if solver is None:
        return {}
    first = [float(start.get(s, 0.0)) for s in fixed] if start is not None else None
    root = solver.solve([values[s] for s in others], first, quick=True)
    if root is None:
        return None
    return {s: float(v) for s, v in zip(fixed, root, strict=True)}


def consistent_states(
    system: System, functions: Sequence[sp.Expr], dependent: Sequence[int], count: int
) -> Iterator[State]:
    """``count`` consistent states (the module's conventions); the rates are not set. Stops early when the
    position constraints cannot be solved at a draw: the caller counts what it got."""
    rng = random.Random(_SEED)
    coords = system.coordinates
    position, fixed, others = _position_unknowns(system, functions, dependent)
    solver = _Solver(position, fixed, others) if position else None
    found = 0
    # first near the reference configuration, then, if too few draws close there (a loop that closes only
    # with the crank near theta = pi), over the whole turn: the first pass's states are kept either way
    for spread in _SPREADS:
        for _ in range(_DRAWS * count):
            if found == count:
                return
            values = _free_values(system, rng)
            for c in coords:
                if c.q not in fixed:
                    values[c.q] = mpmath.mpf(rng.uniform(-spread, spread))
            if solver is not None:
                root = solver.solve([values[s] for s in others])
                if root is None:
                    continue
                values.update(dict(zip(fixed, root, strict=True)))
            found += 1
            yield State(values)
        if solver is None:
            return


def damped_gauss_newton(
    residual: Callable[[list[mpmath.mpf]], Sequence[object]],
    jacobian: Callable[[list[mpmath.mpf]], Sequence[Sequence[object]]],
    start: Sequence[float | mpmath.mpf],
    tolerance: float | mpmath.mpf = _ROOT_TOLERANCE,
    iterations: int = 60,
    stall: float | None = None,
) -> list[mpmath.mpf] | None:
    """A root of ``residual`` (a vector function of k unknowns, with as many components or more) near
    ``start``, by damped Gauss-Newton (Levenberg-Marquardt): each step solves (J^T J + mu I) dx = J^T r, mu
    shrinking after a step that lowers |r| and growing after one that does not. Redundant equations do not
    stop it (the normal equations are damped); inconsistent ones leave a residual, and ``None`` is
    returned, as it is when |r| is not below ``tolerance`` after ``iterations`` steps or an evaluation
    fails. With ``stall``, the search also gives up early at a minimum that is not a root: when a step
    lowers |r| by less than that fraction of it, or the damping has grown past 1e12. Works in mpmath's
    current precision (the callers choose it).

    Examples
    ========

    >>> import mpmath
    >>> root = damped_gauss_newton(lambda x: [x[0] ** 2 - 2], lambda x: [[2 * x[0]]], [1.0], tolerance=1e-12)
    >>> mpmath.nstr(root[0], 10)
    '1.414213562'
    """
    k = len(start)
    x = mpmath.matrix([mpmath.mpf(v) for v in start])
    mu = mpmath.mpf("1e-3")
    try:
        r = mpmath.matrix(list(residual(list(x))))
        for _ in range(iterations):
            if mpmath.norm(r) < tolerance:
                return [mpmath.mpf(mpmath.re(v)) for v in x]
            j = mpmath.matrix([list(row) for row in jacobian(list(x))])
            step = mpmath.lu_solve(j.T * j + mu * mpmath.eye(k), j.T * r)
            trial = x - step
            r_trial = mpmath.matrix(list(residual(list(trial))))
            if mpmath.norm(r_trial) < mpmath.norm(r):
                if stall is not None and mpmath.norm(r) - mpmath.norm(r_trial) < stall * mpmath.norm(r):
                    return None
                x, r, mu = trial, r_trial, mu / 3
            else:
                mu *= 4
                if stall is not None and mu > 1e12:
                    return None
    except (ArithmeticError, ValueError, TypeError, ZeroDivisionError):
        return None
    return None


class _Solver:
    """A root of the position constraints in ``fixed`` for given values of ``others`` (as many equations as
    unknowns, or more when some are redundant), by :func:`damped_gauss_newton` from a few starting points
    (or from the one given)."""

    def __init__(self, equations: Sequence[sp.Expr], fixed: Sequence[sp.Symbol], others: Sequence[sp.Symbol]) -> None:
        args = [*fixed, *others]
        self.k = len(fixed)
        self.f = sp.lambdify(args, list(equations), modules="mpmath")
        self.jac = sp.lambdify(args, sp.Matrix(equations).jacobian(list(fixed)).tolist(), modules="mpmath")

    def solve(
        self,
        rest: Sequence[mpmath.mpf | float],
        start: Sequence[float] | None = None,
        quick: bool = False,
    ) -> list[mpmath.mpf] | None:
        """A root from ``start``, or from each of the fixed starting points in turn; ``quick``: in double
        precision, giving up early where there is no root (for the numbers of a figure or a simulation)."""
        k = self.k
        starts = [list(start)] if start is not None else [[s + 0.1 * i for i in range(k)] for s in _STARTS]
        dps, tolerance = (17, mpmath.mpf("1e-13")) if quick else (30, _ROOT_TOLERANCE)
        with mpmath.workdps(dps):
            rest = [mpmath.mpf(v) for v in rest]
            for first in starts:
                root = damped_gauss_newton(
                    lambda x: self.f(*x, *rest),
                    lambda x: self.jac(*x, *rest),
                    first,
                    tolerance,
                    stall=1e-3 if quick else None,
                )
                if root is not None:
                    return root
        return None


def _short(e: sp.Expr) -> sp.Expr:
    """A short expression in its simplest form (trigonometric identities, factors)."""
    e = tidy(sp.expand(e))
    if sp.count_ops(e) > 80:
        return e
    simpler = sp.factor(sp.simplify(e))
    return simpler if sp.count_ops(simpler) <= sp.count_ops(e) else e


def _rank(a: mpmath.matrix) -> int:
    if a.rows == 0:
        return 0
    s = mpmath.svd_r(a, compute_uv=False)
    top = max(abs(x) for x in s) if len(s) else 0
    return sum(1 for x in s if abs(x) > _RANK_TOLERANCE * max(top, 1))


def _evaluate(m: sp.MatrixBase, values: dict[sp.Symbol, mpmath.mpf]) -> mpmath.matrix:
    with mpmath.workdps(30):
        return mpmath.matrix([[mpmath.mpf(sp.N(e.subs(values), 30)) for e in row] for row in m.tolist()])


def _solve_positions(
    functions: Sequence[sp.Expr], system: System, dependent: Sequence[int]
) -> tuple[tuple[tuple[int, sp.Expr], ...], ...]:
    """The position analysis in closed form: the dependent coordinates that position constraints fix,
    by branch. Linear constraints give one branch; others are left to the numeric analysis (empty)."""
    position = [f for f, c in zip(functions, system.constraints, strict=True) if c.kind is ConstraintKind.POSITION]
    if not position:
        return ()
    qs = [system.coordinates[i].q for i in dependent]
    fixed = [(i, q) for i, q in zip(dependent, qs, strict=True) if any(q in f.free_symbols for f in position)]
    fixed = fixed[: len(position)]
    unknowns = [q for _, q in fixed]
    try:
        a, rhs = sp.linear_eq_to_matrix([sp.expand(f) for f in position], unknowns)
    except (sp.PolynomialError, ValueError):
        return ()
    if a.free_symbols & set(unknowns) or a.shape[0] != a.shape[1] or a.det() == 0:
        return ()
    solution = a.LUsolve(rhs)
    return (tuple((i, tidy(solution[k])) for k, (i, _) in enumerate(fixed)),)


def constraint_kinematics(system: System) -> ConstraintKinematics:
    """A, b, B and T of the spec's constraints, with the checks at consistent states.

    Raises :class:`~tutgen.errors.DerivationError` at the constraint concerned when the position
    constraints hold at no configuration, when the constraints are redundant or inconsistent (A of rank
    less than m at a consistent state), or when A_d is singular for the chosen independent coordinates
    (with a choice that works, if there is one).
    """
    coords = system.coordinates
    q = [c.q for c in coords]
    qd = [c.qd for c in coords]
    n, m = len(q), len(system.constraints)
    rows: list[list[sp.Expr]] = []
    functions: list[sp.Expr] = []
    for con in system.constraints:
        f = con.expression
        functions.append(f)
        if con.kind is ConstraintKind.POSITION:
            rows.append([tidy(sp.diff(f, qi)) for qi in q])
        else:
            rows.append([tidy(sp.diff(f, qdi)) for qdi in qd])
    a = sp.ImmutableMatrix(rows)
    velocity = [sum((a[k, j] * qd[j] for j in range(n)), sp.Integer(0)) for k in range(m)]
    bias = sp.ImmutableMatrix(
        [tidy(sum((sp.diff(v, q[j]) * qd[j] for j in range(n)), sp.Integer(0))) for v in velocity]
    )
    names = [c.name for c in coords]
    independent = tuple(names.index(x) for x in system.independent_coordinates)
    dependent = tuple(j for j in range(n) if j not in independent)

    states = list(consistent_states(system, functions, dependent, 1))
    if not states:
        held = [c for c in system.constraints if c.kind is ConstraintKind.POSITION]
        raise DerivationError(
            f"the position constraints ({', '.join(c.name for c in held)}) "
            f"hold at no configuration tried ({_DRAWS * len(_SPREADS)} random values of "
            f"{', '.join(system.independent_coordinates)}): they are inconsistent, or the loop does not close; "
            "check the lengths and the constraint expressions",
            held[0].origin,
        )
    values = states[0].values
    a_num = _evaluate(a, values)
    if _rank(a_num) < m:
        # the first constraint that adds nothing to those before it
        k = next(k for k in range(1, m + 1) if _rank(_evaluate(a.extract(list(range(k)), list(range(n))), values)) < k)
        k -= 1
        con = system.constraints[k]
        raise DerivationError(
            f"constraint '{con.name}' is redundant or inconsistent with those before it: the constraint "
            f"Jacobian A has rank {_rank(a_num)} < {m} at a consistent state; remove it or state the constraints "
            "independently",
            con.origin,
        )
    a_d = a.extract(list(range(m)), list(dependent))
    if _rank(_evaluate(a_d, values)) < m:
        good = [
            combo
            for combo in combinations(range(n), n - m)
            if _rank(_evaluate(a.extract(list(range(m)), [j for j in range(n) if j not in combo]), values)) == m
        ]
        hint = f"; e.g. independent_coordinates: [{', '.join(names[j] for j in good[0])}]" if good else ""
        raise DerivationError(
            f"the independent coordinates [{', '.join(system.independent_coordinates)}] cannot be kept: the "
            f"constraints do not determine the rates of {', '.join(names[j] for j in dependent)} from theirs "
            f"(dA/dq of the dependent coordinates is singular){hint}",
            system.constraints[0].origin,
        )
    a_i = a.extract(list(range(m)), list(independent))
    # B = -A_d^-1 A_i by Cramer's rule, numerator and determinant each simplified (they are short: the
    # four-bar's determinant is b c sin(theta3 - theta4), where its dead points are)
    det = _short(a_d.det(method="berkowitz"))
    adj = a_d.adjugate()
    b_mat = (-(adj * a_i)).applyfunc(lambda e: _short(e) / det)
    t_rows: list[list[sp.Expr]] = []
    for j in range(n):
        if j in independent:
            t_rows.append([sp.Integer(1 if independent.index(j) == k else 0) for k in range(len(independent))])
        else:
            t_rows.append(list(b_mat.row(dependent.index(j))))
    rates = {
        qd[j]: sum((b_mat[r, k] * qd[independent[k]] for k in range(len(independent))), sp.Integer(0))
        for r, j in enumerate(dependent)
    }
    positions = _solve_positions(functions, system, dependent)
    return ConstraintKinematics(
        constraints=system.constraints,
        functions=tuple(functions),
        jacobian=a,
        bias=bias,
        independent=independent,
        dependent=dependent,
        velocity_ratios=sp.ImmutableMatrix(b_mat),
        determinant=det,
        velocity_map=sp.ImmutableMatrix(t_rows),
        positions=positions,
        rates=rates,
        is_holonomic=all(c.kind is ConstraintKind.POSITION for c in system.constraints),
        loop=None if positions else loop_analysis(system, functions, dependent),
    )
