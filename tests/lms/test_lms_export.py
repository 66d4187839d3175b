"""The LMS exports as their importers read them: Moodle XML (the elements of moodle/moodle's
question/format/xml/format.php and of qtype_stack's questions), the QTI 2.1 package (manifest, items,
test); hostile text inert in both; the same bytes on every build; what QTI cannot hold named; and the
round trip: the answers read back out of both exports are marked correct by the check (tests/lms/roundtrip.py)."""

from __future__ import annotations

import base64
import html
import io
import re
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.lms.conftest import HOSTILE, TUTORIAL, build
from tests.lms.roundtrip import mark, write_tree
from tutgen.lms.qti import QTI_NS
from tutgen.lms.readback import qti_answers

#: The text formats format.php's trans_format knows.
FORMATS = {"html", "moodle_auto_format", "plain_text", "markdown"}
#: The question types format.php imports itself, and STACK's (imported by its plugin).
TYPES = {"category", "cloze", "numerical", "stack"}
#: A Cloze NUMERICAL sub-question as qtype_multianswer reads it: {weight:NUMERICAL:=answer:tolerance}.
CLOZE = re.compile(r"\{(\d+):NUMERICAL:=(-?\d+(?:\.\d+)?):(\d+(?:\.\d+)?)\}")
#: Any Cloze marker at all (qtype_multianswer's question-type names).
ANY_CLOZE = re.compile(r"\{\d*:(?:NUMERICAL|SHORTANSWER|MULTICHOICE|MC|SA|NM)", re.I)
NUMBER = re.compile(r"-?\d+(?:\.\d+)?")


def questions(xml_text: str) -> list[ET.Element]:
    return list(ET.fromstring(xml_text).iter("question"))


def texts(q: ET.Element) -> list[str]:
    """Every text of a question as the importer stores it (names, the category path, HTML)."""
    return [el.text or "" for el in q.iter("text")]


def test_moodle_xml_has_the_elements_the_importer_reads(mini: dict[str, Any]) -> None:
    qs = questions(mini["questions-moodle.xml"])
    assert qs[0].get("type") == "category"
    kinds: dict[str, int] = {}
    for q in qs:
        kind = q.get("type") or ""
        assert kind in TYPES
        kinds[kind] = kinds.get(kind, 0) + 1
        if kind == "category":
            path = q.findtext("category/text") or ""
            assert path.startswith("$course$/top/Mini ")
            assert "a//b" in path  # a slash in the sheet's title is not a sub-category
            continue
        assert q.findtext("name/text"), "import_headers refuses a question without a name"
        for field in ("questiontext", "generalfeedback"):
            el = q.find(field)
            assert el is not None and el.get("format") in FORMATS and el.findtext("text")
        ident = q.findtext("idnumber") or ""
        assert re.fullmatch(r"p\d\d-[a-z-]+--v00[12]|hostile-pendulum--v00[12]", ident), ident
        text = q.findtext("questiontext/text") or ""
        for f in q.findall("questiontext/file"):
            assert f.get("encoding") == "base64" and f.get("path") == "/"
            svg = base64.b64decode(f.text or "", validate=True).decode("utf-8")
            assert "<svg" in svg
            assert f'src="@@PLUGINFILE@@/{f.get("name")}"' in text
        if kind == "cloze":
            found = CLOZE.findall(text)
            assert found and len(found) == len(ANY_CLOZE.findall(text))
        if kind == "stack":
            names = [i.findtext("name") for i in q.iter("input")]
            variables = {
                line.split(":")[0] for line in (q.findtext("questionvariables/text") or "").splitlines() if line
            }
            for name in names:
                assert text.count(f"[[input:{name}]]") == 1 and text.count(f"[[validation:{name}]]") == 1
            assert len(re.findall(r"\[\[input:", text)) == len(names)
            feedback = q.findtext("specificfeedback/text") or ""
            for prt in q.iter("prt"):
                node = prt.find("node")
                assert node is not None
                assert f"[[feedback:{prt.findtext('name')}]]" in feedback
                assert node.findtext("sans") in names and node.findtext("tans") in variables
                assert node.findtext("answertest") in ("AlgEquiv", "NumAbsolute")
                if node.findtext("answertest") == "NumAbsolute":
                    assert NUMBER.fullmatch(node.findtext("testoptions") or "")
    # problem 1 is numbers only (core Cloze); 2, 3 and the pendulum have expressions (STACK)
    assert kinds == {"category": 5, "cloze": 2, "stack": 6}


def test_moodle_numbers_carry_the_instructors_tolerance(mini: dict[str, Any]) -> None:
    q = next(q for q in questions(mini["questions-moodle.xml"]) if q.get("type") == "cloze")
    for _, value, tol in CLOZE.findall(q.findtext("questiontext/text") or ""):
        v, t = float(value), float(tol)
        # the marking key's 4 significant figures: half a unit of the 4th figure (1e-12 for a zero)
        assert t == pytest.approx(0.5 * 10 ** (int(f"{abs(v):e}".split("e")[1]) - 3)) if v else t <= 1e-9


