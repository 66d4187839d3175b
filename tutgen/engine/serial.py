"""H(q), C(q, q_dot) q_dot and G(q) of serial arms, fast enough for a fully symbolic 6-DOF arm.

The general route (:mod:`tutgen.engine.lagrange`, run by :mod:`tutgen.engine.pipeline`) works in world
components and tidies every entry with trigonometric identities, which is right for a worked solution
of two or three coordinates but grows too fast beyond. Here, for a chain of revolute, prismatic and
fixed joints from the ground (each placed by :func:`tutgen.engine.placement.place_joint`):

- Every velocity Jacobian is kept in the link's own axes and propagated joint by joint, as in the
  velocity pass of recursive Newton-Euler: ``^c J = ^cR_p (^p J_v + ^p J_w x lever)``. ``^cR_p``
  depends on the joint's own coordinate only, so no product R I R^T is ever formed and the link
  inertia (given about the centre of mass in body axes) is used as given:
  H = sum_i m_i J_vi^T J_vi + J_wi^T I_i J_wi (+ the reflected rotor inertia n^2 J_m on H_ii).
- Gravity is carried into each link's axes the same way (``^c g = ^cR_p ^p g``), so
  U = -sum m g . r_c is a scalar per link and G = dU/dq exactly.
- Every quantity is a :class:`~tutgen.engine.trigpoly.TrigPoly`: canonical, so sin^2 + cos^2 = 1
  and every cancellation happens by construction, with no ``simplify``; derivatives are exact, so
  the Christoffel symbols Gamma_ijk = (dH_ij/dq_k + dH_ik/dq_j - dH_jk/dq_i) / 2 are cheap.
- sympy is only the output layer: each entry is converted once, its coefficients grouped by a
  greedy Horner scheme (``TrigAlgebra.coefficient_expr``) and assembled without sympy's flatten.
  The symbols Gamma_ijk (j <= k) are converted once, when C q_dot or C is first read, and C q_dot and C
  are written from them.

The tutorial's table h_ijk is converted on first use (``functools.cached_property``): a 6-DOF arm
has about two hundred of them, and H, C q_dot, G are what a simulation needs.

What it costs (2 shared cores, sympy 1.14, pure-Python coefficients): a fully symbolic PUMA-like 6R
arm (every mass, centre of mass and inertia entry a symbol) about 3 s for H, C q_dot and G with
H at 37k operations (KanesMethod, unsimplified: 5 s and 41k in the same run); a planar 3R arm of
point masses 11 ms, 4R 28 ms (Kane + trigsimp: 1.1 s and 6.7 s, with larger H); planar 10R 1 s.
About half of the 6-DOF time is building the sympy output (C q_dot alone is 140k operations).
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass, field
from functools import cached_property

import sympy as sp
from sympy import QQ

from tutgen.engine.derivation import Check
from tutgen.engine.inertia import body_inertia
from tutgen.engine.inverse_dynamics import numeric_inverse_dynamics
from tutgen.engine.lazytable import LazyMatrix
from tutgen.engine.placement import place_joint
from tutgen.engine.trigpoly import TrigAlgebra, TrigPoly, monomial_times_sum
from tutgen.errors import DerivationError
from tutgen.model.system import GROUND, Joint, JointKind, System

__all__ = [
    "LARGE",
    "REMARK_FAST_PATH",
    "SerialDynamics",
    "cse_form",
    "is_large_serial_chain",
    "is_serial_chain",
    "numeric_checks",
    "numeric_inverse_dynamics",
    "serial_checks",
    "serial_dynamics",
    "skew_check",
]

Vec3 = list[TrigPoly]
Mat3 = list[list[TrigPoly]]
_HALF = QQ(1, 2)


def is_serial_chain(system: System) -> bool:
    """True when every body hangs from the ground by a chain of revolute, prismatic and fixed joints
    with relative angles, each moving joint driving its own coordinate and every coordinate driven
    by a joint (no bodies placed by ``position``/``orientation``, no given energy).

    A kinematic tree (a fixed tool on a link, two branches) is accepted too: each body's Jacobians
    come from its parent's alone, so the propagation is the same.
    """
    if system.kinetic_energy is not None or system.potential_energy is not None:
        return False
    if not system.bodies or not system.coordinates:
        return False
    by_child = {j.child: j for j in system.joints}
    if any(b.name not in by_child for b in system.bodies):
        return False
    if any(b.position is not None or b.rotation is not None or b.rotation_rates for b in system.bodies):
        return False
    driven: list[sp.Symbol] = []
    for j in system.joints:
        if j.absolute or j.kind not in (JointKind.REVOLUTE, JointKind.PRISMATIC, JointKind.FIXED):
            return False
        if j.kind is JointKind.FIXED:
            if j.coordinate is not None:
                return False
            continue
        if j.coordinate is None:
            return False
        driven.append(j.coordinate.q)
    coords = [c.q for c in system.coordinates]
    if sorted(driven, key=str) != sorted(coords, key=str) or len(set(driven)) != len(driven):
        return False
    # every chain reaches the ground (validate.py rejects loops; a body placed without a joint would
    # have been caught above)
    names = {b.name for b in system.bodies}
    return all(j.parent == GROUND or j.parent in names for j in system.joints)


@dataclass(frozen=True)
class _Exact:
    """The exact results, kept for the Christoffel symbols, C and the checks."""

    algebra: TrigAlgebra
    h: list[list[TrigPoly]]  # full n x n
    dh: list[list[list[TrigPoly]]]  # dh[i][j][k] = dH_ij / dq_k
    gammas: dict[tuple[int, int, int], TrigPoly]  # Gamma_ijk for j <= k, nonzero only
    g: list[TrigPoly]
    u: TrigPoly


@dataclass(frozen=True)
class SerialDynamics:
    """H q_ddot + C(q, q_dot) q_dot + G(q) of a serial arm, as sympy matrices.

    ``christoffel`` uses the tutorial's convention (as :attr:`Derivation.christoffel`):
    h_ijk = dH_ij/dq_k - dH_jk/dq_i / 2, so C_i = sum_jk h_ijk q_dot_j q_dot_k; ``christoffel_first_kind``
    is the symmetric Gamma_ijk = (dH_ij/dq_k + dH_ik/dq_j - dH_jk/dq_i) / 2, and ``coriolis_matrix``
    C_ij = sum_k Gamma_ijk q_dot_k, so that H_dot - 2 C is skew. Only nonzero symbols are listed.
    """

    coordinates: tuple[sp.Symbol, ...]
    rates: tuple[sp.Symbol, ...]
    mass_matrix: sp.ImmutableMatrix
    coriolis_vector: sp.ImmutableMatrix
    gravity_vector: sp.ImmutableMatrix
    potential_energy: sp.Expr  # of gravity
    timings: tuple[tuple[str, float], ...]
    exact: _Exact = field(repr=False, compare=False)
    _christoffel_cache: dict[tuple[int, int, int], TrigPoly] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )

    @cached_property
    def christoffel_polys(self) -> dict[tuple[int, int, int], TrigPoly]:
        """The tutorial's h_ijk, nonzero only, exactly (:meth:`christoffel_poly` of each nonzero key)."""
        return {key: self.christoffel_poly(key) for key in self.christoffel_keys}

    @cached_property
    def christoffel_keys(self) -> tuple[tuple[int, int, int], ...]:
        """The keys (i, j, k) of the nonzero h_ijk, in order, found without computing them:
        h_ijk = dH_ij/dq_k - dH_jk/dq_i / 2 is zero exactly when dH_ij/dq_k = dH_jk/dq_i / 2, which is
        decided frequency by frequency, usually at the first (issue 17: a worked solution counts them)."""
        n = len(self.coordinates)
        dh = self.exact.dh
        return tuple(
            (i, j, k) for i in range(n) for j in range(n) for k in range(n) if not _is_half_of(dh[i][j][k], dh[j][k][i])
        )

    def christoffel_min_ops(self, key: tuple[int, int, int]) -> int:
        """A lower bound of ``sympy.count_ops`` of the tutorial's h_ijk (at most its
        :meth:`TrigPoly.min_ops <tutgen.engine.trigpoly.TrigPoly.min_ops>`), without computing it: the terms of
        dH_ij/dq_k and dH_jk/dq_i / 2 at a frequency only one of them has cannot cancel, so h_ijk has at
        least those terms (s of them: s - 1 additions) and their cosines and sines."""
        i, j, k = key
        a, b = self.exact.dh[i][j][k].terms, self.exact.dh[j][k][i].terms
        zero = self.exact.algebra.zero_k
        size = trig = 0
        for freq in a.keys() ^ b.keys():
            size += len(a[freq] if freq in a else b[freq])
            if freq[0] != zero:
                trig += sum(1 for v in freq[0] if v)
        return max(size - 1, 0) + trig

    def christoffel_poly(self, key: tuple[int, int, int]) -> TrigPoly:
        """The tutorial's h_ijk of ``key``, exactly (computed once; zero for a key not in
        :attr:`christoffel_keys`)."""
        hit = self._christoffel_cache.get(key)
        if hit is None:
            i, j, k = key
            dh = self.exact.dh
            hit = TrigPoly.combination([dh[i][j][k], dh[i][j][k]], [dh[j][k][i]], _HALF)
            self._christoffel_cache[key] = hit
        return hit

    @cached_property
    def christoffel_first_kind_polys(self) -> dict[tuple[int, int, int], TrigPoly]:
        """Gamma_ijk, nonzero only, both orders of j, k (the same object), exactly."""
        out: dict[tuple[int, int, int], TrigPoly] = {}
        for (i, j, k), gam in self.exact.gammas.items():
            out[(i, j, k)] = out[(i, k, j)] = gam
        return out

    @cached_property
    def christoffel_first_kind(self) -> dict[tuple[int, int, int], sp.Expr]:
        """Gamma_ijk (both orders of j, k: the same object), nonzero only, converted to sympy on first read
        (C q_dot and C are written from them)."""
        first: dict[tuple[int, int, int], sp.Expr] = {}
        for (i, j, k), gam in self.exact.gammas.items():
            first[(i, j, k)] = first[(i, k, j)] = gam.to_expr()
        return dict(sorted(first.items()))

    def coriolis_entries(self) -> list[sp.Expr]:
        """C q_dot entry by entry: C_i = sum_j Gamma_ijj q_dot_j^2 + 2 sum_{j<k} Gamma_ijk q_dot_j q_dot_k,
        the same grouping by rate monomials that TrigPoly.to_expr(rates) gives, without converting C on its
        own."""
        first = self.christoffel_first_kind
        rates = self.rates
        keys = self.exact.gammas
        return [
            monomial_times_sum(
                [
                    (first[key], 1 if key[1] == key[2] else 2, (rates[key[1]], rates[key[2]]))
                    for key in keys
                    if key[0] == i
                ]
            )
            for i in range(len(self.coordinates))
        ]

    def coriolis_min_ops(self, matrix: bool = False) -> int:
        """A lower bound of ``sympy.count_ops`` of C q_dot (or, ``matrix``, of C) without converting: each
        symbol's own (:meth:`TrigPoly.min_ops <tutgen.engine.trigpoly.TrigPoly.min_ops>`), which C_i keeps
        whole as a factor of its rate monomial; in C q_dot those products are distinct terms of C_i (one
        addition fewer than symbols in the row). The bound of C q_dot holds for the equations of motion,
        which have C q_dot's terms among theirs; in C each symbol occurs at least once, but an entry may
        have a single term."""
        per_row = [0] * len(self.coordinates)
        total = 0
        for (i, _, _), p in self.exact.gammas.items():
            per_row[i] += 1
            total += p.min_ops()
        return total if matrix else total + sum(max(k - 1, 0) for k in per_row)

    def coriolis_dimension_terms(self) -> list[sp.Expr]:
        """For the dimensional check without converting C q_dot: per row i, the sum over the symbols
        Gamma_ijk of q_dot_j q_dot_k (m_1 + m_2 + ...), where m_1, m_2, ... are the distinct monomials of
        Gamma_ijk's coefficients without their numbers and trigonometric factors. The trigonometric
        factors are of revolute angles (dimensionless) and numbers have no dimension, so the terms of
        C_i have the dimensions of these monomials times q_dot_j q_dot_k and nothing else."""
        alg = self.exact.algebra
        gens = alg.gens
        rows: list[list[sp.Expr]] = [[] for _ in self.coordinates]
        for (i, j, k), gam in self.exact.gammas.items():
            monomials = sorted({m for c in gam.terms.values() for m in c})
            inner = sp.Add(*[sp.Mul(*[gens[g] ** e for g, e in enumerate(m) if e]) for m in monomials])
            rows[i].append(self.rates[j] * self.rates[k] * inner)
        return [sp.Add(*r) for r in rows]

    def mass_dimension_terms(self) -> list[list[sp.Expr]]:
        """For the dimensional check without H's entries written out: each H_ij as the sum of the distinct
        monomials of its coefficients, without their numbers and trigonometric factors (as
        :meth:`coriolis_dimension_terms` for C). A coefficient that is a number alone (a motor's rotor
        inertia given as a number) stands as the number 2, which the check, like any number but 1 and -1,
        takes to be of unknown dimension, as it took the number itself."""
        gens = self.exact.algebra.gens
        out: list[list[sp.Expr]] = []
        for row in self.exact.h:
            out.append([])
            for p in row:
                monomials = sorted({m for c in p.terms.values() for m in c})
                terms = [
                    sp.Mul(*[gens[g] ** e for g, e in enumerate(m) if e]) if any(m) else sp.Integer(2)
                    for m in monomials
                ]
                out[-1].append(sp.Add(*terms))
        return out

    @cached_property
    def christoffel(self) -> dict[tuple[int, int, int], sp.Expr]:
        return {key: h.to_expr() for key, h in self.christoffel_polys.items()}

    @cached_property
    def coriolis_matrix(self) -> sp.ImmutableMatrix:
        """C_ij = sum_k Gamma_ijk q_dot_k, assembled from the converted symbols (no new conversion)."""
        n = len(self.coordinates)
        gam = self.christoffel_first_kind
        return sp.ImmutableMatrix(
            n,
            n,
            lambda i, j: monomial_times_sum(
                [(gam[(i, j, k)], 1, (self.rates[k],)) for k in range(n) if (i, j, k) in gam]
            ),
        )


