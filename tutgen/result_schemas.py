"""The parts of the solution JSON's schema (tutgen solve --format json, docs/json-output.md): values,
vectors and matrices, each result's object, Newton–Euler's (planar too), the analysis, the figure and the
simulation. tutgen.schemas assembles them into the solution schema and reuses the value shapes in the
answers, key and check schemas; split from it to keep each module under 800 lines."""

from __future__ import annotations

EXPR = {"type": "string", "minLength": 1, "description": "An expression in the spec grammar."}
VALUE = {"anyOf": [{"type": "number"}, EXPR], "description": "A number or an expression."}
VEC3 = {"type": "array", "items": VALUE, "minItems": 3, "maxItems": 3}
VECTOR = {"type": "array", "items": VALUE}
MATRIX = {"type": "array", "items": {"type": "array", "items": VALUE}}
BY_NAME_VEC3 = {"type": "object", "additionalProperties": VEC3}
SYMBOLS = {
    "type": "object",
    "propertyNames": {"pattern": "^[1-9][0-9]*,[1-9][0-9]*,[1-9][0-9]*$"},
    "additionalProperties": VALUE,
}
PART = {
    "type": "object",
    "properties": {
        "shape": {"type": "string"},
        "volume": VALUE,
        "mass": VALUE,
        "centroid": VEC3,
        "axis_distances": VEC3,
        "inertia_centroid": MATRIX,
        "inertia_tensor": MATRIX,
    },
    "required": ["shape", "mass", "centroid", "inertia_tensor"],
}
BODY = {
    "type": "object",
    "properties": {
        "mass": VALUE,
        "center_of_mass": VEC3,
        "inertia_tensor": MATRIX,
        "inertia_tensor_com": MATRIX,
        "principal_moments": {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3},
        "principal_axes": {"type": "array", "items": VEC3, "minItems": 3, "maxItems": 3},
        "principal_moments_com": {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3},
        "principal_axes_com": {"type": "array", "items": VEC3, "minItems": 3, "maxItems": 3},
        "parts": {"type": "object", "additionalProperties": PART},
    },
    "required": ["mass", "center_of_mass", "inertia_tensor"],
}
LAGRANGE_TERM = {
    "type": "object",
    "properties": {
        "coordinate": {"type": "string"},
        "dL_dqdot": VALUE,
        "ddt_dL_dqdot": VALUE,
        "dL_dq": VALUE,
        "generalized_force": VALUE,
    },
    "required": ["coordinate", "dL_dqdot", "ddt_dL_dqdot", "dL_dq", "generalized_force"],
}
ROTOR = {
    "type": "object",
    "properties": {
        "coordinate": {"type": "string"},
        "rotor_inertia": VALUE,
        "gear_ratio": VALUE,
        "reflected_inertia": VALUE,
    },
    "required": ["coordinate", "rotor_inertia", "gear_ratio", "reflected_inertia"],
}
PAIR = {"type": "array", "items": VALUE, "minItems": 2, "maxItems": 2}
PLANAR_FORCE = {
    "type": "object",
    "properties": {
        "name": {"type": "string"},
        "kind": {"type": "string"},
        "source": {"type": ["string", "null"]},
        "point": PAIR,
        "force": PAIR,
        "torque": VALUE,
    },
    "required": ["name", "kind", "source", "point", "force", "torque"],
}
PLANAR = {
    "type": "object",
    "properties": {
        "balances": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "body": {"type": "string"},
                    "about": {"type": "string"},
                    "joint": {"type": "string"},
                    "point": PAIR,
                    "forces": {"type": "array", "items": PLANAR_FORCE},
                    "sum_fx": VALUE,
                    "sum_fy": VALUE,
                    "sum_m": VALUE,
                },
                "required": ["body", "about", "joint", "point", "forces", "sum_fx", "sum_fy", "sum_m"],
            },
        },
        "elimination": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "coordinate": {"type": "string"},
                    "joint": {"type": "string"},
                    "contributions": {
                        "type": "array",
                        "items": {
                            "type": "object",
                            "properties": {
                                "body": {"type": "string"},
                                "kind": {"enum": ["moment", "force_moment", "force"]},
                                "via": {"type": ["string", "null"]},
                                "value": VALUE,
                            },
                            "required": ["body", "kind", "via", "value"],
                        },
                    },
                    "eliminated": {"type": "array", "items": {"type": "string"}},
                    "equation": VALUE,
                },
                "required": ["coordinate", "joint", "contributions", "eliminated", "equation"],
            },
        },
        "reactions": {
            "type": "object",
            "additionalProperties": {
                "type": "object",
                "properties": {
                    "kind": {"enum": ["revolute", "prismatic", "fixed"]},
                    "parent": {"type": "string"},
                    "child": {"type": "string"},
                    "unknowns": {"type": "object", "additionalProperties": VALUE},
                    "force": PAIR,
                    "moment": VALUE,
                    "solved_from": {"type": "string"},
                },
                "required": ["kind", "parent", "child", "unknowns", "force", "moment", "solved_from"],
            },
        },
    },
    "required": ["balances", "elimination", "reactions"],
}
NEWTON_EULER = {
    "type": "object",
    "properties": {
        "method": {"enum": ["recursive", "per_body", "projection"]},
        "equations_of_motion": VECTOR,
        "reaction_forces": {
            "type": "object",
            "additionalProperties": {
                "type": "object",
                "properties": {"force": VEC3, "moment": VEC3},
                "required": ["force", "moment"],
            },
        },
        "agrees_with_lagrange": {"const": True},
        "remarks": {"type": "array", "items": {"type": "string"}},
        "planar": PLANAR,
        "constraint_reactions": {
            "type": "object",
            "description": "A constrained spec's constraint reactions, in its multipliers (issue 21)",
            "additionalProperties": {
                "type": "object",
                "properties": {
                    "kind": {"enum": ["pin", "generalized"]},
                    "constraints": {"type": "array", "items": {"type": "string"}},
                    "multipliers": {"type": "array", "items": {"type": "string"}},
                    "generalized_force": VECTOR,
                    "parent": {"type": "string"},
                    "child": {"type": "string"},
                    "force_on_parent": VEC3,
                    "force_on_child": VEC3,
                },
                "required": ["kind", "constraints", "multipliers", "generalized_force"],
            },
        },
        "agrees_with_reduction": {"const": True},
    },
    "required": ["method", "equations_of_motion", "agrees_with_lagrange"],
}
COMPLEX = {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2, "description": "[re, im]"}
STABILITY = {"enum": ["asymptotically stable", "stable", "unstable", "conditional", "undetermined"]}
AT = {"type": "object", "additionalProperties": VALUE, "description": "Each coordinate's value."}
EQUILIBRIA = {
    "type": "object",
    "properties": {
        "residual": VECTOR,
        "method": {"enum": ["symbolic", "numeric", "none"]},
        "free_coordinates": {"type": "array", "items": {"type": "string"}},
        "solutions": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "at": AT,
                    "stability": STABILITY,
                    "reason": {"type": "string"},
                    "exists_where": {"type": "array", "items": EXPR},
                    "stable_where": {"type": "array", "items": EXPR},
                },
                "required": ["at", "stability", "reason"],
            },
        },
        "remark": {"type": "string"},
    },
    "required": ["residual", "method", "free_coordinates", "solutions"],
}
MODE = {
    "type": "object",
    "properties": {
        "eigenvalue": COMPLEX,
        "natural_frequency": {"type": "number", "description": "|lambda|, rad/s"},
        "frequency_hz": {"type": "number"},
        "damping_ratio": {"type": ["number", "null"]},
        "shape": {"type": "array", "items": COMPLEX},
    },
    "required": ["eigenvalue", "natural_frequency", "frequency_hz", "damping_ratio", "shape"],
}
LINEAR_MODEL = {
    "type": "object",
    "properties": {
        "about": AT,
        "inputs": {"type": "array", "items": {"type": "string"}},
        "mass_matrix": MATRIX,
        "damping_matrix": MATRIX,
        "stiffness_matrix": MATRIX,
        "input_matrix": MATRIX,
        "state_matrix": MATRIX,
        "state_input_matrix": MATRIX,
        "stability": STABILITY,
        "reason": {"type": "string"},
        "characteristic_polynomial": VALUE,
        "stiffness_minors": VECTOR,
        "stable_where": {"type": "array", "items": EXPR},
        "modes": {"type": "array", "items": MODE},
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
MOMENTUM = {
    "type": "object",
    "properties": {
        "bodies": {
            "type": "object",
            "additionalProperties": {
                "type": "object",
                "properties": {k: VEC3 for k in ("linear", "angular_com", "angular_com_body", "angular_origin")},
                "required": ["linear", "angular_com", "angular_com_body", "angular_origin"],
            },
        },
        **{
            k: VEC3
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
                "properties": {"name": {"type": "string"}, "value": VALUE, "why": {"type": "string"}},
                "required": ["name", "value", "why"],
            },
        },
    },
    "required": ["bodies", "linear", "angular_origin", "angular_origin_rate", "support_moment", "conserved"],
}
STEADY_MOTION = {
    "type": "object",
    "description": "ask: [steady_motion] (docs/json-output.md#steady-motion).",
    "properties": {
        "cyclic": {"type": "array", "items": {"type": "string"}},
        "rates": AT,
        "free": {"type": "array", "items": {"type": "string"}},
        "others": {"type": "array", "items": {"type": "string"}},
        "free_others": {"type": "array", "items": {"type": "string"}},
        "held": {"enum": ["rate", "momentum", "mixed"]},
        "residual": VECTOR,
        "method": {"enum": ["symbolic", "numeric", "none"]},
        "remark": {"type": "string"},
        "states": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "at": AT,
                    "exists": {"type": ["boolean", "null"]},
                    "exists_where": {"type": "array", "items": EXPR},
                    "required": AT,
                    "inputs": AT,
                    "momenta": AT,
                    "mass_matrix": MATRIX,
                    "damping_matrix": MATRIX,
                    "stiffness_matrix": MATRIX,
                    "stability": {"enum": [*STABILITY["enum"], "neutral", "none"]},
                    "reason": {"type": "string"},
                    "stable_where": {"type": "array", "items": EXPR},
                    "eigenvalues": {"type": "array", "items": {"type": "array", "items": {"type": "number"}}},
                },
                "required": ["at", "exists", "required", "mass_matrix", "stiffness_matrix", "stability", "reason"],
            },
        },
    },
    "required": ["cyclic", "rates", "free", "others", "held", "residual", "method", "states"],
}
PROGRAM = {
    "type": "object",
    "description": "A serial arm's H, C q_dot and G as a straight-line program (issue 17): the definitions "
    "in evaluation order, each using only earlier names, then the three matrices in terms of them.",
    "properties": {
        "definitions": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {"name": {"type": "string"}, "value": VALUE},
                "required": ["name", "value"],
            },
        },
        "mass_matrix": MATRIX,
        "coriolis_vector": VECTOR,
        "gravity_vector": VECTOR,
    },
    "required": ["definitions", "mass_matrix", "coriolis_vector", "gravity_vector"],
}
CONSTRAINTS = {
    "type": "object",
    "description": "A constrained spec's results (issue 21, docs/constraints.md): the constraints in order (loop "
    "closures first), A, B, T, det A_d, the position analysis by branch, the multipliers and the reduced equations.",
    "properties": {
        "names": {"type": "array", "items": {"type": "string"}},
        "kinds": {"type": "array", "items": {"enum": ["position", "velocity"]}},
        "functions": VECTOR,
        "jacobian": MATRIX,
        "independent_coordinates": {"type": "array", "items": {"type": "string"}},
        "dependent_coordinates": {"type": "array", "items": {"type": "string"}},
        "velocity_ratios": MATRIX,
        "dependent_determinant": VALUE,
        "velocity_map": MATRIX,
        "acceleration_terms": VECTOR,
        "position_analysis": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "sign": {"enum": [-1, 0, 1]},
                    "positions": {"type": "object", "additionalProperties": VALUE},
                },
                "required": ["sign", "positions"],
            },
        },
        "multipliers": {"type": "array", "items": {"type": "string"}},
        "constraint_forces": VECTOR,
        "multipliers_in_accelerations": VECTOR,
        "multiplier_values": VECTOR,
        "reduced": {
            "type": "object",
            "properties": {
                "mass_matrix": MATRIX,
                "coriolis_vector": VECTOR,
                "gravity_vector": VECTOR,
                "generalized_forces": VECTOR,
                "equations_of_motion": VECTOR,
                "accelerations": VECTOR,
            },
            "required": [
                "mass_matrix",
                "coriolis_vector",
                "gravity_vector",
                "generalized_forces",
                "equations_of_motion",
            ],
        },
    },
    "required": [
        "names",
        "kinds",
        "functions",
        "jacobian",
        "independent_coordinates",
        "dependent_coordinates",
        "velocity_map",
        "multipliers",
        "constraint_forces",
        "multipliers_in_accelerations",
        "reduced",
    ],
}
#: the driven coordinates (`prescribed:`, `rate:`; docs/json-output.md#prescribed)
PRESCRIBED = {
    "type": "object",
    "properties": {
        "coordinates": {
            "type": "object",
            "additionalProperties": {
                "type": "object",
                "properties": {
                    "motion": VALUE,
                    "rate": VALUE,
                    "acceleration": VALUE,
                    "kind": {"enum": ["torque", "force", "generalized force"]},
                    "drive": VALUE,
                    "drive_along_motion": VALUE,
                },
                "required": ["motion", "rate", "acceleration", "kind", "drive"],
            },
        },
        "free_coordinates": {"type": "array", "items": {"type": "string"}},
        "mass_matrix": MATRIX,
        "coriolis_vector": VECTOR,
        "gravity_vector": VECTOR,
        "driving_vector": VECTOR,
        "generalized_forces": VECTOR,
        "equations_of_motion": VECTOR,
    },
    "required": ["coordinates", "free_coordinates", "equations_of_motion"],
}
RESULTS = {
    "type": "object",
    "properties": {
        "bodies": {"type": "object", "additionalProperties": BODY},
        "mass": VALUE,
        "center_of_mass": VEC3,
        "inertia_tensor": MATRIX,
        "principal_moments": {"type": "array", "items": {"type": "number"}},
        "positions": BY_NAME_VEC3,
        "velocities": BY_NAME_VEC3,
        "angular_velocities": BY_NAME_VEC3,
        "speeds_squared": {"type": "object", "additionalProperties": VALUE},
        "body_kinetic_energies": {"type": "object", "additionalProperties": VALUE},
        "kinetic_energy": VALUE,
        "potential_energy": VALUE,
        "lagrangian": VALUE,
        "lagrange_terms": {"type": "array", "items": LAGRANGE_TERM},
        "generalized_forces": VECTOR,
        "mass_matrix": MATRIX,
        "coriolis_vector": VECTOR,
        "coriolis_matrix": MATRIX,
        "gravity_vector": VECTOR,
        "mass_matrix_determinant": VALUE,
        "rotors": {"type": "object", "additionalProperties": ROTOR},
        "equations_of_motion": VECTOR,
        "christoffel": SYMBOLS,
        "christoffel_first_kind": SYMBOLS,
        "program": PROGRAM,
        "expanded": {
            "type": "boolean",
            "description": "With program: false when the entries written out (mass_matrix, coriolis_vector, "
            "christoffel, ...) are left out for their size (tutgen solve --expand writes them).",
        },
        "expanded_note": {"type": "string", "description": "With expanded false: why, in words."},
        "newton_euler": NEWTON_EULER,
        "equilibria": EQUILIBRIA,
        "linearization": {"type": "array", "items": LINEAR_MODEL},
        "momentum": MOMENTUM,
        "constraints": CONSTRAINTS,
        "steady_motion": STEADY_MOTION,
        "prescribed": PRESCRIBED,
    },
}
FIGURE = {
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
STATE = {
    "type": "object",
    "additionalProperties": {
        "type": "object",
        "properties": {"q": {"type": "number"}, "qd": {"type": "number"}},
        "required": ["q", "qd"],
    },
}
#: `ask: [simulation]` (docs/json-output.md#simulation): the plots' files beside the .json and the run's numbers
SIMULATION = {
    "type": "object",
    "properties": {
        "files": {"type": "object", "additionalProperties": {"type": "string"}},
        "interval": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
        "reached": {"type": "number"},
        "integrator": {
            "type": "object",
            "properties": {
                "method": {"type": "string"},
                "rtol": {"type": "number"},
                "atol": {"type": "number"},
                "steps": {"type": "integer"},
            },
        },
        "samples": {"type": "integer"},
        "inputs": {"type": "object", "additionalProperties": {"type": "string"}},
        "initial": STATE,
        "final": STATE,
        "energy": {
            "type": "object",
            "properties": {
                "initial": {"type": "number"},
                "final": {"type": "number"},
                "conservative": {"type": "boolean"},
                "drift": {"type": ["number", "null"]},
                "tolerance": {"type": "number"},
                "check_passed": {"type": ["boolean", "null"]},
            },
        },
        "stopped": {"type": ["string", "null"]},
    },
    "required": ["files", "interval", "integrator", "energy", "stopped"],
}
CHECK = {
    "type": "object",
    "properties": {"name": {"type": "string"}, "passed": {"type": "boolean"}, "detail": {"type": "string"}},
    "required": ["name", "passed", "detail"],
}
