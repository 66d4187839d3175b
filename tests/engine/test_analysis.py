"""Issue 18: equilibria and linear models, against independent references.

- the cart-pole's linear model about its upright and hanging positions against sympy.physics.mechanics'
  ``KanesMethod.linearize`` of a twin built from the validated model alone (tests/engine/test_mechanics_generic.py);
- the eigenvalues of A against ``numpy.linalg.eig`` of a finite-difference Jacobian of the nonlinear state
  equations x_dot = [q_dot, H^-1 (Q - C - G)], built from H and the equations of motion, not from K and D;
- the two-mass chain's frequencies and mode shapes, and a damped oscillator's damping ratio, against their
  closed forms; the bead on a spinning hoop's equilibria and stability conditions against a hand derivation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tests.engine.test_mechanics_generic import MechanicsModel
from tests.models import system_of
from tutgen.engine.pipeline import derive
from tutgen.errors import SpecErrors

CART = str(SPECS / "examples" / "h-inverted-pendulum-cart.yaml")
HOOP = str(SPECS / "examples" / "i-bead-spinning-hoop.yaml")
CHAIN = str(SPECS / "examples" / "j-two-mass-chain-modes.yaml")


def _kane_linear(system, about: dict[str, float]) -> tuple[np.ndarray, np.ndarray]:
    """Kane's linear model of the system's twin: (M, A) at the rest state ``about``, parameters at
    their values, the input F (if any) at 0."""
    from sympy.physics.mechanics import KanesMethod

    model = MechanicsModel(system)
    bodies, loads = model.bodies_and_loads()
    assert all(e == 0 for e in model.extra_forces()), "the twin's forces must all be Kane's loads"
    kd = [q.diff(model.t) - u for q, u in zip(model.qs, model.us, strict=True)]
    km = KanesMethod(model.n_frame, q_ind=model.qs, u_ind=model.us, kd_eqs=kd)
    km.kanes_equations(bodies, loads)
    values = {sp.Symbol(p.name): p.value for p in system.parameters if p.value is not None}
    values |= {sp.Symbol(p.name): 0 for p in system.parameters if p.value is None}
    op = {q: about[c.name] for q, c in zip(model.qs, system.coordinates, strict=True)}
    op |= {u: 0 for u in model.us}
    op |= {u.diff(model.t): 0 for u in model.us}
    # the state [dq, du] with u = q_dot: x_dot = A x + B r
    a, _, _ = km.linearize(op_point=op, A_and_B=True, simplify=False)
    a = np.array(sp.Matrix(a).xreplace(values).subs(op).evalf().tolist(), dtype=float)
    mass = np.array(km.mass_matrix.xreplace(values).subs(op).evalf().tolist(), dtype=float)
    return mass, a


@pytest.mark.parametrize("theta", [0.0, math.pi], ids=["hanging", "upright"])
def test_linear_model_matches_kane_linearize(theta: float) -> None:
    system, d, _ = solved(CART)
    model = next(m for m in d.analysis.classified if abs(float(m.about[1][1]) - theta) < 1e-12)
    mass, a = _kane_linear(system, {"x": 0.0, "theta": theta})
    ours_m = np.array(d.numeric(model.mass).evalf().tolist(), dtype=float)
    ours_a = np.array(d.numeric(model.state_matrix).evalf().tolist(), dtype=float)
    assert np.allclose(ours_m, mass, rtol=1e-12, atol=1e-12)
    assert np.allclose(ours_a, a, rtol=1e-10, atol=1e-10)


def _state_function(d):
    """x_dot = [q_dot, H(q)^-1 (Q - C - G)] numerically, with the inputs at 0: built from H and the
    equations of motion, independently of the linear model's K and D."""
    s = d.system
    q = [c.q for c in s.coordinates]
    qd = [c.qd for c in s.coordinates]
    zero_acc = {c.qdd: 0 for c in s.coordinates}
    inputs = {p.symbol: 0 for p in s.parameters if p.value is None}
    bias = sp.Matrix(d.numeric(d.equations_of_motion.xreplace(zero_acc))).xreplace(inputs)  # C + G - Q
    h = sp.Matrix(d.numeric(d.mass_matrix)).xreplace(inputs)
    fh = sp.lambdify([q], h, "numpy")
    fb = sp.lambdify([q, qd], bias, "numpy")
    n = len(q)

    def f(x: np.ndarray) -> np.ndarray:
        acc = np.linalg.solve(np.array(fh(x[:n]), dtype=float), -np.array(fb(x[:n], x[n:]), dtype=float).ravel())
        return np.concatenate([x[n:], acc])

    return f


