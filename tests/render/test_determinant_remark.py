"""What the matrix form says of det H is derived from det H (issue 15): never zero and why, or where."""

from __future__ import annotations

import re

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.render.sections.matrix import least_value, singular_sentence
from tutgen.render.views import solution_view

theta, r, m, a = sp.symbols("theta_2 r m a")


def test_det_that_never_vanishes_is_said_so_with_its_least_value() -> None:
    text = singular_sentence(2 - sp.cos(theta) ** 2, [theta], sp.latex)
    assert "never zero" in text and "\\ge 1 > 0" in text and "singular where" not in text
    text = singular_sentence(m**2 * a**2 * (m + m * sp.sin(theta) ** 2), [theta], sp.latex)
    assert "never zero (for positive values of the parameters)" in text


def test_det_that_vanishes_is_said_where_and_the_place_is_a_zero() -> None:
    text = singular_sentence(9 * r**2, [r], sp.latex)
    where = re.search(r"at \$r = ([^$]+)\$", text)
    assert where is not None and (9 * r**2).subs(r, sp.sympify(where.group(1))) == 0
    text = singular_sentence(sp.sin(theta) * sp.cos(r), [theta, r], sp.latex)  # a factor in each coordinate
    assert "at $\\theta_{2} = 0,\\ \\theta_{2} = \\pi,\\ r = - \\frac{\\pi}{2},\\ r = \\frac{\\pi}{2}$" in text
    assert "whatever the other coordinates" in text
    text = singular_sentence(sp.sin(theta) + sp.cos(r), [theta, r], sp.latex)  # two coordinates in one: not decided
    assert "where it vanishes, if any" in text


l1, l2, m1, m2, phi = sp.symbols("l_1 l_2 m_1 m_2 phi")
#: determinants as tutgen's specs print them (p08, the rotor on a tilting plate c, the driven support q, the
#: top g), with what the sentence must say: a bound, no bound, or the zeros
CASES = [
    (l2**2 * m2 * (l1**2 * (m1 + m2) + 2 * l1 * l2 * m2 * sp.cos(theta) + l2**2 * m2 * sp.cos(theta) ** 2), "bound"),
    (
        m2 * (6 * a**2 * m1 + a**4 * m2 * sp.sin(theta) ** 2 - 4 * l1**4 * m2 * sp.sin(theta) ** 2 + 4 * l1**4 * m2),
        "never",
    ),
    (-(l1**2) * m * (-m2 * a**2 + 2 * l2**2 * m * sp.sin(phi - theta) ** 2 - 2 * l2**2 * m) / 2, "bound"),
    (a**2 * m**3 * (3 * a**2 + l1**2) ** 2 * sp.sin(theta) ** 2 / 288, "zeros"),
    (m1 * m2 + m1 * m2 * sp.sin(theta) ** 2 + m2**2 * sp.sin(phi) ** 2, "bound"),
]


@pytest.mark.parametrize(("det", "claim"), CASES, ids=["p08", "c", "q", "g", "d"])
def test_what_the_sentence_says_of_det_holds_at_random_values(det: sp.Expr, claim: str) -> None:
    """The closed forms (a sum of positive terms, a quadratic with no real root, a line in sin² positive at
    both ends, a product of sines) are checked against the determinant at random positive parameters and
    random angles: never below the bound, zero where it says."""
    import random

    rng = random.Random(17)
    coordinates = [q for q in (theta, phi) if det.has(q)]
    text = singular_sentence(det, coordinates, sp.latex)
    params = sorted(det.free_symbols - set(coordinates), key=str)
    if claim == "zeros":
        assert "singular where it vanishes" in text
        assert det.subs(theta, 0) == 0 and det.subs(theta, sp.pi) == 0
        return
    assert "never zero" in text
    bound = re.search(r"\\ge (.+) > 0\$", text)
    assert (bound is not None) is (claim == "bound"), text
    least = least_value(det.subs({p: sp.Symbol(p.name, positive=True) for p in params}), set(coordinates))
    if least is not None:
        least = least.subs({sp.Symbol(p.name, positive=True): p for p in params})
        assert f"\\ge {sp.latex(least)} > 0" in text
    for _ in range(200):
        values = {p: rng.uniform(0.05, 3.0) for p in params} | {q: rng.uniform(-4, 4) for q in coordinates}
        value = float(det.subs(values))
        assert value > 0
        if least is not None:
            assert value >= float(least.subs(values)) * (1 - 1e-12) > 0


def _words(path: str) -> str:
    view = solution_view(solved(path)[1])
    parts = [p for s in view["sections"] for b in s["blocks"] if b["kind"] == "text" for p in b["parts"]]
    parts += [p for remark in view["remarks"] for p in remark]
    return " ".join(p.get("text", p.get("tex", "")) for p in parts)


def test_tutorial_p10_and_p09_say_it_once_and_truly() -> None:
    p10 = _words(str(SPECS / "tutorial-1" / "p10-given-kinetic-energy.yaml"))
    assert "never zero" in p10 and "singular where it vanishes" not in p10
    p09 = _words(str(SPECS / "tutorial-1" / "p09-pr-manipulator.yaml"))
    assert p09.count("cannot be solved for every acceleration") == 1


def test_det_sympy_cannot_decide_is_said_without_a_claim(monkeypatch: pytest.MonkeyPatch) -> None:
    """sympy's solvers raise many kinds of error (mpmath's NoConvergence in a sheet's variant): the
    sentence then claims nothing it has not derived."""
    import sympy.calculus.util as util

    def fails(*args: object, **kwargs: object) -> None:
        raise RuntimeError("convergence to root failed")

    monkeypatch.setattr(util, "minimum", fails)
    # 2 + cos θ has no closed form here (an odd power): sympy's solvers decide it
    text = singular_sentence(2 + sp.cos(theta), [theta], sp.latex)
    assert "never zero" in text and "\\ge" not in text
    monkeypatch.setattr(sp, "solveset", fails)
    assert "where it vanishes, if any" in singular_sentence(2 + sp.cos(theta), [theta], sp.latex)
