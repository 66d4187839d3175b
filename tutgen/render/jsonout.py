"""The JSON output: tutgen's machine contract (documented in docs/json-output.md).

Numbers are JSON numbers; expressions are strings in the spec grammar, with a coordinate x's
velocity and acceleration written x_dot and x_ddot. Keys appear only for results that apply.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import sympy as sp

from tutgen.engine.analysis import LinearModel, SteadyMotion
from tutgen.engine.analysis.equilibria import existence
from tutgen.engine.derivation import Derivation
from tutgen.engine.ne_types import PlanarNewtonEuler
from tutgen.engine.newton_euler import ConstraintReaction, NewtonEuler
from tutgen.engine.serial import LARGE
from tutgen.engine.steps import Step
from tutgen.figure.view import figure_json
from tutgen.model.system import Ask
from tutgen.render.blocks import PRINT_BUDGET, PROGRAM_BUDGET
from tutgen.render.grammar import grammar_text
from tutgen.render.sections.newton_euler import free_bodies
from tutgen.render.size import count_ops_upto
from tutgen.version import __version__

JSON_FORMAT_VERSION = 1


def expr_text(expr: sp.Expr) -> str:
    """An expression in the spec grammar (``**`` for powers, exact fractions, ``exp(1)`` for e), its
    terms in sympy's argument order (tutgen.render.grammar: fast and the same under any hash seed)."""
    return grammar_text(expr)


def value(expr: Any) -> Any:
    """A JSON value: an int or float for numbers, a string for expressions."""
    if isinstance(expr, (int, float)):
        return expr
    expr = sp.sympify(expr) if not isinstance(expr, sp.Basic) else expr
    if expr.is_Integer:
        return int(expr)
    if expr.is_number:
        if not isinstance(expr, sp.Rational) and expr.is_real is False:  # (a rational is real: not asked)
            return expr_text(expr)
        return float(sp.N(expr, 17))
    return expr_text(expr)


def vector(m: sp.MatrixBase) -> list[Any]:
    """A column (or any vector) as a flat JSON list."""
    return [value(e) for e in m]


def matrix(m: sp.MatrixBase) -> list[Any]:
    """A matrix as a list of rows, whatever its shape (a 1 x 1 matrix stays [[x]])."""
    return [[value(m[i, j]) for j in range(m.shape[1])] for i in range(m.shape[0])]


#: a serial arm whose H, C q_dot and G written out have more operations than this together (sympy's
#: count_ops, counted only up to it) is given in the JSON by ``results.program`` alone unless the entries
#: are asked for (``tutgen solve --expand``): the worked solution's own threshold for printing the program
EXPAND_BUDGET = PROGRAM_BUDGET

#: with ``results.expanded`` false, an equation side of a step with more operations than this (what a
#: worked solution prints whole, tutgen.render.blocks.PRINT_BUDGET) is ``null``, value and LaTeX
STEP_SIDE_BUDGET = PRINT_BUDGET

#: the keys of ``results`` that hold entries written out: absent when ``results.expanded`` is false
EXPANDED_KEYS = (
    "kinetic_energy",
    "lagrangian",
    "mass_matrix",
    "coriolis_vector",
    "coriolis_matrix",
    "gravity_vector",
    "mass_matrix_determinant",
    "equations_of_motion",
    "christoffel",
    "christoffel_first_kind",
)

NOTE_NOT_EXPANDED = (
    "Written out, H, C q_dot and G have more than {budget} operations: they are given by results.program "
    "(the definitions x_k in order, then H, C q_dot and G in terms of them). The entries written out "
    f"({', '.join(EXPANDED_KEYS)}) are left out: tutgen solve --expand writes them."
)


def is_program_only(d: Derivation) -> bool:
    """Whether the JSON of ``d`` gives H, C q_dot and G by their program alone when not asked to expand
    them: a serial arm with a program, no springs (the program's G is gravity's), and more than
    ``EXPAND_BUDGET`` operations written out (a budgeted count: C q_dot is not converted for it)."""
    if d.program is None or d.system.springs or d.mass_matrix is None:
        return False
    parts = [d.mass_matrix, d.coriolis_vector, d.gravity_vector]
    return count_ops_upto([p for p in parts if p is not None], EXPAND_BUDGET) > EXPAND_BUDGET


