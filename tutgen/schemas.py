"""JSON Schemas (draft 2020-12) of the files tutgen reads and writes: ``tutgen schema --kind KIND``.

- ``spec``: a problem spec (docs/spec-format.md), generated from the validator's own model
  (tutgen/spec/schema.py), so editors complete and check what the validator accepts;
- ``sheet``: a tutorial sheet file (docs/sheets.md), its keys taken from the sheet reader's;
- ``solution``: the JSON of ``tutgen solve --format json`` (docs/json-output.md), format 1.

Each has an ``$id`` of the form ``urn:tutgen:schema:KIND:VERSION`` (the version of that file's
format: a new version, a new ``$id``). Documents may carry keys a schema does not name (the JSON
contract adds keys without a format bump), so the output schemas leave objects open; the input schemas
are as strict as the readers are. A spec's semantic limits that JSON Schema cannot state (a name used
before it is declared, a dimension mismatch) are the validator's: ``tutgen solve`` reports them at
their file:line:col.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

DIALECT = "https://json-schema.org/draft/2020-12/schema"

#: the format version of each kind of file (the number in its ``$id``)
VERSIONS = {"spec": 1, "sheet": 1, "solution": 1}


def schema_id(kind: str) -> str:
    return f"urn:tutgen:schema:{kind}:{VERSIONS[kind]}"


def _head(kind: str, title: str, description: str) -> dict[str, Any]:
    return {"$schema": DIALECT, "$id": schema_id(kind), "title": title, "description": description}


def spec_schema() -> dict[str, Any]:
    from tutgen.spec.schema import json_schema

    schema = json_schema()
    assert schema["$id"] == schema_id("spec")
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

_EXPR = {"type": "string", "minLength": 1, "description": "An expression in the spec grammar."}
_VALUE = {"anyOf": [{"type": "number"}, _EXPR], "description": "A number or an expression."}
_VEC3 = {"type": "array", "items": _VALUE, "minItems": 3, "maxItems": 3}
_VECTOR = {"type": "array", "items": _VALUE}
_MATRIX = {"type": "array", "items": {"type": "array", "items": _VALUE}}
_BY_NAME_VEC3 = {"type": "object", "additionalProperties": _VEC3}
_SYMBOLS = {
    "type": "object",
    "propertyNames": {"pattern": "^[1-9][0-9]*,[1-9][0-9]*,[1-9][0-9]*$"},
    "additionalProperties": _VALUE,
}
_PART = {
    "type": "object",
    "properties": {
        "shape": {"type": "string"},
        "volume": _VALUE,
        "mass": _VALUE,
        "centroid": _VEC3,
        "axis_distances": _VEC3,
        "inertia_centroid": _MATRIX,
        "inertia_tensor": _MATRIX,
    },
    "required": ["shape", "mass", "centroid", "inertia_tensor"],
}
_BODY = {
    "type": "object",
    "properties": {
        "mass": _VALUE,
        "center_of_mass": _VEC3,
        "inertia_tensor": _MATRIX,
        "inertia_tensor_com": _MATRIX,
        "principal_moments": {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3},
        "principal_axes": {"type": "array", "items": _VEC3, "minItems": 3, "maxItems": 3},
        "parts": {"type": "object", "additionalProperties": _PART},
    },
    "required": ["mass", "center_of_mass", "inertia_tensor"],
}
_LAGRANGE_TERM = {
    "type": "object",
    "properties": {
        "coordinate": {"type": "string"},
        "dL_dqdot": _VALUE,
        "ddt_dL_dqdot": _VALUE,
        "dL_dq": _VALUE,
        "generalized_force": _VALUE,
    },
    "required": ["coordinate", "dL_dqdot", "ddt_dL_dqdot", "dL_dq", "generalized_force"],
}
_ROTOR = {
    "type": "object",
    "properties": {
        "coordinate": {"type": "string"},
        "rotor_inertia": _VALUE,
        "gear_ratio": _VALUE,
        "reflected_inertia": _VALUE,
    },
    "required": ["coordinate", "rotor_inertia", "gear_ratio", "reflected_inertia"],
}
_NEWTON_EULER = {
    "type": "object",
    "properties": {
        "method": {"enum": ["recursive", "per_body", "projection"]},
        "equations_of_motion": _VECTOR,
        "reaction_forces": {
            "type": "object",
            "additionalProperties": {
                "type": "object",
                "properties": {"force": _VEC3, "moment": _VEC3},
                "required": ["force", "moment"],
            },
        },
        "agrees_with_lagrange": {"const": True},
        "remarks": {"type": "array", "items": {"type": "string"}},
    },
    "required": ["method", "equations_of_motion", "agrees_with_lagrange"],
}
_COMPLEX = {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2, "description": "[re, im]"}
_STABILITY = {"enum": ["asymptotically stable", "stable", "unstable", "conditional", "undetermined"]}
_AT = {"type": "object", "additionalProperties": _VALUE, "description": "Each coordinate's value."}
_EQUILIBRIA = {
    "type": "object",
    "properties": {
        "residual": _VECTOR,
        "method": {"enum": ["symbolic", "numeric", "none"]},
        "free_coordinates": {"type": "array", "items": {"type": "string"}},
        "solutions": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "at": _AT,
                    "stability": _STABILITY,
                    "reason": {"type": "string"},
                    "exists_where": {"type": "array", "items": _EXPR},
                    "stable_where": {"type": "array", "items": _EXPR},
                },
                "required": ["at", "stability", "reason"],
            },
        },
        "remark": {"type": "string"},
    },
    "required": ["residual", "method", "free_coordinates", "solutions"],
}
_MODE = {
    "type": "object",
    "properties": {
        "eigenvalue": _COMPLEX,
        "natural_frequency": {"type": "number", "description": "|lambda|, rad/s"},
        "frequency_hz": {"type": "number"},
        "damping_ratio": {"type": ["number", "null"]},
        "shape": {"type": "array", "items": _COMPLEX},
    },
    "required": ["eigenvalue", "natural_frequency", "frequency_hz", "damping_ratio", "shape"],
}
_LINEAR_MODEL = {
    "type": "object",
    "properties": {
        "about": _AT,
        "inputs": {"type": "array", "items": {"type": "string"}},
        "mass_matrix": _MATRIX,
        "damping_matrix": _MATRIX,
        "stiffness_matrix": _MATRIX,
        "input_matrix": _MATRIX,
        "state_matrix": _MATRIX,
        "state_input_matrix": _MATRIX,
        "stability": _STABILITY,
        "reason": {"type": "string"},
        "characteristic_polynomial": _VALUE,
        "stiffness_minors": _VECTOR,
        "stable_where": {"type": "array", "items": _EXPR},
        "modes": {"type": "array", "items": _MODE},
    },
    "required": [
        "about",
        "inputs",
        "mass_matrix",
        "damping_matrix",
        "stiffness_matrix",
        "input_matrix",
        "state_matrix",
        "state_input_matrix",
        "stability",
        "reason",
    ],
}
_MOMENTUM = {
    "type": "object",
    "properties": {
        "bodies": {
            "type": "object",
            "additionalProperties": {
                "type": "object",
                "properties": {k: _VEC3 for k in ("linear", "angular_com", "angular_com_body", "angular_origin")},
                "required": ["linear", "angular_com", "angular_com_body", "angular_origin"],
            },
        },
        **{
            k: _VEC3
            for k in (
                "linear",
                "angular_origin",
                "angular_origin_rate",
                "gravity_moment",
                "support_moment",
                "steady_support_moment",
            )
        },
        "conserved": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {"name": {"type": "string"}, "value": _VALUE, "why": {"type": "string"}},
                "required": ["name", "value", "why"],
            },
        },
    },
    "required": ["bodies", "linear", "angular_origin", "angular_origin_rate", "support_moment", "conserved"],
}
_RESULTS = {
    "type": "object",
    "properties": {
        "bodies": {"type": "object", "additionalProperties": _BODY},
        "mass": _VALUE,
        "center_of_mass": _VEC3,
        "inertia_tensor": _MATRIX,
        "principal_moments": {"type": "array", "items": {"type": "number"}},
        "positions": _BY_NAME_VEC3,
        "velocities": _BY_NAME_VEC3,
        "angular_velocities": _BY_NAME_VEC3,
        "speeds_squared": {"type": "object", "additionalProperties": _VALUE},
        "body_kinetic_energies": {"type": "object", "additionalProperties": _VALUE},
        "kinetic_energy": _VALUE,
        "potential_energy": _VALUE,
        "lagrangian": _VALUE,
        "lagrange_terms": {"type": "array", "items": _LAGRANGE_TERM},
        "generalized_forces": _VECTOR,
        "mass_matrix": _MATRIX,
        "coriolis_vector": _VECTOR,
        "coriolis_matrix": _MATRIX,
        "gravity_vector": _VECTOR,
        "mass_matrix_determinant": _VALUE,
        "rotors": {"type": "object", "additionalProperties": _ROTOR},
        "equations_of_motion": _VECTOR,
        "christoffel": _SYMBOLS,
        "christoffel_first_kind": _SYMBOLS,
        "newton_euler": _NEWTON_EULER,
        "equilibria": _EQUILIBRIA,
        "linearization": {"type": "array", "items": _LINEAR_MODEL},
        "momentum": _MOMENTUM,
    },
}
_FIGURE = {
    "type": "object",
    "properties": {
        "svg": {"type": ["string", "null"]},
        "file": {"type": ["string", "null"]},
        "generated": {"type": "boolean"},
        "view": {"enum": ["planar", "oblique", None]},
        "at": {"type": "object", "additionalProperties": {"type": "number"}},
        "sizes": {"type": "object", "additionalProperties": {"type": "number"}},
        "labels": {"type": "array", "items": {"type": "string"}},
        "remarks": {"type": "array", "items": {"type": "string"}},
        "free_bodies": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "body": {"type": "string"},
                    "svg": {"type": "string"},
                    "labels": {"type": "array", "items": {"type": "string"}},
                },
                "required": ["body", "svg", "labels"],
            },
        },
    },
}
_CHECK = {
    "type": "object",
    "properties": {"name": {"type": "string"}, "passed": {"type": "boolean"}, "detail": {"type": "string"}},
    "required": ["name", "passed", "detail"],
}


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
            "results": _RESULTS,
            "figure": _FIGURE,
            "remarks": {"type": "array", "items": {"type": "string"}},
            "checks": {"type": "array", "items": _CHECK},
        },
        "required": ["tutgen", "format", "title", "coordinates", "parameters", "results", "remarks", "checks"],
    }


#: ``tutgen schema --kind KIND``: each kind's schema
SCHEMAS: dict[str, Callable[[], dict[str, Any]]] = {
    "spec": spec_schema,
    "sheet": sheet_schema,
    "solution": solution_schema,
}
