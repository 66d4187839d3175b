"""The closed-form position analysis of a planar loop: its two branches, by the half-angle substitution.

A loop closed by one pin gives two loop-closure equations in two dependent coordinates. When one of them
is an angle u of a rigid link, the equations are linear in cos u and sin u,

    X + M (cos u, sin u) = 0,    M M^T = L^2 I  (L: the link's length, M = L times a rotation),

and the sum of their squares eliminates u: X . X - L^2 = 0, an equation in the other coordinate v alone
(the four-bar's Freudenstein equation; the slider-crank's quadratic in the slider's position). Then:

- v an angle: the equation is A cos v + B sin v + C = 0, and with t = tan(v/2) (cos v = (1 - t^2)/(1 + t^2),
  sin v = 2t/(1 + t^2)) the quadratic (C - A) t^2 + 2B t + (C + A) = 0, so
  v = 2 atan2(-B +- sqrt(A^2 + B^2 - C^2), C - A);
- v a length: the equation is P v^2 + Q v + R = 0, so v = -Q/(2P) +- sqrt((Q^2 - 4PR)/(4P^2)).

The branch is the sign of the root (+1 or -1). Where the discriminant is negative the loop cannot be
assembled (a four-bar whose links violate Grashof's condition, at the crank angles it cannot reach); where
it is zero the two branches meet, a dead point (det A_d = 0). The eliminated angle follows from v on either
branch: (cos u, sin u) = -M^T X / L^2, so u = atan2 of the components of -M^T X (L^2 > 0 dropped).
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy as sp

from tutgen.engine.tidy import tidy
from tutgen.model.system import ConstraintKind, System

__all__ = [
    "LoopAnalysis",
    "LoopBranch",
    "assembly_at",
    "assembly_ranges",
    "branch_at",
    "branch_values",
    "loop_analysis",
]

_SEED = 20261202
_DRAWS = 12  # random numbers at which both branches are checked
_SHORT_OPS = 30  # only expressions this short are simplified


@dataclass(frozen=True)
class LoopBranch:
    """One branch: the sign of its square root, and each dependent coordinate's closed form."""

    sign: int  # +1 or -1
    positions: tuple[tuple[int, sp.Expr], ...]  # (coordinate index, closed form), the solved one first


@dataclass(frozen=True)
class LoopAnalysis:
    """The position analysis of one loop (the module's conventions); indices are into the coordinates."""

    eliminated: int  # u: the link angle eliminated by the sum of squares
    solved: int  # v: the coordinate solved first
    link_length: sp.Expr  # L
    elimination: sp.Expr  # X . X - L^2, = 0: the equation in v alone
    is_angle: bool  # whether v is an angle (half-angle substitution) or a length (a quadratic)
    # A, B, C of A cos v + B sin v + C = 0 (v an angle), or P, Q, R of P v^2 + Q v + R = 0 (a length)
    coefficients: tuple[sp.Expr, sp.Expr, sp.Expr]
    # (C - A, 2B, C + A) of the quadratic in t = tan(v/2), when v is an angle
    half_angle: tuple[sp.Expr, sp.Expr, sp.Expr] | None
    discriminant: sp.Expr  # A^2 + B^2 - C^2, or (Q^2 - 4PR)/(4P^2): negative where the loop cannot close
    eliminated_value: sp.Expr  # u in terms of v: atan2(...)
    branches: tuple[LoopBranch, LoopBranch]  # the + root, then the - root
    # a four-bar (four revolute pins, one independent angle w): its sides in loop order, each a 2-vector
    # (the link of w, the link of u, the link of v, the ground) summing to zero, and their lengths
    sides: tuple[sp.ImmutableMatrix, ...] = ()
    lengths: tuple[sp.Expr, ...] = ()
    crank: int | None = None  # w, the four-bar's independent angle