def derivation_to_json(d: Derivation, expand: bool = True) -> dict[str, Any]:
    """The JSON document for one derivation (numeric parameters substituted).

    ``expand=False``: a large serial arm (:func:`is_program_only`) gets ``results.program`` and
    ``results.expanded: false`` instead of the entries written out (:data:`EXPANDED_KEYS`), which are
    then never converted to sympy nor printed; every other derivation is the same either way."""
    system = d.system
    written = expand or not is_program_only(d)  # the entries written out (EXPANDED_KEYS)
    out = {
        "tutgen": __version__,
        "format": JSON_FORMAT_VERSION,
        "title": system.title,
        "coordinates": [c.name for c in system.coordinates],
        "parameters": {p.name: (value(p.value) if p.value is not None else None) for p in system.parameters},
        "results": _results(d, written),
        "steps": steps_json(d, written),  # additive: the worked solution's steps, docs/json-output.md#steps
        "figure": {**figure_json(system), "free_bodies": _free_bodies(d)},  # additive, docs/json-output.md
        "remarks": list(d.remarks),
        "checks": [{"name": c.name, "passed": c.passed, "detail": c.detail} for c in d.checks],
    }
    if d.simulation is not None:  # additive, `ask: [simulation]` only: docs/json-output.md#simulation
        from tutgen.render.sections.simulation import simulation_json

        out["simulation"] = simulation_json(d.simulation)
    return out


def results_to_json(d: Derivation, expand: bool = True, working: bool = True) -> dict[str, Any]:
    """``results`` of :func:`derivation_to_json` alone, without the document's steps, figure and free-body
    diagrams, which no answer key holds (a sheet's keys: most of the time of the whole document).
    ``working=False`` also leaves out the planar Newton–Euler working (``newton_euler.planar``: the free
    bodies in words), which is not an answer."""
    return _results(d, expand or not is_program_only(d), working)