def _is_half_of(a: TrigPoly, b: TrigPoly) -> bool:
    """a = b / 2, exactly: the same frequencies, each coefficient of a half of b's (stops at the first
    that differs)."""
    if a.terms.keys() != b.terms.keys():
        return False
    return all(c == b.terms[key].mul_ground(_HALF) for key, c in a.terms.items())


def _coriolis_matrix(ex: _Exact) -> list[list[TrigPoly]]:
    """C_ij = sum_k Gamma_ijk q_dot_k, exactly (for :func:`skew_check`)."""
    alg = ex.algebra
    n = len(ex.h)
    dh = ex.dh
    half = alg.ring.ground_new(alg.ring.domain(1, 2))
    qd = [alg.rate(s) for s in alg.rates]
    out = []
    for i in range(n):
        row = []
        for j in range(n):
            acc = alg.zero
            for k in range(n):
                gam = dh[i][j][k] + dh[i][k][j] - dh[j][k][i]
                acc = acc + gam.scale(qd[k])
            row.append(acc.scale(half))
        out.append(row)
    return out


# ---------------------------------------------------------------------------------------------
# The derivation
# ---------------------------------------------------------------------------------------------


def _constants(system: System) -> list[sp.Expr]:
    """Every constant that enters the coefficients, so the algebra knows its generators up front."""
    out: list[sp.Expr] = []
    for body in system.bodies:
        bi = body_inertia(body)
        out += [bi.mass, *bi.com, *bi.inertia_com]
        for part in bi.parts:
            out += [part.mass, *part.centroid, *part.inertia_centroid]
    for j in system.joints:
        out += [*j.origin_offset, *j.rotation, *j.axis, j.offset, sp.cos(j.offset), sp.sin(j.offset)]
        if j.reflected_inertia is not None:
            out.append(j.reflected_inertia)
    if system.gravity is not None:
        out += list(system.gravity)
    return [sp.sympify(e) for e in out]


