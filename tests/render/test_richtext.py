"""A statement's ``$…$`` maths (a RichText) is typeset by the results' printer; its text stays escaped."""

from __future__ import annotations

import dataclasses

from tests.conftest import SPECS, solved
from tutgen.model.text import MathSpan, RichText

P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"


def _with_statement() -> object:
    system, d, _ = solved(str(P05))
    c = system.coordinates[0]
    statement = RichText(
        "Arm & motor: $theta1_dot^2 > 0$ at 50%",
        ("Arm & motor: ", MathSpan("theta1_dot^2 > 0", (c.qd**2, 0), (">",)), " at 50%"),
    )
    return dataclasses.replace(d, system=dataclasses.replace(system, statement=statement))


def test_statement_maths_is_typeset_and_text_escaped_in_latex() -> None:
    from tutgen.render.latex import render_latex

    tex = render_latex(_with_statement())
    assert r"\textbf{Problem.} Arm \& motor: $\dot{\theta}_1^{2} > 0$ at 50\%" in tex
    assert "theta1_dot" not in tex


def test_statement_maths_is_typeset_and_text_escaped_in_markdown() -> None:
    from tutgen.render.markdown import render_markdown

    md = render_markdown(_with_statement())
    assert r"**Problem.** Arm & motor: $\dot{\theta}_1^{2} > 0$ at 50%" in md
    assert "theta1_dot" not in md


def test_a_plain_statement_stays_escaped_text() -> None:
    from tutgen.render.latex import render_latex

    system, d, _ = solved(str(P05))
    d2 = dataclasses.replace(d, system=dataclasses.replace(system, statement="cost $5 & up"))
    assert r"\textbf{Problem.} cost \$5 \& up" in render_latex(d2)