def _qti(mini: dict[str, Any]) -> zipfile.ZipFile:
    return zipfile.ZipFile(io.BytesIO(mini["questions-qti.zip"]))


def test_qti_package_manifest_items_and_test(mini: dict[str, Any]) -> None:
    zf = _qti(mini)
    names = zf.namelist()
    assert names == sorted(names) and "imsmanifest.xml" in names and "assessment.xml" in names
    assert {i.date_time for i in zf.infolist()} == {(1980, 1, 1, 0, 0, 0)}
    cp = "{http://www.imsglobal.org/xsd/imscp_v1p1}"
    manifest = ET.fromstring(zf.read("imsmanifest.xml"))
    assert manifest.findtext(f"{cp}metadata/{cp}schema") == "QTIv2.1 Package"
    listed = {f.get("href") for f in manifest.iter(f"{cp}file")}
    assert listed == set(names) - {"imsmanifest.xml"}  # every file is a resource's, and there is nothing else
    ids = [r.get("identifier") or "" for r in manifest.iter(f"{cp}resource")]
    assert len(ids) == len(set(ids)) and all(re.fullmatch(r"[A-Za-z_][\w.-]*", i) for i in ids)
    items = [r for r in manifest.iter(f"{cp}resource") if r.get("type") == "imsqti_item_xmlv2p1"]
    for res in items:
        item = ET.fromstring(zf.read(res.get("href") or ""))
        assert item.tag == f"{{{QTI_NS}}}assessmentItem" and item.get("identifier") == res.get("identifier")
        declared = {d.get("identifier") for d in item.iter(f"{{{QTI_NS}}}responseDeclaration")}
        used = [i.get("responseIdentifier") for i in item.iter(f"{{{QTI_NS}}}textEntryInteraction")]
        assert used and sorted(used) == sorted(declared)
        for d in item.iter(f"{{{QTI_NS}}}responseDeclaration"):
            assert d.get("baseType") == "float"
            assert NUMBER.fullmatch(d.findtext(f"{{{QTI_NS}}}correctResponse/{{{QTI_NS}}}value") or "")
        # the XSD's order of an item's children
        order = [child.tag.split("}")[1] for child in item]
        rank = ["responseDeclaration", "outcomeDeclaration", "itemBody", "responseProcessing", "modalFeedback"]
        assert [rank.index(t) for t in order] == sorted(rank.index(t) for t in order)
        for el in item.iter():
            assert "style" not in el.attrib  # not in QTI's XHTML subset
    test = ET.fromstring(zf.read("assessment.xml"))
    sections = list(test.iter(f"{{{QTI_NS}}}assessmentSection"))
    # problems 1 and 2 have numbers; 3 and the pendulum none: no item, and named in the notes
    assert [s.get("title") for s in sections][:1] == ["Problem 1. Mass moments of inertia of a composite body"]
    assert len(sections) == 2
    for s in sections:
        assert s.find(f"{{{QTI_NS}}}selection").get("select") == "1"  # type: ignore[union-attr]
        assert len(s.findall(f"{{{QTI_NS}}}assessmentItemRef")) == 2


def test_qti_names_what_it_leaves_out(mini: dict[str, Any]) -> None:
    notes = mini["notes"]
    p02 = next(n for n in notes if "p02-pivoted-rod" in n)
    assert p02.endswith("): kinetic_energy")  # the expression; its inertia tensor (numbers) is in the item
    p03 = next(n for n in notes if "p03-cart-pendulum" in n)
    assert p03.endswith(
        "): positions, velocities, kinetic_energy, potential_energy, lagrange_terms, equations_of_motion"
    )
    assert not any("p01" in n for n in notes)


def test_qti_leaves_out_a_result_that_is_partly_an_expression(tmp_path: Path) -> None:
    # problem 7's Christoffel symbols are zero but for six: the zeros alone are not asked
    files = build(f"title: Seven\nproblems:\n  - {TUTORIAL / 'p07-belt-driven-arm.yaml'}\n", tmp_path, 0, ("qti",))
    assert files["notes"][0].endswith(", christoffel")
    assert qti_answers(files["questions-qti.zip"]) == {}  # nothing of it is numeric: no item


HOSTILE_BITS = ("<img src=x", "<script", "<iframe", "<svg", "<b>")