class _Exactly:
    """:class:`~tutgen.engine.placement.Scalars` over exact trigonometric polynomials (nothing is named)."""

    def __init__(self, alg: TrigAlgebra, index: dict[sp.Symbol, int]) -> None:
        self.alg = alg
        self.index = index
        self.zero = alg.zero
        self.one = alg.one
        self.const = alg.const

    def add(self, *terms: TrigPoly) -> TrigPoly:
        return _sum(terms) if terms else self.zero

    def mul(self, *factors: TrigPoly) -> TrigPoly:
        acc = factors[0]
        for f in factors[1:]:
            acc = acc * f
        return acc

    def neg(self, a: TrigPoly) -> TrigPoly:
        return -a

    def sub(self, a: TrigPoly, b: TrigPoly) -> TrigPoly:
        return a - b

    def name(self, a: TrigPoly) -> TrigPoly:
        return a

    def turn(self, joint: Joint) -> tuple[TrigPoly, TrigPoly]:
        """cos(q + offset), sin(q + offset) by the angle-sum formulas: the offset is a constant."""
        assert joint.coordinate is not None
        k = self.index[joint.coordinate.q]
        cq, sq = self.alg.cos(k), self.alg.sin(k)
        off = sp.sympify(joint.offset)
        if off != 0:
            co, so = self.alg.coefficient(sp.cos(off)), self.alg.coefficient(sp.sin(off))
            cq, sq = cq.scale(co) - sq.scale(so), sq.scale(co) + cq.scale(so)
        return cq, sq


