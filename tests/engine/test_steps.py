"""The worked solution's steps (tutgen/engine/steps.py): which exist for each tutorial problem (from
the JSON ``steps``), that ``ask`` and ``methods`` govern the output, and that the records' equations
are true: H read off T equals H, each Christoffel symbol's definition evaluates to its value.

The expected step lists are the tutorial's (../shared/seed/tutorial-1.md): what each problem asks
for and the working its solution shows, not tutgen's output copied.
"""

from __future__ import annotations

import dataclasses
import re

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.engine.pipeline import derive
from tutgen.engine.steps import H_ENTRY, StepKind, plan_steps
from tutgen.model.system import Ask, Method
from tutgen.render.markdown import render_markdown
from tutgen.spec.validate import load_system_text

TUTORIAL = SPECS / "tutorial-1"

# the energies and the equations of motion by Lagrange, then the matrix form and the Christoffel
# symbols: what problems 3-9 ask ("obtain the dynamic equations ... and express them in matrix form")
LAGRANGE = [
    "kinematics",
    "kinetic_energy",
    "potential_energy",
    "lagrangian",
    "lagrange_equations",
    "equations_of_motion",
    "mass_matrix",
    "matrix_form",
    "mass_matrix_derivatives",
    "christoffel",
]


@pytest.mark.parametrize(
    ("spec", "kinds"),
    [
        # p01: a composite body that does not move: its mass properties only
        pytest.param("p01-composite-inertia", ["inertia"], id="p01"),
        # p02: "the kinetic energy of the rod": its inertia (a rigid rod), its motion, T; nothing after
        pytest.param("p02-pivoted-rod", ["inertia", "kinematics", "kinetic_energy"], id="p02"),
        # p03: "once with the Lagrangian formulation and once with the Newton-Euler formulation"
        pytest.param("p03-cart-pendulum", [*LAGRANGE[:5], "newton_euler", *LAGRANGE[5:]], id="p03"),
        pytest.param("p04-rp-arm", LAGRANGE, id="p04"),
        pytest.param("p05-rr-arm", LAGRANGE, id="p05"),  # "using the Lagrangian formulation": no Newton-Euler
        pytest.param("p07-belt-driven-arm", LAGRANGE, id="p07"),
        # p09 has no gravity and no springs: no potential energy to write down
        pytest.param("p09-pr-manipulator", [k for k in LAGRANGE if k != "potential_energy"], id="p09"),
        # p10: T is given; H read off it, then the Christoffel symbols from dH/dq
        pytest.param(
            "p10-given-kinetic-energy",
            ["kinetic_energy", "mass_matrix", "matrix_form", "mass_matrix_derivatives", "christoffel"],
            id="p10",
        ),
    ],
)
def test_steps_of_each_tutorial_problem(spec: str, kinds: list[str]) -> None:
    _, _, doc = solved(str(TUTORIAL / f"{spec}.yaml"))
    assert [s["kind"] for s in doc["steps"]] == kinds
    ids = [s["id"] for s in doc["steps"]]
    for i, step in enumerate(doc["steps"]):  # each depends on earlier steps only, and says why
        assert set(step["depends_on"]) <= set(ids[:i])
        assert step["why"] and step["quantity"]
        for eq in step["equations"]:
            assert isinstance(eq["lhs"], str) and eq["lhs_latex"]


def test_steps_p02_prints_t_and_nothing_else() -> None:
    """p02 asks for T: no Newton-Euler, no checks of equations it was not shown, no H."""
    _, d, doc = solved(str(TUTORIAL / "p02-pivoted-rod.yaml"))
    text = render_markdown(d)
    assert "Newton" not in text and "agree" not in text
    assert "Christoffel" not in text and "Matrix form" not in text and "## Checks" not in text
    assert doc["checks"] == [] and "newton_euler" not in doc["results"]
    assert "T = " in text


def test_steps_ask_kinetic_energy_only() -> None:
    system = load_system_text(
        """
        {tutgen: 1, title: pendulum, parameters: [m, l, g], coordinates: [theta], gravity: [0, -g, 0],
         bodies: {bob: {mass: m}},
         joints: {pin: {type: revolute, parent: ground, child: bob, axis: z, coordinate: theta,
                        origin: [0, 0, 0]}},
         ask: [kinetic_energy]}
        """
    )
    d = derive(system, "both")  # even when both methods are asked for on the command line
    assert [s.kind for s in d.steps] == [StepKind.KINEMATICS, StepKind.KINETIC_ENERGY]
    assert d.newton_euler is None and d.checks == ()
    text = render_markdown(d)
    headings = re.findall(r"^## \d+\. (.+)$", text, re.M)
    assert headings == ["Kinematics", "Energies"]


def test_steps_ask_equations_of_motion_brings_what_it_needs() -> None:
    system, _, _ = solved(str(TUTORIAL / "p05-rr-arm.yaml"))
    only = dataclasses.replace(system, ask=frozenset({Ask.EQUATIONS_OF_MOTION}))
    assert [k.value for k, _ in plan_steps(only)] == LAGRANGE[:6]
    both = dataclasses.replace(only, methods=(Method.LAGRANGE, Method.NEWTON_EULER))
    plan = dict(plan_steps(both))
    assert set(plan[StepKind.EQUATIONS_OF_MOTION]) == {StepKind.LAGRANGE_EQUATIONS, StepKind.NEWTON_EULER}
    ne_only = dataclasses.replace(only, methods=(Method.NEWTON_EULER,))
    assert [k.value for k, _ in plan_steps(ne_only)] == ["kinematics", "newton_euler", "equations_of_motion"]


