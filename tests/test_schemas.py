"""The JSON Schemas of `tutgen schema --kind`: each a valid draft 2020-12 schema with its own $id, that
accepts every spec, sheet and solution JSON of this repository and refuses what the readers refuse."""

from __future__ import annotations

import copy
import json
from typing import Any

import jsonschema
import pytest
import yaml

from tests.conftest import HEAVY_SPECS, ROOT, SPECS, all_specs, solved
from tutgen.schemas import SCHEMAS, schema_id


def validator(kind: str) -> jsonschema.Draft202012Validator:
    return jsonschema.Draft202012Validator(SCHEMAS[kind]())


def errors(kind: str, doc: Any) -> list[str]:
    return [f"{'/'.join(map(str, e.absolute_path))}: {e.message}" for e in validator(kind).iter_errors(doc)]


@pytest.mark.parametrize("kind", sorted(SCHEMAS))
def test_each_schema_is_a_draft_2020_12_schema_with_its_own_id(kind: str) -> None:
    schema = SCHEMAS[kind]()
    jsonschema.Draft202012Validator.check_schema(schema)
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema["$id"] == schema_id(kind) and schema["$id"].startswith(f"urn:tutgen:schema:{kind}:")
    json.dumps(schema)  # plain JSON


@pytest.mark.parametrize("spec", all_specs(), ids=lambda p: p.stem)
def test_every_spec_of_the_repository_fits_the_spec_schema(spec: Any) -> None:
    assert errors("spec", yaml.safe_load(spec.read_text(encoding="utf-8"))) == []


def test_the_spec_schema_refuses_an_unknown_key() -> None:
    doc = yaml.safe_load((SPECS / "tutorial-1/p05-rr-arm.yaml").read_text(encoding="utf-8"))
    assert errors("spec", doc) == []
    assert errors("spec", {**doc, "bodys": {}}) != []


@pytest.mark.parametrize("sheet", sorted(SPECS.rglob("*sheet*.yaml")), ids=lambda p: p.stem)
def test_every_sheet_of_the_repository_fits_the_sheet_schema(sheet: Any) -> None:
    assert errors("sheet", yaml.safe_load(sheet.read_text(encoding="utf-8"))) == []


@pytest.mark.parametrize(
    "change",
    [
        {"titel": "T"},  # unknown key
        {"problems": []},  # no problem
        {"problems": [{"vary": {"m": 1}}]},  # a problem without its spec
        {"problems": [{"spec": "p.yaml", "vary": {"m": {"range": [1, 2], "choices": [1]}}}]},  # both
        {"tutgen_sheet": 2},
    ],
)
def test_the_sheet_schema_refuses_what_the_reader_refuses(change: dict[str, Any]) -> None:
    doc = yaml.safe_load((SPECS / "tutorial-1/sheet.yaml").read_text(encoding="utf-8"))
    assert errors("sheet", doc | change) != []


@pytest.mark.parametrize(
    "spec",
    # the numeric PUMA's JSON is built for this test alone (half a minute): with -m slow
    [pytest.param(p, marks=pytest.mark.slow) if p.stem == "puma560-numeric" else p for p in all_specs()
     if p.stem not in HEAVY_SPECS],
    ids=lambda p: p.stem,
)  # fmt: skip
def test_every_solution_json_fits_the_solution_schema(spec: Any) -> None:
    assert errors("solution", json.loads(json.dumps(solved(str(spec))[2].doc))) == []


@pytest.mark.parametrize(
    ("where", "value"),
    [(("format",), 2), (("results", "mass_matrix"), "m"), (("checks",), [{"name": "x"}]), (("coordinates",), [1])],
)
def test_the_solution_schema_refuses_a_broken_document(where: tuple[str, ...], value: Any) -> None:
    doc = copy.deepcopy(json.loads(json.dumps(solved(str(SPECS / "tutorial-1/p03-cart-pendulum.yaml"))[2].doc)))
    target = doc
    for key in where[:-1]:
        target = target[key]
    target[where[-1]] = value
    assert errors("solution", doc) != []