def test_moodle_hostile_text_is_inert(mini: dict[str, Any]) -> None:
    for q in questions(mini["questions-moodle.xml"]):
        for text in texts(q):
            # the HTML as stored: user markup only ever as escaped text, no importer marker from it
            for tag in re.findall(r"<(\w+)", text):
                assert tag in {
                    "p",
                    "h2",
                    "h3",
                    "strong",
                    "em",
                    "code",
                    "img",
                    "div",
                    "table",
                    "thead",
                    "tbody",
                    "tr",
                    "th",
                    "td",
                    "ul",
                    "li",
                }
            for bit in HOSTILE_BITS:
                assert bit not in text
            assert not ANY_CLOZE.search(text.replace("NUMERICAL:=", "")) or q.get("type") == "cloze"
            assert "{@" not in text and "{#" not in text  # STACK's CAS text
            assert text.count("@@PLUGINFILE@@") == len(re.findall(r'src="@@PLUGINFILE@@/[\w.-]+\.svg"', text))
            assert re.sub(r'<img src="@@PLUGINFILE@@/[\w.-]+\.svg" alt="[^"<>]*" />', "", text).count("<img") == 0
    stack = next(q for q in questions(mini["questions-moodle.xml"]) if (q.findtext("idnumber") or "").startswith("hos"))
    shown = html.unescape(stack.findtext("questiontext/text") or "")  # what a browser shows: the text as written
    assert "{1:NUMERICAL:=0:1}" in shown and "[[input:ans1]] [[feedback:prt1]]" in shown


def test_qti_hostile_text_is_inert(mini: dict[str, Any]) -> None:
    zf = _qti(mini)
    for name in zf.namelist():
        if not name.endswith(".xml"):
            continue
        root = ET.fromstring(zf.read(name))
        for el in root.iter():
            tag = el.tag.split("}")[1]
            assert tag not in {"script", "iframe", "svg", "b"}
            assert not any(a.startswith("on") for a in el.attrib)
            if tag == "img":
                assert re.fullmatch(r"figures/[\w.-]+\.svg", el.get("src") or "")


def test_exports_are_byte_identical_across_builds(tmp_path: Path, mini: dict[str, Any]) -> None:
    sheet = f"title: Mini\nproblems:\n  - spec: {TUTORIAL / 'p01-composite-inertia.yaml'}\n  - {HOSTILE}\n"
    first = build(sheet, tmp_path, 1)
    second = build(sheet, tmp_path, 1)
    for name in ("questions-moodle.xml", "questions-qti.zip"):
        assert first[name] == second[name]
    assert first["questions-qti.zip"] != mini["questions-qti.zip"]  # not a constant


def test_nominal_sheet_exports_one_question_per_problem(tmp_path: Path) -> None:
    sheet = f"title: One\nproblems:\n  - {TUTORIAL / 'p01-composite-inertia.yaml'}\n"
    files = build(sheet, tmp_path, 0, ("md", "moodle"))
    assert "questions.md" in files and "questions-qti.zip" not in files
    idents = [q.findtext("idnumber") for q in questions(files["questions-moodle.xml"]) if q.get("type") != "category"]
    assert idents == ["p01-composite-inertia--nominal"]


def test_roundtrip_answers_read_back_are_marked_correct(mini: dict[str, Any], tmp_path: Path) -> None:
    write_tree(mini, tmp_path)
    results = mark(tmp_path, mini)
    assert [r for r in results if r[2] != "pass"] == []
    assert len([r for r in results if r[0] == "moodle"]) == 8  # 4 problems x 2 variants
    assert {r[1] for r in results if r[0] == "qti"} == {
        f"{p}--{v}" for p in ("p01-composite-inertia", "p02-pivoted-rod") for v in ("v001", "v002")
    }


def test_roundtrip_a_wrong_number_is_marked_wrong(mini: dict[str, Any], tmp_path: Path) -> None:
    from tutgen.check.run import load_reference, mark_file

    write_tree(mini, tmp_path)
    answers = qti_answers(mini["questions-qti.zip"])["p01-composite-inertia--v001"]
    answers["inertia_tensor"][0][0] = str(float(answers["inertia_tensor"][0][0]) * 1.01)
    path = tmp_path / "wrong.yaml"
    path.write_text(yaml.safe_dump(answers), encoding="utf-8")
    ref = load_reference(tmp_path / "variants/v001/specs/p01-composite-inertia.yaml")
    assert mark_file(ref, path).status == "fail"


def test_cli_sheet_writes_the_exports_and_names_what_qti_leaves_out(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from tutgen.cli.main import app

    sheet = tmp_path / "sheet.yaml"
    sheet.write_text(f"title: Two\nproblems:\n  - {TUTORIAL / 'p02-pivoted-rod.yaml'}\n", encoding="utf-8")
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["sheet", str(sheet), "-o", str(out), "-f", "moodle", "-f", "qti", "-n", "1"])
    assert result.exit_code == 0, result.output
    assert (out / "questions-moodle.xml").is_file() and (out / "questions-qti.zip").is_file()
    assert (
        "note: qti: left out of p02-pivoted-rod (every variant; QTI 2.1 has no algebraic answers): kinetic_energy"
        in (result.output)
    )
    assert "Traceback" not in result.output
