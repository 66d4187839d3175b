"""Moodle XML (``tutgen sheet -f moodle``): a question category per sheet, a sub-category per problem
holding one question per variant, for a quiz's "random question from category".

What each problem becomes (docs/lms.md):

- every graded part numeric: a core **Cloze** question (``cloze``, Moodle's multianswer) whose
  ``{n:NUMERICAL:=value:tolerance}`` fields are numerical sub-questions with the instructor's tolerance,
  a matrix laid out as a table; a single number: a core **numerical** question;
- any part symbolic: a **STACK** question (``type="stack"``, the qtype_stack plugin: Moodle core has no
  type that marks algebra; ``shortanswer`` would compare strings and mark ``m*g*l`` wrong against
  ``g*l*m``, and ``calculated`` asks for a number). Each symbolic part is an input whose answer is
  tested ``AlgEquiv`` (algebraic equivalence) against the teacher's answer in Maxima syntax; each
  numeric entry an input tested ``NumAbsolute`` with the instructor's tolerance.

The worked solution is each question's general feedback (HTML, maths as ``\\( … \\)``), the figure an
SVG embedded in the question text (``<file encoding="base64">`` and ``@@PLUGINFILE@@``). Every text is
written as XML character data (ElementTree escapes ``< > &``, so a ``]]>`` or ``<img onerror=…>`` in a
statement is inert), and HTML built from tutgen's own Markdown with raw HTML off (:mod:`tutgen.lms.html`).
"""

from __future__ import annotations

import base64
import html
import re
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from decimal import Decimal
from typing import Any

from tutgen.lms.html import inert, markdown_html
from tutgen.lms.questions import LmsQuestion, Part

#: Maxima's names for the constants and functions tutgen's grammar writes differently.
_TO_MAXIMA = {"pi": "%pi", "I": "%i", "E": "%e", "Abs": "abs"}
_FROM_MAXIMA = {v: k for k, v in _TO_MAXIMA.items()}
_NAME = re.compile(r"%?[A-Za-z_][A-Za-z_0-9]*")

#: The STACK version the questions are written for (a STACK 4.4 question file).
STACK_VERSION = "2023010400"


def number_text(x: float | int) -> str:
    """A number as a plain decimal (no exponent, which not every Moodle field reads): the shortest text
    that reads back as the same float."""
    if isinstance(x, int):
        return str(x)
    text = format(Decimal(repr(float(x))), "f")
    return text.rstrip("0").rstrip(".") if "." in text else text


def maxima(value: Any) -> str:
    """A result (an expression in tutgen's grammar, a number, a list, a list of rows) in Maxima syntax:
    ``**`` is Maxima's too; constants renamed (``%pi``); a matrix as ``matrix([…],[…])``; a number that
    is a short decimal as the exact fraction it stands for, so that AlgEquiv compares exactly."""
    if isinstance(value, list):
        if value and all(isinstance(r, list) for r in value):
            return "matrix(" + ",".join("[" + ",".join(maxima(e) for e in r) + "]" for r in value) + ")"
        return "[" + ",".join(maxima(e) for e in value) + "]"
    if isinstance(value, bool):
        raise TypeError("not an answer")
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        exact = Decimal(repr(value))
        if len(exact.as_tuple().digits) <= 10:
            num, den = exact.as_integer_ratio()
            return f"{num}/{den}" if den != 1 else str(num)
        return repr(value)
    return _NAME.sub(lambda m: _TO_MAXIMA.get(m.group(0), m.group(0)), str(value))


def from_maxima(text: str) -> Any:
    """The inverse of :func:`maxima` for what it writes: a tutgen expression, a list, a list of rows."""
    text = text.strip()
    if text.startswith("matrix(") and text.endswith(")"):
        return [from_maxima(row) for row in split_top(text[len("matrix(") : -1])]
    if text.startswith("[") and text.endswith("]"):
        return [from_maxima(e) for e in split_top(text[1:-1])]
    return _NAME.sub(lambda m: _FROM_MAXIMA.get(m.group(0), m.group(0)), text)