@pytest.mark.parametrize("kind", sorted(SCHEMAS))
def test_the_shipped_schema_files_are_up_to_date(kind: str) -> None:
    """schemas/KIND.schema.json, which the specs' editor line points at, is what `tutgen schema --kind`
    prints (after a schema change: `tutgen schema -k KIND > schemas/KIND.schema.json`)."""
    from tutgen.render.jsonout import dumps

    shipped = ROOT / "schemas" / f"{kind}.schema.json"
    assert shipped.read_text(encoding="utf-8") == dumps(SCHEMAS[kind]()), f"regenerate {shipped.name}"


@pytest.mark.parametrize("path", sorted(SPECS.rglob("*.yaml")), ids=lambda p: p.stem)
def test_every_example_names_its_schema_for_editors(path: Any) -> None:
    kind = "sheet" if "sheet" in path.stem else "spec"
    first = path.read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith("# yaml-language-server: $schema=")
    target = (path.parent / first.split("$schema=", 1)[1]).resolve()
    assert target == (ROOT / "schemas" / f"{kind}.schema.json").resolve()


# --- the answers file and the marking key ---

ANSWERS = sorted((ROOT / "tests" / "check" / "answers").glob("*-printed.yaml"))
KEYS = sorted((ROOT / "tests" / "check" / "answers").glob("*-key.yaml"))


def _yaml(path: Any) -> Any:
    return yaml.safe_load(path.read_text(encoding="utf-8"))


@pytest.mark.parametrize("path", ANSWERS, ids=lambda p: p.stem)
def test_every_answers_file_of_the_repository_fits_the_answers_schema(path: Any) -> None:
    assert errors("answers", _yaml(path)) == []


@pytest.mark.parametrize("path", KEYS, ids=lambda p: p.stem)
def test_every_marking_key_of_the_repository_fits_the_key_schema(path: Any) -> None:
    assert errors("key", _yaml(path)) == []


def _reader_refuses(reader: Any, text: str, tmp_path: Any) -> bool:
    """Whether the file's reader reports an error for ``text`` (raised, or kept for the marking)."""
    from tutgen.errors import SpecErrors

    path = tmp_path / "file.yaml"
    path.write_text(text, encoding="utf-8")
    try:
        read = reader(path)
    except SpecErrors:
        return True
    return bool(getattr(read, "errors", ()))


@pytest.mark.parametrize(
    "text",
    [
        "tolerance: {rel_tol: 0.5}\n",  # tolerances are the instructor's
        "rel_tol: 0.5\n",
        "H: [[m]]\n",  # a textbook letter, not a result key
        "mass_matrx: [[m]]\n",
        "student: true\n",
        "- kinetic_energy: m\n",  # not a mapping
    ],
    ids=["tolerance", "rel-tol", "letter", "misspelt", "student-bool", "list"],
)
def test_the_answers_schema_refuses_what_the_reader_refuses(text: str, tmp_path: Any) -> None:
    from tutgen.check.answers import read_answers

    assert _reader_refuses(read_answers, text, tmp_path)
    assert errors("answers", yaml.safe_load(text)) != []


def test_the_answers_schema_takes_the_forms_students_write(tmp_path: Any) -> None:
    from tutgen.check.answers import read_answers

    text = (
        "student: 1234\nspec: p05.yaml\nkinetic_energy: m*v**2/2\nmass_matrix[1,2]: 0\n"
        "lagrange_terms.theta.dL_dq: -m*g*l*sin(theta)\nequations_of_motion: {theta: 'tau = m*l**2*theta_ddot'}\n"
        "bodies.link1.inertia_tensor: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n"
    )
    assert not _reader_refuses(read_answers, text, tmp_path)
    assert errors("answers", yaml.safe_load(text)) == []
    assert errors("answers", None) == []  # an empty file answers nothing: every item missing


@pytest.mark.parametrize(
    "text",
    [
        "ask: []\n",
        "ask: [mass_matrx]\n",
        "tolerance: {rel_tol: -1}\n",
        "tolerance: {rel: 0.1}\n",
        "significant_figures: 16\n",
        "items: {mass_matrix: {scaling: maybe}}\n",
        "tolerances: {}\n",
    ],
    ids=["empty-ask", "unknown-ask", "negative", "unknown-tolerance", "figures", "scaling", "unknown-key"],
)
def test_the_key_schema_refuses_what_the_reader_refuses(text: str, tmp_path: Any) -> None:
    from tutgen.check.key import read_key

    assert _reader_refuses(read_key, text, tmp_path)
    assert errors("key", yaml.safe_load(text)) != []