def _short(e: sp.Expr) -> sp.Expr:
    """The shortest of a few simplified forms (trigonometric identities, factors)."""
    e = tidy(sp.expand(e))
    if sp.count_ops(e) > _SHORT_OPS:  # a four-bar's discriminant: trigsimp takes seconds, and it stays long
        return e
    trig = tidy(sp.trigsimp(e))
    options = [e, tidy(sp.factor(e)), trig, tidy(sp.factor(trig))]
    return min(options, key=lambda x: (sp.count_ops(x), sp.default_sort_key(x)))


def _linear_in_cos_sin(equations: Sequence[sp.Expr], u: sp.Symbol) -> tuple[sp.Matrix, sp.Matrix] | None:
    """X and M of X + M (cos u, sin u) = 0, or None when the equations are not of that form."""
    cu, su = sp.Dummy("cu"), sp.Dummy("su")
    x_rows, m_rows = [], []
    for f in equations:
        g = sp.expand(sp.expand_trig(f)).subs({sp.cos(u): cu, sp.sin(u): su})
        if u in g.free_symbols:
            return None
        try:
            poly = sp.Poly(g, cu, su)
        except sp.PolynomialError:
            return None
        if poly.total_degree() > 1:
            return None
        x_rows.append(g.subs({cu: 0, su: 0}))
        m_rows.append([poly.coeff_monomial(cu), poly.coeff_monomial(su)])
    return sp.Matrix(x_rows), sp.Matrix(m_rows)


def _link_length(m: sp.Matrix) -> sp.Expr | None:
    """L when M M^T = L^2 I (M is L times a rotation, or a reflection), else None."""
    mm = (m * m.T).applyfunc(lambda e: sp.trigsimp(sp.expand(e)))
    if sp.simplify(mm[0, 1]) != 0 or sp.simplify(mm[0, 0] - mm[1, 1]) != 0 or mm[0, 0] == 0:
        return None
    length = sp.sqrt(sp.factor(mm[0, 0]))
    return sp.simplify(length)


def _analyse(system: System, equations: Sequence[sp.Expr], u_index: int, v_index: int) -> LoopAnalysis | None:
    coords = system.coordinates
    u, v = coords[u_index].q, coords[v_index].q
    split = _linear_in_cos_sin(equations, u)
    if split is None:
        return None
    x, m = split
    length = _link_length(m)
    if length is None or u in x.free_symbols or v not in x.free_symbols:
        return None
    cv, sv = sp.Dummy("cv"), sp.Dummy("sv")
    elimination = sp.expand(sp.expand_trig(sp.expand((x.T * x)[0, 0] - length**2)))
    is_angle = coords[v_index].dimension == "angle" or _turns(system, v)
    if is_angle:
        g = sp.expand(elimination.subs({sp.cos(v): cv, sp.sin(v): sv}).subs(sv**2, 1 - cv**2))
        if v in g.free_symbols:
            return None
        try:
            poly = sp.Poly(g, cv, sv)
        except sp.PolynomialError:
            return None
        if poly.total_degree() > 1:
            return None
        a, b = poly.coeff_monomial(cv), poly.coeff_monomial(sv)
        c = g.subs({cv: 0, sv: 0})
        a, b, c = (_short(k) for k in (a, b, c))
        half = (_short(c - a), _short(2 * b), _short(c + a))
        disc = _short(a**2 + b**2 - c**2)
        roots = [2 * sp.atan2(-b + s * sp.sqrt(disc), c - a) for s in (1, -1)]
        coefficients = (a, b, c)
    else:
        try:
            poly = sp.Poly(elimination, v)
        except sp.PolynomialError:
            return None
        if poly.degree() != 2:
            return None
        p, q, r = (_short(poly.coeff_monomial(v**k)) for k in (2, 1, 0))
        if p.free_symbols & {cc.q for cc in coords}:
            return None
        half = None
        disc = _short((q**2 - 4 * p * r) / (4 * p**2))
        roots = [_short(-q / (2 * p)) + s * sp.sqrt(disc) for s in (1, -1)]
        coefficients = (p, q, r)
    sides, lengths, crank = _four_bar_sides(system, x, m, u, v) if is_angle else ((), (), None)
    # (cos u, sin u) = -M^T X / L^2: the angle of -M^T X / L (L > 0: the parameters are positive)
    w = (-(m.T * x) / length).applyfunc(lambda e: _short(e))
    eliminated_value = sp.atan2(w[1], w[0])
    branches = tuple(
        LoopBranch(sign, ((v_index, root), (u_index, eliminated_value.xreplace({v: root}))))
        for sign, root in zip((1, -1), roots, strict=True)
    )
    return LoopAnalysis(
        eliminated=u_index,
        solved=v_index,
        link_length=length,
        elimination=_short(elimination),
        is_angle=is_angle,
        coefficients=coefficients,
        half_angle=half,
        discriminant=disc,
        eliminated_value=eliminated_value,
        branches=branches,  # type: ignore[arg-type]
        sides=sides,
        lengths=lengths,
        crank=crank,
    )


