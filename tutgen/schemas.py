"""JSON Schemas (draft 2020-12) of the files tutgen reads and writes: ``tutgen schema --kind KIND``.

- ``spec``: a problem spec (docs/spec-format.md), generated from the validator's own model
  (tutgen/spec/schema.py), so editors complete and check what the validator accepts;
- ``sheet``: a tutorial sheet file (docs/sheets.md), its keys taken from the sheet reader's;
- ``solution``: the JSON of ``tutgen solve --format json`` (docs/json-output.md), format 1;
- ``answers``: an answers file for ``tutgen check`` (docs/check.md), its keys the result keys;
- ``key``: the instructor's marking key (``tutgen check --key``, a sheet's ``marking-*.yaml``);
- ``check``: the JSON of ``tutgen check --format json``; ``summary``: of ``--summary FILE.json``;
- ``simulation``: the JSON trajectory ``tutgen simulate`` writes (docs/simulate.md).

Each has an ``$id`` of the form ``urn:tutgen:schema:KIND:VERSION`` (the version of that file's
format: a new version, a new ``$id``). Documents may carry keys a schema does not name (the JSON
contract adds keys without a format bump), so the output schemas leave objects open; the input schemas
are as strict as the readers are. A spec's semantic limits that JSON Schema cannot state (a name used
before it is declared, a dimension mismatch) are the validator's: ``tutgen solve`` reports them at
their file:line:col.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any

from tutgen.result_schemas import (
    CHECK,
    FIGURE,
    RESULTS,
    SIMULATION,
)

DIALECT = "https://json-schema.org/draft/2020-12/schema"

#: the format version of each kind of file (the number in its ``$id``; for an output, its ``format`` key)
VERSIONS = {"spec": 1, "sheet": 1, "solution": 1, "answers": 1, "key": 1, "check": 1, "summary": 1, "simulation": 1}


def schema_id(kind: str) -> str:
    return f"urn:tutgen:schema:{kind}:{VERSIONS[kind]}"


def _head(kind: str, title: str, description: str) -> dict[str, Any]:
    return {"$schema": DIALECT, "$id": schema_id(kind), "title": title, "description": description}


def spec_name() -> dict[str, Any]:
    """A name a spec declares (a parameter, coordinate, body, part, joint, spring, damper, load): what
    :meth:`tutgen.spec.builders.context.Context.check_name` accepts. An ASCII identifier, not a Python
    keyword, a function of the expression grammar, ``pi``, ``t`` or ``ground``, and not ``NAME_dot`` or
    ``NAME_ddot`` (a coordinate's rates)."""
    import keyword

    from tutgen.model.system import GROUND
    from tutgen.spec.expr import FUNCTIONS

    reserved = sorted({*keyword.kwlist, *FUNCTIONS, "pi", "t", GROUND})
    return {
        "type": "string",
        "pattern": "^[A-Za-z_][A-Za-z0-9_]*$",
        "not": {"anyOf": [{"enum": reserved}, {"pattern": "_d?dot$"}]},
        "description": "A name: letters, digits and _, starting with a letter (e.g. m1, theta_2).",
    }


#: The named sections of a spec, whose keys (or, written as a list, items) are names
_NAMED = ("parameters", "coordinates", "bodies", "joints", "springs", "dampers", "loads")


def spec_schema() -> dict[str, Any]:
    """The validator's model as JSON Schema (tutgen/spec/schema.py), with the limits the validator
    checks beyond that model (they are stated here, where the schema is served, so that an editor
    flags them as it flags a misspelt key): name patterns, at most ``MAX_COORDINATES`` coordinates,
    and keys that exclude each other."""
    from tutgen.spec.builders.coordinates import MAX_COORDINATES
    from tutgen.spec.schema import json_schema

    schema = json_schema()
    assert schema["$id"] == schema_id("spec")
    props, defs = schema["properties"], schema["$defs"]
    defs["Name"] = spec_name()
    name = {"$ref": "#/$defs/Name"}
    for section in _NAMED:
        props[section] = copy.deepcopy(props[section])  # sections share dicts (the list form of names)
        for form in props[section].get("anyOf", [props[section]]):
            if form.get("type") == "object":
                form["propertyNames"] = name
            elif form.get("type") == "array":
                form["items"] = name
    for form in props["coordinates"]["anyOf"]:
        form["maxItems" if form["type"] == "array" else "maxProperties"] = MAX_COORDINATES
    props["coordinates"]["description"] += f" At most {MAX_COORDINATES}."
    for form in defs["BodySpec"]["properties"]["parts"]["anyOf"]:
        if form.get("type") == "object":
            form["propertyNames"] = name
    # a body is a composite of `parts` or has its own mass, centre and inertia; a part has a mass or a density
    defs["BodySpec"]["not"] = {"required": ["parts"], "anyOf": [{"required": [k]} for k in ("mass", "com", "inertia")]}
    for part, part_schema in defs.items():
        if part.endswith("Part") and {"mass", "density"} <= set(part_schema.get("properties", {})):
            part_schema["not"] = {"required": ["mass", "density"]}
    # given energies replace the bodies: no bodies, joints, arm or gravity beside them
    schema["if"] = {"required": ["energy"], "properties": {"energy": {"type": "object"}}}
    schema["then"] = {
        "properties": {
            "bodies": {"maxProperties": 0},
            "joints": {"maxProperties": 0},
            "arm": {"type": "null"},
            "gravity": {"type": "null"},
        }
    }
    return schema


# --- the sheet file ---

_NUMBER_OR_TEXT = {"anyOf": [{"type": "number"}, {"type": "string"}]}
_VARY_ENTRY = {
    "description": "A parameter's entry for this sheet: a value ('9.81 m/s^2', 2), or a set of allowed values.",
    "anyOf": [
        _NUMBER_OR_TEXT,
        {
            "type": "object",
            "properties": {
                "range": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
                "step": {"type": "number", "exclusiveMinimum": 0},
                "choices": {"type": "array", "items": {"type": "number"}, "minItems": 1, "uniqueItems": True},
                "unit": {"type": "string"},
                "value": _NUMBER_OR_TEXT,
            },
            "additionalProperties": False,
            "not": {"required": ["range", "choices"]},
        },
    ],
}


def sheet_schema() -> dict[str, Any]:
    from tutgen.sheet.model import PROBLEM_KEYS, SHEET_KEYS

    text = {"type": "string", "description": "Text; inline maths between $…$ (\\$ is a dollar sign)."}
    known: dict[str, Any] = {
        "tutgen_sheet": {"const": 1, "description": "The sheet format version."},
        "title": text,
        "course": text,
        "date": {"type": "string", "description": "Printed as written (never today's date)."},
    }
    problem_known: dict[str, Any] = {
        "spec": {"type": "string", "description": "The spec's path, relative to the sheet file."},
        "vary": {
            "type": "object",
            "propertyNames": {"pattern": "^[A-Za-z][A-Za-z0-9_]*$"},
            "additionalProperties": _VARY_ENTRY,
        },
    }
    # a key the reader gained after this schema was written is still described (as anything), never refused
    problem = {
        "type": "object",
        "properties": {k: problem_known.get(k, {}) for k in PROBLEM_KEYS},
        "required": ["spec"],
        "additionalProperties": False,
    }
    return {
        **_head("sheet", "tutgen sheet", "A tutorial sheet for tutgen sheet (docs/sheets.md)."),
        "type": "object",
        "properties": {
            **{k: known.get(k, {}) for k in SHEET_KEYS if k != "problems"},
            "problems": {
                "type": "array",
                "minItems": 1,
                "items": {"anyOf": [{"type": "string", "description": "A spec's path."}, problem]},
            },
        },
        "required": ["title", "problems"],
        "additionalProperties": False,
    }


# --- the solution JSON (docs/json-output.md) ---


def solution_schema() -> dict[str, Any]:
    return {
        **_head("solution", "tutgen solution", "The results of tutgen solve --format json (docs/json-output.md)."),
        "type": "object",
        "properties": {
            "tutgen": {"type": "string", "description": "The version of the program that wrote it."},
            "format": {"const": VERSIONS["solution"]},
            "title": {"type": "string"},
            "coordinates": {"type": "array", "items": {"type": "string"}},
            "parameters": {"type": "object", "additionalProperties": {"type": ["number", "null"]}},
            "results": RESULTS,
            "figure": FIGURE,
            "simulation": SIMULATION,
            "remarks": {"type": "array", "items": {"type": "string"}},
            "checks": {"type": "array", "items": CHECK},
        },
        "required": ["tutgen", "format", "title", "coordinates", "parameters", "results", "remarks", "checks"],
    }


# --- the answers file and the marking key (docs/check.md) ---


def _result_key(what: str) -> dict[str, Any]:
    """A result key: a key of ``results`` in the solution JSON, then ``.name`` or ``[i,j]`` parts (the
    reader's grammar, :func:`tutgen.spec.builders.marking.parse_key`, checks the parts)."""
    from tutgen.spec.builders.marking import RESULT_KEYS

    return {
        "type": "string",
        "pattern": "^(?:" + "|".join(RESULT_KEYS) + r")(?:[.\[].*)?$",
        "description": f"{what}: a result key of tutgen solve --format json, e.g. mass_matrix, "
        "mass_matrix[1,2], lagrange_terms.theta.dL_dq, bodies.link1.inertia_tensor",
    }


def answers_schema() -> dict[str, Any]:
    answer = {
        "description": "An answer: an expression in the spec grammar, a number, a list (vector, matrix) "
        "or a mapping (equations of motion by coordinate, entries by name); true/false and null are "
        "read too (a sheet's answer key copies the results, `agrees_with_lagrange: true` among them).",
        "anyOf": [
            {"type": ["string", "number", "boolean", "null"]},
            {"type": "array", "items": {"$ref": "#/$defs/answer"}},
            {"type": "object", "additionalProperties": {"$ref": "#/$defs/answer"}},
        ],
    }
    label = {"type": ["string", "number"], "description": "Informational text."}
    return {
        **_head("answers", "tutgen answers", "A student's answers for tutgen check (docs/check.md)."),
        "type": ["object", "null"],
        "$defs": {"answer": answer},
        "properties": {
            "spec": {**label, "description": "The spec the answers are for (informational)."},
            "student": {**label, "description": "The student's name, for the reports."},
            "steady_motion": _steady_answer(),
        },
        # tolerances are the instructor's: `tolerance`, `rel_tol`, … are not result keys, so refused
        "propertyNames": {"anyOf": [{"enum": ["spec", "student"]}, _result_key("An answered item")]},
        "additionalProperties": {"$ref": "#/$defs/answer"},
    }


def _steady_answer() -> dict[str, Any]:
    """``steady_motion`` in an answers file: its motions, each found by its values (docs/check.md)."""
    from tutgen.check.steady import STABILITY_WORDS

    table = {"type": "object", "additionalProperties": {"$ref": "#/$defs/answer"}}
    conditions = {
        "description": "Inequalities in the spec grammar ('g <= R*omega**2'), a list of them, or 'always'.",
        "anyOf": [{"type": ["string", "boolean"]}, {"type": "array", "items": {"type": "string"}}],
    }
    motion = {
        "type": "object",
        "properties": {
            "at": {
                **table,
                "description": "The value of each coordinate not held, or an equation it satisfies "
                "('cos(theta) = g/(R*omega**2)'); an angle counts up to a multiple of 2 pi.",
            },
            "exists_where": conditions,
            "required": {**table, "description": "The generalized force each held coordinate needs."},
            "inputs": {**table, "description": "The input of a driven coordinate that gives it."},
            "momenta": {**table, "description": "The momentum dL/dq_dot of each held coordinate."},
            "stability": {"type": "string", "description": "One of: " + ", ".join(STABILITY_WORDS) + "."},
            "stable_where": conditions,
        },
        "required": ["at"],
        "additionalProperties": False,
    }
    return {
        "description": "The steady motions, in any order, each matched with tutgen's by its `at` values.",
        "anyOf": [{"type": "array", "items": motion}, motion],
    }


def _tolerance(extra: dict[str, Any] | None = None) -> dict[str, Any]:
    return {
        "type": "object",
        "properties": {
            "rel_tol": {"type": "number", "minimum": 0, "description": "Relative tolerance of every number."},
            "abs_tol": {"type": "number", "minimum": 0, "description": "Absolute tolerance of every number."},
            "rounded": {"type": "boolean", "description": "A decimal must be the result correctly rounded."},
            **(extra or {}),
        },
        "additionalProperties": False,
    }


def key_schema() -> dict[str, Any]:
    from tutgen.spec.builders.marking import MARKING_FIELDS

    known: dict[str, Any] = {
        "ask": {
            "type": "array",
            "minItems": 1,
            "items": _result_key("An item graded"),
            "description": "The items graded, in this order.",
        },
        "tolerance": _tolerance(),
        "items": {
            "type": "object",
            "propertyNames": _result_key("An item or entry"),
            "additionalProperties": _tolerance({"scaling": {"type": "boolean"}}),
            "description": "Per item or entry: its tolerance, and whether equations may be scaled.",
        },
        "significant_figures": {
            "type": "integer",
            "minimum": 0,
            "maximum": 15,
            "description": "Decimals read as the result rounded to this many figures (0: exact).",
        },
    }
    return {
        **_head("key", "tutgen marking key", "The instructor's marking key, tutgen check --key (docs/check.md)."),
        "type": ["object", "null"],
        "properties": {k: known.get(k, {}) for k in MARKING_FIELDS},
        "additionalProperties": False,
    }


# --- the JSON of tutgen check (docs/check.md) ---


def _format(kind: str) -> dict[str, Any]:
    return {"const": VERSIONS[kind], "description": "The version of this document's layout."}


def check_schema() -> dict[str, Any]:
    from tutgen.check.report import FILE_STATUSES
    from tutgen.check.verdicts import Status

    status = {"enum": [s.value for s in Status]}
    text_or_null = {"type": ["string", "null"]}
    entry = {
        "type": "object",
        "properties": {
            "name": {"type": "string"},
            "status": status,
            "how": {"type": "string"},
            "feedback": {"type": "string"},
            "location": {"type": "string"},
            "given": text_or_null,
            "expected": text_or_null,
        },
        "required": ["name", "status", "location"],
    }
    item = {
        "type": "object",
        "properties": {
            "name": {"type": "string"},
            "status": status,
            "location": {"type": "string"},
            "remarks": {"type": "array", "items": {"type": "string"}},
            "entries": {"type": "array", "items": entry},
        },
        "required": ["name", "status", "entries"],
    }
    count = {"type": "integer", "minimum": 0}
    file = {
        "type": "object",
        "properties": {
            "answers": {"type": "string"},
            "student": text_or_null,
            "status": {"enum": list(FILE_STATUSES)},
            "counts": {"type": "object", "properties": {s.value: count for s in Status}},
            "errors": {"type": "array", "items": {"type": "string"}},
            "limit": text_or_null,
            "items": {"type": "array", "items": item},
        },
        "required": ["answers", "status", "counts", "errors", "items"],
    }
    return {
        **_head("check", "tutgen check report", "The report of tutgen check --format json (docs/check.md)."),
        "type": "object",
        "properties": {
            "tutgen": {"type": "string", "description": "The version of the program that wrote it."},
            "format": _format("check"),
            "spec": {"type": "string"},
            "title": {"type": "string"},
            "summary": {
                "type": "object",
                "properties": {"files": count, **{s: count for s in FILE_STATUSES}},
                "required": ["files", *FILE_STATUSES],
            },
            "marking": {
                "type": "object",
                "properties": {
                    "source": {"type": "string"},
                    "asked": {"type": "array", "items": {"type": "string"}},
                    "note": {"type": "string"},
                },
            },
            "files": {"type": "array", "items": file},
        },
        "required": ["tutgen", "format", "spec", "summary", "files"],
    }


def summary_schema() -> dict[str, Any]:
    from tutgen.check.report import FILE_STATUSES, SUMMARY_FIELDS

    count = {"type": "integer", "minimum": 0}
    row = {
        "type": "object",
        "properties": {
            name: count if name not in ("file", "student", "status", "wrong_items") else {"type": "string"}
            for name in SUMMARY_FIELDS
        }
        | {"status": {"enum": list(FILE_STATUSES)}},
        "required": list(SUMMARY_FIELDS),
    }
    return {
        **_head("summary", "tutgen check summary", "tutgen check --summary FILE.json: a row per answers file."),
        "type": "object",
        "properties": {
            "format": _format("summary"),
            "spec": {"type": "string"},
            "files": {"type": "array", "items": row},
        },
        "required": ["format", "spec", "files"],
    }


# --- the JSON trajectory of tutgen simulate (docs/simulate.md) ---


def simulation_schema() -> dict[str, Any]:
    series = {"type": "array", "items": {"type": "number"}}
    by_name_series = {"type": "object", "additionalProperties": series}
    by_name = {"type": "object", "additionalProperties": {"type": "number"}}
    number_or_null = {"type": ["number", "null"]}
    return {
        **_head("simulation", "tutgen simulation", "The trajectory tutgen simulate writes (docs/simulate.md)."),
        "type": "object",
        "properties": {
            "tutgen": {"type": "string", "description": "The version of the program that wrote it."},
            "format": _format("simulation"),
            "spec": {"type": "string"},
            "coordinates": {"type": "array", "items": {"type": "string"}},
            "parameters": by_name,
            "inputs": {"type": "object", "additionalProperties": {"type": "string"}},
            "integrator": {
                "type": "object",
                "properties": {
                    "method": {"type": "string"},
                    "rtol": {"type": "number"},
                    "atol": {"type": "number"},
                    "steps": {"type": "integer", "minimum": 0},
                    "evaluations": {"type": "integer", "minimum": 0},
                },
                "required": ["method", "rtol", "atol"],
            },
            "interval": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
            "initial": {
                "type": "object",
                "properties": {"q": by_name, "qd": by_name},
                "required": ["q", "qd"],
            },
            "t": series,
            "q": by_name_series,
            "qd": by_name_series,
            "energy": {
                "type": "object",
                "properties": {"kinetic": series, "potential": series, "total": series},
                "required": ["kinetic", "potential", "total"],
            },
            "energy_check": {
                "type": "object",
                "properties": {
                    "conservative": {"type": "boolean"},
                    "relative_drift": number_or_null,
                    "tolerance": number_or_null,
                    "passed": {"type": ["boolean", "null"]},
                },
                "required": ["conservative", "passed"],
            },
            "stopped": {
                "anyOf": [
                    {"type": "null"},
                    {
                        "type": "object",
                        "properties": {
                            "reason": {"type": ["string", "null"]},
                            "message": {"type": "string"},
                            "t": number_or_null,
                            "q": {"type": ["array", "null"], "items": {"type": "number"}},
                        },
                        "required": ["reason", "message"],
                    },
                ]
            },
            "constraints": {
                "description": "A constrained spec's run only: the constraints' residuals and multipliers "
                "at the samples (docs/simulate.md#constrained-specs).",
                "type": "object",
                "properties": {
                    "method": {"const": "baumgarte"},
                    "stabilisation": {"type": "number", "description": "Baumgarte's rate alpha, 1/s."},
                    "solved_positions": {"type": "array", "items": {"type": "string"}},
                    "solved_rates": {"type": "array", "items": {"type": "string"}},
                    "max_residual": number_or_null,
                    "items": {
                        "type": "array",
                        "items": {
                            "type": "object",
                            "properties": {
                                "name": {"type": "string"},
                                "kind": {"enum": ["position", "velocity"]},
                                "multiplier": {"type": "string"},
                                "residual": series,
                                "lambda": series,
                            },
                            "required": ["name", "kind", "multiplier", "residual", "lambda"],
                        },
                    },
                },
                "required": ["method", "stabilisation", "max_residual", "items"],
            },
        },
        "required": ["tutgen", "format", "spec", "coordinates", "t", "q", "qd", "energy", "energy_check", "stopped"],
    }


#: ``tutgen schema --kind KIND``: each kind's schema
SCHEMAS: dict[str, Callable[[], dict[str, Any]]] = {
    "spec": spec_schema,
    "sheet": sheet_schema,
    "solution": solution_schema,
    "answers": answers_schema,
    "key": key_schema,
    "check": check_schema,
    "summary": summary_schema,
    "simulation": simulation_schema,
}