def _fd_jacobian(f, x0: np.ndarray, h: float = 1e-6) -> np.ndarray:
    cols = []
    for j in range(len(x0)):
        e = np.zeros_like(x0)
        e[j] = h
        cols.append((f(x0 + e) - f(x0 - e)) / (2 * h))
    return np.stack(cols, axis=1)


@pytest.mark.parametrize("spec", [CART, CHAIN], ids=["cart", "chain"])
def test_eigenvalues_match_numpy_of_finite_differences(spec: str) -> None:
    _, d, _ = solved(spec)
    f = _state_function(d)
    for model in d.analysis.classified or d.analysis.linear:
        x0 = np.array([float(v) for _, v in model.about] + [0.0] * len(model.about))
        reference = np.linalg.eigvals(_fd_jacobian(f, x0))
        ours = []
        for m in model.modes:
            ours += [m.eigenvalue] + ([m.eigenvalue.conjugate()] if m.eigenvalue.imag else [])
        assert len(ours) == len(reference)
        for lam in reference:
            assert min(abs(lam - z) for z in ours) < 1e-5 * max(1.0, abs(lam))


def test_cart_pole_equilibria_and_verdicts() -> None:
    _, d, doc = solved(CART)
    eq = d.analysis.equilibria
    assert eq.free == ("x",)
    assert [dict(s)["theta"] for s in eq.solutions] == [0, sp.pi]
    verdicts = [m.verdict for m in d.analysis.classified]
    assert verdicts == ["stable", "unstable"]
    (upright,) = d.analysis.linear
    assert upright.about == (("x", 0), ("theta", sp.pi))
    # upright: lambda^2 = (M + m) m g (l/2) / det(H) with the rod's inertia m l^2/3 about the hinge
    m_, big, l_, g = 0.2, 1.0, 0.6, 9.81
    det = (big + m_) * m_ * l_**2 / 3 - (m_ * l_ / 2) ** 2
    lam = math.sqrt((big + m_) * m_ * g * l_ / 2 / det)
    assert max(m.eigenvalue.real for m in upright.modes) == pytest.approx(lam, rel=1e-9)
    assert doc["results"]["linearization"][0]["stability"] == "unstable"
    assert [s["stability"] for s in doc["results"]["equilibria"]["solutions"]] == ["stable", "unstable"]
    assert any(c.name == "linearization_matches_finite_differences" and c.passed for c in d.checks)


def test_two_mass_chain_modes_match_closed_form() -> None:
    _, d, doc = solved(CHAIN)
    (model,) = d.analysis.linear
    assert model.verdict == "stable"
    k, m = 100.0, 1.0
    # K = k [[2, -1], [-1, 1]], M = m I: omega^2 = (k/m)(3 -+ sqrt 5)/2, shapes [1, (1 +- sqrt 5)/2]
    omegas = sorted(math.sqrt(k / m * (3 + sgn * math.sqrt(5)) / 2) for sgn in (-1, 1))
    assert [mode.natural_frequency for mode in model.modes] == pytest.approx(omegas, rel=1e-10)
    assert [mode.frequency_hz for mode in model.modes] == pytest.approx([w / (2 * math.pi) for w in omegas])
    assert all(mode.damping_ratio == pytest.approx(0.0, abs=1e-12) for mode in model.modes)
    slow = np.real(model.modes[0].shape)
    assert slow[0] / slow[1] == pytest.approx(2 / (1 + math.sqrt(5)), rel=1e-9)
    modes = doc["results"]["linearization"][0]["modes"]
    assert modes[0]["natural_frequency"] == pytest.approx(omegas[0])