def _sum(items: object) -> TrigPoly:
    it = iter(items)  # type: ignore[call-overload]
    acc = next(it)
    for x in it:
        acc = acc + x
    return acc


def _apply(r: Mat3, v: Vec3) -> Vec3:
    out = []
    for i in range(3):
        acc = None
        for k in range(3):
            if r[i][k] and v[k]:
                t = r[i][k] * v[k]
                acc = t if acc is None else acc + t
        out.append(acc if acc is not None else v[0].algebra.zero)
    return out


def _cross(a: Vec3, b: Vec3) -> Vec3:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _dot(a: Vec3, b: Vec3) -> TrigPoly:
    acc = None
    for x, y in zip(a, b, strict=True):
        if x and y:
            t = x * y
            acc = t if acc is None else acc + t
    return acc if acc is not None else a[0].algebra.zero


def _add(a: Vec3, b: Vec3) -> Vec3:
    return [x + y for x, y in zip(a, b, strict=True)]


def serial_dynamics(system: System) -> SerialDynamics:
    """H, C(q, q_dot) q_dot and G of a serial chain (see :func:`is_serial_chain`), exactly.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> arm = load_system_text('''
    ... tutgen: 1
    ... title: two links
    ... parameters: [m1, m2, l1, l2, g]
    ... coordinates: [t1, t2]
    ... gravity: [0, -g, 0]
    ... bodies: {a: {mass: m1, com: [l1, 0, 0]}, b: {mass: m2, com: [l2, 0, 0]}}
    ... joints:
    ...   j1: {type: revolute, parent: ground, child: a, coordinate: t1}
    ...   j2: {type: revolute, parent: a, child: b, origin: [l1, 0, 0], coordinate: t2}
    ... ''')
    >>> serial_dynamics(arm).mass_matrix[0, 1]
    l1*l2*m2*cos(t2) + l2**2*m2
    """
    start = time.perf_counter()
    coords = [c.q for c in system.coordinates]
    rates = tuple(c.qd for c in system.coordinates)
    n = len(coords)
    index = {c.q: i for i, c in enumerate(system.coordinates)}
    by_child = {j.child: j for j in system.joints}
    revolute = [False] * n
    for j in system.joints:
        if j.coordinate is not None:
            revolute[index[j.coordinate.q]] = j.kind is JointKind.REVOLUTE
    alg = TrigAlgebra(coords, revolute, _constants(system), rates)
    const = alg.const
    zero = alg.zero

    # link-frame quantities, parents first: Jacobians of the frame origin (jv) and of the angular
    # velocity (jw), column by coordinate index; the origin's position and gravity in link axes
    gravity = list(system.gravity) if system.gravity is not None else [0, 0, 0]
    jv: dict[str, dict[int, Vec3]] = {GROUND: {}}
    jw: dict[str, dict[int, Vec3]] = {GROUND: {}}
    pos: dict[str, Vec3] = {GROUND: [zero, zero, zero]}
    grav: dict[str, Vec3] = {GROUND: [const(x) for x in gravity]}
    has_gravity = any(sp.sympify(x) != 0 for x in gravity)

    scalars = _Exactly(alg, index)

    def place(name: str) -> None:
        if name in jv:
            return
        joint = by_child[name]
        place(joint.parent)
        at = place_joint(scalars, joint)
        rt, lever = at.transpose, at.lever
        pjv, pjw = jv[joint.parent], jw[joint.parent]
        cjv: dict[int, Vec3] = {}
        cjw: dict[int, Vec3] = {}
        for col in pjw:
            cjw[col] = _apply(rt, pjw[col])
            cjv[col] = _apply(rt, _add(pjv[col], _cross(pjw[col], lever)))
        if at.motion is not None:
            assert joint.coordinate is not None
            k = index[joint.coordinate.q]
            cjw[k], cjv[k] = at.motion
        jv[name], jw[name] = cjv, cjw
        pos[name] = _apply(rt, _add(pos[joint.parent], lever))
        grav[name] = _apply(rt, grav[joint.parent]) if has_gravity else [zero, zero, zero]

    for body in system.bodies:
        place(body.name)
    t_kin = time.perf_counter()

    # H = sum over bodies: translation of each mass element + rotation about the centre of mass
    # the products of each H_ab, summed in one pass at the end (TrigPoly.sum_of_products)
    products: list[list[list[tuple[TrigPoly, TrigPoly]]]] = [[[] for _ in range(n)] for _ in range(n)]
    u = zero
    for body in system.bodies:
        bi = body_inertia(body)
        cols = sorted(jw[body.name])
        if len(bi.parts) > 1:  # part by part, as lagrange.py: the com (a quotient) never enters
            elements = [(p.mass, p.centroid) for p in bi.parts]
            inertia = sum((sp.Matrix(p.inertia_centroid) for p in bi.parts), sp.zeros(3, 3))
        else:
            elements = [(bi.mass, bi.com)]
            inertia = sp.Matrix(bi.inertia_com)
        wj = jw[body.name]
        first_moment = [zero, zero, zero]
        for mass, at in elements:
            m = alg.coefficient(mass)
            if not m:
                continue
            p = [const(x) for x in at]
            first_moment = [fm + pc.scale(m) for fm, pc in zip(first_moment, p, strict=True)]
            vc = {c: _add(jv[body.name][c], _cross(wj[c], p)) for c in cols}
            mvc = {c: [x.scale(m) for x in vc[c]] for c in cols}
            for a_i, a in enumerate(cols):
                for b in cols[a_i:]:
                    products[a][b] += [(x, y) for x, y in zip(vc[a], mvc[b], strict=True) if x and y]
            u = u - _dot(grav[body.name], pos[body.name]).scale(m)
        if inertia != sp.zeros(3, 3):
            im = [[const(inertia[r, s]) for s in range(3)] for r in range(3)]
            iw = {c: _apply(im, wj[c]) for c in cols}
            for a_i, a in enumerate(cols):
                for b in cols[a_i:]:
                    products[a][b] += [(x, y) for x, y in zip(wj[a], iw[b], strict=True) if x and y]
        if has_gravity:
            u = u - _dot(grav[body.name], first_moment)
    h = [[TrigPoly.sum_of_products(pairs) if pairs else zero for pairs in row] for row in products]
    for joint in system.joints:
        if joint.coordinate is not None and joint.reflected_inertia is not None:
            k = index[joint.coordinate.q]
            h[k][k] = h[k][k] + const(joint.reflected_inertia)
    for a in range(n):
        for b in range(a):
            h[a][b] = h[b][a]
    t_h = time.perf_counter()

    # C q_dot from the Christoffel symbols of the first kind, G = dU/dq
    dh = [[[h[i][j].diff(k) for k in range(n)] for j in range(n)] for i in range(n)]
    # (C q_dot itself is never formed as a TrigPoly: it is written from the converted symbols, and the
    # numeric checks contract the symbols' values)
    gammas: dict[tuple[int, int, int], TrigPoly] = {}  # Gamma_ijk, j <= k
    for i in range(n):
        for j in range(n):
            for k in range(j, n):
                gam = TrigPoly.combination([dh[i][j][k], dh[i][k][j]], [dh[j][k][i]], _HALF)
                if gam:
                    gammas[(i, j, k)] = gam
    g_vec = [u.diff(i) for i in range(n)]
    t_c = time.perf_counter()

    mass_matrix = sp.ImmutableMatrix(n, n, lambda i, j: h[min(i, j)][max(i, j)].to_expr())
    mass_matrix = sp.ImmutableMatrix(n, n, _mirror(mass_matrix, n))
    gravity_vector = sp.ImmutableMatrix([g.to_expr() for g in g_vec])
    u_expr = u.to_expr()
    t_out = time.perf_counter()
    timings = (
        ("kinematics", t_kin - start),
        ("mass_matrix", t_h - t_kin),
        ("coriolis_gravity", t_c - t_h),
        ("to_sympy", t_out - t_c),
        ("total", t_out - start),
    )
    exact = _Exact(alg, h, dh, gammas, g_vec, u)
    # C q_dot is converted when first read (the Christoffel symbols are most of the conversion: 2.6 of the
    # symbolic PUMA's 3.8 s), so that a worked solution that only sizes it never converts it (issue 17)
    dyn: SerialDynamics
    coriolis = LazyMatrix(n, 1, lambda: dyn.coriolis_entries(), lambda: dyn.coriolis_min_ops())
    dyn = SerialDynamics(tuple(coords), rates, mass_matrix, coriolis, gravity_vector, u_expr, timings, exact)
    return dyn