def _four_bar_sides(
    system: System, x: sp.Matrix, m: sp.Matrix, u: sp.Symbol, v: sp.Symbol
) -> tuple[tuple[sp.ImmutableMatrix, ...], tuple[sp.Expr, ...], int | None]:
    """X = X0 + M_w (cos w, sin w) + M_v (cos v, sin v) with one other angle w: the four sides (M_w e_w,
    M e_u, M_v e_v, X0) and their lengths; empty when X is not of that form."""
    coords = system.coordinates
    split_v = _linear_in_cos_sin(list(x), v)
    if split_v is None:
        return (), (), None
    rest, m_v = split_v
    others = [j for j, c in enumerate(coords) if c.q in rest.free_symbols]
    if len(others) != 1:
        return (), (), None
    w = coords[others[0]].q
    split_w = _linear_in_cos_sin(list(rest), w)
    if split_w is None:
        return (), (), None
    x0, m_w = split_w
    if x0.free_symbols & {c.q for c in coords}:
        return (), (), None
    l_w, l_v, l_u = _link_length(m_w), _link_length(m_v), _link_length(m)
    l_0 = sp.simplify(sp.sqrt(sp.factor(sp.expand(x0[0] ** 2 + x0[1] ** 2))))
    if l_w is None or l_v is None or l_u is None or l_0 == 0:
        return (), (), None

    def side(mat: sp.Matrix, q: sp.Symbol) -> sp.ImmutableMatrix:
        return sp.ImmutableMatrix((mat * sp.Matrix([sp.cos(q), sp.sin(q)])).applyfunc(_short))

    # the sides in the order of the chain: the crank, the link pinned to it, the other, the ground
    joint_of = {j.coordinate.q: j for j in system.joints if j.coordinate is not None}
    if w not in joint_of or u not in joint_of or v not in joint_of:
        return (), (), None
    crank_body = joint_of[w].child
    if joint_of[u].parent == crank_body:
        sides = (side(m_w, w), side(m, u), side(m_v, v), sp.ImmutableMatrix(x0))
        lengths = (l_w, l_u, l_v, l_0)
    elif joint_of[v].parent == crank_body:
        sides = (side(m_w, w), side(m_v, v), side(m, u), sp.ImmutableMatrix(x0))
        lengths = (l_w, l_v, l_u, l_0)
    else:
        return (), (), None
    return sides, lengths, others[0]


def assembly_at(analysis: LoopAnalysis, values: Mapping[sp.Symbol, float]) -> str | None:
    """A four-bar's assembly (circuit) at ``values`` (numbers for the parameters and the coordinates).

    With the sides laid end to end from the crank's fixed pivot O2 (O2 -> A -> B -> O4 -> O2, angles
    counterclockwise), ``"open"`` when A -> B -> O4 turns clockwise and ``"crossed"`` when it turns
    counterclockwise: in the textbook picture (O4 to the right of O2, the crank above the ground) the open
    assembly has B beyond the line A O4 and the crossed one its mirror image about that line. The turn
    changes only where the coupler and the rocker are in line, a dead point, so each branch keeps its name
    while the loop can be assembled. ``None`` when not a four-bar, a number is missing, or at a dead point.
    """
    if not analysis.sides:
        return None
    table = {k: sp.Float(v) for k, v in values.items()}
    try:
        coupler, rocker = ([float(e.xreplace(table)) for e in side] for side in analysis.sides[1:3])
    except TypeError:
        return None
    turn = coupler[0] * rocker[1] - coupler[1] * rocker[0]
    if abs(turn) < 1e-12:
        return None
    return "open" if turn < 0 else "crossed"


