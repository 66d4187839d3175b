"""The course tutorial's answer key (shared/seed/answers.yaml) as tutgen answers files.

answers.yaml names its answers the tutorial's way (T, H, C, intermediate.dL_dtheta2, velocity.m2.0);
:func:`answers_file` turns one problem into the mapping of an answers file (result keys of
``tutgen solve --format json``), either the whole key (the correct values) or only what the
tutorial prints (with the printed text where the key lists a typo). :func:`typo_entries` names
the report entries at which `tutgen check` must flag the typos.
"""

from __future__ import annotations

from typing import Any

from tests.conftest import SPECS
from tests.seed import ANSWERS as ANSWERS
from tests.seed import BODY_OF, SPEC_OF, problems

RESULT_OF = {
    "T": "kinetic_energy",
    "U": "potential_energy",
    "H": "mass_matrix",
    "C": "coriolis_vector",
    "C_matrix": "coriolis_matrix",
    "G": "gravity_vector",
    "H_determinant": "mass_matrix_determinant",
}
# problems 1 and 2: the answer key's numbers -> result keys (None: no result holds that number)
_PARTS = "bodies.body.parts"
NUMBER_OF = {
    1: {
        "block_volume": f"{_PARTS}.block.volume",
        "block_mass": f"{_PARTS}.block.mass",
        "cylinder_volume": f"{_PARTS}.cylinder.volume",
        "cylinder_mass": f"{_PARTS}.cylinder.mass",
        "block_Ixx": f"{_PARTS}.block.inertia_tensor[1,1]",
        "block_Iyy": f"{_PARTS}.block.inertia_tensor[2,2]",
        "block_Izz": f"{_PARTS}.block.inertia_tensor[3,3]",
        "cylinder_Ixx": f"{_PARTS}.cylinder.inertia_tensor[1,1]",
        "cylinder_Iyy": f"{_PARTS}.cylinder.inertia_tensor[2,2]",
        "cylinder_Izz": f"{_PARTS}.cylinder.inertia_tensor[3,3]",
        "point_Ixx": f"{_PARTS}.point.inertia_tensor[1,1]",
        "point_Iyy": f"{_PARTS}.point.inertia_tensor[2,2]",
        "point_Izz": f"{_PARTS}.point.inertia_tensor[3,3]",
        "cylinder_axis_distances": f"{_PARTS}.cylinder.axis_distances",
        "Ixx": "inertia_tensor[1,1]",
        "Iyy": "inertia_tensor[2,2]",
        "Izz": "inertia_tensor[3,3]",
        "inertia_tensor": "inertia_tensor",
        "principal_moments": "principal_moments",
        "product_of_inertia_xy": None,  # P_xy = -J_xy: a different sign convention, no result of its own
        "principal_axis_angle_deg": None,
    },
    2: {
        "pivot_to_centroid": "bodies.rod.center_of_mass[1]",
        "centroidal_inertia": "bodies.rod.inertia_tensor_com[3,3]",
        "pivot_inertia": "bodies.rod.inertia_tensor[3,3]",
        "T_coefficient": None,  # the coefficient of theta_dot**2 in T: answered by T (kinetic_energy)
    },
}
# where each typo of the answer key is reported
TYPO_ENTRY = {
    (1, "cylinder_Ixx"): f"{_PARTS}.cylinder.inertia_tensor[1,1]",
    (1, "Ixx"): "inertia_tensor[1,1]",
    (2, "T_coefficient"): "kinetic_energy",
    (5, "intermediate.dL_dtheta2"): "lagrange_terms[2].dL_dq",
    (7, "velocity.m2.0"): "velocities.link2[1]",
    (8, "C.0"): "coriolis_vector[1]",
}


def spec_path(pid: int) -> str:
    return str(SPECS / "tutorial-1" / SPEC_OF[pid])


def typo_entries(pid: int) -> set[str]:
    """The report entries at which the printed answers of problem ``pid`` must be flagged."""
    return {TYPO_ENTRY[(pid, t["answer_key"])] for t in problems()[pid].get("typos", [])}


def answers_file(pid: int, *, printed: bool) -> dict[str, Any]:
    """Problem ``pid`` of the answer key as an answers file (problems 3 to 10; for 1 and 2 see
    :func:`numbers_file`). ``printed``: only what the tutorial prints, typos as printed."""
    problem = problems()[pid]
    answers = problem["answers"]
    typos = {t["answer_key"]: t["printed"] for t in problem.get("typos", [])} if printed else {}
    keys = problem["printed_in_tutorial"] if printed else list(answers)
    coords = problem["coordinates"]
    out: dict[str, Any] = {}
    for key in keys:
        value = answers[key]
        if key in RESULT_OF:
            if isinstance(value, list) and not isinstance(value[0], list):
                value = [typos.get(f"{key}.{i}", v) for i, v in enumerate(value)]
            out[RESULT_OF[key]] = value
        elif key in ("christoffel", "christoffel_first_kind"):
            shown = problem.get("printed_christoffel_keys") if printed and key == "christoffel" else None
            out[key] = {",".join(k[1:]): value[k] for k in (shown or value)}
        elif key == "intermediate":
            for c in coords:
                names = {f"dL_d{c}_dot": "dL_dqdot", f"ddt_dL_d{c}_dot": "ddt_dL_dqdot", f"dL_d{c}": "dL_dq"}
                for src, dst in names.items():
                    if src in value:
                        out[f"lagrange_terms.{c}.{dst}"] = typos.get(f"intermediate.{src}", value[src])
        elif key == "equations_of_motion":
            out[key] = {eq["coordinate"]: f"{eq['lhs']} = {eq['force']}" for eq in value}
        elif key in ("position", "velocity"):
            result = "positions" if key == "position" else "velocities"
            for body, comps in value.items():
                for i, text in enumerate(comps):
                    out[f"{result}.{BODY_OF[pid][body]}[{i + 1}]"] = typos.get(f"{key}.{body}.{i}", text)
        elif key == "velocity_squared":
            for body, text in value.items():
                out[f"speeds_squared.{BODY_OF[pid][body]}"] = text
        else:
            raise KeyError(f"problem {pid}: no result for the answer key's '{key}'")
    return out


def numbers_file(pid: int) -> tuple[dict[str, Any], dict[str, Any]]:
    """Problem 1 or 2 of the answer key as an answers file (the correct values) and a marking key
    (its tolerances: the instructor's, never the answers file's)."""
    out: dict[str, Any] = {}
    rules: dict[str, Any] = {}
    for key, spec in problems()[pid]["answers"].items():
        if key == "T":
            out["kinetic_energy"] = spec
            continue
        target = NUMBER_OF[pid][key]
        if target is None or any(k.startswith(target + "[") or target.startswith(k + "[") for k in out):
            continue  # an entry may be answered once: the whole tensor or its entries, not both
        out[target] = spec["value"]
        rule = {k: spec[k] for k in ("rel_tol", "abs_tol") if k in spec}
        if rule:
            rules[target] = rule
    return out, {"items": rules} if rules else {}
