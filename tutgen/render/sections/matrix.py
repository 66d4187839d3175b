"""The matrix form H(q) q_ddot + C(q, q_dot) + G(q) = Q, written out, entry by entry or as the program
of a serial arm, and the Christoffel symbols."""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.engine.steps import Step, StepKind
from tutgen.model.system import ChristoffelConvention, System
from tutgen.render import blocks as budgets  # PRINT_BUDGET, PROGRAM_BUDGET read when a section is built
from tutgen.render.blocks import (
    Block,
    SolutionContext,
    display,
    long_decimals,
    ops,
    para,
    prose,
    said,
    section,
    stacked,
)
from tutgen.render.layout import LINE_WIDTH_PT, tex_width
from tutgen.render.order import expanded_form
from tutgen.render.printer import TexPrinter
from tutgen.render.size import nonzero_count
from tutgen.spec.units import DIMENSIONS, Dimension

ENERGY, TIME = DIMENSIONS["energy"], DIMENSIONS["time"]


def matrix_form(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    if d.mass_matrix is None or not d.has_step(StepKind.MASS_MATRIX):
        return None
    with_c_g = d.has_step(StepKind.MATRIX_FORM)
    sec = section(
        "Matrix form",
        "$H(q)\\ddot q + C(q,\\dot q) + G(q) = Q$, with $H$ read off "
        "$T = \\tfrac12 \\dot q^T H \\dot q$ and $G = \\partial U/\\partial q$.",
    )
    size = ops(d.mass_matrix, d.coriolis_vector, d.gravity_vector)
    if size > budgets.PROGRAM_BUDGET and d.program is not None and not s.springs:
        sec["blocks"] += program_blocks(d, tex, num, size, with_c_g)
    elif size > budgets.PRINT_BUDGET:
        sec["blocks"] += entry_by_entry(d, tex, num, with_c_g)
    else:
        sec["blocks"] += read_off(d, tex, num)
        h = num(d.mass_matrix)
        sec["blocks"].append(display(f"H = {tex(h)}{tex.unit(h, shared(inertia_dimensions(s)))}"))
    if with_c_g and size <= budgets.PRINT_BUDGET:
        forces, torque = force_dimensions(s)
        c_vec, g_vec, q_vec = (num(v) for v in (d.coriolis_vector, d.gravity_vector, d.generalized_forces))
        unit = shared(forces)
        shown = [f"{n} = {tex(v)}{tex.unit(v, unit, torque)}" for n, v in (("C", c_vec), ("G", g_vec), ("Q", q_vec))]
        sec["blocks"].append(display(",\\quad ".join(shown)))
        sec["blocks"] += assembled(c) + coriolis_matrix_blocks(c)
    if size <= budgets.PRINT_BUDGET:
        sec["blocks"] += determinant_blocks(c)
    return sec


def _step(d: Derivation, kind: StepKind) -> Step | None:
    return next((st for st in d.steps if st.kind is kind), None)


def read_off(d: Derivation, tex: TexPrinter, num: Any) -> list[Block]:
    """T = 1/2 q_dot^T H q_dot written out term by term, and each H_ij read off the coefficient of
    q_dot_i q_dot_j in T (the mass-matrix step's equations), as the tutorial's problem 10 does."""
    step = _step(d, StepKind.MASS_MATRIX)
    entries = [e for e in step.equations if isinstance(e.lhs, sp.Indexed)] if step is not None else []
    if not entries:
        return []
    rates = [tex(q.qd) for q in d.system.coordinates]
    terms = []
    for e in entries:
        i, j = (int(x) - 1 for x in e.lhs.indices)
        if i == j:
            terms.append(f"\\tfrac12 H_{{{i + 1}{i + 1}}}{rates[i]}^2")
        else:
            terms.append(f"H_{{{i + 1}{j + 1}}}{rates[i]}{rates[j]}")
    lines = []
    for e in entries:
        i, j = (int(x) - 1 for x in e.lhs.indices)
        name = f"H_{{{i + 1}{j + 1}}}" + (f" = H_{{{j + 1}{i + 1}}}" if i != j else "")
        lines.append(f"{name} = {tex(num(e.rhs))}")
    return [
        para(
            prose(
                "Compare $T = \\tfrac12\\dot q^T H\\dot q = " + " + ".join(terms) + "$ with $T$ term by term: "
                "$H_{ii}$ is twice the coefficient of $\\dot q_i^2$, and $H_{ij}$ ($i \\ne j$) the coefficient "
                "of $\\dot q_i \\dot q_j$:"
            )
        ),
        display(",\\quad ".join(lines)),
    ]


def _partial(a: int, b: int, k: int, d: Derivation) -> str:
    """dH_ab/dq_k, 0-based, with H's symmetry written out as H_ab (a <= b)."""
    a, b = min(a, b), max(a, b)
    return f"\\frac{{\\partial H_{{{a + 1}{b + 1}}}}}{{\\partial {d.system.coordinates[k].latex}}}"


def inertia_dimensions(s: System) -> list[list[Dimension | None]]:
    """The dimension of each H_ij: an energy over the dimensions of the rates q̇_i q̇_j (kg m² between
    two angles, kg between two lengths, kg m between one of each); None where a coordinate's is unknown."""
    rates = [q.si_dimension / TIME if q.si_dimension is not None else None for q in s.coordinates]
    return [[ENERGY / (ri * rj) if ri is not None and rj is not None else None for rj in rates] for ri in rates]


def force_dimensions(s: System) -> tuple[list[Dimension | None], bool]:
    """The dimension of each C_i, G_i, Q_i (an energy over the coordinate's: N m for an angle, N for a
    length), and whether they are all torques (printed N m rather than J)."""
    dims = [ENERGY / q.si_dimension if q.si_dimension is not None else None for q in s.coordinates]
    return dims, all(q.si_dimension is not None and q.si_dimension.is_dimensionless for q in s.coordinates)


def shared(dims: list[Any]) -> Dimension | None:
    """The one dimension of all the entries of a matrix (nested lists flattened), or None."""
    flat = [x for row in dims for x in (row if isinstance(row, list) else [row])]
    return flat[0] if flat and all(x is not None and x == flat[0] for x in flat) else None


#: the assembled H q_ddot + C + G = Q and det H are printed only for results this short (operations)
ASSEMBLED_BUDGET = 400


def assembled(c: SolutionContext) -> list[Block]:
    """The matrix form with the matrices written out once, ``[H][q̈] + [C] + [G] = [Q]`` (as tutorial
    problem 9 prints it), when it fits on one line; it is not broken across lines (the entries above are)."""
    d, tex, num = c.d, c.tex, c.num
    if ops(d.mass_matrix, d.coriolis_vector, d.gravity_vector) > ASSEMBLED_BUDGET:
        return []
    qdd = sp.ImmutableMatrix([q.qdd for q in c.s.coordinates])
    parts = [f"{tex(num(d.mass_matrix))} {tex(qdd)}"]
    parts += [tex(num(v)) for v in (d.coriolis_vector, d.gravity_vector) if any(e != 0 for e in v)]
    line = " + ".join(parts) + f" = {tex(num(d.generalized_forces))}"
    if tex_width(line) > LINE_WIDTH_PT:
        return []
    return [para(prose("Assembled:")), display(line)]


def coriolis_matrix_blocks(c: SolutionContext) -> list[Block]:
    """``C = C'(q, q̇) q̇``: the matrix with ``C'_{ij} = Σ_k c_{ijk} q̇_k`` (the symmetric symbols), the one
    tutorial problem 7 prints, for which ``Ḣ - 2C'`` is skew-symmetric; the form ``H q̈ + C' q̇ + G = Q``."""
    d, tex, num = c.d, c.tex, c.num
    if d.coriolis_matrix is None or all(e == 0 for e in d.coriolis_matrix):
        return []
    qd = sp.ImmutableMatrix([q.qd for q in c.s.coordinates])
    return [
        para(
            prose(
                "The same $C$ is a matrix times the rates, $C = C'(q,\\dot q)\\,\\dot q$ with "
                "$C'_{ij} = \\sum_k c_{ijk}\\dot q_k$, so that $H\\ddot q + C'\\dot q + G = Q$ "
                "and $\\dot H - 2C'$ is skew-symmetric:"
            )
        ),
        display(f"C' = {tex(num(d.coriolis_matrix).applyfunc(_common_factor))},\\quad C = C' {tex(qd)}"),
    ]


def _common_factor(entry: sp.Expr) -> sp.Expr:
    """An entry of C' with what its terms share taken out, when that is shorter (``-S(θ̇₁ + θ̇₂)`` rather
    than ``-S θ̇₁ - S θ̇₂``): the same value, printed as a teacher factors it."""
    factored = sp.factor_terms(entry)
    shared = [f for f in sp.Mul.make_args(factored) if not f.is_number and not isinstance(f, sp.Add)]
    if not shared:  # only a sign or a number would come out: -[a + b] reads worse than -a - b
        return entry
    return factored if sp.count_ops(factored) < sp.count_ops(entry) else entry


def determinant_blocks(c: SolutionContext) -> list[Block]:
    """``det H`` where it matters: when it depends on the coordinates (the configurations where it vanishes
    are singular) or is zero (then ``H`` cannot be inverted, as in tutorial problem 9)."""
    d, tex, num = c.d, c.tex, c.num
    det = d.mass_matrix_determinant
    if det is None or ops(det) > ASSEMBLED_BUDGET or d.mass_matrix.shape[0] < 2:
        return []
    coordinates = {s for q in c.s.coordinates for s in (q.q, q.qd)}
    if det == 0:
        return [
            display("\\det H = 0"),
            # what a singular H means is said once, in the remarks (tutgen/engine/remarks.py)
            para(prose("$H$ is singular in every configuration; the remarks say what follows.")),
        ]
    if not (sp.sympify(det).free_symbols & coordinates):
        return []
    shown = num(factor_det(det))
    return [
        para(prose("Its determinant depends on the configuration:")),
        display(f"\\det H = {tex(shown)}"),
        para(prose(singular_sentence(shown, [q.q for q in c.s.coordinates], tex))),
    ]


def singular_sentence(det: sp.Expr, coordinates: list[sp.Symbol], tex: Any) -> str:
    """What ``det H`` says about where ``H`` is singular, derived from it (maths between ``$``): never (no
    real zero, e.g. ``2 - \\cos^2\\theta_2 \\ge 1``), where (the zeros in its one coordinate, or of its
    factors in one coordinate each), or, when that is not decided here, that it is singular where the
    determinant vanishes. Other symbols (masses, lengths) are taken positive, and the sentence says so.

    The closed forms come first (:func:`least_value`, :func:`factor_zeros`: a sum of positive terms, a
    product of a sine, a cosine or a coordinate and such sums); sympy's ``solveset`` and ``minimum`` only
    for what they leave, in one coordinate (they took 40 % of a sheet variant's rendering)."""
    det = sp.sympify(det)
    qs = [q for q in coordinates if det.has(q)]
    params = sorted(det.free_symbols - set(coordinates), key=str)
    positive = {p: sp.Dummy(p.name, positive=True) for p in params}
    back = {v: k for k, v in positive.items()}
    assumed = " (for positive values of the parameters)" if params else ""
    signed = det.subs(positive)  # the parameters positive, as every test below takes them
    least = least_value(signed, set(qs))
    if least is not None:
        return _never_zero(least.subs(back), qs, assumed, tex)
    if positive_over_square(signed, set(qs)):
        return _never_zero(None, qs, assumed, tex)
    zeros = factor_zeros(signed, qs)
    if zeros is not None:
        where = ",\\ ".join(f"{tex(q)} = {tex(z.subs(back))}" for q, z in zeros)
        others = " (whatever the other coordinates)" if len(qs) > 1 else ""
        return f"$H$ is singular where it vanishes{assumed}: at ${where}${others}."
    if len(qs) == 1:
        q = qs[0]
        try:
            found = sp.solveset(signed, q, sp.S.Reals)
        except Exception:  # sympy cannot decide (it raises many kinds, mpmath's NoConvergence too): unknown
            found = None
        if found is sp.S.EmptySet:
            try:  # its least value, the reason it is never zero (2 + cos θ_2 ≥ 1 since cos ≥ -1)
                from sympy.calculus.util import minimum

                least = minimum(signed, q, sp.S.Reals)
            except Exception:  # no closed form, or no convergence (mpmath): the zeros alone decide
                least = None
            return _never_zero(least.subs(back) if least is not None and least.is_positive else None, qs, assumed, tex)
        if isinstance(found, sp.FiniteSet):
            where = ",\\ ".join(f"{tex(q)} = {tex(z.subs(back))}" for z in found)
            return f"$H$ is singular where it vanishes{assumed}: at ${where}$."
    return "$H$ is singular in the configurations where it vanishes, if any."


def _never_zero(least: sp.Expr | None, qs: list[sp.Symbol], assumed: str, tex: Any) -> str:
    """The sentence for a determinant with no real zero, with its least value (or a lower bound) when it is
    known and short enough for a line of prose."""
    why = ""
    if least is not None:
        bound = tex(least)
        if tex_width(bound) <= LINE_WIDTH_PT / 3:
            names = [f"${tex(q)}$" for q in qs]
            every = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
            why = (
                f", since $\\det H \\ge {bound} > 0$ for every {every}"
                if len(qs) == 1
                else (f", since $\\det H \\ge {bound} > 0$ for all {every}")
            )
    zero = f"it has no real zero in ${tex(qs[0])}$" if len(qs) == 1 else "it has no real zero"
    return (
        f"It is never zero{assumed}{why}: {zero}, so $H$ is invertible in "
        "every configuration and the equations can always be solved for the accelerations."
    )


def _even_power(factor: sp.Expr) -> bool:
    base, exp = factor.as_base_exp()
    return bool(exp.is_Integer and exp > 0 and exp % 2 == 0 and base.is_extended_real is not False)


def least_value(det: sp.Expr, coordinates: set[sp.Symbol]) -> sp.Expr | None:
    """A positive lower bound of ``det`` over every configuration when one is read off its terms: expanded
    (as it is, with every ``\\cos^2 x`` written ``1 - \\sin^2 x``, or every ``\\sin^2 x`` written ``1 -
    \\cos^2 x``), each term a positive coefficient times even powers of functions of the coordinates, and
    some terms free of them: their sum is the bound (p05's ``m_1 m_2 a_1^2 a_2^2``; the least value itself
    where every even power can vanish together, as it can in one coordinate). ``None`` when no form is
    such a sum; the parameters in ``det`` must already be positive symbols."""
    x = sp.Wild("x")
    forms = [
        expanded_form(f)
        for f in (det, det.replace(sp.cos(x) ** 2, 1 - sp.sin(x) ** 2), det.replace(sp.sin(x) ** 2, 1 - sp.cos(x) ** 2))
    ]
    for form in forms:
        free: list[sp.Expr] = []
        for term in sp.Add.make_args(form):
            coefficient, varying = term.as_independent(*coordinates, as_Add=False)
            if not coefficient.is_positive:
                break
            if varying == 1:
                free.append(coefficient)
            elif not all(_even_power(f) for f in sp.Mul.make_args(varying)):
                break
        else:
            if free:
                return sp.Add(*free)
    for form in forms:
        least = _quadratic_least(form, coordinates)
        if least is not None:
            return least
    return None


def positive_over_square(det: sp.Expr, coordinates: set[sp.Symbol]) -> bool:
    """Whether ``det``, with every ``\\cos^2 x`` written ``1 - \\sin^2 x``, is ``A + B \\sin^2 x`` in one
    angle ``x`` with ``A > 0`` and ``A + B > 0``: a line in ``\\sin^2 x``, which stays in ``[0, 1]``, is
    positive at both ends and so everywhere (the tilting plate's rotor, where ``B`` has no sign).
    """
    x = sp.Wild("x")
    form = sp.expand(det.replace(sp.cos(x) ** 2, 1 - sp.sin(x) ** 2))
    squares = {f.base for f in form.atoms(sp.Pow) if isinstance(f.base, sp.sin) and f.exp == 2}
    if len(squares) != 1:
        return False
    s = sp.Dummy("s")
    line = _coefficients(form.subs(squares.pop() ** 2, s), s, 1, coordinates)
    if line is None:
        return False
    b, a = line
    return bool(a.is_positive and sp.factor(a + b).is_positive)


def _coefficients(expr: sp.Expr, u: sp.Basic, degree: int, coordinates: set[sp.Symbol]) -> list[sp.Expr] | None:
    """The coefficients of ``expr`` as a polynomial of exactly ``degree`` in ``u``, highest first, when they
    are free of the coordinates; ``None`` otherwise."""
    try:
        poly = sp.Poly(expr, u)
    except sp.PolynomialError:
        return None
    coefficients = poly.all_coeffs()
    if poly.degree() != degree or any(c.free_symbols & coordinates for c in coefficients):
        return None
    return coefficients


def _quadratic_least(det: sp.Expr, coordinates: set[sp.Symbol]) -> sp.Expr | None:
    """``c - b^2/(4a)`` of ``a u^2 + b u + c`` in one function ``u`` of the coordinates, when ``a > 0`` and
    ``b^2 < 4ac``: its least value over every real ``u``, so a lower bound over a turn (p08's ``m_1 l_1^2 +
    m_2 (l_1 + l_2 \\cos\\theta_2)^2`` times ``m_2 l_2^2``: ``m_1 m_2 l_1^2 l_2^2``)."""
    varying = {a for a in det.atoms(sp.Function, sp.Symbol) if a.free_symbols & coordinates}
    generators = {a for a in varying if not any(a != b and b.has(a) for b in varying)}
    if len(generators) != 1:
        return None
    quadratic = _coefficients(det, generators.pop(), 2, coordinates)
    if quadratic is None:
        return None
    a, b, c = quadratic
    if not a.is_positive or not sp.factor(b**2 - 4 * a * c).is_negative:
        return None
    least = sp.factor(c - b**2 / (4 * a))
    return least if least.is_positive else None


def factor_zeros(det: sp.Expr, coordinates: list[sp.Symbol]) -> list[tuple[sp.Symbol, sp.Expr]] | None:
    """The zeros of a product whose factors are positive (free of the coordinates, or with a
    :func:`least_value`) but for powers of ``\\sin q``, ``\\cos q`` or ``q`` itself: each such factor's
    zeros in a turn, ``(q, value)`` in the coordinates' order (the top's ``\\sin^2\\theta``: ``θ = 0, π``).
    ``None`` when a factor is none of these."""
    zeros: dict[sp.Symbol, list[sp.Expr]] = {}
    for factor in sp.Mul.make_args(sp.factor_terms(det)):
        if not factor.free_symbols & set(coordinates):
            if not factor.is_positive:
                return None
            continue
        base, exp = factor.as_base_exp()
        if not (exp.is_Integer and exp > 0):
            return None
        if base in coordinates:
            zeros.setdefault(base, []).append(sp.S.Zero)
        elif isinstance(base, sp.sin) and base.args[0] in coordinates:
            zeros.setdefault(base.args[0], []).extend((sp.S.Zero, sp.pi))
        elif isinstance(base, sp.cos) and base.args[0] in coordinates:
            zeros.setdefault(base.args[0], []).extend((-sp.pi / 2, sp.pi / 2))
        elif least_value(factor, set(coordinates)) is None:
            return None
    if not zeros:
        return None
    return [(q, z) for q in coordinates if q in zeros for z in sorted(set(zeros[q]), key=float)]


@lru_cache(maxsize=256)
def factor_det(det: sp.Expr) -> sp.Expr:
    """``det H`` in its shortest factored form (``m_2 a_1^2 a_2^2 (m_1 + m_2 \\sin^2\\theta_2)``): factored
    as it is, and with every ``\\cos^2 x`` written ``1 - \\sin^2 x``; the model's form when neither is shorter.
    Remembered: a sheet's variants share their problem's symbolic ``det H`` (only their numbers differ)."""
    x = sp.Wild("x")
    candidates = [det]
    for form in (det, det.replace(sp.cos(x) ** 2, 1 - sp.sin(x) ** 2)):
        try:
            candidates.append(sp.factor(sp.expand(form)))
        except (sp.PolynomialError, NotImplementedError):
            continue
    return min(candidates, key=sp.count_ops)  # min keeps the first of equally short forms


def christoffel_symbols(c: SolutionContext) -> dict[str, Any] | None:
    """The non-zero dH_ij/dq_k, then each non-zero Christoffel symbol from its definition in both
    conventions (the tutorial's h_ijk and the symmetric c_ijk of the first kind), then C as a vector."""
    d, tex, num = c.d, c.tex, c.num
    if not d.has_step(StepKind.CHRISTOFFEL) or not d.christoffel:  # asked first: a large arm's convert on reading
        return None
    convention = d.system.conventions.christoffel
    show_h = convention is not ChristoffelConvention.FIRST_KIND
    show_c = convention is not ChristoffelConvention.ASADA_SLOTINE
    sec = section("Christoffel symbols", _christoffel_intro(show_h, show_c))
    blocks = sec["blocks"]
    blocks.append(_christoffel_definitions(show_h, show_c))
    size = ops(d.christoffel)  # a large arm's table (tutgen.engine.lazytable) is sized without converting it
    nonzero = [] if size > budgets.PRINT_BUDGET else [(k, v) for k, v in sorted(d.christoffel.items()) if v != 0]
    if size > budgets.PRINT_BUDGET:
        blocks.append(
            para(
                prose(
                    f"{nonzero_count(d.christoffel)} of the {len(d.christoffel)} symbols $h_{{ijk}}$ are nonzero; "
                    f"together they have {said(size)} operations, too many to print here. They are in the JSON output "
                    "(tutgen solve --format json, under christoffel), and $C$ above is their contraction."
                )
            )
        )
        return sec
    if not nonzero:
        blocks.append(para(prose("$H$ is constant, so every Christoffel symbol vanishes and $C = 0$.")))
        return sec
    # the derivatives of H's entries, from the step that lists them (H symmetric: i <= j)
    step = _step(d, StepKind.MASS_MATRIX_DERIVATIVES)
    coords = {q.q: k for k, q in enumerate(d.system.coordinates)}
    derivative: dict[tuple[int, int, int], sp.Expr] = {}
    for e in step.equations if step is not None else ():
        a, b = (int(x) - 1 for x in e.lhs.expr.indices)
        derivative[a, b, coords[e.lhs.variables[0]]] = e.rhs
    # a large serial arm's route has its symbols from the recursion, without the table of dH/dq
    defined = bool(derivative)
    if defined:
        blocks.append(
            para(
                prose(
                    "The entries of $H$ that depend on the coordinates, differentiated (all other "
                    "$\\partial H_{ij}/\\partial q_k$ are zero; $H_{ji} = H_{ij}$):"
                )
            )
        )
        blocks.append(
            display(",\\quad ".join(f"{_partial(a, b, k, d)} = {tex(num(v))}" for (a, b, k), v in derivative.items()))
        )

    def dh(a: int, b: int, k: int) -> sp.Expr:
        return derivative.get((min(a, b), max(a, b), k), sp.Integer(0))

    lines = []
    for (i, j, k), v in nonzero:
        first, second = dh(i, j, k), dh(j, k, i)
        line = f"h_{{{i + 1}{j + 1}{k + 1}}}"
        if defined:
            line += f" = {_partial(i, j, k, d)} - \\tfrac12 {_partial(j, k, i, d)}"
        if first != 0 and second != 0:  # both terms: their values, before the sum
            line += f" = {tex(num(first))} - \\tfrac12\\left({tex(num(second))}\\right)"
        elif second != 0:  # the half-derivative alone: its value, so the sign and the half are seen
            line += f" = -\\tfrac12\\left({tex(num(second))}\\right)"
        lines.append(f"{line} = {tex(num(v))}")
    from_definition = " from its definition" if defined else ""
    if show_h:
        blocks.append(para(prose(f"Each nonzero $h_{{ijk}}${from_definition} (all other $h_{{ijk}}$ are zero):")))
        blocks.append(stacked(lines))
    first_kind = [(k, v) for k, v in sorted(d.christoffel_first_kind.items()) if v != 0]
    if show_c:
        blocks.append(para(prose(f"Each nonzero $c_{{ijk}}${from_definition} ($c_{{ikj}} = c_{{ijk}}$):")))
        blocks.append(
            stacked(
                [
                    f"c_{{{i + 1}{j + 1}{k + 1}}} = "
                    + (
                        f"\\tfrac12\\left({_partial(i, j, k, d)} + {_partial(i, k, j, d)} - "
                        f"{_partial(j, k, i, d)}\\right) = "
                        if defined
                        else ""
                    )
                    + tex(num(v))
                    for (i, j, k), v in first_kind
                    if j <= k
                ]
            )
        )
    if d.coriolis_vector is not None:
        blocks.append(para(prose("Contracted with the rates as above:")))
        blocks.append(display(f"C = {tex(num(d.coriolis_vector))}"))
    return sec


def _christoffel_intro(show_h: bool, show_c: bool) -> str:
    """The section's opening sentence: the convention printed (the spec's ``conventions: {christoffel: …}``);
    the definitions and the sum that gives C from them follow as a display (:func:`_christoffel_definitions`)."""
    if show_h and show_c:
        return (
            "In the tutorial's convention (Asada and Slotine) $h_{ijk}$, not symmetric in $j, k$, and as the "
            "symmetric symbols of the first kind $c_{ijk}$, each with the same sum for $C$:"
        )
    if show_h:
        return "In the tutorial's convention (Asada and Slotine), not symmetric in $j, k$:"
    return "The symbols of the first kind, symmetric in $j, k$:"


def _christoffel_definitions(show_h: bool, show_c: bool) -> Block:
    """The definitions of the conventions printed, and C as their contraction with the rates."""
    parts = []
    if show_h:
        parts.append(
            "h_{ijk} = \\frac{\\partial H_{ij}}{\\partial q_k} - \\frac12 \\frac{\\partial H_{jk}}{\\partial q_i}"
        )
    if show_c:
        parts.append(
            "c_{ijk} = \\frac12\\left(\\frac{\\partial H_{ij}}{\\partial q_k} + \\frac{\\partial H_{ik}}{\\partial q_j}"
            " - \\frac{\\partial H_{jk}}{\\partial q_i}\\right)"
        )
    symbol = "h_{ijk}" if show_h else "c_{ijk}"
    parts.append(f"C_i = \\sum_{{j,k}} {symbol}\\,\\dot q_j \\dot q_k")
    return display(",\\quad ".join(parts))


def entry_by_entry(d: Derivation, tex: TexPrinter, numeric: Any, with_c_g: bool) -> list[Block]:
    """H (upper triangle; H is symmetric), C and G one entry per display, for results too long for a
    matrix on a page."""

    def num(e: Any) -> Any:
        return long_decimals(numeric(e))

    n = d.mass_matrix.shape[0]
    h_dims = inertia_dimensions(d.system)
    f_dims, _ = force_dimensions(d.system)
    blocks: list[Block] = [para(prose("$H$ is symmetric, $H_{ji} = H_{ij}$; its entries on and above the diagonal:"))]
    for i in range(n):
        for j in range(i, n):
            entry = num(d.mass_matrix[i, j])
            blocks.append(display(tex.equation(f"H_{{{i + 1}{j + 1}}}", entry, dimension=h_dims[i][j])))
    if with_c_g:
        angles = [q.si_dimension is not None and q.si_dimension.is_dimensionless for q in d.system.coordinates]
        for name, vec in (("C", d.coriolis_vector), ("G", d.gravity_vector), ("Q", d.generalized_forces)):
            for i in range(n):
                entry = num(vec[i])
                unit = tex.unit(entry, f_dims[i], angles[i])
                blocks.append(display(tex.equation(f"{name}_{{{i + 1}}}", entry) + unit))
    return blocks


def program_blocks(d: Derivation, tex: TexPrinter, numeric: Any, size: int, with_c_g: bool) -> list[Block]:
    """H, C and G of a serial arm as the straight-line program of tutgen.engine.recursive: the
    intermediate quantities x_k of a recursive Newton-Euler pass (C q_dot with q_ddot = 0 and no gravity,
    G with the arm at rest) and of the composite-rigid-body algorithm (H), in evaluation order."""
    program = d.program
    assert program is not None

    def num(e: Any) -> Any:
        return long_decimals(numeric(e))

    n = len(d.system.coordinates)
    outputs = (
        (program.mass_matrix, program.coriolis_vector, program.gravity_vector) if with_c_g else (program.mass_matrix,)
    )
    needed = program.needed(*outputs)
    blocks: list[Block] = [
        para(
            prose(
                f"Written out, the entries of $H$, $C$ and $G$ have {said(size)} operations. They are computed here "
                f"by the recursion that defines them instead: {len(needed)} intermediate quantities $x_k$, "
                "each from earlier ones (a recursive Newton-Euler pass in the link frames gives $C$ with "
                "$\\ddot q = 0$ and no gravity, and $G$ with the arm at rest; the composite-rigid-body "
                "algorithm gives $H$). The JSON output gives the same program, and with "
                "$\\texttt{-{}-expand}$ the entries written out."
            )
        )
    ]
    # one alignment each (align* breaks across pages between its rows, under \\allowdisplaybreaks)
    blocks.append(stacked([f"{tex(x)} = {tex(num(e))}" for x, e in needed]))
    blocks.append(para(prose("$H$ is symmetric, $H_{ji} = H_{ij}$; its entries on and above the diagonal:")))
    blocks.append(
        stacked(
            [f"H_{{{i + 1}{j + 1}}} = {tex(num(program.mass_matrix[i, j]))}" for i in range(n) for j in range(i, n)]
        )
    )
    if with_c_g:
        lines = [f"C_{{{i + 1}}} = {tex(num(program.coriolis_vector[i]))}" for i in range(n)]
        lines += [f"G_{{{i + 1}}} = {tex(num(program.gravity_vector[i]))}" for i in range(n)]
        lines += [f"Q_{{{i + 1}}} = {tex(num(d.generalized_forces[i]))}" for i in range(n)]
        blocks.append(stacked(lines))
    return blocks
