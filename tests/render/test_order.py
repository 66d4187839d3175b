"""A teacher's term order and signs (tutgen.render.order; docs/typesetting.md), against the tutorial."""

from __future__ import annotations

import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.render.printer import TexPrinter, forget
from tutgen.render.views import solution_view

P03 = SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"
P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"


def _boxed(spec: object, title: str) -> list[str]:
    view = solution_view(solved(str(spec))[1])
    section = next(s for s in view["sections"] if s["title"] == title)
    return [b["tex"] for b in section["blocks"] if "tex" in b]  # displays (not the prose between them)


def test_p03_equations_read_as_the_tutorial_prints_them() -> None:
    """Tutorial p03: F = (m_1+m_2)ẍ + m_2 l cos θ θ̈ − m_2 l sin θ θ̇² + kx (inertia, velocity, spring)."""
    first, second = _boxed(P03, "Equations of motion")
    assert first == (
        r"\left(m_1 + m_2\right) \ddot{x} + m_2 l \cos\theta\, \ddot{\theta}"
        r" - m_2 l \sin\theta\, \dot{\theta}^{2} + k x = F"
    )
    assert second == r"m_2 l \cos\theta\, \ddot{x} + m_2 l^{2} \ddot{\theta} + m_2 l g \sin\theta = \tau"


def test_p03_kinetic_energy_has_the_half_in_front_and_rates_in_coordinate_order() -> None:
    """½(m_1+m_2)ẋ² first, the rates of a product in the order of the coordinates (the tutorial's m_2lẋθ̇),
    and the rate products as the quadratic form ½ Σ H_ij q̇_i q̇_j is read row by row: ẋ², ẋθ̇, θ̇²."""
    energies = _boxed(P03, "Energies")
    assert (
        r"T = \tfrac{1}{2} \left(m_1 + m_2\right) \dot{x}^{2} + m_2 l \cos\theta\, \dot{x} \dot{\theta}"
        r" + \tfrac{1}{2} m_2 l^{2} \dot{\theta}^{2}"
    ) in energies


def test_p05_gravity_is_collected_with_a_positive_bracket_after_the_accelerations() -> None:
    first = _boxed(P05, "Equations of motion")[0]
    accelerations = first.index(r"\ddot{\theta}_1"), first.index(r"\ddot{\theta}_2")
    assert accelerations[0] < accelerations[1] < first.index(r"\dot{\theta}")
    assert r"+ \left(m_1 + m_2\right) a_1 g \cos\theta_1" in first
    assert first.endswith(r"= \tau_1")


def test_a_bracket_with_a_negative_lead_takes_its_sign_outside() -> None:
    system = solved(str(P05))[0]
    g, m1, m2 = (next(p.symbol for p in system.parameters if str(p.symbol) == n) for n in ("g", "m1", "m2"))
    expr = sp.Mul(g, -m1 - m2, evaluate=False)
    assert TexPrinter(system)(expr) == r"- \left(m_1 + m_2\right) g"


def test_ordered_printing_keeps_the_value() -> None:
    from tutgen.render.order import equation_terms

    system, d, _ = solved(str(P05))
    for eq, force in zip(d.equations_of_motion, d.generalized_forces, strict=True):
        terms = equation_terms(eq + force, system)
        assert terms is not None
        assert sp.expand(sum(sign * body for sign, body in terms) - (eq + force)) == 0


P08 = SPECS / "tutorial-1" / "p08-spatial-rr.yaml"


def test_p08_inertia_entry_is_the_tutorials_perfect_square() -> None:
    """Tutorial p08: H_11 = m_1 l_1² + m_2 (l_1 + l_2 cos θ_2)², not its three expanded terms; the value kept."""
    system, d, _ = solved(str(P08))
    tex = TexPrinter(system)
    assert tex(d.mass_matrix[0, 0]) == r"m_1 l_1^{2} + m_2 \left(l_1 + l_2 \cos\theta_2\right)^{2}"
    # with rates in it the sum is not squared up: an energy keeps its rates' order
    t2d = next(c.qd for c in system.coordinates if str(c.q) == "theta2")
    assert r"\right)^{2}" not in tex(sp.expand(d.mass_matrix[0, 0] * t2d))