def _mirror(m: sp.MatrixBase, n: int) -> list[sp.Expr]:
    """Row-major entries with the lower triangle taken from the upper one (the same objects)."""
    return [m[min(i, j), max(i, j)] for i in range(n) for j in range(n)]


# ---------------------------------------------------------------------------------------------
# Checks and common subexpressions
# ---------------------------------------------------------------------------------------------


def skew_check(dyn: SerialDynamics) -> bool:
    """H_dot - 2 C is skew-symmetric, exactly (canonical TrigPolys: N + N^T compares with zero)."""
    ex = dyn.exact
    alg = ex.algebra
    n = len(ex.h)
    qd = [alg.rate(s) for s in dyn.rates]
    cm = _coriolis_matrix(ex)
    hdot = [[_sum([ex.dh[i][j][k].scale(qd[k]) for k in range(n)] or [alg.zero]) for j in range(n)] for i in range(n)]
    two = alg.ring.ground_new(alg.ring.domain(2))
    for i in range(n):
        for j in range(i, n):
            s = hdot[i][j] - cm[i][j].scale(two) + hdot[j][i] - cm[j][i].scale(two)
            if s:
                return False
    return True


def cse_form(dyn: SerialDynamics) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.ImmutableMatrix]]:
    """Common subexpressions of H, C q_dot and G together (``sympy.cse``): the replacements
    x_k = ..., and the three matrices written with them, for code generation or a compact listing.

    The trigonometric functions and the grouped coefficients repeat between the entries, so the
    listing shrinks (tests/engine/test_serial.py checks that it does and that it substitutes back).
    """
    exprs = [dyn.mass_matrix, dyn.coriolis_vector, dyn.gravity_vector]
    replacements, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("x"), order="none")
    return replacements, [sp.ImmutableMatrix(r) for r in reduced]


