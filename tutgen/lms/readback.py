"""Reading the answers back out of an LMS export, as the importer would store them: the round trip.

:func:`moodle_answers` and :func:`qti_answers` return, per question (``problem--variant``), the
answers file (docs/check.md) that the export's correct answers make; ``tutgen check`` must mark it
correct against the variant's spec and marking key. Only what the importers read is used: Moodle's
STACK question variables, PRT answer notes and Cloze/numerical answers; QTI's correct responses. The
part each answer belongs to is the ``data-part`` (Moodle) or ``label`` (QTI) of the element around its
inputs, and a STACK answer note.
"""

from __future__ import annotations

import html
import io
import re
import xml.etree.ElementTree as ET
import zipfile
from typing import Any

from tutgen.lms.moodle import from_maxima
from tutgen.lms.qti import QTI_NS
from tutgen.lms.questions import answers_from, path_of

_ENTRY = re.compile(r"^(.*?)(?:\[(\d+)(?:,(\d+))?\])?$")
_PART = re.compile(r'data-part="([^"]*)" data-shape="([^"]*)"')
_CLOZE = re.compile(r"\{\d+:NUMERICAL:=([^:}]+):[^}]*\}")


def _shaped(values: list[str], shape: str) -> Any:
    if shape == "1":
        return values[0]
    if "x" in shape:
        rows, cols = (int(n) for n in shape.split("x"))
        return [values[i * cols : (i + 1) * cols] for i in range(rows)]
    return values


def _cloze_parts(text: str) -> dict[tuple[str, ...], Any]:
    out: dict[tuple[str, ...], Any] = {}
    marks = list(_PART.finditer(text))
    for i, m in enumerate(marks):
        end = marks[i + 1].start() if i + 1 < len(marks) else len(text)
        values = _CLOZE.findall(text[m.end() : end])
        out[path_of(html.unescape(m.group(1)))] = _shaped(values, m.group(2))
    return out


def _stack_parts(q: ET.Element) -> dict[tuple[str, ...], Any]:
    variables: dict[str, str] = {}
    for line in (q.findtext("questionvariables/text") or "").splitlines():
        name, _, value = line.partition(":")
        variables[name.strip()] = value.strip().rstrip(";")
    entries: dict[tuple[str, ...], dict[tuple[int, ...], str]] = {}
    out: dict[tuple[str, ...], Any] = {}
    for prt in q.iter("prt"):
        node = prt.find("node")
        assert node is not None
        note = (node.findtext("trueanswernote") or "").removesuffix("-T")
        value = variables[node.findtext("tans") or ""]
        m = _ENTRY.match(note)
        assert m is not None
        path = path_of(m.group(1))
        if node.findtext("answertest") == "NumAbsolute":
            index = tuple(int(g) for g in m.groups()[1:] if g)
            entries.setdefault(path, {})[index] = value
        else:
            out[path] = from_maxima(value)
    for path, found in entries.items():
        if () in found:
            out[path] = found[()]
        elif all(len(i) == 1 for i in found):
            out[path] = [found[(i,)] for i in range(1, len(found) + 1)]
        else:
            rows = max(i for i, _ in found)
            cols = max(j for _, j in found)
            out[path] = [[found[(i, j)] for j in range(1, cols + 1)] for i in range(1, rows + 1)]
    return out


def moodle_answers(xml_text: str) -> dict[str, dict[str, Any]]:
    """Per question idnumber, the answers file its correct answers make (see the module's docstring)."""
    root = ET.fromstring(xml_text)
    out: dict[str, dict[str, Any]] = {}
    for q in root.iter("question"):
        qtype = q.get("type")
        if qtype == "category":
            continue
        ident = q.findtext("idnumber") or ""
        if qtype == "stack":
            values = _stack_parts(q)
        elif qtype == "cloze":
            values = _cloze_parts(q.findtext("questiontext/text") or "")
        elif qtype == "numerical":
            m = _PART.search(q.findtext("questiontext/text") or "")
            assert m is not None
            values = {path_of(html.unescape(m.group(1))): q.findtext("answer/text")}
        else:
            raise ValueError(f"unexpected question type {qtype}")
        out[ident] = answers_from(values)
    return out


def qti_answers(package: bytes) -> dict[str, dict[str, Any]]:
    """Per item identifier, the answers file its correct responses make."""
    ns = {"q": QTI_NS}
    out: dict[str, dict[str, Any]] = {}
    with zipfile.ZipFile(io.BytesIO(package)) as zf:
        for name in sorted(n for n in zf.namelist() if n.startswith("items/") and n.endswith(".xml")):
            item = ET.fromstring(zf.read(name))
            correct = {
                d.get("identifier"): d.findtext("q:correctResponse/q:value", namespaces=ns)
                for d in item.findall("q:responseDeclaration", ns)
            }
            values: dict[tuple[str, ...], Any] = {}
            for box in item.iter(f"{{{QTI_NS}}}div"):
                classes = (box.get("class") or "").split()
                if "tutgen-part" not in classes:
                    continue
                shape = next(c for c in classes if c.startswith("tutgen-shape-")).removeprefix("tutgen-shape-")
                got = [correct[i.get("responseIdentifier")] for i in box.iter(f"{{{QTI_NS}}}textEntryInteraction")]
                values[path_of(box.get("label") or "")] = _shaped([str(v) for v in got], shape)
            out[item.get("identifier") or name] = answers_from(values)
    return out