def _turns(system: System, q: sp.Symbol) -> bool:
    """Whether a coordinate without a dimension is a revolute joint's angle."""
    for j in system.joints:
        if j.coordinate is not None and j.coordinate.q == q:
            return j.kind.value == "revolute"
    return False


def _holds(system: System, equations: Sequence[sp.Expr], analysis: LoopAnalysis) -> bool:
    """Whether both branches satisfy the equations at seeded random numbers (parameters in [0.5, 2], the
    other coordinates in [-pi, pi]) wherever they are real: a closed form is shown only once checked."""
    rng = random.Random(_SEED)
    coords = system.coordinates
    solved = [coords[analysis.solved].q, coords[analysis.eliminated].q]
    args = sorted(set().union(*(f.free_symbols for f in equations)) - set(solved), key=sp.default_sort_key)
    moving = {c.q for c in coords}
    disc = sp.lambdify(args, analysis.discriminant, modules="math")
    f = sp.lambdify([*args, *solved], list(equations), modules="math")
    roots = [
        sp.lambdify(args, [dict(b.positions)[analysis.solved], dict(b.positions)[analysis.eliminated]], modules="math")
        for b in analysis.branches
    ]
    tested = 0
    for _ in range(_DRAWS):
        values = [rng.uniform(-math.pi, math.pi) if x in moving else rng.uniform(0.5, 2) for x in args]
        try:
            if disc(*values) < 0:
                continue  # no assembly at these numbers
            for root in roots:
                if max(abs(r) for r in f(*values, *root(*values))) > 1e-9:
                    return False
        except (ArithmeticError, ValueError, TypeError):
            return False
        tested += 1
    return tested > 0


def loop_analysis(system: System, functions: Sequence[sp.Expr], dependent: Sequence[int]) -> LoopAnalysis | None:
    """The closed-form position analysis of a single planar loop (the module's conventions): two position
    constraints in two dependent coordinates, one of them a link's angle. The first dependent angle that
    can be eliminated is (the coupler before the rocker, the connecting rod before the slider); ``None``
    when the constraints are not of this form, or when its branches do not satisfy them at random numbers
    (the numeric solve is then the only position analysis)."""
    position = [f for f, c in zip(functions, system.constraints, strict=True) if c.kind is ConstraintKind.POSITION]
    if len(position) != 2:
        return None
    used = [j for j in dependent if any(system.coordinates[j].q in f.free_symbols for f in position)]
    if len(used) != 2:
        return None
    for u_index, v_index in (tuple(used), tuple(reversed(used))):
        found = _analyse(system, position, u_index, v_index)
        if found is not None and _holds(system, position, found):
            return found
    return None


def branch_at(
    analysis: LoopAnalysis, values: Mapping[sp.Symbol, float], coordinates: Sequence[sp.Symbol]
) -> int | None:
    """The sign (+1 or -1) of the branch on which ``values`` (numbers for the parameters and all the
    coordinates) lie, or ``None`` when on neither (a symbol without a number, or no assembly there)."""
    table = {k: sp.Float(v) for k, v in values.items()}
    for branch in analysis.branches:
        ok = True
        for j, e in branch.positions:
            try:
                got = complex(sp.N(e.xreplace(table)))
            except (TypeError, ValueError):
                return None
            want = float(values[coordinates[j]]) if coordinates[j] in values else math.nan
            if abs(got.imag) > 1e-9 or not math.isfinite(want):
                ok = False
                break
            diff = got.real - want
            if j == analysis.eliminated or analysis.is_angle:  # an angle: the same modulo a turn
                diff = math.remainder(diff, 2 * math.pi)
            if abs(diff) > 1e-6:
                ok = False
                break
        if ok:
            return branch.sign
    return None


