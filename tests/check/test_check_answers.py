"""Reading answers files: key paths, reserved keys, tolerances, and located errors."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from tests.check.helpers import errors, mark_text, tutorial, verdicts
from tutgen.check.answers import MSG_NO_TOLERANCE, RESULT_KEYS, Tolerance, parse_key, read_answers
from tutgen.check.compare import Status
from tutgen.errors import SpecErrors


@pytest.mark.parametrize(
    ("key", "segments"),
    [
        pytest.param("mass_matrix", ("mass_matrix",), id="name"),
        pytest.param("mass_matrix[1,2]", ("mass_matrix", (1, 2)), id="matrix-entry"),
        pytest.param("mass_matrix[1, 2]", ("mass_matrix", (1, 2)), id="spaces-in-index"),
        pytest.param("christoffel[1,1,2]", ("christoffel", (1, 1, 2)), id="christoffel-entry"),
        pytest.param("lagrange_terms[2].dL_dq", ("lagrange_terms", (2,), "dL_dq"), id="bracket-then-name"),
        pytest.param("lagrange_terms.2.dL_dq", ("lagrange_terms", (2,), "dL_dq"), id="dotted-index"),
        pytest.param("lagrange_terms.theta2.dL_dq", ("lagrange_terms", "theta2", "dL_dq"), id="coordinate-name"),
        pytest.param(
            "bodies.body.inertia_tensor[3,3]", ("bodies", "body", "inertia_tensor", (3, 3)), id="nested-dotted"
        ),
    ],
)
def test_answers_parse_key(key: str, segments: tuple) -> None:
    assert parse_key(key) == segments


@pytest.mark.parametrize(
    ("key", "message"),
    [
        pytest.param("mass_matrix[0,1]", "indices start at 1", id="zero-index"),
        pytest.param("mass_matrix[a]", "'[a]' is not an index", id="name-index"),
        pytest.param("christoffel.1,1,2", "'1,1,2' is not a name or an index", id="dotted-christoffel"),
        pytest.param("mass_matrix..x", "'' is not a name or an index", id="empty-part"),
        pytest.param("[1]", "a key starts with a result name", id="index-first"),
    ],
)
def test_answers_parse_key_rejects(key: str, message: str) -> None:
    with pytest.raises(ValueError) as info:
        parse_key(key)
    assert message in str(info.value)


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "answers.yaml"
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def test_answers_read_reserved_keys_and_items(tmp_path: Path) -> None:
    sheet = read_answers(
        write(
            tmp_path,
            """\
            spec: specs/tutorial-1/p04-rp-arm.yaml
            student: Ada
            kinetic_energy: "m*r**2*theta_dot**2/2 + m*r_dot**2/2"
            mass_matrix[2,2]: m
            """,
        )
    )
    assert (sheet.student, sheet.spec) == ("Ada", "specs/tutorial-1/p04-rp-arm.yaml")
    assert sheet.tolerance == Tolerance()
    assert [(i.key, i.location.line, i.location.col) for i in sheet.items] == [
        ("kinetic_energy", 3, 1),
        ("mass_matrix[2,2]", 4, 1),
    ]
    assert sheet.errors == ()


def test_answers_read_keeps_numbers_as_written(tmp_path: Path) -> None:
    sheet = read_answers(write(tmp_path, "inertia_tensor: [[1.0e-2, 2.530e-2, 0.0]]\n"))
    assert [sheet.raw_number(("inertia_tensor", 0, i), v) for i, v in enumerate((0.01, 0.0253, 0.0))] == [
        "1.0e-2",
        "2.530e-2",
        "0.0",
    ]


def test_answers_read_not_a_mapping(tmp_path: Path) -> None:
    with pytest.raises(SpecErrors) as info:
        read_answers(write(tmp_path, "- kinetic_energy\n"))
    message = "answers.yaml:1:1: error: expected a mapping of result keys to answers, found a list"
    assert str(info.value).endswith(message)


def test_answers_read_yaml_syntax_error_is_located(tmp_path: Path) -> None:
    with pytest.raises(SpecErrors) as info:
        read_answers(write(tmp_path, 'kinetic_energy: "m*r\n'))
    assert "answers.yaml:2:1: error:" in str(info.value)


def test_answers_read_missing_file(tmp_path: Path) -> None:
    with pytest.raises(SpecErrors) as info:
        read_answers(tmp_path / "nope.yaml")
    assert "nope.yaml: error: cannot read file" in str(info.value)


def test_answers_result_keys_are_the_json_contract() -> None:
    """Every result key tutgen writes is a key an answers file may use."""
    ref = tutorial(5)
    assert set(ref.results) <= set(RESULT_KEYS)


NO_TOLERANCE = MSG_NO_TOLERANCE


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param(
            "H: 1\n",
            [
                "answers.yaml:1:1: error: unknown result 'H'; expected one of: "
                + ", ".join(RESULT_KEYS)
                + "\n  hint: did you mean 'mass_matrix'?"
            ],
            id="textbook-letter",
        ),
        pytest.param(
            "tolerance: {rel_tol: 1e300}\n",
            ["answers.yaml:1:1: error: " + NO_TOLERANCE.format(key="tolerance")],
            id="file-tolerance-refused",
        ),
        pytest.param(
            "mass_matrix: {value: [[m, 0], [0, m]], rel_tol: 1e300}\n",
            ["answers.yaml:1:40: error: " + NO_TOLERANCE.format(key="rel_tol")],
            id="item-tolerance-refused",
        ),
        pytest.param(
            "mass_matrix: {value: [[m, 0], [0, m]], rounded: true}\nrel_tol: 1\n",
            [
                "answers.yaml:1:40: error: " + NO_TOLERANCE.format(key="rounded"),
                "answers.yaml:2:1: error: " + NO_TOLERANCE.format(key="rel_tol"),
            ],
            id="rounded-and-tolerance-key-refused",
        ),
        pytest.param(
            "mass_matrix: [[m, 0], [0, m]]\nmass_matrix[1,1]: m\n",
            [
                "answers.yaml:2:1: error: 'mass_matrix[1,1]' answers mass_matrix[1,1] again "
                "(already answered by 'mass_matrix'); each entry may be answered once"
            ],
            id="answered-twice-overlapping",
        ),
        pytest.param(
            "christoffel: {'1,1,2': 0, h112: 1}\n",
            ["answers.yaml:1:27: error: 'h112' answers christoffel[1,1,2] again (already answered as '1,1,2')"],
            id="answered-twice-in-a-table",
        ),
        pytest.param(
            "student: [a, b]\n",
            ["answers.yaml:1:10: error: 'student' must be a text, found a list"],
            id="student-not-text",
        ),
        pytest.param(
            "mass_matrix[3,1]: m\n",
            [
                "answers.yaml:1:1: error: cannot read the key 'mass_matrix[3,1]': mass_matrix has 2 entries; "
                "there is no entry [3]"
            ],
            id="index-out-of-range",
        ),
        pytest.param(
            "equations_of_motion: {theta: a = b = c, s: 0}\n",
            ["answers.yaml:1:41: error: equations_of_motion has no entry 's'; expected one of: theta, r"],
            id="equation-errors",
        ),
        pytest.param(
            "velocities: [1, 2]\n",
            ["answers.yaml:1:13: error: velocities is a table: expected a mapping of its entries (tip)"],
            id="not-a-table",
        ),
        pytest.param(
            "lagrange_terms.theta.dL_dq: 1\nlagrange_terms[1].dL_dq: 2\n",
            [
                "answers.yaml:2:1: error: 'lagrange_terms[1].dL_dq' answers lagrange_terms[1].dL_dq again "
                "(already answered by 'lagrange_terms.theta.dL_dq'); each entry may be answered once"
            ],
            id="answered-twice",
        ),
    ],
)
def test_answers_errors_are_located(text: str, expected: list[str]) -> None:
    assert errors(mark_text(tutorial(4), text)) == expected


@pytest.mark.parametrize(
    ("text", "entry", "feedback"),
    [
        pytest.param(
            "kinetic_energy: m*(r_dot**2\nmass_matrix: [[m*r**2, 0], [0, m]]\n",
            "kinetic_energy",
            "cannot read the answer: unclosed '(': expected ')', found the end of the text (at 1:19)",
            id="unclosed-parenthesis",
        ),
        pytest.param(
            "mass_matrix[1,1]: 2 kgg\nmass_matrix[2,2]: m\n",
            "mass_matrix[1,1]",
            "cannot read the answer: unknown unit 'kgg' (did you mean 'kg'?) (at 1:21)",
            id="unknown-unit",
        ),
        pytest.param(
            "equations_of_motion: {theta: a = b = c}\nmass_matrix[2,2]: m\n",
            "equations_of_motion[1]",
            "cannot read the answer: an equation has one '=': write 'lhs = rhs' (at 1:36)",
            id="two-equals",
        ),
        pytest.param(
            "mass_matrix: [[m*r**2, 0], [0, true]]\n",
            "mass_matrix[2,2]",
            "cannot read the answer: expected an expression or a number, found true/false",
            id="boolean",
        ),
    ],
)
def test_answers_entry_that_does_not_parse_is_wrong_and_the_file_is_marked(
    text: str, entry: str, feedback: str
) -> None:
    """One entry that does not parse is wrong, with its parse error at its place; the other entries of
    the file are still marked (it used to make the whole file invalid, exit 3)."""
    result = mark_text(tutorial(4), text)
    marks = verdicts(result)
    folder = str(Path(result.path).parent) + "/"
    status, said = marks.pop(entry)
    assert (status, said.replace(folder, "")) == (Status.WRONG, feedback)
    assert marks and all(s is Status.CORRECT for s, _ in marks.values()), marks


def test_answers_result_not_derived_for_this_spec() -> None:
    found = errors(mark_text(tutorial(1), "christoffel: 0\n"))
    assert found == [
        "answers.yaml:1:1: error: cannot read the key 'christoffel': this spec has no result 'christoffel' "
        "(its spec does not ask for it)\n  hint: this spec's results are: bodies, mass, center_of_mass, "
        "inertia_tensor, principal_moments"
    ]
