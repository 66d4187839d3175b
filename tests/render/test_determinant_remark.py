"""What the matrix form says of det H is derived from det H (issue 15): never zero and why, or where."""

from __future__ import annotations

import re

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.render.sections.matrix import singular_sentence
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
    text = singular_sentence(sp.sin(theta) * sp.cos(r), [theta, r], sp.latex)  # two coordinates: not decided
    assert "where it vanishes, if any" in text


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
    text = singular_sentence(2 - sp.cos(theta) ** 2, [theta], sp.latex)
    assert "never zero" in text and "\\ge" not in text
    monkeypatch.setattr(sp, "solveset", fails)
    assert "where it vanishes, if any" in singular_sentence(2 - sp.cos(theta) ** 2, [theta], sp.latex)