def _results(d: Derivation, written: bool, working: bool = True) -> dict[str, Any]:
    """The document's ``results``; ``written``: whether the entries written out (:data:`EXPANDED_KEYS`)
    are given; ``working``: whether the planar Newton–Euler working is."""
    system = d.system
    num = d.numeric
    ask = system.ask
    program_only = not written
    results: dict[str, Any] = {}

    if Ask.INERTIA in ask and d.inertia:
        bodies: dict[str, Any] = {}
        for bi, principal in zip(d.inertia, d.principal, strict=True):
            entry: dict[str, Any] = {
                "mass": value(num(bi.mass)),
                "center_of_mass": vector(num(bi.com)),
                "inertia_tensor": matrix(num(bi.inertia_origin)),
                "inertia_tensor_com": matrix(num(bi.inertia_com)),
            }
            if principal.origin is not None:
                entry["principal_moments"] = list(principal.origin.moments)
                entry["principal_axes"] = [list(a) for a in principal.origin.axes]
            if principal.com is not None:  # additive: about the centre of mass G, docs/json-output.md
                entry["principal_moments_com"] = list(principal.com.moments)
                entry["principal_axes_com"] = [list(a) for a in principal.com.axes]
            entry["parts"] = {
                p.name: {
                    "shape": p.shape.value,
                    **({"volume": value(num(p.volume))} if p.volume is not None else {}),
                    "mass": value(num(p.mass)),
                    "centroid": vector(num(p.centroid)),
                    "axis_distances": [value(num(x)) for x in p.axis_distances],
                    "inertia_centroid": matrix(num(p.inertia_centroid)),
                    "inertia_tensor": matrix(num(p.inertia_origin)),
                }
                for p in bi.parts
            }
            bodies[bi.name] = entry
        results["bodies"] = bodies
        if len(d.inertia) == 1:
            only = bodies[d.inertia[0].name]
            for key in ("mass", "center_of_mass", "inertia_tensor", "principal_moments"):
                if key in only:
                    results[key] = only[key]

    if d.kinetic_energy is not None:
        if d.kinematics and (Ask.KINETIC_ENERGY in ask or Ask.EQUATIONS_OF_MOTION in ask):
            results["positions"] = {k.name: vector(num(k.com)) for k in d.kinematics}
            results["velocities"] = {k.name: vector(num(k.velocity)) for k in d.kinematics}
            results["angular_velocities"] = {k.name: vector(num(k.angular_velocity)) for k in d.kinematics}
            results["speeds_squared"] = {e.name: value(num(e.speed_squared)) for e in d.energies}
            results["body_kinetic_energies"] = {e.name: value(num(e.kinetic)) for e in d.energies}
        if Ask.KINETIC_ENERGY in ask and written:
            results["kinetic_energy"] = value(num(d.kinetic_energy))
        if Ask.POTENTIAL_ENERGY in ask and d.potential_energy is not None:
            results["potential_energy"] = value(num(d.potential_energy))
        if Ask.LAGRANGIAN in ask and d.lagrangian is not None and written:
            results["lagrangian"] = value(num(d.lagrangian))
        if Ask.LAGRANGE_EQUATIONS in ask:
            results["lagrange_terms"] = [
                {
                    "coordinate": t.coordinate,
                    "dL_dqdot": value(num(t.dL_dqd)),
                    "ddt_dL_dqdot": value(num(t.ddt_dL_dqd)),
                    "dL_dq": value(num(t.dL_dq)),
                    "generalized_force": value(num(t.generalized_force)),
                }
                for t in d.lagrange_terms
            ]
        if (Ask.EQUATIONS_OF_MOTION in ask or Ask.LAGRANGE_EQUATIONS in ask) and d.generalized_forces is not None:
            results["generalized_forces"] = vector(num(d.generalized_forces))
        if (Ask.MATRIX_FORM in ask or Ask.CHRISTOFFEL in ask) and written:
            assert d.mass_matrix is not None
            results["mass_matrix"] = matrix(num(d.mass_matrix))
        if Ask.MATRIX_FORM in ask and written:
            assert d.coriolis_vector is not None and d.coriolis_matrix is not None and d.gravity_vector is not None
            results["coriolis_vector"] = vector(num(d.coriolis_vector))
            results["coriolis_matrix"] = matrix(num(d.coriolis_matrix))
            results["gravity_vector"] = vector(num(d.gravity_vector))
            if d.mass_matrix_determinant is not None:
                results["mass_matrix_determinant"] = value(num(d.mass_matrix_determinant))
        rotors = [j for j in system.joints if j.reflected_inertia is not None and j.coordinate is not None]
        if rotors and (Ask.MATRIX_FORM in ask or Ask.EQUATIONS_OF_MOTION in ask):
            # what the motors add to H (on its diagonal): spec data, listed so that H can be read
            results["rotors"] = {
                j.name: {
                    "coordinate": j.coordinate.name,
                    "rotor_inertia": value(num(j.rotor_inertia)),
                    "gear_ratio": value(num(j.gear_ratio if j.gear_ratio is not None else sp.Integer(1))),
                    "reflected_inertia": value(num(j.reflected_inertia)),
                }
                for j in rotors
                if j.coordinate is not None
            }
        if Ask.EQUATIONS_OF_MOTION in ask and d.equations_of_motion is not None and written:
            results["equations_of_motion"] = vector(num(d.equations_of_motion))
        if d.program is not None and (Ask.MATRIX_FORM in ask or program_only):
            results["program"] = _program(d, num)
            results["expanded"] = written  # additive (issue 17): false, the entries are left to the program
            if not written:
                results["expanded_note"] = NOTE_NOT_EXPANDED.format(budget=EXPAND_BUDGET)
        if Ask.CHRISTOFFEL in ask and written:
            large = len(system.coordinates) >= LARGE  # n^3 symbols, most of them zero: nonzero only
            results["christoffel"] = _christoffel(d.christoffel, num, large)
            results["christoffel_first_kind"] = _christoffel(d.christoffel_first_kind, num, large)
        if d.newton_euler is not None and Ask.EQUATIONS_OF_MOTION in ask:
            results["newton_euler"] = _newton_euler(d.newton_euler, num, working)
        if d.analysis is not None:  # issue 18: equilibria, linear models, momentum (below)
            results.update(analysis_results(d))
        if d.constraints is not None:  # additive, issue 21: multipliers, reduced equations (docs/json-output.md)
            results["constraints"] = constraints_json(d)
        if d.prescribed is not None:  # additive, issue 18.4: docs/json-output.md#prescribed
            results["prescribed"] = prescribed_results(d)
    return results