@dataclass(frozen=True)
class NumericReport:
    """What :func:`numeric_checks` found, worst over its random states."""

    agreement: float  # largest relative difference of H q_ddot + C q_dot + G from Newton-Euler's torques
    skew: float  # largest |N_ij + N_ji| / scale for N = H_dot - 2 C
    lowest_eigenvalue: float  # of H, relative to its largest
    states: int


def numeric_checks(system: System, dyn: SerialDynamics, states: int = 5, seed: int = 20261124) -> NumericReport:
    """The fast path's checks, in floats at ``states`` random states (parameters without a value in
    [0.5, 2], q in [-3, 3], rates and accelerations in [-2, 2]), evaluated on the exact polynomials:

    - H q_ddot + C q_dot + G against :func:`numeric_inverse_dynamics`, an independent recursive
      Newton-Euler pass in world axes;
    - N = H_dot - 2 C skew-symmetric, with H_dot_ij = sum_k dH_ij/dq_k q_dot_k;
    - the eigenvalues of H (positive semi-definite: T >= 0).
    """
    import numpy as np

    from tutgen.engine.trigpoly import NumericEvaluator

    rng = random.Random(seed)
    ex = dyn.exact
    n = len(dyn.coordinates)
    known = system.values
    params = [p.symbol for p in system.parameters]
    keys = list(ex.gammas)
    polys = [ex.h[i][j] for i in range(n) for j in range(n)] + ex.g + [ex.gammas[key] for key in keys]
    polys += [ex.dh[i][j][k] for i in range(n) for j in range(n) for k in range(n)]
    evaluate = NumericEvaluator(ex.algebra, polys)
    worst_agree = worst_skew = 0.0
    lowest = math.inf
    for _ in range(states):
        values: dict[sp.Symbol, float] = {s: float(known[s]) if s in known else rng.uniform(0.5, 2.0) for s in params}
        extra = {s for g in ex.algebra.gens for s in sp.sympify(g).free_symbols}
        for sym in sorted(extra - set(values) - set(dyn.coordinates) - set(dyn.rates), key=str):
            values[sym] = rng.uniform(0.5, 2.0)
        q = [rng.uniform(-3, 3) for _ in range(n)]
        qd = [rng.uniform(-2, 2) for _ in range(n)]
        qdd = [rng.uniform(-2, 2) for _ in range(n)]
        values |= dict(zip(dyn.coordinates, q, strict=True)) | dict(zip(dyn.rates, qd, strict=True))
        flat = np.array(evaluate(values))
        h = flat[: n * n].reshape(n, n)
        g = flat[n * n : n * n + n]
        gam = flat[n * n + n : n * n + n + len(keys)]
        dh = flat[n * n + n + len(keys) :].reshape(n, n, n)
        c = np.zeros(n)
        for (i, j, k), value in zip(keys, gam, strict=True):  # C_i = sum_jk Gamma_ijk q_dot_j q_dot_k
            c[i] += value * qd[j] * qd[k] * (1 if j == k else 2)
        ours = h @ np.array(qdd) + c + g
        theirs = numeric_inverse_dynamics(system, values, q, qd, qdd)
        scale = max(1.0, *(abs(x) for x in theirs))
        worst_agree = max(worst_agree, *(abs(a - b) / scale for a, b in zip(ours, theirs, strict=True)))
        v = np.array(qd)
        hdot = dh @ v
        c = 0.5 * (dh @ v + np.einsum("ikj,k->ij", dh, v) - np.einsum("jki,k->ij", dh, v))
        skew = hdot - 2 * c
        worst_skew = max(worst_skew, float(np.max(np.abs(skew + skew.T))) / max(1.0, float(np.max(np.abs(hdot)))))
        eig = np.linalg.eigvalsh((h + h.T) / 2)
        lowest = min(lowest, float(eig[0]) / max(1.0, float(np.max(np.abs(eig)))))
    return NumericReport(float(worst_agree), float(worst_skew), float(lowest), states)