def test_a_sum_that_is_no_square_is_printed_as_before() -> None:
    """The square form is taken only when a mass's coefficient factors to a square of the coordinates'
    functions: (m_1 + m_2) a² + 2 m_2 a b cos q stays arranged."""
    system, _, _ = solved(str(P05))
    tex = TexPrinter(system)
    names = {str(s): s for s in _symbols(system)}
    m2, a1, a2, t2 = (names[n] for n in ("m2", "a1", "a2", "theta2"))
    printed = tex(m2 * (a1**2 + a2**2 + 2 * a1 * a2 * sp.cos(t2)))
    assert r"\right)^{2}" not in printed


def _symbols(system) -> set[sp.Symbol]:
    return {p.symbol for p in system.parameters} | {c.q for c in system.coordinates}


def test_c_prime_entries_take_their_common_factor_out() -> None:
    """p05's C'_12 = -m_2 a_1 a_2 sin θ_2 (θ̇_1 + θ̇_2), the bracket of rates after the sine."""
    view = solution_view(solved(str(P05))[1])
    section = next(s for s in view["sections"] if s["title"] == "Matrix form")
    shown = " ".join(b.get("tex", "") for b in section["blocks"])
    assert r"- m_2 a_1 a_2 \sin\theta_2\, \left(\dot{\theta}_1 + \dot{\theta}_2\right)" in shown


def test_a_square_free_coefficient_is_not_factored(monkeypatch) -> None:
    """``sympy.factor`` (multivariate Hensel lifting) is called only on a mass's coefficient whose square-free
    decomposition has a square in the coordinates' functions: a planar 5-link chain's H coefficients, all
    square-free, ran for minutes in it (issue 17). p08's square is still found, through ``factor``."""
    import tutgen.render.order as order

    calls: list[sp.Expr] = []
    real = sp.factor

    def counting(expr: sp.Expr, *args: object, **kwargs: object) -> sp.Expr:
        calls.append(expr)
        return real(expr, *args, **kwargs)

    monkeypatch.setattr(order.sp, "factor", counting)
    forget()  # what an earlier test printed is remembered (tutgen.render.printer._PRINTED)
    system, d, _ = solved(str(P08))
    tex = TexPrinter(system)
    assert r"m_2 \left(l_1 + l_2 \cos\theta_2\right)^{2}" in tex(d.mass_matrix[0, 0])
    assert calls, "p08's square is found by factoring its coefficient"
    calls.clear()
    system, _, _ = solved(str(P05))
    names = {str(s): s for s in _symbols(system)}
    m2, a1, a2, t1, t2 = (names[n] for n in ("m2", "a1", "a2", "theta1", "theta2"))
    # |r|² of a link's end: (a_1 cos θ_1 + a_2 cos θ_2)² + (a_1 sin θ_1 + a_2 sin θ_2)², square-free expanded
    r2 = sp.expand((a1 * sp.cos(t1) + a2 * sp.cos(t2)) ** 2 + (a1 * sp.sin(t1) + a2 * sp.sin(t2)) ** 2)
    printed = TexPrinter(system)(m2 * r2)
    assert r"\right)^{2}" not in printed
    assert calls == []


def test_a_variants_numeric_masses_are_not_factored(monkeypatch) -> None:
    """A sheet's variant has every mass a number: no mass to gather the terms over, so no square is printed
    and nothing is factored or decomposed to look for one (issue 17: p08's variants spent a fifth of their
    time there). The printed text is what it was."""
    import tutgen.render.order as order

    calls: list[sp.Expr] = []
    real_factor, real_sqf = sp.factor, sp.sqf_list

    def counting(real):  # type: ignore[no-untyped-def]
        def call(expr: sp.Expr, *args: object, **kwargs: object) -> object:
            calls.append(expr)
            return real(expr, *args, **kwargs)

        return call

    monkeypatch.setattr(order.sp, "factor", counting(real_factor))
    monkeypatch.setattr(order.sp, "sqf_list", counting(real_sqf))
    forget()
    system, d, _ = solved(str(P08))
    values = {p.symbol: sp.Rational(3 + i, 2) for i, p in enumerate(system.parameters) if p.name[:1] in "ml"}
    h11 = d.mass_matrix[0, 0].xreplace(values)
    printed = TexPrinter(system)(h11)
    assert calls == []
    assert r"\right)^{2}" not in printed
    assert sp.expand(order.arranged(h11, order.levels_of(system)) - h11) == 0


