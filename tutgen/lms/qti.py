"""An IMS QTI 2.1 package (``tutgen sheet -f qti``): a zip with ``imsmanifest.xml``, one
``assessmentItem`` per problem and variant, and an ``assessmentTest`` that draws one variant of each
problem (a section per problem, ``<selection select="1"/>``).

QTI 2.1 has numeric responses but no algebraic ones, so an item holds a problem's numeric results only,
each entry a ``textEntryInteraction`` of base type float, scored with ``equal`` within the instructor's
absolute tolerance; a graded result with an expression in it cannot be expressed and is left out whole,
named in the notes the export returns (never exported as a string to match). A problem with no
numeric result has no item.
The worked solution is the item's ``modalFeedback``, the figure an SVG file of the package.

Deterministic: entries in sorted order, every entry's time fixed (1980-01-01), no randomness.
"""

from __future__ import annotations

import io
import re
import xml.etree.ElementTree as ET
import zipfile
from collections.abc import Sequence

from tutgen.lms.html import markdown_html
from tutgen.lms.moodle import number_text
from tutgen.lms.questions import LmsQuestion, Part

QTI_NS = "http://www.imsglobal.org/xsd/imsqti_v2p1"
CP_NS = "http://www.imsglobal.org/xsd/imscp_v1p1"
XSI_NS = "http://www.w3.org/2001/XMLSchema-instance"
QTI_XSD = "http://www.imsglobal.org/xsd/qti/qtiv2p1/imsqti_v2p1.xsd"
CP_XSD = "http://www.imsglobal.org/xsd/qti/qtiv2p1/qtiv2p1_imscpv1p2_v1p0.xsd"

#: The attributes QTI's XHTML subset allows on what markdown-it writes (``style`` is not among them).
_ATTRS = {"src", "alt", "href", "class", "id", "label", "width", "height"}
_ZIP_TIME = (1980, 1, 1, 0, 0, 0)


def _q(tag: str) -> str:
    return f"{{{QTI_NS}}}{tag}"


def ident(text: str) -> str:
    """A QTI identifier (an XML NCName) from a problem key and a variant id."""
    text = re.sub(r"[^A-Za-z0-9._-]", "_", text)
    return text if re.match(r"[A-Za-z_]", text) else f"I-{text}"


def _xhtml(fragment: str) -> list[ET.Element]:
    """An HTML fragment of :func:`markdown_html` as QTI elements (its XHTML subset: no ``style``)."""
    root = ET.fromstring(f"<div>{fragment}</div>")
    for el in root.iter():
        el.tag = _q(el.tag)
        for name in list(el.attrib):
            if name not in _ATTRS:
                del el.attrib[name]
    return list(root)


def _sub(parent: ET.Element, tag: str, attrs: dict[str, str] | None = None, text: str | None = None) -> ET.Element:
    el = ET.SubElement(parent, _q(tag), attrs or {})
    if text is not None:
        el.text = text
    return el


def _entries(part: Part) -> list[tuple[float, float]]:
    v, t = part.value, part.tolerance
    if part.shape == "scalar":
        return [(v, t)]
    if part.shape == "list":
        return list(zip(v, t, strict=True))
    return [(e, te) for row, trow in zip(v, t, strict=True) for e, te in zip(row, trow, strict=True)]


