"""The LMS writers on hand-made questions (no derivation): a single number as a Moodle numerical
question, Maxima syntax there and back, maths and escaped dollars in the HTML."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from tutgen.lms.html import markdown_html
from tutgen.lms.moodle import from_maxima, maxima, moodle_xml, number_text
from tutgen.lms.questions import LmsQuestion, Part, entry_tolerance, label_of, path_of
from tutgen.lms.readback import moodle_answers


def question(*parts: Part) -> LmsQuestion:
    return LmsQuestion("p1-mass", 1, "v001", "Variant 1", "A mass", "Find $m_1$.", "$$m = 2$$", None, parts)


def test_moodle_single_number_is_a_numerical_question() -> None:
    xml = moodle_xml("S", [question(Part(("mass",), 6.7674335, True, 0.0005))])
    q = next(q for q in ET.fromstring(xml).iter("question") if q.get("type") != "category")
    assert q.get("type") == "numerical"
    assert q.findtext("answer/text") == "6.7674335" and q.find("answer").get("fraction") == "100"  # type: ignore[union-attr]
    assert q.findtext("answer/tolerance") == "0.0005"
    assert moodle_answers(xml) == {"p1-mass--v001": {"mass": "6.7674335"}}


@pytest.mark.parametrize(
    ("value", "text", "back"),
    [
        pytest.param("2*pi*m*r**2", "2*%pi*m*r**2", "2*pi*m*r**2", id="pi"),
        pytest.param(
            [["m1 + m2", 4.75], [0, "Abs(x)"]],
            "matrix([m1 + m2,19/4],[0,abs(x)])",
            [["m1 + m2", "19/4"], ["0", "Abs(x)"]],
            id="matrix",
        ),
        pytest.param([1, "x_dot", 0.1], "[1,x_dot,1/10]", ["1", "x_dot", "1/10"], id="list"),
        pytest.param(6.767433508808227, "6.767433508808227", "6.767433508808227", id="long-float-kept"),
    ],
)
def test_maxima_text_and_back(value: object, text: str, back: object) -> None:
    assert maxima(value) == text
    assert from_maxima(text) == back


def test_number_text_has_no_exponent() -> None:
    assert number_text(1e-12) == "0.000000000001" and number_text(2.5e7) == "25000000" and number_text(3) == "3"


def test_tolerance_follows_the_printed_figures_or_the_stated_rule() -> None:
    assert entry_tolerance(17.1675, {}, 4) == pytest.approx(0.005)
    assert entry_tolerance(0.0, {}, 4) == 1e-12
    assert entry_tolerance(200.0, {"rel_tol": 0.01}, 4) == pytest.approx(2.0)
    assert entry_tolerance(200.0, {"abs_tol": 0.5}, 4) == 0.5


def test_labels_name_per_coordinate_records() -> None:
    path = ("lagrange_terms", "[theta]", "dL_dq")
    assert label_of(path) == "lagrange_terms[theta].dL_dq" and path_of(label_of(path)) == path


def test_html_maths_kept_and_escaped_dollars_are_text() -> None:
    out = markdown_html(r"Cost \$5 for $a_1 < b_{2}$ and *x*." + "\n\n$$\n\\frac{1}{2}\n$$\n", inert_markers=True)
    assert r"Cost $5 for \(a_1 &lt; b_&#123;2&#125;\) and <em>x</em>." in out
    assert r"<p>\[\frac&#123;1&#125;&#123;2&#125;\]</p>" in out