def _p05_levels():
    from tutgen.render.order import levels_of

    system = solved(str(P05))[0]
    return system, levels_of(system)


def test_an_arrangement_that_would_change_the_value_is_not_used(monkeypatch) -> None:
    """Each group's printed coefficient is tested against the group's terms (issue 17: once per group,
    not per sum): a coefficient that lost a term makes the whole sum print as sympy has it."""
    from tutgen.render import order

    system, levels = _p05_levels()
    m1, m2, a1 = (next(p.symbol for p in system.parameters if str(p.symbol) == n) for n in ("m1", "m2", "a1"))
    q1 = system.coordinates[0]
    expr = (m1 + m2) * a1**2 * q1.qdd + m2 * a1 * sp.cos(q1.q) * q1.qd**2
    order.forget()
    found = order.arranged_terms(expr, levels)
    assert found is not None
    assert sp.expand(sum(s * b for s, b in found) - expr) == 0

    real = sp.factor_terms

    def drops_a_term(e: sp.Expr, *args: object, **kwargs: object) -> sp.Expr:
        out = real(e, *args, **kwargs)
        terms = sp.Add.make_args(sp.expand(out))
        return real(sp.Add(*terms[1:])) if len(terms) > 1 else out

    order.forget()
    monkeypatch.setattr(order.sp, "factor_terms", drops_a_term)
    assert order.arranged_terms(expr, levels) is None
    order.forget()


def test_a_group_with_sines_and_cosines_squared_keeps_its_value() -> None:
    """sin² + cos² in a group's coefficient: the trigonometric simplification would print 1, which is
    not what the sum expands to, so the sum is not arranged (its value is kept either way)."""
    from tutgen.render import order

    system, levels = _p05_levels()
    m2, a2 = (next(p.symbol for p in system.parameters if str(p.symbol) == n) for n in ("m2", "a2"))
    q1, q2 = system.coordinates
    expr = m2 * a2**2 * sp.sin(q2.q) ** 2 * q1.qdd + m2 * a2**2 * sp.cos(q2.q) ** 2 * q1.qdd
    order.forget()
    found = order.arranged_terms(expr, levels)
    assert found is None or sp.expand(sum(s * b for s, b in found) - expr) == 0


def test_already_expanded_only_where_expand_changes_nothing() -> None:
    """``already_expanded`` spares ``sympy.expand`` its walks (issue 17); it may say False of an expanded
    sum, never True of one that expand would change. Checked on every sum of the tutorial's results and
    their variants' numbers, and on forms each hint of expand rewrites."""
    from tutgen.render.order import already_expanded

    x, y, z, q1, q2 = sp.symbols("x y z q1 q2")
    m = sp.Symbol("m", positive=True)
    rewritten = [
        (x + y) ** 2,
        sp.Mul(x, y + z, evaluate=False),
        sp.exp(x + y),
        sp.log(m * sp.Symbol("n", positive=True)),
        sp.cos(sp.Mul(2, q1 + q2, evaluate=False)) ** 2,
        sp.sin(q1 * (q2 + 1)),
    ]
    for e in rewritten:
        assert sp.expand(e) != e, e  # (the test's own premise)
        assert not already_expanded(e), e
    kept = [x, 2 * x * y**2, sp.Rational(3, 2) * m * sp.cos(q1 + 2 * q2) ** 2 - sp.Float("0.5") * x * sp.sin(q1)]
    for e in kept:
        assert already_expanded(e) and sp.expand(e) == e, e
    sums = 0
    for spec in sorted((SPECS / "tutorial-1").glob("p*.yaml")):
        d = solved(str(spec))[1]
        results = [d.kinetic_energy, d.potential_energy, d.lagrangian]
        results += [*(d.equations_of_motion or []), *(d.mass_matrix or [])]
        values = {p.symbol: sp.Rational(7, 4) for p in d.system.parameters}
        for e in [r for r in results if isinstance(r, sp.Expr)]:
            for sub in sp.preorder_traversal(e):
                for candidate in (sub, sub.xreplace(values)):
                    if isinstance(candidate, sp.Expr) and candidate.is_Add and already_expanded(candidate):
                        sums += 1
                        assert sp.expand(candidate) == candidate, candidate
    assert sums > 100