def _free_bodies(d: Derivation) -> list[dict[str, Any]]:
    """The free-body diagrams of the planar Newton–Euler step where it is printed: each body's SVG
    beside a Markdown solution and what it labels (``force:<the step's name of the force>``)."""
    return [{"body": v["body"], "svg": v["svg"], "labels": v["labels"]} for v in free_bodies(d)]


def _newton_euler(ne: NewtonEuler, num: Any, working: bool = True) -> dict[str, Any]:
    """The Newton-Euler results: the equations in Lagrange's contract ((H q_ddot + C + G - Q)_i, each
    = 0, same order and sign), and each joint's reaction: the force and the moment (about the joint's
    origin) that the parent exerts on the child, world components."""
    return {
        "method": ne.method.value,
        "equations_of_motion": vector(num(ne.equations_of_motion)),
        "reaction_forces": {
            r.joint: {"force": vector(num(r.force)), "moment": vector(num(r.moment))} for r in ne.reactions
        },
        "agrees_with_lagrange": ne.agrees_with_lagrange,
        "remarks": list(ne.remarks),
        **({"planar": _planar(ne.planar, num)} if ne.planar is not None and working else {}),
        **(_constraint_reactions(ne, num) if ne.constraint_reactions else {}),
    }


def _constraint_reactions(ne: NewtonEuler, num: Any) -> dict[str, Any]:
    """A constrained spec's constraint reactions in its multipliers, and the check with the reduced
    route (additive, issue 21, docs/json-output.md#newton_euler)."""

    def entry(cr: ConstraintReaction) -> dict[str, Any]:
        out: dict[str, Any] = {
            "kind": cr.kind,
            "constraints": list(cr.constraints),
            "multipliers": [str(x) for x in cr.multipliers],
            "generalized_force": vector(num(sp.ImmutableMatrix(cr.generalized_force))),
        }
        if cr.kind == "pin":
            assert cr.on_parent is not None and cr.on_child is not None
            out |= {
                "parent": cr.parent,
                "child": cr.child,
                "force_on_parent": vector(num(cr.on_parent)),
                "force_on_child": vector(num(cr.on_child)),
            }
        return out

    return {
        "constraint_reactions": {cr.name: entry(cr) for cr in ne.constraint_reactions},
        "agrees_with_reduction": ne.reduction is not None and ne.reduction.passed,
    }


def _planar(planar: PlanarNewtonEuler, num: Any) -> dict[str, Any]:
    """Newton-Euler as taught for a planar system (additive, docs/json-output.md#planar): per body its
    free-body diagram (every force, D'Alembert's included: where it acts, its x, y components, its
    couple about z) and its three balances, each = 0, with the reactions as unknowns; the elimination,
    coordinate by coordinate; the reactions solved last."""

    def pair(xy: tuple[sp.Expr, sp.Expr]) -> list[Any]:
        return [value(num(xy[0])), value(num(xy[1]))]

    return {
        "balances": [
            {
                "body": b.body,
                "about": b.about,
                "joint": b.joint,
                "point": pair(b.point),
                "forces": [
                    {
                        "name": f.name,
                        "kind": f.kind.value,
                        "source": f.source,
                        "point": pair(f.point),
                        "force": pair(f.force),
                        "torque": value(num(f.torque)),
                    }
                    for f in b.forces
                ],
                "sum_fx": value(num(b.sum_fx)),
                "sum_fy": value(num(b.sum_fy)),
                "sum_m": value(num(b.sum_m)),
            }
            for b in planar.balances
        ],
        "elimination": [
            {
                "coordinate": s.coordinate,
                "joint": s.joint,
                "contributions": [
                    {"body": c.body, "kind": c.kind, "via": c.via, "value": value(num(c.expr))} for c in s.contributions
                ],
                "eliminated": [str(u) for u in s.eliminated],
                "equation": value(num(s.equation)),
            }
            for s in planar.steps
        ],
        "reactions": {
            r.joint: {
                "kind": r.kind.value,
                "parent": r.parent,
                "child": r.child,
                "unknowns": {str(u): value(num(v)) for u, v in zip(r.unknowns, r.values, strict=True)},
                "force": pair(r.force),
                "moment": value(num(r.moment)),
                "solved_from": r.solved_from,
            }
            for r in planar.reactions
        },
    }