# ---------------------------------------------------------------------------------------------
# The route of derive() for large serial arms (tutgen/engine/pipeline.py assembles it)
# ---------------------------------------------------------------------------------------------

#: Serial chains with at least this many coordinates take the fast path in ``derive``: below it the
#: general route is quick (a 3-DOF arm derives in seconds) and shows Lagrange's equations term by term,
#: which a worked solution of a small arm wants; from four on those expansions run to pages and the
#: general route's tidying grows too fast (minutes at six).
LARGE = 4

REMARK_FAST_PATH = (
    "This arm is a serial chain with {n} coordinates, so H, C and G were derived by the route for serial arms: "
    "velocity Jacobians in each link's own axes, exact trigonometric polynomials, and C from the Christoffel "
    "symbols of H. Lagrange's equations term by term, each body's kinematics and energies, and the Newton-Euler "
    "derivation are omitted: they would run to pages. The result is checked numerically against an independent "
    "recursive Newton-Euler computation."
)


def is_large_serial_chain(system: System) -> bool:
    """The rule of ``derive``'s fast path: a serial chain (:func:`is_serial_chain`) with at least
    ``LARGE`` coordinates."""
    return len(system.coordinates) >= LARGE and is_serial_chain(system)


#: a relative difference below this is floating-point round-off (double precision: about 1e-16 per
#: operation); it is reported as "below 1e-12", not as the noise figure itself (3.0e-16 one run, 2.9e-16 on
#: another machine's BLAS)
ROUND_OFF = 1e-12