def item_xml(q: LmsQuestion, parts: Sequence[Part], figure_href: str) -> str:
    """One ``assessmentItem``: the question, an input per numeric entry, the worked solution."""
    who = f" ({q.label})" if q.label else ""
    item = ET.Element(
        _q("assessmentItem"),
        {
            f"{{{XSI_NS}}}schemaLocation": f"{QTI_NS} {QTI_XSD}",
            "identifier": ident(q.ident),
            "title": f"Problem {q.number}{who}: {q.title}",
            "adaptive": "false",
            "timeDependent": "false",
        },
    )
    responses: list[tuple[str, float, float]] = []
    for part in parts:
        for value, tol in _entries(part):
            responses.append((f"RESPONSE_{len(responses) + 1}", value, tol))
    for rid, value, _ in responses:
        decl = _sub(item, "responseDeclaration", {"identifier": rid, "cardinality": "single", "baseType": "float"})
        _sub(_sub(decl, "correctResponse"), "value", text=number_text(value))
    for name, default in (("SCORE", "0"), ("MAXSCORE", str(len(responses)))):
        decl = _sub(item, "outcomeDeclaration", {"identifier": name, "cardinality": "single", "baseType": "float"})
        _sub(_sub(decl, "defaultValue"), "value", text=default)
    _sub(item, "outcomeDeclaration", {"identifier": "FEEDBACK", "cardinality": "single", "baseType": "identifier"})
    body = _sub(item, "itemBody")
    question = markdown_html(q.question_md, figure_src=figure_href)
    _sub(body, "div", {"class": "tutgen-question"}).extend(_xhtml(question))
    n = 0
    for part in parts:
        dims = "1" if part.shape == "scalar" else str(len(part.value))
        if part.shape == "matrix":
            dims = f"{len(part.value)}x{len(part.value[0])}"
        box = _sub(body, "div", {"class": f"tutgen-part tutgen-shape-{dims}", "label": part.label})
        p = _sub(box, "p")
        _sub(p, "code", text=part.label)
        p[-1].tail = " ="
        cells = []
        for _ in _entries(part):
            n += 1
            cells.append({"responseIdentifier": f"RESPONSE_{n}", "expectedLength": "12"})
        if part.shape == "matrix":
            cols = len(part.value[0])
            tbody = _sub(_sub(box, "table", {"class": "tutgen-matrix"}), "tbody")
            for i in range(0, len(cells), cols):
                tr = _sub(tbody, "tr")
                for cell in cells[i : i + cols]:
                    _sub(_sub(tr, "td"), "textEntryInteraction", cell)
        else:
            row = _sub(box, "p")
            for cell in cells:
                _sub(row, "textEntryInteraction", cell)
    rp = _sub(item, "responseProcessing")
    for rid, _, tol in responses:
        cond = _sub(_sub(rp, "responseCondition"), "responseIf")
        eq = _sub(cond, "equal", {"toleranceMode": "absolute", "tolerance": f"{number_text(tol)} {number_text(tol)}"})
        _sub(eq, "variable", {"identifier": rid})
        _sub(eq, "correct", {"identifier": rid})
        add = _sub(_sub(cond, "setOutcomeValue", {"identifier": "SCORE"}), "sum")
        _sub(add, "variable", {"identifier": "SCORE"})
        _sub(add, "baseValue", {"baseType": "float"}, "1")
    show = _sub(rp, "setOutcomeValue", {"identifier": "FEEDBACK"})
    _sub(show, "baseValue", {"baseType": "identifier"}, "SOLUTION")
    fb = _sub(
        item,
        "modalFeedback",
        {"outcomeIdentifier": "FEEDBACK", "identifier": "SOLUTION", "showHide": "show", "title": "Worked solution"},
    )
    _sub(fb, "div", {"class": "tutgen-solution"}).extend(_xhtml(markdown_html(q.feedback_md)))
    return _document(item)