def branch_values(
    analysis: LoopAnalysis,
    values: Mapping[sp.Symbol, float],
    coordinates: Sequence[sp.Symbol],
    sign: int,
    assembly: str | None = None,
) -> dict[sp.Symbol, float] | None:
    """The dependent coordinates on one branch at ``values`` (numbers for the parameters and the other
    coordinates): for a four-bar with ``assembly`` given, the branch of that assembly (``"open"`` or
    ``"crossed"``: at other lengths the same assembly may have the other sign), else the branch of
    ``sign``. ``None`` where the branch is not real there (the loop cannot be assembled) or a number is
    missing. Angles are given in [-pi, pi]."""
    table = {k: sp.Float(v) for k, v in values.items()}
    found: list[tuple[int, dict[sp.Symbol, float]]] = []
    for branch in analysis.branches:
        out: dict[sp.Symbol, float] = {}
        for j, e in branch.positions:
            try:
                got = complex(sp.N(e.xreplace(table)))
            except (TypeError, ValueError):
                return None
            if abs(got.imag) > 1e-9 or not math.isfinite(got.real):
                return None
            angle = j == analysis.eliminated or analysis.is_angle
            out[coordinates[j]] = math.remainder(got.real, 2 * math.pi) if angle else got.real  # in [-pi, pi]
        found.append((branch.sign, out))
    if assembly is not None and analysis.sides:
        for _sign, out in found:
            if assembly_at(analysis, {**values, **out}) == assembly:
                return out
    return next((out for s, out in found if s == sign), None)


def assembly_ranges(
    analysis: LoopAnalysis, values: Mapping[sp.Symbol, float], samples: int = 720
) -> list[tuple[float, float]] | None:
    """The intervals of a four-bar's crank angle (radians, within [-pi, pi]) where the loop can be
    assembled (the discriminant is not negative), at numbers for every parameter: ``[(-pi, pi)]`` when
    the crank turns fully. ``None`` when not a four-bar or a number is missing. Each end is found by
    bisection between the samples where the discriminant changes sign."""
    if analysis.crank is None:
        return None
    table = {k: sp.Float(v) for k, v in values.items()}
    expr = analysis.discriminant.xreplace(table)
    crank = next(iter(expr.free_symbols), None)
    if len(expr.free_symbols) > 1:
        return None
    if crank is None:  # the discriminant does not depend on the crank: all or nothing
        return [(-math.pi, math.pi)] if float(expr) >= 0 else []
    f = sp.lambdify([crank], expr, modules="math")

    def ok(t: float) -> bool:
        return f(t) >= 0

    def edge(lo: float, hi: float) -> float:
        inside = ok(lo)
        for _ in range(60):
            mid = (lo + hi) / 2
            if ok(mid) == inside:
                lo = mid
            else:
                hi = mid
        return (lo + hi) / 2

    grid = [-math.pi + 2 * math.pi * k / samples for k in range(samples + 1)]
    flags = [ok(t) for t in grid]
    if all(flags):
        return [(-math.pi, math.pi)]
    out: list[tuple[float, float]] = []
    start: float | None = grid[0] if flags[0] else None
    for k in range(1, len(grid)):
        if flags[k] and not flags[k - 1]:
            start = edge(grid[k - 1], grid[k])
        elif not flags[k] and flags[k - 1] and start is not None:
            out.append((start, edge(grid[k - 1], grid[k])))
            start = None
    if start is not None:
        out.append((start, grid[-1]))
    # an interval through the angle pi: one range, from its start to past pi
    if len(out) > 1 and out[0][0] == grid[0] and out[-1][1] == grid[-1]:
        out = [(out[-1][0], out[0][1] + 2 * math.pi), *out[1:-1]]
    return out
