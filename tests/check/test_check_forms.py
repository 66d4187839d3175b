"""The table of answer forms and their verdicts in docs/check.md, each row a test: the docs cannot
drift from what `tutgen check` does."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.check.helpers import mark_text, reference
from tests.conftest import ROOT, SPECS

DOC = ROOT / "docs" / "check.md"
#: The spec names the table uses.
SPEC_OF = {
    "p01": SPECS / "tutorial-1" / "p01-composite-inertia.yaml",
    "p04": SPECS / "tutorial-1" / "p04-rp-arm.yaml",
    "p05": SPECS / "tutorial-1" / "p05-rr-arm.yaml",
    "rod": Path(__file__).parent / "specs" / "rod-variant.yaml",
}
_ROW = re.compile(r"\| (?P<spec>\w+) \| `(?P<answer>[^`]+)` \| (?P<verdict>\w+) \| (?P<says>.+) \|")


def table_rows() -> list[tuple[str, str, str, str]]:
    """(spec, answer, verdict, what the report says) of each row between the answer-forms markers."""
    text = DOC.read_text(encoding="utf-8")
    start = text.index("<!-- answer-forms:")
    block = text[start : text.index("<!-- /answer-forms -->", start)]
    rows = []
    for line in block.splitlines()[3:]:  # the marker, the header, the rule
        match = _ROW.fullmatch(line.strip())
        assert match, f"a row of the answer-forms table is not of the form | spec | `answer` | verdict | says |: {line}"
        rows.append((match["spec"], match["answer"], match["verdict"], match["says"].strip()))
    return rows


ROWS = table_rows()


def test_forms_table_has_every_kind_of_row() -> None:
    assert len(ROWS) >= 20
    assert {v for _, _, v, _ in ROWS} == {"correct", "wrong"}


@pytest.mark.parametrize(("spec", "answer", "verdict", "says"), ROWS, ids=[f"{s}:{a}" for s, a, _, _ in ROWS])
def test_forms_table_row(spec: str, answer: str, verdict: str, says: str) -> None:
    result = mark_text(reference(SPEC_OF[spec]), answer + "\n")
    assert not result.errors, result.errors
    (item,) = result.items
    said = [f"{e.name}: " + " ".join(t for t in (e.how, e.feedback) if t) for e in item.entries] + list(item.remarks)
    assert item.status.value == verdict, (item.status, said)
    assert any(says in text for text in said), (says, said)