def _document(root: ET.Element) -> str:
    ET.register_namespace("", QTI_NS)
    ET.register_namespace("xsi", XSI_NS)
    ET.indent(root, space="  ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def omitted_items(q: LmsQuestion) -> list[str]:
    """The graded items (result keys) QTI 2.1 cannot hold: those with an expression in any part. An
    item is exported whole or not at all, so that a question never asks the zero Christoffel symbols
    and leaves out the others."""
    out: list[str] = []
    for p in q.parts:
        if not p.numeric and p.path[0] not in out:
            out.append(p.path[0])
    return out


def qti_package(title: str, questions: Sequence[LmsQuestion]) -> tuple[bytes, list[str]]:
    """The zip of a sheet's questions (see the module's docstring), and the notes naming what was left
    out: per problem, the graded results with an expression in them (in every variant or in some)."""
    files: dict[str, str | bytes] = {}
    resources: list[tuple[str, str, list[str]]] = []
    sections: dict[str, tuple[str, list[tuple[str, str]]]] = {}
    left: dict[str, dict[str, list[str]]] = {}
    for q in questions:
        omitted = omitted_items(q)
        parts = [p for p in q.parts if p.path[0] not in omitted]
        for key in omitted:
            left.setdefault(q.problem, {}).setdefault(key, []).append(q.variant)
        if not parts:
            continue
        rid = ident(q.ident)
        href = f"items/{rid}.xml"
        deps = [href]
        figure_href = ""
        if q.figure is not None:
            figure_href = f"figures/{rid}.svg"
            files[f"items/{figure_href}"] = q.figure[1]
            deps.append(f"items/{figure_href}")
        files[href] = item_xml(q, parts, figure_href)
        resources.append((rid, href, deps))
        name = f"Problem {q.number}. {q.title}"
        sections.setdefault(q.problem, (name, []))[1].append((rid, href))
    files["assessment.xml"] = _test(title, sections)
    files["imsmanifest.xml"] = _manifest(resources)
    notes = []
    for problem, labels in left.items():
        counts = {len(v) for v in labels.values()}
        which = "every variant" if len(counts) == 1 else "some variants"
        notes.append(f"qti: left out of {problem} ({which}; QTI 2.1 has no algebraic answers): " + ", ".join(labels))
    return _zip(files), notes


def _test(title: str, sections: dict[str, tuple[str, list[tuple[str, str]]]]) -> str:
    test = ET.Element(
        _q("assessmentTest"),
        {f"{{{XSI_NS}}}schemaLocation": f"{QTI_NS} {QTI_XSD}", "identifier": "tutgen-sheet", "title": title},
    )
    part = _sub(
        test, "testPart", {"identifier": "sheet", "navigationMode": "nonlinear", "submissionMode": "simultaneous"}
    )
    for problem, (name, refs) in sections.items():
        sec = _sub(part, "assessmentSection", {"identifier": ident(f"S-{problem}"), "title": name, "visible": "true"})
        _sub(sec, "selection", {"select": "1"})  # one variant of each problem per student
        for rid, href in refs:
            _sub(sec, "assessmentItemRef", {"identifier": rid, "href": href})
    return _document(test)


def _manifest(resources: Sequence[tuple[str, str, list[str]]]) -> str:
    def c(tag: str) -> str:
        return f"{{{CP_NS}}}{tag}"

    m = ET.Element(c("manifest"), {"identifier": "tutgen-manifest", f"{{{XSI_NS}}}schemaLocation": f"{CP_NS} {CP_XSD}"})
    meta = ET.SubElement(m, c("metadata"))
    ET.SubElement(meta, c("schema")).text = "QTIv2.1 Package"
    ET.SubElement(meta, c("schemaversion")).text = "1.0.0"
    ET.SubElement(m, c("organizations"))
    res = ET.SubElement(m, c("resources"))
    t = ET.SubElement(
        res, c("resource"), {"identifier": "tutgen-test", "type": "imsqti_test_xmlv2p1", "href": "assessment.xml"}
    )
    ET.SubElement(t, c("file"), {"href": "assessment.xml"})
    for rid, _, _ in resources:
        ET.SubElement(t, c("dependency"), {"identifierref": rid})
    for rid, href, deps in resources:
        r = ET.SubElement(res, c("resource"), {"identifier": rid, "type": "imsqti_item_xmlv2p1", "href": href})
        for dep in deps:
            ET.SubElement(r, c("file"), {"href": dep})
    ET.register_namespace("", CP_NS)
    ET.register_namespace("xsi", XSI_NS)
    ET.indent(m, space="  ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(m, encoding="unicode") + "\n"


def _zip(files: dict[str, str | bytes]) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        for name in sorted(files):
            info = zipfile.ZipInfo(name, date_time=_ZIP_TIME)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            info.create_system = 3
            data = files[name]
            zf.writestr(info, data.encode("utf-8") if isinstance(data, str) else data)
    return buf.getvalue()