def _step(d, kind: StepKind):
    return next(s for s in d.steps if s.kind is kind)


@pytest.mark.parametrize("spec", ["p03-cart-pendulum", "p05-rr-arm", "p07-belt-driven-arm", "p10-given-kinetic-energy"])
def test_steps_mass_matrix_read_off_t_is_h(spec: str) -> None:
    """Each H_ij read off the coefficients of T equals H (built from the Hessian of T in the engine)."""
    _, d, _ = solved(str(TUTORIAL / f"{spec}.yaml"))
    entries = [e for e in _step(d, StepKind.MASS_MATRIX).equations if isinstance(e.lhs, sp.Indexed)]
    n = len(d.system.coordinates)
    assert len(entries) == n * (n + 1) // 2
    for e in entries:
        i, j = (int(x) - 1 for x in e.lhs.indices)
        assert sp.simplify(e.rhs - d.mass_matrix[i, j]) == 0


def test_steps_p10_against_the_tutorial() -> None:
    """The tutorial's p10: H_11 = 3 + 2 cos theta2, H_12 = 1 + cos theta2, H_22 = 1; h_112 = -2 sin theta2,
    h_122 = -sin theta2, h_111 = h_121 = 0; C = [-sin theta2 (2 theta1_dot theta2_dot + theta2_dot^2),
    sin theta2 theta1_dot^2]."""
    _, d, _ = solved(str(TUTORIAL / "p10-given-kinetic-energy.yaml"))
    first, second = d.system.coordinates  # the spec's symbols (with their assumptions)
    t2, t1d, t2d = second.q, first.qd, second.qd
    read = {
        tuple(int(x) for x in e.lhs.indices): e.rhs
        for e in _step(d, StepKind.MASS_MATRIX).equations
        if isinstance(e.lhs, sp.Indexed)
    }
    assert read == {(1, 1): 3 + 2 * sp.cos(t2), (1, 2): 1 + sp.cos(t2), (2, 2): sp.Integer(1)}
    symbols = {}
    for e in _step(d, StepKind.CHRISTOFFEL).equations:
        if isinstance(e.lhs, sp.Indexed) and str(e.lhs.base) == "h" and not e.rhs.has(sp.Derivative):
            symbols[tuple(int(x) for x in e.lhs.indices)] = e.rhs
    assert symbols[1, 1, 2] == -2 * sp.sin(t2) and symbols[1, 2, 2] == -sp.sin(t2)
    assert (1, 1, 1) not in symbols and (1, 2, 1) not in symbols  # zero: not listed
    c = next(e.rhs for e in _step(d, StepKind.CHRISTOFFEL).equations if e.lhs == sp.Symbol("C"))
    assert sp.simplify(c[0] + sp.sin(t2) * (2 * t1d * t2d + t2d**2)) == 0
    assert sp.simplify(c[1] - sp.sin(t2) * t1d**2) == 0
    text = render_markdown(d)
    assert "\\frac{\\partial H_{11}}{\\partial \\theta_2} = - 2 \\sin\\theta_2" in text
    assert "Compare $T = \\tfrac12\\dot q^T H\\dot q = \\tfrac12 H_{11}" in text


@pytest.mark.parametrize("spec", ["p03-cart-pendulum", "p05-rr-arm", "p10-given-kinetic-energy"])
def test_steps_christoffel_definitions_evaluate_to_their_values(spec: str) -> None:
    """Each symbol's definition, its dH_ij/dq_k replaced by the derivatives of H itself, is its value;
    every non-zero symbol of both conventions is listed; the derivative table is H's."""
    _, d, _ = solved(str(TUTORIAL / f"{spec}.yaml"))
    h = d.mass_matrix

    def evaluate(expr: sp.Expr) -> sp.Expr:
        return expr.replace(
            lambda x: isinstance(x, sp.Derivative),
            lambda x: sp.diff(h[int(x.expr.indices[0]) - 1, int(x.expr.indices[1]) - 1], x.variables[0]),
        )

    for e in _step(d, StepKind.MASS_MATRIX_DERIVATIVES).equations:
        assert sp.simplify(evaluate(e.lhs) - e.rhs) == 0
    equations = [e for e in _step(d, StepKind.CHRISTOFFEL).equations if isinstance(e.lhs, sp.Indexed)]
    definitions = {e.lhs: e.rhs for e in equations if e.rhs.has(sp.Derivative)}
    values = {e.lhs: e.rhs for e in equations if not e.rhs.has(sp.Derivative)}
    assert definitions.keys() == values.keys()
    for name, definition in definitions.items():
        assert sp.simplify(evaluate(definition) - values[name]) == 0
    tutorial = {k for k, v in d.christoffel.items() if v != 0}
    first = {k for k, v in d.christoffel_first_kind.items() if v != 0}
    listed = {(str(n.base), tuple(int(x) - 1 for x in n.indices)) for n in values}
    assert listed == {("h", k) for k in tutorial} | {("c", k) for k in first}
    assert all(
        isinstance(e.lhs.expr, sp.Indexed) and e.lhs.expr.base == H_ENTRY
        for e in _step(d, StepKind.MASS_MATRIX_DERIVATIVES).equations
    )