# --- the JSON tutgen check and tutgen simulate write ---

P04 = SPECS / "tutorial-1" / "p04-rp-arm.yaml"


@pytest.fixture
def p04_check(monkeypatch: pytest.MonkeyPatch, tmp_path: Any) -> Any:
    """A real `tutgen check` of problem 4 (derived from the session cache) with a right, a wrong and an
    invalid answers file: its JSON report and JSON summary."""
    import tutgen.engine.pipeline
    from tutgen.check.report import render_json, render_summary
    from tutgen.check.run import check

    solved(str(P04))
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(system.source)[1])
    files = {
        "right.yaml": "student: Ada\nkinetic_energy: m*(r**2*theta_dot**2 + r_dot**2)/2\n",
        "wrong.yaml": "kinetic_energy: m*r**2*theta_dot**2/2\nmass_matrix: [[m*r^2, 0], [0, 2*m]]\n",
        "bad.yaml": "kinetic_energy: [\n",
    }
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    run = check(P04, [tmp_path / n for n in files], jobs=1)
    return json.loads(render_json(run)), json.loads(render_summary(run, "json"))


def test_the_check_report_and_summary_fit_their_schemas(p04_check: Any) -> None:
    report, summary = p04_check
    assert [f["status"] for f in report["files"]] == ["fail", "fail", "invalid"]  # every branch is there
    assert report["format"] == summary["format"] == 1
    assert errors("check", report) == []
    assert errors("summary", summary) == []


@pytest.mark.parametrize(
    ("where", "value"),
    [
        (("format",), 2),
        (("files", 0, "status"), "great"),
        (("files", 0, "items", 0, "entries", 0, "status"), "nearly"),
        (("summary", "files"), -1),
        (("files", 0, "counts", "correct"), "one"),
    ],
)
def test_the_check_schema_refuses_a_broken_report(p04_check: Any, where: tuple[Any, ...], value: Any) -> None:
    report = copy.deepcopy(p04_check[0])
    target = report
    for key in where[:-1]:
        target = target[key]
    target[where[-1]] = value
    assert errors("check", report) != []
    del report["format"]
    assert errors("check", report) != []


def test_the_simulation_json_fits_its_schema(monkeypatch: pytest.MonkeyPatch, tmp_path: Any) -> None:
    import tutgen.engine.pipeline
    from tutgen.sim.files import write_simulation
    from tutgen.sim.run import Settings

    spec = SPECS / "tutorial-1" / "p02-pivoted-rod.yaml"
    solved(str(spec))
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(system.source)[1])
    settings = Settings(values={}, q0={"theta": "10deg"}, qd0={}, t_end=0.5, samples=11, method="auto")
    write_simulation(spec, tmp_path, settings, plots=False, force=False)
    (path,) = tmp_path.glob("*.json")
    doc = json.loads(path.read_text(encoding="utf-8"))
    assert doc["format"] == 1 and errors("simulation", doc) == []
    assert errors("simulation", {**doc, "format": "1"}) != []
    assert errors("simulation", {**doc, "t": ["0"]}) != []
    assert errors("simulation", {k: v for k, v in doc.items() if k != "energy_check"}) != []


@pytest.mark.parametrize("kind", ["solution", "check", "summary", "simulation"])
def test_every_json_output_schema_requires_its_format_version(kind: str) -> None:
    schema = SCHEMAS[kind]()
    assert "format" in schema["required"]
    assert schema["properties"]["format"]["const"] == int(schema["$id"].rsplit(":", 1)[1])


def test_schema_kinds_are_the_commands_choices() -> None:
    from typer.testing import CliRunner

    from tutgen.cli.main import app

    for kind in SCHEMAS:
        result = CliRunner().invoke(app, ["schema", "--kind", kind])
        assert result.exit_code == 0 and json.loads(result.stdout)["$id"] == schema_id(kind)