def _difference(x: float) -> str:
    return f"below {ROUND_OFF:.0e}" if x < ROUND_OFF else f"{x:.1e}"


def serial_checks(system: System, dyn: SerialDynamics) -> list[Check]:
    """The fast route's checks as :class:`Check` values (:func:`numeric_checks`), and H = H^T; a failed one
    raises :class:`~tutgen.errors.DerivationError`: a negative mass or inertia given in the spec, or else
    a tutgen bug."""
    report = numeric_checks(system, dyn)
    h = dyn.mass_matrix
    checks = [
        Check(
            "matrix_form_equals_newton_euler",
            report.agreement < 1e-8,
            f"H q_ddot + C + G equals a numeric recursive Newton-Euler pass at {report.states} random states "
            f"(largest relative difference {_difference(report.agreement)})",
        ),
        Check("skew_symmetry", report.skew < 1e-8, f"H_dot - 2 C is skew-symmetric at {report.states} random states"),
        Check("symmetric_mass_matrix", h == h.T, "H = H^T"),
        Check(
            "positive_semidefinite_mass_matrix",
            report.lowest_eigenvalue > -1e-12,
            f"H is positive {'definite' if report.lowest_eigenvalue > 1e-12 else 'semi-definite'} "
            f"at {report.states} random states",
        ),
    ]
    for check in checks:
        if not check.passed:
            negative = [p for p in system.parameters if p.value is not None and p.value.is_negative]
            if check.name == "positive_semidefinite_mass_matrix" and negative:
                given = ", ".join(f"{p.name} = {sp.sstr(p.value)}" for p in negative)
                raise DerivationError(
                    "the mass matrix H has a negative eigenvalue: the kinetic energy could be negative; a mass "
                    f"or inertia must not be negative (given: {given})",
                    negative[0].origin,
                )
            raise DerivationError(
                f"internal check failed: {check.name} ({check.detail}); please report this spec as a tutgen bug",
                system.origin,
            )
    return checks