def split_top(text: str) -> list[str]:
    """``text`` split at its commas outside brackets."""
    out, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        elif ch == "," and depth == 0:
            out.append(text[start:i])
            start = i + 1
    out.append(text[start:])
    return [s.strip() for s in out]


def _text(parent: ET.Element, tag: str, text: str, **attrs: str) -> ET.Element:
    el = ET.SubElement(parent, tag, attrs)
    ET.SubElement(el, "text").text = text
    return el


def _leaf(parent: ET.Element, tag: str, text: str = "") -> ET.Element:
    el = ET.SubElement(parent, tag)
    el.text = text
    return el


#: Question and category names are shown by Moodle as (filtered) HTML: no markup, no marker in them.
_PLAIN = str.maketrans({"<": "\u2039", ">": "\u203a", "{": "(", "}": ")", "[": "(", "]": ")", "@": "(at)", "&": "+"})


def plain_name(text: str) -> str:
    """A spec's title as a Moodle name: ``< >`` as ``‹ ›``, brackets as parentheses, no ``@`` or ``&``."""
    return text.translate(_PLAIN)


def category_path(*names: str) -> str:
    """A Moodle category path under the course's top category (names plain); ``/`` in a name is ``//``."""
    return "/".join(["$course$", "top", *(plain_name(n).replace("/", "//") for n in names)])


def _category(quiz: ET.Element, path: str, info_html: str) -> None:
    q = ET.SubElement(quiz, "question", {"type": "category"})
    _text(q, "category", path)
    _text(q, "info", info_html, format="html")
    _leaf(q, "idnumber")


def _entries(part: Part) -> list[tuple[str, Any, Any]]:
    """(index text, value, tolerance) of each entry of a numeric part: ``""``, ``[2]`` or ``[1,3]``
    (1-based, as docs/check.md names entries)."""
    v, t = part.value, part.tolerance
    if part.shape == "scalar":
        return [("", v, t)]
    if part.shape == "list":
        return [(f"[{i + 1}]", e, te) for i, (e, te) in enumerate(zip(v, t, strict=True))]
    return [
        (f"[{i + 1},{j + 1}]", e, te)
        for i, (row, trow) in enumerate(zip(v, t, strict=True))
        for j, (e, te) in enumerate(zip(row, trow, strict=True))
    ]


def _dims(part: Part) -> str:
    if part.shape == "scalar":
        return "1"
    if part.shape == "list":
        return str(len(part.value))
    return f"{len(part.value)}x{len(part.value[0])}"


def _grid(part: Part, cells: Sequence[str]) -> str:
    """The part's inputs laid out as its shape: inline (one input for the whole part), a row, or a table;
    wrapped in an element that names the part (``data-part``, ``data-shape``), which an importer ignores
    and the round trip reads."""
    label = inert(html.escape(part.label))
    shape = _dims(part) if len(cells) > 1 else "1"
    head = f'<div class="tutgen-part" data-part="{label}" data-shape="{shape}"><p><code>{label}</code> = '
    if len(cells) == 1:
        return head + cells[0] + "</p></div>\n"
    if part.shape == "list":  # the brackets as references: STACK reads [[ as the start of a marker
        return head + "&#91; " + ", ".join(cells) + " &#93;</p></div>\n"
    cols = len(part.value[0])
    rows = [cells[i : i + cols] for i in range(0, len(cells), cols)]
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in r) + "</tr>" for r in rows)
    return head + f'</p><table class="tutgen-matrix">{body}</table></div>\n'


def _question_html(q: LmsQuestion) -> str:
    return markdown_html(q.question_md, inert_markers=True, figure_src="@@PLUGINFILE@@/")


