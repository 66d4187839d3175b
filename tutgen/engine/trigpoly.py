"""An exact, canonical algebra of trigonometric polynomials, for the dynamics of serial arms.

A :class:`TrigPoly` is a real expression

    f = sum over k of  a_k cos(k . theta) + b_k sin(k . theta)

where theta are the revolute coordinates, k an integer frequency vector and a_k, b_k polynomials
(sympy's sparse ``PolyElement`` over QQ) in everything else: parameters, prismatic coordinates and
rates. Each frequency is stored once, with its first nonzero component positive (cos(-x) = cos x,
sin(-x) = -sin x), so the representation is canonical: two TrigPolys are equal exactly when their
dicts are equal, and sin^2 + cos^2 = 1 holds by construction, never by ``simplify``.

Why Fourier terms rather than monomials in cos(theta_j), sin(theta_j): for a chain of parallel axes
the monomial form of cos(theta_2 + ... + theta_n) has 2^(n-2) terms while the Fourier form has one,
so cost stays polynomial in n, and converting back gives cos(theta_2 + theta_3), cos(2 theta_2): the
compact form ``trigsimp`` would find. Products turn into sums (cos A cos B = (cos(A-B) + cos(A+B))/2),
derivatives are exact (d/dtheta_j cos(k.theta) = -k_j sin(k.theta)).

Examples
========
>>> import sympy as sp
>>> t1, t2, m = sp.symbols("t1 t2 m")
>>> alg = TrigAlgebra([t1, t2], [True, True], [m])
>>> c1, s1 = alg.cos(0), alg.sin(0)
>>> (c1 * c1 + s1 * s1) == alg.one
True
>>> (alg.const(m) * alg.cos(0) * alg.cos(1) - alg.const(m) * alg.sin(0) * alg.sin(1)).to_expr()
m*cos(t1 + t2)
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import sympy as sp
from sympy import QQ
from sympy.core.add import Add, _addsort
from sympy.core.mul import Mul, _mulsort
from sympy.polys.polyutils import parallel_dict_from_expr
from sympy.polys.rings import PolyElement, PolyRing

__all__ = ["NumericEvaluator", "TrigAlgebra", "TrigPoly", "monomial_times_sum"]

Freq = tuple[int, ...]
Key = tuple[Freq, int]  # (k, 0) is cos(k . theta), (k, 1) is sin(k . theta)
_HALF = QQ(1, 2)


def _canonical(k: Freq, kind: int) -> tuple[Freq, int, int]:
    """(k', kind, sign) with k' = +-k whose first nonzero entry is positive; sign 0 for sin(0)."""
    for v in k:
        if v > 0:
            return k, kind, 1
        if v < 0:
            return tuple(-x for x in k), kind, (-1 if kind else 1)
    return k, kind, (0 if kind else 1)


class TrigAlgebra:
    """The coordinates, which of them are angles, and the ring of the coefficients.

    ``constants`` are every expression that will enter as a coefficient (masses, lengths, inertias,
    entries of fixed rotations): they fix the ring's generators in one pass, so that a non-polynomial
    piece such as ``sqrt(2)``, ``pi`` or ``1/l`` becomes a generator of its own.
    """

    def __init__(
        self,
        coordinates: Sequence[sp.Symbol],
        revolute: Sequence[bool],
        constants: Iterable[sp.Expr],
        rates: Sequence[sp.Symbol] = (),
    ) -> None:
        self.coordinates = tuple(coordinates)
        self.revolute = tuple(revolute)
        self.rates = tuple(rates)
        self.n = len(self.coordinates)
        values = [sp.sympify(c) for c in constants]
        prismatic = [q for q, r in zip(self.coordinates, self.revolute, strict=True) if not r]
        seeds = [*values, *prismatic, *rates]
        dicts, gens = parallel_dict_from_expr(seeds) if seeds else ([], ())
        # generators that are not symbols (sqrt(2), 1/l, cos(alpha)) stand in the ring as dummies
        self.gens: tuple[sp.Expr, ...] = tuple(gens)
        ring_symbols = [g if isinstance(g, sp.Symbol) else sp.Dummy(f"g{i}") for i, g in enumerate(self.gens)]
        self.ring = PolyRing(ring_symbols or [sp.Dummy("unit")], QQ)
        self._cache: dict[sp.Expr, PolyElement] = {}
        for expr, d in zip(seeds, dicts, strict=True):
            if not self.gens:
                self._cache[expr] = self.ring.ground_new(QQ.from_sympy(sp.sympify(d.get((), 0))))
            else:
                self._cache[expr] = self.ring.from_dict({m: QQ.from_sympy(c) for m, c in d.items()})
        self.zero_k: Freq = (0,) * self.n
        self.one = TrigPoly(self, {(self.zero_k, 0): self.ring.one})
        self.zero = TrigPoly(self, {})
        self._gen_index = {g: i for i, g in enumerate(self.gens)}
        self._trig_cache: dict[Key, tuple[int, sp.Expr]] = {}
        self._angle_cache: dict[Freq, tuple[sp.Expr, bool]] = {}

    # -- building ---------------------------------------------------------------------------------
    def coefficient(self, expr: sp.Expr | int) -> PolyElement:
        """A constant (or polynomial in prismatic coordinates and rates) as a ring element."""
        expr = sp.sympify(expr)
        if expr.is_Rational:
            return self.ring.ground_new(QQ(int(expr.p), int(expr.q)))
        hit = self._cache.get(expr)
        if hit is None:
            (d,), _ = parallel_dict_from_expr([expr], gens=self.gens)
            hit = self.ring.from_dict({m: QQ.from_sympy(c) for m, c in d.items()})
            self._cache[expr] = hit
        return hit

    def const(self, expr: sp.Expr | int) -> TrigPoly:
        c = self.coefficient(expr)
        return TrigPoly(self, {(self.zero_k, 0): c} if c else {})

    def _unit(self, j: int) -> Freq:
        return tuple(1 if i == j else 0 for i in range(self.n))

    def cos(self, j: int) -> TrigPoly:
        """cos(theta_j) of the j-th coordinate (an angle)."""
        return TrigPoly(self, {(self._unit(j), 0): self.ring.one})

    def sin(self, j: int) -> TrigPoly:
        return TrigPoly(self, {(self._unit(j), 1): self.ring.one})

    def rate(self, symbol: sp.Symbol) -> PolyElement:
        return self.coefficient(symbol)

    # -- back to sympy ----------------------------------------------------------------------------
    def _trig(self, key: Key) -> tuple[int, sp.Expr]:
        """(sign, f) with sign * f = cos/sin(k . theta), f as sympy writes it: sympy turns sin(-x) into
        -sin(x) by its own rule for which sign an argument shows, so the sign is folded into the
        coefficient rather than left as a factor -1 inside a product."""
        hit = self._trig_cache.get(key)
        if hit is None:
            k, kind = key
            turned = self._angle_cache.get(k)  # the angle, and whether sympy shows it negated, once per k
            if turned is None:
                angle = sp.Add(*[v * q for v, q in zip(k, self.coordinates, strict=True) if v])
                turned = (-angle, True) if angle.could_extract_minus_sign() else (angle, False)
                self._angle_cache[k] = turned
            angle, negated = turned
            sign = -1 if negated and kind else 1
            # unevaluated: sympy's cos/sin would return the same object after trying every rule on an
            # argument that is a sum of coordinates with integer factors and no sign to pull out, which was
            # most of converting a 6-DOF arm's H (tests/engine/test_serial.py compares with the evaluated)
            hit = (sign, sp.sin(angle, evaluate=False) if kind else sp.cos(angle, evaluate=False))
            self._trig_cache[key] = hit
        return hit

    def coefficient_expr(self, p: PolyElement) -> sp.Expr:
        """A coefficient polynomial as a sympy expression, grouped by a greedy multivariate Horner
        scheme (common factors pulled out), which keeps count_ops low without any factorization."""
        return _grouped([(m, c) for m, c in p.items()], self.gens)


class NumericEvaluator:
    """Many TrigPolys compiled for evaluation in floats at many states (numpy, one pass per state).

    Evaluating the exact polynomials directly is what makes the checks of a 6-DOF arm cheap: no
    sympy expression is printed or compiled (``lambdify`` of a fully symbolic H alone takes seconds).
    """

    def __init__(self, algebra: TrigAlgebra, polys: Sequence[TrigPoly]) -> None:
        import numpy as np

        self.algebra = algebra
        self.count = len(polys)
        # the monomials are stored once each, sparsely (a 6-DOF arm's ~200 000 terms share a few
        # thousand monomials of ~70 generators, each with a handful of factors): per distinct monomial
        # its factors (generator, exponent), flat, and where its run starts
        unique: dict[tuple[int, ...], int] = {}
        which: list[int] = []
        coeffs: list[float] = []
        groups: list[int] = []  # terms per (polynomial, frequency): its owner and frequency repeated
        owners: list[int] = []
        freqs: list[tuple[int, ...]] = []
        kinds: list[int] = []
        for index, p in enumerate(polys):
            for (k, kind), c in p.terms.items():
                which += [unique.setdefault(m, len(unique)) for m in c.keys()]
                coeffs += [float(v) for v in c.values()]
                groups.append(len(c))
                owners.append(index)
                freqs.append(k)
                kinds.append(kind)
        factor_gen: list[int] = []
        factor_exp: list[int] = []
        starts: list[int] = []
        for m in unique:
            starts.append(len(factor_gen))
            for g, e in enumerate(m):
                if e:
                    factor_gen.append(g)
                    factor_exp.append(e)
            if len(factor_gen) == starts[-1]:  # the monomial 1: one factor 1 (generator -1 reads 1.0)
                factor_gen.append(-1)
                factor_exp.append(1)
        self.factor_gen = np.array(factor_gen, dtype=int)
        self.factor_exp = np.array(factor_exp, dtype=float)
        self.starts = np.array(starts, dtype=int)
        self.which = np.array(which, dtype=int)
        self.coeffs = np.array(coeffs, dtype=float)
        counts = np.array(groups, dtype=int)
        self.owner = np.repeat(np.array(owners, dtype=int), counts)
        self.group = np.repeat(np.arange(len(groups)), counts)
        self.freqs = np.array(freqs, dtype=float).reshape(len(freqs), algebra.n)
        self.is_sin = np.array(kinds, dtype=bool)

    def __call__(self, values: dict[sp.Symbol, float]) -> list[float]:
        """The values of the polynomials at a state (coordinates, rates and parameters by symbol)."""
        import numpy as np

        alg = self.algebra
        floats = {s: sp.Float(v) for s, v in values.items()}
        gens = np.array([float(sp.sympify(g).xreplace(floats)) for g in alg.gens] + [1.0])  # [-1] is 1.0
        angles = np.array([float(values[q]) if r else 0.0 for q, r in zip(alg.coordinates, alg.revolute, strict=True)])
        phase = self.freqs @ angles
        trig = np.where(self.is_sin, np.sin(phase), np.cos(phase))
        out = np.zeros(self.count)
        if not len(self.which):
            return [float(x) for x in out]
        distinct = np.multiply.reduceat(gens[self.factor_gen] ** self.factor_exp, self.starts)
        np.add.at(out, self.owner, self.coeffs * distinct[self.which] * trig[self.group])
        return [float(x) for x in out]


class TrigPoly:
    """A trigonometric polynomial; see the module docstring. Immutable by convention."""

    __slots__ = ("algebra", "terms")

    def __init__(self, algebra: TrigAlgebra, terms: dict[Key, PolyElement]) -> None:
        self.algebra = algebra
        self.terms = terms

    # -- arithmetic ------------------------------------------------------------------------------
    def __add__(self, other: TrigPoly) -> TrigPoly:
        out = dict(self.terms)
        for key, c in other.terms.items():
            s = out.get(key)
            if s is None:
                out[key] = c
            else:
                s = s + c
                if s:
                    out[key] = s
                else:
                    del out[key]
        return TrigPoly(self.algebra, out)

    def __neg__(self) -> TrigPoly:
        return TrigPoly(self.algebra, {k: -c for k, c in self.terms.items()})

    def __sub__(self, other: TrigPoly) -> TrigPoly:
        return self + (-other)

    @staticmethod
    def combination(plus: Sequence[TrigPoly], minus: Sequence[TrigPoly], factor: object) -> TrigPoly:
        """(sum of ``plus`` - sum of ``minus``) times a nonzero rational ``factor``, in one pass: no
        intermediate sums or negations, and the factor applied once per frequency by a number, not by a
        product of polynomials (a 6-DOF arm's Christoffel symbols, issue 17). ``plus`` is not empty."""
        out: dict[Key, PolyElement] = {}
        for p in plus:
            for key, c in p.terms.items():
                s = out.get(key)
                out[key] = c if s is None else s + c
        for p in minus:
            for key, c in p.terms.items():
                s = out.get(key)
                out[key] = -c if s is None else s - c
        return TrigPoly(plus[0].algebra, {k: v.mul_ground(factor) for k, v in out.items() if v})

    def scale(self, c: PolyElement) -> TrigPoly:
        """Multiplied by a coefficient (a polynomial without angles)."""
        if not c:
            return self.algebra.zero
        if c.is_ground:  # a number: each coefficient times it, without a product of polynomials
            return self.times(c.LC)
        out = {}
        for k, v in self.terms.items():
            p = v * c
            if p:
                out[k] = p
        return TrigPoly(self.algebra, out)

    def times(self, q: object) -> TrigPoly:
        """Multiplied by a nonzero rational number (an element of QQ)."""
        return TrigPoly(self.algebra, {k: v.mul_ground(q) for k, v in self.terms.items()})

    def __mul__(self, other: TrigPoly) -> TrigPoly:
        return TrigPoly.sum_of_products([(self, other)])

    @staticmethod
    def sum_of_products(pairs: Sequence[tuple[TrigPoly, TrigPoly]]) -> TrigPoly:
        """The sum of x * y over the ``pairs`` (not empty), in one pass: the coefficients are summed as
        plain dicts (monomial -> number) per frequency and made polynomials once at the end, and the
        products of two trigonometric factors are halved once per frequency, not each on its own (issue 17:
        adding each product to a polynomial copied the growing sum every time; the symbolic PUMA's H is
        a third of its derivation)."""
        alg = pairs[0][0].algebra
        ring = alg.ring
        zero = alg.zero_k
        nothing = ring.domain.zero
        monomial_mul = ring.monomial_mul
        whole: dict[Key, dict[tuple[int, ...], object]] = {}
        halves: dict[Key, dict[tuple[int, ...], object]] = {}

        def add(into: dict[Key, dict[tuple[int, ...], object]], key: Key, terms: list, negative: bool) -> None:
            d = into.get(key)
            if d is None:
                d = into[key] = {}
            get = d.get
            if negative:
                for m, v in terms:
                    d[m] = get(m, nothing) - v
            else:
                for m, v in terms:
                    d[m] = get(m, nothing) + v

        for x, y in pairs:
            y_terms = [(key, list(c.items())) for key, c in y.terms.items()]
            for (ka, fa), ca in x.terms.items():
                a_const = ka == zero
                a_items = list(ca.items())
                for (kb, fb), b_items in y_terms:
                    c = [(monomial_mul(m1, m2), v1 * v2) for m1, v1 in a_items for m2, v2 in b_items]
                    if a_const:
                        add(whole, (kb, fb), c, False)
                        continue
                    if kb == zero:
                        add(whole, (ka, fa), c, False)
                        continue
                    ks = tuple([p + q for p, q in zip(ka, kb, strict=True)])  # canonical: both were
                    kd, _, sign = _canonical(tuple([p - q for p, q in zip(ka, kb, strict=True)]), 1)
                    if fa == 0 and fb == 0:  # cos a cos b = (cos(a-b) + cos(a+b)) / 2
                        add(halves, (kd, 0), c, False)
                        add(halves, (ks, 0), c, False)
                    elif fa == 1 and fb == 1:  # sin a sin b = (cos(a-b) - cos(a+b)) / 2
                        add(halves, (kd, 0), c, False)
                        add(halves, (ks, 0), c, True)
                    else:  # sin a cos b = (sin(a+b) + sin(a-b)) / 2;  cos a sin b = (sin(a+b) - sin(a-b)) / 2
                        add(halves, (ks, 1), c, False)
                        if kd != zero:
                            add(halves, (kd, 1), c, (fa == 1) != (sign > 0))
        for key, d in halves.items():
            add(whole, key, [(m, v * _HALF) for m, v in d.items() if v], False)
        new = ring.zero.new
        out: dict[Key, PolyElement] = {}
        for key, d in whole.items():
            poly = new({m: v for m, v in d.items() if v})
            if poly:
                out[key] = poly
        return TrigPoly(alg, out)

    def diff(self, j: int) -> TrigPoly:
        """d/dq_j: exact, by the frequency (an angle) or coefficient by coefficient (any other)."""
        alg = self.algebra
        out: dict[Key, PolyElement] = {}
        if alg.revolute[j]:
            for (k, kind), c in self.terms.items():
                if k[j]:
                    # d cos(k.t) = -k_j sin(k.t);  d sin(k.t) = k_j cos(k.t)
                    out[(k, 1 - kind)] = c.mul_ground(QQ(-k[j] if kind == 0 else k[j]))
            return TrigPoly(alg, out)
        x = alg.ring.gens[alg._gen_index[alg.coordinates[j]]]
        for key, c in self.terms.items():
            d = c.diff(x)
            if d:
                out[key] = d
        return TrigPoly(alg, out)

    # -- comparison and output ---------------------------------------------------------------------
    def __eq__(self, other: object) -> bool:
        return isinstance(other, TrigPoly) and self.terms == other.terms

    def __hash__(self) -> int:  # pragma: no cover - mutable-looking values are not hashed
        return hash(frozenset(self.terms))

    def is_zero(self) -> bool:
        return not self.terms

    def __bool__(self) -> bool:
        return bool(self.terms)

    def __repr__(self) -> str:
        return f"TrigPoly({self.to_expr()})"

    def size(self) -> int:
        """Number of (frequency, monomial) terms: the work a product costs."""
        return sum(len(c) for c in self.terms.values())

    def min_ops(self) -> int:
        """A lower bound of ``sympy.count_ops(self.to_expr())``, without converting (issue 17): the s terms
        are a sum of at least s - 1 additions (grouping pulls out factors but never merges two terms), and
        each frequency k other than 0 is a cos or sin (one operation) of an argument with one term per
        nonzero k_j (one addition fewer). count_ops counts a repeated subexpression each time it occurs."""
        trig = sum(sum(1 for v in key[0] if v) for key in self.terms if key[0] != self.algebra.zero_k)
        return max(self.size() - 1, 0) + trig

    def to_expr(self, outer: Sequence[sp.Symbol] = ()) -> sp.Expr:
        """The sympy expression: one grouped coefficient per cos/sin, the constant term first.

        With ``outer`` (e.g. the rates), terms are first collected by monomials in those symbols,
        each carrying its own trigonometric polynomial: C q_dot reads as sum of q_dot_j q_dot_k (...).
        """
        alg = self.algebra
        if outer:
            where = [alg._gen_index[s] for s in outer if s in alg._gen_index]
            split: dict[tuple[int, ...], dict[Key, list[tuple[tuple[int, ...], object]]]] = {}
            for key, c in self.terms.items():
                for m, v in c.items():
                    om = tuple(m[i] for i in where)
                    inner = list(m)
                    for i in where:
                        inner[i] = 0
                    split.setdefault(om, {}).setdefault(key, []).append((tuple(inner), v))
            parts = []
            for om in sorted(split, reverse=True):
                fourier = _fourier(alg, split[om])
                for i, e in zip(where, om, strict=True):
                    for _ in range(e):
                        fourier = _times(fourier, alg.gens[i])
                parts.append(fourier)
            return _fast_add(parts)
        return _fourier(alg, {key: list(c.items()) for key, c in self.terms.items()})


def _fourier(alg: TrigAlgebra, terms: dict[Key, list[tuple[tuple[int, ...], object]]]) -> sp.Expr:
    """sum over frequencies of grouped coefficient x cos/sin, the constant term first."""
    parts = []
    for key, monomials in terms.items():
        if key[0] == alg.zero_k:
            parts.append(_grouped(monomials, alg.gens))
            continue
        sign, trig = alg._trig(key)
        coeff = _grouped(monomials if sign > 0 else [(m, -c) for m, c in monomials], alg.gens)  # type: ignore[operator]
        parts.append(_times(coeff, trig))
    return _fast_add(parts)


def _grouped(terms: list[tuple[tuple[int, ...], object]], gens: Sequence[sp.Expr]) -> sp.Expr:
    """sum c_m x^m, grouped: common content and monomial pulled out, then split on the generator that
    occurs in the most terms (x (..) + rest), recursively. Linear in the number of terms per level."""
    sparse = [({i: e for i, e in enumerate(m) if e}, c) for m, c in terms]
    return _grouped_sparse(sparse, gens)


def _grouped_sparse(terms: list[tuple[dict[int, int], object]], gens: Sequence[sp.Expr]) -> sp.Expr:
    if not terms:
        return sp.Integer(0)
    if len(terms) == 1:
        m, c = terms[0]
        return _fast_mul(_rational(c), _powers(m, gens))
    counts: dict[int, int] = {}
    for m, _ in terms:
        for i in m:
            counts[i] = counts.get(i, 0) + 1
    everywhere = {i: min(m[i] for m, _ in terms) for i, k in counts.items() if k == len(terms)}
    content = _content([c for _, c in terms])
    if everywhere or content != 1:
        inner = [
            ({i: e - everywhere.get(i, 0) for i, e in m.items() if e != everywhere.get(i, 0)}, c / content)
            for m, c in terms
        ]
        return _fast_mul(_rational(content), [*_powers(everywhere, gens), _grouped_sparse(inner, gens)])
    best = max(counts, key=lambda i: (counts[i], -i), default=None)
    if best is None or counts[best] < 2:
        return _fast_add([_fast_mul(_rational(c), _powers(m, gens)) for m, c in terms])
    with_x = []
    rest = []
    for m, c in terms:
        if best in m:
            d = dict(m)
            if d[best] == 1:
                del d[best]
            else:
                d[best] -= 1
            with_x.append((d, c))
        else:
            rest.append((m, c))
    x_part = _times(_grouped_sparse(with_x, gens), gens[best])
    return _fast_add([x_part, _grouped_sparse(rest, gens)])


# -- building sympy expressions without sympy's flatten -----------------------------------------------
# Add and Mul normally re-sort and re-collect their arguments on every construction, which is most of
# the cost of printing a 6-DOF arm's C q_dot (tens of thousands of terms). The sums and products built
# here are already collected (distinct monomials, distinct bases), so they are assembled from sorted
# arguments directly: the objects are the ones Add(*args) / Mul(*args) would give. They are commutative
# (every generator is a parameter, a coordinate, a rate or a number, and cos/sin of coordinates), which
# is passed rather than asked of every argument (issue 17).


def _fast_add(terms: Sequence[sp.Expr]) -> sp.Expr:
    """Add(*terms) for terms no two of which are alike (true of distinct monomials and frequencies)."""
    args: list[sp.Expr] = []
    number: sp.Expr = sp.Integer(0)
    for t in terms:
        for a in t.args if t.is_Add else (t,):
            if a.is_Number:
                number = number + a
            else:
                args.append(a)
    if not args:
        return number
    if number == 0 and len(args) == 1:
        return args[0]
    _addsort(args)
    if number != 0:
        args.insert(0, number)
    return Add._from_args(args, True)


def _fast_mul(coeff: sp.Rational, factors: Sequence[sp.Expr]) -> sp.Expr:
    """coeff * prod(factors) for factors that are not numbers or products and have distinct bases;
    a number times one sum stays unexpanded, as sympy's own ``_keep_coeff`` keeps it."""
    if not factors:
        return coeff
    if len(factors) == 1 and (coeff == 1 or factors[0].is_Add):
        return factors[0] if coeff == 1 else Mul._from_args((coeff, factors[0]), True)
    args = list(factors)
    _mulsort(args)
    if coeff != 1:
        args.insert(0, coeff)
    return Mul._from_args(args, True)


def _times(expr: sp.Expr, factor: sp.Expr) -> sp.Expr:
    """expr * factor, for a factor that is a symbol, a power or a function; powers of the same base
    are merged (x * x y = x**2 y)."""
    if expr.is_Number:
        return _fast_mul(expr, [factor])  # type: ignore[arg-type]
    coeff, parts = (
        (expr.args[0], list(expr.args[1:]))
        if expr.is_Mul and expr.args[0].is_Number
        else (
            sp.Integer(1),
            list(expr.args) if expr.is_Mul else [expr],
        )
    )
    base, exp = factor.as_base_exp()
    for i, p in enumerate(parts):
        b, e = p.as_base_exp()
        if b == base and not p.is_Add:
            parts[i] = sp.Pow(base, e + exp)
            return _fast_mul(coeff, parts)  # type: ignore[arg-type]
    return _fast_mul(coeff, [*parts, factor])  # type: ignore[arg-type]


def monomial_times_sum(terms: Sequence[tuple[sp.Expr, int, Sequence[sp.Symbol]]]) -> sp.Expr:
    """sum of c * expr * prod(symbols) over (expr, c, symbols), assembled like the rest of this module's
    output (canonical sympy objects, no flatten): how C q_dot and C are written from the Christoffel
    symbols, sum Gamma_ijk q_dot_j q_dot_k, once each symbol has been converted."""
    parts = []
    for expr, c, symbols in terms:
        e = _scaled(expr, c)
        for s in symbols:
            e = _times(e, s)
        parts.append(e)
    return _fast_add(parts) if parts else sp.Integer(0)


def _scaled(expr: sp.Expr, c: int) -> sp.Expr:
    """c * expr, the number merged into a product's coefficient; a sum stays a sum times c."""
    if c == 1:
        return expr
    if expr.is_Number:
        return expr * c
    if expr.is_Mul:
        coeff, rest = (
            (expr.args[0], list(expr.args[1:])) if expr.args[0].is_Number else (sp.Integer(1), list(expr.args))
        )
        return _fast_mul(coeff * c, rest)
    return _fast_mul(sp.Integer(c), [expr])


def _powers(m: dict[int, int], gens: Sequence[sp.Expr]) -> list[sp.Expr]:
    return [gens[i] if e == 1 else sp.Pow(gens[i], e) for i, e in sorted(m.items())]


def _rational(c: object) -> sp.Rational:
    return sp.Rational(int(c.numerator), int(c.denominator))  # type: ignore[attr-defined]


def _content(coeffs: list[object]) -> object:
    """gcd of numerators over lcm of denominators, positive; 1 if the signs are mixed or all negative
    would flip the sign of a sum a reader expects to read as written."""
    from math import gcd, lcm

    num = 0
    den = 1
    for c in coeffs:
        num = gcd(num, int(c.numerator))  # type: ignore[attr-defined]
        den = lcm(den, int(c.denominator))  # type: ignore[attr-defined]
    return QQ(num, den)