#: an equation side longer than this (characters of its text form) has no LaTeX in ``steps``
#: (``null``): the entries of a large serial arm, printed as a program in the worked solution anyway
STEP_LATEX_LIMIT = 20000


def steps_json(d: Derivation, expanded: bool = True) -> list[dict[str, Any]]:
    """The worked solution's steps in teaching order (tutgen.engine.steps): kind, quantity, why, the
    ids of the steps each depends on, and its equations, each side as a value (like ``results``,
    parameters with values substituted) and as LaTeX; not ``expanded`` (``results.expanded`` false), a
    side of more than ``STEP_SIDE_BUDGET`` operations is ``null`` (never converted nor printed)."""
    from tutgen.render.printer import TexPrinter  # the printer of the worked solutions

    tex = TexPrinter(d.system)
    num = d.numeric

    def side(expr: sp.Basic) -> tuple[Any, str | None]:
        if not expanded and count_ops_upto([expr], STEP_SIDE_BUDGET) > STEP_SIDE_BUDGET:
            return None, None
        if isinstance(expr, sp.MatrixBase):
            shown = num(expr)
            data: Any = matrix(shown)
            size = len(str(data))
        else:
            shown = num(expr)
            data = value(shown)
            size = len(str(data))
        return data, (tex(shown) if size <= STEP_LATEX_LIMIT else None)

    def one(step: Step) -> dict[str, Any]:
        equations = []
        for eq in step.equations:
            rhs, rhs_tex = side(eq.rhs)
            equations.append({"lhs": expr_text(eq.lhs), "rhs": rhs, "lhs_latex": tex(eq.lhs), "rhs_latex": rhs_tex})
        return {
            "id": step.id,
            "kind": step.kind.value,
            "quantity": step.quantity,
            "why": step.why,
            "depends_on": list(step.depends_on),
            "equations": equations,
        }

    return [one(step) for step in d.steps]


def _christoffel(table: Mapping[tuple[int, int, int], sp.Expr], num: Any, nonzero_only: bool) -> dict[str, Any]:
    """Every symbol, zeros included, or (a system of ``LARGE`` or more coordinates) the nonzero ones."""
    entries = ((key, value(num(e))) for key, e in sorted(table.items()))
    return {f"{i + 1},{j + 1},{k + 1}": v for (i, j, k), v in entries if not (nonzero_only and v == 0)}


def _program(d: Derivation, num: Any) -> dict[str, Any]:
    """A serial arm's H, C q_dot and G as the straight-line program of tutgen.engine.recursive: the
    definitions x_k = ... in evaluation order (each uses only earlier ones), and the three matrices
    written with them; substituted back, they equal mass_matrix, coriolis_vector and gravity_vector."""
    program = d.program
    assert program is not None
    return {
        "definitions": [{"name": str(x), "value": value(num(e))} for x, e in program.definitions],
        "mass_matrix": matrix(num(program.mass_matrix)),
        "coriolis_vector": vector(num(program.coriolis_vector)),
        "gravity_vector": vector(num(program.gravity_vector)),
    }


def dumps(doc: Any) -> str:
    """Deterministic JSON text: fixed key order (as built), two-space indent, trailing newline."""
    return json.dumps(doc, indent=2, ensure_ascii=False, allow_nan=False) + "\n"


# ---------------------------------------------------------------------------------------------
# Issue 18: results.equilibria, results.linearization and results.momentum
# (docs/json-output.md#equilibria-and-linearization); complex numbers as [re, im]
# ---------------------------------------------------------------------------------------------


def _complex(z: complex) -> list[float]:
    return [z.real + 0.0, z.imag + 0.0]


def _at(values: tuple[tuple[str, Any], ...], num: Any) -> dict[str, Any]:
    return {name: value(num(v)) for name, v in values}


def _relations(relations: Any) -> list[str]:
    """Inequalities in the spec grammar, e.g. ``g > R*omega**2``."""
    return [f"{expr_text(w.lhs)} {w.rel_op} {expr_text(w.rhs)}" for w in relations]