# --- the spec schema carries the validator's semantic limits ---


def _p02() -> dict[str, Any]:
    return _yaml(SPECS / "tutorial-1" / "p02-pivoted-rod.yaml")


def _with(doc: dict[str, Any], *path_value: Any) -> dict[str, Any]:
    doc = copy.deepcopy(doc)
    *path, value = path_value
    target = doc
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = value
    return doc


@pytest.mark.parametrize(
    "doc",
    [
        pytest.param(_with(_p02(), "coordinates", [f"q{i}" for i in range(13)]), id="13-coordinates-list"),
        pytest.param(_with(_p02(), "coordinates", {f"q{i}": None for i in range(13)}), id="13-coordinates-map"),
        pytest.param(_with(_p02(), "parameters", "2m", {"value": 1}), id="name-starts-with-digit"),
        pytest.param(_with(_p02(), "parameters", "sin", {"value": 1}), id="name-is-a-function"),
        pytest.param(_with(_p02(), "parameters", "lambda", {"value": 1}), id="name-is-a-keyword"),
        pytest.param(_with(_p02(), "coordinates", ["theta_dot"]), id="name-is-a-rate"),
        pytest.param(_with(_p02(), "bodies", "ground", {"mass": "m"}), id="body-called-ground"),
        pytest.param(_with(_p02(), "bodies", "rod", "parts", "rod bar", {"shape": "point", "mass": "m"}), id="part"),
        pytest.param(_with(_p02(), "bodies", "rod", "mass", "m"), id="parts-and-mass"),
        pytest.param(_with(_p02(), "bodies", "rod", "parts", "rod", "density", 7800), id="mass-and-density"),
        pytest.param(
            _with(_yaml(SPECS / "tutorial-1" / "p10-given-kinetic-energy.yaml"), "bodies", {"b": {"mass": 1}}),
            id="energy-and-bodies",
        ),
        pytest.param(
            _with(_yaml(SPECS / "tutorial-1" / "p10-given-kinetic-energy.yaml"), "gravity", [0, -9.81, 0]),
            id="energy-and-gravity",
        ),
    ],
)
def test_the_spec_schema_refuses_what_the_validator_refuses(doc: dict[str, Any]) -> None:
    from tutgen.api import loads
    from tutgen.errors import SpecErrors

    with pytest.raises(SpecErrors):
        loads(yaml.safe_dump(doc, sort_keys=False))
    assert errors("spec", doc) != []


def test_the_spec_schema_takes_twelve_coordinates_and_plain_names() -> None:
    doc = _with(_p02(), "coordinates", {f"q{i}": None for i in range(12)})
    assert errors("spec", doc) == []
    assert errors("spec", _with(_p02(), "parameters", "theta_dot2", {"value": 1})) == []


@pytest.mark.slow  # a sheet with one variant: 6 s
def test_a_sheets_answer_keys_and_marking_keys_fit_their_schemas(tmp_path: Any) -> None:
    """What `tutgen sheet` writes for a variant: its spec, its answer key (an answers file that
    `tutgen check` marks right) and its marking key."""
    from typer.testing import CliRunner

    from tutgen.cli.main import app

    sheet = tmp_path / "sheet.yaml"
    sheet.write_text(
        f"title: One\nproblems:\n  - spec: {SPECS / 'tutorial-1' / 'p03-cart-pendulum.yaml'}\n"
        "    vary:\n      m1: {range: [1, 5], step: 0.5, unit: kg}\n",
        encoding="utf-8",
    )
    result = CliRunner().invoke(app, ["sheet", str(sheet), "-o", str(tmp_path / "out"), "-n", "1", "-j", "1", "-q"])
    assert result.exit_code == 0, result.output
    variant = tmp_path / "out" / "variants" / "v001"
    assert errors("answers", _yaml(variant / "key-p03-cart-pendulum.yaml")) == []
    assert errors("key", _yaml(variant / "marking-p03-cart-pendulum.yaml")) == []
    assert errors("spec", _yaml(variant / "specs" / "p03-cart-pendulum.yaml")) == []