def _head(quiz: ET.Element, q: LmsQuestion, qtype: str, text: str) -> ET.Element:
    el = ET.SubElement(quiz, "question", {"type": qtype})
    who = f" ({q.label})" if q.label else ""
    _text(el, "name", plain_name(f"Problem {q.number}{who}: {q.title}"))
    qt = _text(el, "questiontext", text, format="html")
    if q.figure is not None:
        name, svg = q.figure
        f = ET.SubElement(qt, "file", {"name": name, "path": "/", "encoding": "base64"})
        f.text = base64.b64encode(svg.encode("utf-8")).decode("ascii")
    _text(el, "generalfeedback", markdown_html(q.feedback_md, inert_markers=True), format="html")
    if qtype != "cloze":
        _leaf(el, "defaultgrade", str(max(1, len(q.parts))))
    _leaf(el, "penalty", "0.1")
    _leaf(el, "hidden", "0")
    _leaf(el, "idnumber", q.ident[:100])
    return el


def _cloze(quiz: ET.Element, q: LmsQuestion) -> None:
    text = _question_html(q)
    for part in q.parts:
        share = max(1, round(12 / len(_entries(part))))  # a part is worth about the same, however many entries
        cells = [f"{{{share}:NUMERICAL:={number_text(v)}:{number_text(t)}}}" for _, v, t in _entries(part)]
        text += _grid(part, cells)
    _head(quiz, q, "cloze", text)


def _numerical(quiz: ET.Element, q: LmsQuestion) -> None:
    part = q.parts[0]
    text = _question_html(q) + _grid(part, ["…"])
    el = _head(quiz, q, "numerical", text)
    ans = ET.SubElement(el, "answer", {"fraction": "100", "format": "moodle_auto_format"})
    ET.SubElement(ans, "text").text = number_text(part.value)
    _text(ans, "feedback", "", format="html")
    _leaf(ans, "tolerance", number_text(part.tolerance))
    _leaf(el, "unitgradingtype", "0")
    _leaf(el, "unitpenalty", "0.1000000")
    _leaf(el, "showunits", "3")
    _leaf(el, "unitsleft", "0")


def _stack_input(el: ET.Element, name: str, kind: str, tans: str, size: int) -> None:
    i = ET.SubElement(el, "input")
    for tag, value in (
        ("name", name),
        ("type", kind),
        ("tans", tans),
        ("boxsize", str(size)),
        ("strictsyntax", "1"),
        ("insertstars", "0"),
        ("syntaxhint", ""),
        ("syntaxattribute", "0"),
        ("forbidwords", ""),
        ("allowwords", ""),
        ("forbidfloat", "0"),
        ("requirelowestterms", "0"),
        ("checkanswertype", "1" if kind == "algebraic" else "0"),
        ("mustverify", "1"),
        ("showvalidation", "1"),
        ("options", ""),
    ):
        _leaf(i, tag, value)


def _stack_prt(el: ET.Element, name: str, sans: str, tans: str, test: str, options: str, note: str) -> None:
    prt = ET.SubElement(el, "prt")
    _leaf(prt, "name", name)
    _leaf(prt, "value", "1.0000000")
    _leaf(prt, "autosimplify", "1")
    _leaf(prt, "feedbackstyle", "1")
    _text(prt, "feedbackvariables", "")
    node = ET.SubElement(prt, "node")
    for tag, value in (
        ("name", "0"),
        ("description", ""),
        ("answertest", test),
        ("sans", sans),
        ("tans", tans),
        ("testoptions", options),
        ("quiet", "0"),
    ):
        _leaf(node, tag, value)
    for side, score in (("true", "1.0000000"), ("false", "0.0000000")):
        _leaf(node, f"{side}scoremode", "=")
        _leaf(node, f"{side}score", score)
        _leaf(node, f"{side}penalty", "")
        _leaf(node, f"{side}nextnode", "-1")
        # the answer note names the graded entry: the quiz's response analysis reads e.g. "kinetic_energy-T"
        _leaf(node, f"{side}answernote", f"{note}-{side[0].upper()}")
        _text(node, f"{side}feedback", "", format="html")