def _linear(m: LinearModel, num: Any) -> dict[str, Any]:
    out: dict[str, Any] = {
        "about": _at(m.about, num),
        "inputs": [str(u) for u in m.inputs],
        "mass_matrix": matrix(num(m.mass)),
        "damping_matrix": matrix(num(m.damping)),
        "stiffness_matrix": matrix(num(m.stiffness)),
        "input_matrix": matrix(num(m.input_matrix)),
        "state_matrix": matrix(num(m.state_matrix)),
        "state_input_matrix": matrix(num(m.state_input)),
        "stability": m.verdict,
        "reason": m.reason,
    }
    if m.characteristic is not None:
        out["characteristic_polynomial"] = value(num(m.characteristic))
    if m.conditions:
        out["stiffness_minors"] = [value(num(c)) for c in m.conditions]
    if m.stable_where:
        out["stable_where"] = _relations(m.stable_where)
    if m.modes is not None:
        out["modes"] = [
            {
                "eigenvalue": _complex(mode.eigenvalue),
                "natural_frequency": mode.natural_frequency,  # rad/s
                "frequency_hz": mode.frequency_hz,
                "damping_ratio": mode.damping_ratio,
                "shape": [_complex(x) for x in mode.shape],
            }
            for mode in m.modes
        ]
    return out


def analysis_results(d: Derivation) -> dict[str, Any]:
    """The keys ``equilibria`` and ``linearization`` of ``results``, those that were derived."""
    a = d.analysis
    if a is None:
        return {}
    num = d.numeric
    out: dict[str, Any] = {}
    if a.equilibria is not None:
        eq = a.equilibria
        out["equilibria"] = {
            "residual": vector(num(eq.residual)),
            "method": eq.method,
            "free_coordinates": list(eq.free),
            "solutions": [
                {
                    "at": _at(sol, num),
                    "stability": m.verdict,
                    "reason": m.reason,
                    **({"exists_where": _relations([x for _, v in sol for x in existence(v)])} if exists else {}),
                    **({"stable_where": _relations(m.stable_where)} if m.stable_where else {}),
                }
                for sol, m in zip(eq.solutions, a.classified, strict=False)
                for exists in [any(existence(v) for _, v in sol)]
            ],
            **({"remark": eq.remark} if eq.remark else {}),
        }
    if a.linear:
        out["linearization"] = [_linear(m, num) for m in a.linear]
    if a.steady is not None:
        out["steady_motion"] = _steady(a.steady, num)
    if a.momentum is not None:
        mo = a.momentum
        out["momentum"] = {
            "bodies": {
                b.name: {
                    "linear": vector(num(b.linear)),
                    "angular_com": vector(num(b.angular_com)),
                    "angular_com_body": vector(num(b.angular_com_body)),
                    "angular_origin": vector(num(b.angular_origin)),
                }
                for b in mo.bodies
            },
            "linear": vector(num(mo.linear)),
            "angular_origin": vector(num(mo.angular_origin)),
            "angular_origin_rate": vector(num(mo.angular_rate)),
            "gravity_moment": vector(num(mo.gravity_moment)),
            "support_moment": vector(num(mo.support_moment)),
            "steady_support_moment": vector(num(mo.steady_support_moment)),
            "conserved": [{"name": q.name, "value": value(num(q.value)), "why": q.why} for q in mo.conserved],
        }
    return out


def _steady(st: SteadyMotion, num: Any) -> dict[str, Any]:
    """``results.steady_motion`` (docs/json-output.md#steady-motion)."""
    states = []
    for x in st.states:
        one: dict[str, Any] = {
            "at": _at(x.at, num),
            "exists": x.exists,
            "exists_where": _relations(x.exists_where),
            "required": _at(x.required, num),
            "inputs": {str(u): value(num(v)) for u, v in x.inputs},
            "momenta": _at(x.momenta, num),
            "mass_matrix": matrix(num(x.mass)),
            "damping_matrix": matrix(num(x.damping)),
            "stiffness_matrix": matrix(num(x.stiffness)),
            "stability": x.verdict,
            "reason": x.reason,
        }
        if x.stable_where:
            one["stable_where"] = _relations(x.stable_where)
        if x.eigenvalues is not None:
            one["eigenvalues"] = [_complex(z) for z in x.eigenvalues]
        states.append(one)
    return {
        "cyclic": list(st.cyclic),
        "rates": _at(st.rates, num),
        "free": list(st.free),
        "others": list(st.others),
        "free_others": list(st.free_others),
        "held": st.held,
        "residual": vector(num(st.residual)),
        "method": st.method,
        **({"remark": st.remark} if st.remark else {}),
        "states": states,
    }