def test_bead_on_hoop_bifurcation() -> None:
    system, d, _ = solved(HOOP)
    eq = d.analysis.equilibria
    theta = system.coordinates[0].q
    m, r, w, g = (next(p.symbol for p in system.parameters if p.name == n) for n in ("m", "R", "omega", "g"))
    found = {sp.simplify(dict(s)["theta"]) for s in eq.solutions}
    assert found == {sp.Integer(0), sp.pi, sp.acos(g / (r * w**2)), -sp.acos(g / (r * w**2))}
    # by hand: U = -m g R cos(theta) - m R^2 w^2 sin(theta)^2/2, U'' = m R (g cos(theta) - R w^2 cos(2 theta))
    u2 = m * r * (g * sp.cos(theta) - r * w**2 * sp.cos(2 * theta))
    for sol, model in zip(eq.solutions, d.analysis.classified, strict=True):
        assert sp.simplify(model.stiffness[0, 0] - u2.subs(theta, dict(sol)["theta"])) == 0
    by_value = {sp.simplify(dict(s)["theta"]): mo for s, mo in zip(eq.solutions, d.analysis.classified, strict=True)}
    assert by_value[sp.pi].verdict == "unstable"
    assert by_value[0].verdict == "conditional"
    assert by_value[0].stable_where == (sp.StrictGreaterThan(g, r * w**2, evaluate=False),)
    assert by_value[sp.acos(g / (r * w**2))].stable_where == (sp.StrictGreaterThan(r * w**2, g, evaluate=False),)


def _oscillator(extra: dict) -> dict:
    spec = {
        "tutgen": 1,
        "title": "damped oscillator",
        "parameters": {"m": 2, "k": 50, "c": 3, "F": {}},
        "coordinates": {"x": {"dimension": "length"}},
        "bodies": {"block": {"mass": "m"}},
        "joints": {
            "slide": {"type": "prismatic", "parent": "ground", "child": "block", "axis": "x", "coordinate": "x"}
        },
        "springs": {"wall": {"stiffness": "k", "extension": "x"}},
        "dampers": {"dash": {"coefficient": "c", "extension": "x"}},
        "loads": {"push": {"body": "block", "force": ["F", 0, 0]}},
        "ask": ["linearization"],
    }
    spec.update(extra)
    return spec


def test_damped_oscillator_damping_ratio_and_input_matrix() -> None:
    d = derive(system_of(_oscillator({"analysis": {"about": {"x": 0}, "inputs": {"F": 0}}})))
    (model,) = d.analysis.linear
    assert model.verdict == "asymptotically stable"
    (mode,) = model.modes
    assert mode.natural_frequency == pytest.approx(5.0)  # sqrt(k/m)
    assert mode.damping_ratio == pytest.approx(3 / (2 * math.sqrt(50 * 2)))  # c / (2 sqrt(k m))
    assert model.input_matrix == sp.ImmutableMatrix([[1]])
    assert d.numeric(model.state_input) == sp.ImmutableMatrix([[0], [sp.Rational(1, 2)]])  # 1/m


def test_given_point_that_is_not_an_equilibrium_is_a_located_spec_error() -> None:
    system = system_of(_oscillator({"analysis": {"about": {"x": 0.1}, "inputs": {"F": 0}}}))
    with pytest.raises(SpecErrors) as info:
        derive(system)
    text = str(info.value)
    assert "'about' is not an equilibrium" in text
    assert "(G - Q)_x = 5.000" in text  # k x = 50 * 0.1 N: by how much it fails
    line, col = text.split(":")[1:3]
    assert (int(line), int(col)) > (1, 1)  # at `about`, not at the top of the spec


def test_input_holds_a_forced_equilibrium() -> None:
    """With F held at 10 N the spring's rest point moves to x = F/k, and it is an equilibrium there."""
    held = {"analysis": {"about": {"x": "1/5"}, "inputs": {"F": 10}}, "ask": ["equilibria"]}
    d = derive(system_of(_oscillator(held)))
    assert [d.numeric(dict(s)["x"]) for s in d.analysis.equilibria.solutions] == [sp.Rational(1, 5)]


def test_no_isolated_equilibrium_is_reported_not_an_error() -> None:
    spec = _oscillator({"ask": ["equilibria"]})
    del spec["springs"]
    d = derive(system_of(spec))
    eq = d.analysis.equilibria
    assert eq.free == ("x",) and eq.method == "symbolic"
    assert d.analysis.classified[0].verdict == "stable"  # neutral along x, damped otherwise: nothing else


def test_default_ask_has_no_analysis() -> None:
    spec = _oscillator({})
    del spec["ask"]
    d = derive(system_of(spec))
    assert d.analysis is None
    assert not {"equilibria", "linearization"} & {st.kind.value for st in d.steps}


