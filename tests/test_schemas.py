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