def prescribed_results(d: Derivation) -> dict[str, Any]:
    """The driven coordinates (tutgen.engine.prescribed): each one's motion and the force or torque that
    drives it, and the free coordinates' equations with the motion substituted, in matrix form."""
    pm = d.prescribed
    assert pm is not None
    num = d.numeric
    driven: dict[str, Any] = {}
    for x in pm.driven:
        entry = {
            "motion": value(num(x.motion)),
            "rate": value(num(x.rate)),
            "acceleration": value(num(x.acceleration)),
            "kind": x.kind,
            "drive": value(num(x.drive)),
        }
        if x.drive_along_motion is not None:
            entry["drive_along_motion"] = value(num(x.drive_along_motion))
        driven[x.name] = entry
    return {
        "coordinates": driven,
        "free_coordinates": [d.system.coordinates[i].name for i in pm.free],
        "mass_matrix": matrix(num(pm.mass_matrix)),
        "coriolis_vector": vector(num(pm.coriolis_vector)),
        "gravity_vector": vector(num(pm.gravity_vector)),
        "driving_vector": vector(num(pm.driving_vector)),
        "generalized_forces": vector(num(pm.generalized_forces)),
        "equations_of_motion": vector(num(pm.equations_of_motion)),
    }


def constraints_json(d: Derivation) -> dict[str, Any] | None:
    """The constrained results for the JSON output's ``results.constraints`` (docs/json-output.md): the
    constraints, A, B, T and det A_d, the position analysis, the multipliers and the reduced equations;
    ``None`` for a spec without constraints. Numeric parameters substituted, as in every result."""

    cd = d.constraints
    if cd is None:
        return None
    ck = cd.kinematics
    num = d.numeric
    names = [x.name for x in d.system.coordinates]
    out: dict[str, Any] = {
        "names": [con.name for con in ck.constraints],
        "kinds": [con.kind.value for con in ck.constraints],
        "functions": [value(num(f)) for f in ck.functions],
        "jacobian": matrix(num(ck.jacobian)),
        "independent_coordinates": [names[j] for j in ck.independent],
        "dependent_coordinates": [names[j] for j in ck.dependent],
        "velocity_ratios": matrix(num(ck.velocity_ratios)),
        "dependent_determinant": value(num(ck.determinant)),
        "velocity_map": matrix(num(ck.velocity_map)),
        "acceleration_terms": vector(num(ck.bias)),
    }
    if ck.positions or ck.loop is not None:
        branches = [(0, ck.positions[0])] if ck.positions else [(b.sign, b.positions) for b in ck.loop.branches]  # type: ignore[union-attr]
        out["position_analysis"] = [
            {"sign": sign, "positions": {names[j]: value(num(e)) for j, e in positions}} for sign, positions in branches
        ]
    out["multipliers"] = [str(lam) for lam in cd.multipliers]
    out["constraint_forces"] = vector(num(cd.constraint_forces))
    out["multipliers_in_accelerations"] = [value(num(e)) for e in cd.multipliers_in_accelerations]
    if cd.multiplier_values:
        out["multiplier_values"] = [value(num(e)) for e in cd.multiplier_values]
    reduced: dict[str, Any] = {
        "mass_matrix": matrix(num(cd.mass_matrix)),
        "coriolis_vector": vector(num(cd.coriolis_vector)),
        "gravity_vector": vector(num(cd.gravity_vector)),
        "generalized_forces": vector(num(cd.generalized_forces)),
        "equations_of_motion": vector(num(cd.equations_of_motion)),
    }
    if cd.accelerations:
        reduced["accelerations"] = [value(num(e)) for e in cd.accelerations]
    out["reduced"] = reduced
    return out