def _stack(quiz: ET.Element, q: LmsQuestion) -> None:
    text = _question_html(q)
    variables: list[str] = []
    inputs: list[tuple[str, str, str, int]] = []
    prts: list[tuple[str, str, str, str, str, str]] = []
    feedback: list[str] = []
    for part in q.parts:
        if part.numeric:
            cells = []
            for index, value, tol in _entries(part):
                n = len(inputs) + 1
                variables.append(f"tutgen_ta{n}: {maxima(value)};")
                inputs.append((f"ans{n}", "numerical", f"tutgen_ta{n}", 10))
                prts.append(
                    (f"prt{n}", f"ans{n}", f"tutgen_ta{n}", "NumAbsolute", number_text(tol), part.label + index)
                )
                cells.append(f"[[input:ans{n}]] [[validation:ans{n}]]")
                feedback.append(f"[[feedback:prt{n}]]")
            text += _grid(part, cells)
        else:
            n = len(inputs) + 1
            kind = "matrix" if part.shape == "matrix" else "algebraic"
            variables.append(f"tutgen_ta{n}: {maxima(part.value)};")
            inputs.append((f"ans{n}", kind, f"tutgen_ta{n}", 40 if kind == "algebraic" else 12))
            prts.append((f"prt{n}", f"ans{n}", f"tutgen_ta{n}", "AlgEquiv", "", part.label))
            text += _grid(part, [f"[[input:ans{n}]] [[validation:ans{n}]]"])
            feedback.append(f"[[feedback:prt{n}]]")
    el = _head(quiz, q, "stack", text)
    _text(el, "stackversion", STACK_VERSION)
    _text(el, "questionvariables", "\n".join(variables))
    _text(el, "specificfeedback", "".join(f"<p>{f}</p>" for f in feedback), format="html")
    _text(el, "questionnote", "", format="html")
    _text(el, "questiondescription", "", format="html")
    for tag, value in (("questionsimplify", "1"), ("assumepositive", "0"), ("assumereal", "1")):
        _leaf(el, tag, value)
    _text(el, "prtcorrect", "Correct answer, well done.", format="html")
    _text(el, "prtpartiallycorrect", "Your answer is partially correct.", format="html")
    _text(el, "prtincorrect", "Incorrect answer.", format="html")
    for tag, value in (
        ("decimals", "."),
        ("scientificnotation", "*10"),
        ("multiplicationsign", "dot"),
        ("sqrtsign", "1"),
        ("complexno", "i"),
        ("inversetrig", "cos-1"),
        ("logicsymbol", "lang"),
        ("matrixparens", "["),
        ("variantsselectionseed", ""),
    ):
        _leaf(el, tag, value)
    for name, kind, tans, size in inputs:
        _stack_input(el, name, kind, tans, size)
    for prt in prts:
        _stack_prt(el, *prt)


def moodle_xml(title: str, questions: Sequence[LmsQuestion]) -> str:
    """The Moodle XML of a sheet's questions (see the module's docstring), in sheet order, each problem's
    variants in variant order; byte-identical for the same questions."""
    quiz = ET.Element("quiz")
    _category(quiz, category_path(title), f"<p>{inert(html.escape(title))}: exported by tutgen.</p>")
    seen: set[str] = set()
    for q in questions:
        if q.problem not in seen:
            seen.add(q.problem)
            name = f"Problem {q.number:02d}. {q.title}"
            info = "<p>One question per variant: add a random question from this category to the quiz.</p>"
            _category(quiz, category_path(title, name), info)
        if not q.parts:
            continue
        if all(p.numeric for p in q.parts):
            if len(q.parts) == 1 and q.parts[0].shape == "scalar":
                _numerical(quiz, q)
            else:
                _cloze(quiz, q)
        else:
            _stack(quiz, q)
    ET.indent(quiz, space="  ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(quiz, encoding="unicode") + "\n"