def test_transcendental_equilibria_are_found_numerically_in_the_box() -> None:
    """G = theta - 2 sin(theta) has no closed-form roots: every root in one turn, found numerically,
    each checked against the residual, and classified by the sign of U'' = 1 - 2 cos(theta)."""
    spec = {
        "tutgen": 1,
        "title": "transcendental well",
        "parameters": {"J": "1 kg*m^2", "k": "1 N*m"},
        "coordinates": {"theta": {"dimension": "angle"}},
        "energy": {"kinetic": "J*theta_dot**2/2", "potential": "k*(2*cos(theta) + theta**2/2)"},
        "ask": ["equilibria"],
    }
    d = derive(system_of(spec))
    eq = d.analysis.equilibria
    assert eq.method == "numeric"
    roots = sorted(float(dict(s)["theta"]) for s in eq.solutions)
    assert len(roots) == 3 and roots[1] == pytest.approx(0.0, abs=1e-9)
    for x in roots:
        assert x - 2 * math.sin(x) == pytest.approx(0.0, abs=1e-9)
    verdicts = {
        round(float(dict(s)["theta"]), 6): m.verdict for s, m in zip(eq.solutions, d.analysis.classified, strict=True)
    }
    assert verdicts[round(roots[1], 6)] == "unstable"
    assert verdicts[round(roots[0], 6)] == verdicts[round(roots[2], 6)] == "stable"


def test_equilibrium_where_the_coordinates_are_singular_is_undetermined_not_a_crash() -> None:
    """The heavy top at rest, θ = 0 and θ = π: H(q0) is singular there (the Euler angles' pole), so the
    linear model has no state space and no eigenvalues; it was a NonInvertibleMatrixError (an internal
    error on the command line). M, D and K are still given, and still match finite differences."""
    import dataclasses

    from tutgen.engine.analysis.linear import SINGULAR_MASS
    from tutgen.model.system import Ask
    from tutgen.render.jsonout import derivation_to_json
    from tutgen.spec.validate import load_system

    system = load_system(SPECS / "examples" / "g-heavy-symmetric-top.yaml")
    d = derive(dataclasses.replace(system, ask=system.ask | {Ask.EQUILIBRIA, Ask.LINEARIZATION}))
    models = d.analysis.classified
    assert [dict(m.about)["theta"] for m in models] == [0, sp.pi]
    for m in models:
        assert sp.Matrix(m.mass).det() == 0
        assert m.state_matrix.shape == (0, 0) and m.modes is None
        assert (m.verdict, m.reason) == ("undetermined", SINGULAR_MASS)
        assert m.check is not None and m.check.passed
    results = derivation_to_json(d)["results"]
    assert [e["stability"] for e in results["equilibria"]["solutions"]] == ["undetermined"] * 2
    assert [(e["state_matrix"], "modes" in e) for e in results["linearization"]] == [([], False)] * 2


def test_equilibria_sympy_cannot_solve_are_said_so_not_denied() -> None:
    """The cart's spring of length sqrt((d + x)^2) has no polynomial form: sympy's factor raised (an internal
    error for `ask: [equilibria]`), and a symbolic spec has no numbers to search: tutgen says that, not
    "no equilibrium" (the cart rests at x = L0 - d)."""
    import dataclasses

    from tutgen.engine.analysis.equilibria import UNSOLVED_REMARK
    from tutgen.model.system import Ask
    from tutgen.spec.validate import load_system

    system = load_system(SPECS / "examples" / "b-cart-pendulum-sphere.yaml")
    eq = derive(dataclasses.replace(system, ask=system.ask | {Ask.EQUILIBRIA})).analysis.equilibria
    assert eq.solutions == () and eq.method == "none" and eq.remark == UNSOLVED_REMARK


def test_finite_difference_check_takes_parameter_values_where_the_equilibrium_is_real() -> None:
    """The bead in the rotating tube rests at phi = asin(k r0/(g m)), real only where k r0 <= g m: the
    check's first test values made it complex (an internal error for `ask: [equilibria]`); the next set
    that makes every equilibrium real is taken, and each model still matches central differences."""
    import dataclasses

    from tutgen.model.system import Ask
    from tutgen.spec.validate import load_system

    system = load_system(SPECS / "examples" / "e-bead-in-rotating-tube.yaml")
    models = derive(dataclasses.replace(system, ask=system.ask | {Ask.EQUILIBRIA})).analysis.classified
    assert any(str(v).startswith("asin") or "asin" in str(v) for m in models for _, v in m.about)
    for m in models:
        assert m.check is not None and m.check.passed and "equal central differences" in m.check.detail
