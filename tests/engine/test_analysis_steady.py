"""Issue 18 point 3: steady motion, against independent references.

- every steady motion satisfies the nonlinear equations of motion of a sympy.physics.mechanics twin
  (Kane's method on a model built from the validated spec alone, tests/engine/test_mechanics_generic.py);
- the stability of each steady motion against the eigenvalues of Kane's full linearisation about it
  (``KanesMethod.linearize`` with the cyclic rate in the operating point): a driven rate keeps its
  row and column out, a free one is kept in, and its two zero eigenvalues (the angle, the momentum)
  are set aside;
- the bead on a hoop's closed forms (cos theta = g/(R omega^2), exists where g <= R omega^2) and the
  conical pendulum's frequency, omega_n^2 = Omega^2 (1 + 3 cos^2 theta), by hand;
- bad input: a named coordinate that is not cyclic (a located spec error naming H, G or Q), a rate at
  which no steady motion exists (a result, not an error).
"""

from __future__ import annotations

import random
from typing import Any

import numpy as np
import pytest
import sympy as sp
import yaml

from tests.conftest import SPECS, solved
from tests.engine.test_mechanics_generic import MechanicsModel
from tests.models import system_of
from tutgen.engine.pipeline import derive
from tutgen.errors import SpecErrors

DRIVEN = str(SPECS / "examples" / "s-bead-on-driven-hoop.yaml")
FREE = str(SPECS / "examples" / "t-bead-on-free-hoop.yaml")
CONE = str(SPECS / "examples" / "u-conical-pendulum.yaml")
TOP = SPECS / "examples" / "g-heavy-symmetric-top.yaml"
ROTOR = SPECS / "examples" / "k-rotor-skewed-disc.yaml"


def _with(path: Any, **changes: Any) -> Any:
    data = yaml.safe_load(open(path, encoding="utf-8").read())
    data.update(changes)
    return system_of(data)


def _fill(system: Any, seed: int) -> dict[str, float]:
    """Values by name for the parameters without one: random positive numbers (inputs, real symbols, 0)."""
    rng = random.Random(seed)
    out = {}
    for p in system.parameters:
        if p.value is not None:
            out[p.name] = float(p.value)
        else:
            out[p.name] = rng.uniform(0.6, 1.8) if p.symbol.is_positive else 0.0
    return out


def _kane(system: Any) -> tuple[Any, MechanicsModel]:
    from sympy.physics.mechanics import KanesMethod

    model = MechanicsModel(system)
    bodies, loads = model.bodies_and_loads()
    kd = [q.diff(model.t) - u for q, u in zip(model.qs, model.us, strict=True)]
    km = KanesMethod(model.n_frame, q_ind=model.qs, u_ind=model.us, kd_eqs=kd)
    km.kanes_equations(bodies, loads)
    return km, model


def _num(d: Any, expr: Any, values: dict[str, float]) -> float:
    """A value of tutgen's at the parameter values (a default rate symbol, phi_dot, at 1.3)."""
    subs = {p.symbol: values[p.name] for p in d.system.parameters}
    subs |= {c.qd: 1.3 for c in d.system.coordinates}
    return float(sp.N(sp.sympify(d.numeric(sp.sympify(expr))).xreplace(subs)))


def _operating_point(d: Any, model: MechanicsModel, state: Any, values: dict[str, float]) -> dict[Any, Any]:
    """The steady motion as Kane's operating point: q_s, u_s = 0, u_c = the rate, every u_dot = 0."""
    at = dict(state.at)
    rates = dict(d.analysis.steady.rates)
    op: dict[Any, Any] = {}
    for c, q, u in zip(d.system.coordinates, model.qs, model.us, strict=True):
        op[q] = _num(d, at.get(c.name, 0), values)
        op[u] = _num(d, rates.get(c.name, 0), values)
        op[u.diff(model.t)] = 0.0
    return op


def _exists(d: Any, state: Any, values: dict[str, float]) -> bool:
    subs = {p.symbol: values[p.name] for p in d.system.parameters}
    subs |= {c.qd: 1.3 for c in d.system.coordinates}
    return all(bool(sp.sympify(d.numeric(x)).xreplace(subs)) for x in state.exists_where)


def _values(system: Any, path: str) -> dict[str, float]:
    """Parameter values where the cones and tilted steady motions exist (R omega^2 > g)."""
    values = _fill(system, 18)
    for rate in ("omega", "Omega"):
        if rate in values:
            values[rate] = 4.0
    return values


@pytest.mark.parametrize("path", [DRIVEN, FREE, CONE], ids=["driven-hoop", "free-hoop", "conical-pendulum"])
def test_steady_motion_satisfies_kanes_equations(path: str) -> None:
    system, d, _ = solved(path)
    km, model = _kane(system)
    values = _values(system, path)
    ref = {sp.Symbol(k): v for k, v in values.items()}
    residual = (km.mass_matrix * sp.Matrix([u.diff(model.t) for u in model.us]) - km.forcing).xreplace(ref)
    checked = 0
    for state in d.analysis.steady.states:
        if not _exists(d, state, values):
            continue
        op = _operating_point(d, model, state, values)
        rows = [complex(sp.N(r.subs(op))) for r in residual]
        held = dict(d.analysis.steady.rates)
        for c, r in zip(system.coordinates, rows, strict=True):
            if c.name in held:
                # a held row is the generalized force the coordinate needs (the input tau at 0 in Kane's)
                assert abs(r - _num(d, dict(state.required)[c.name], values)) < 1e-9
            else:
                assert abs(r) < 1e-9, (c.name, state.at, r)
        checked += 1
    assert checked >= 3


def _reduced_eigenvalues(d: Any, state: Any, values: dict[str, float]) -> np.ndarray:
    subs = {p.symbol: values[p.name] for p in d.system.parameters}
    m = np.array(sp.Matrix(d.numeric(state.mass)).xreplace(subs).evalf().tolist(), dtype=float)
    k = np.array(sp.Matrix(d.numeric(state.stiffness)).xreplace(subs).evalf().tolist(), dtype=float)
    c = np.array(sp.Matrix(d.numeric(state.damping)).xreplace(subs).evalf().tolist(), dtype=float)
    n = m.shape[0]
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(m, k), -np.linalg.solve(m, c)]])
    return np.linalg.eigvals(a)


@pytest.mark.parametrize("path", [DRIVEN, FREE, CONE], ids=["driven-hoop", "free-hoop", "conical-pendulum"])
def test_steady_stability_matches_kanes_linearisation(path: str) -> None:
    system, d, _ = solved(path)
    km, model = _kane(system)
    values = _values(system, path)
    ref = {sp.Symbol(k): v for k, v in values.items()}
    st = d.analysis.steady
    names = [c.name for c in system.coordinates]
    n = len(names)
    held = [names.index(c) for c, _ in st.rates]
    checked = 0
    for state in st.states:
        if not _exists(d, state, values) or state.verdict == "undetermined" or state.pole:
            continue  # at a pole Kane's mass matrix is singular too: test_pole_* below
        op = _operating_point(d, model, state, values)
        a, _, _ = km.linearize(op_point=op, A_and_B=True, simplify=False)
        a = np.array(sp.Matrix(a).xreplace(ref).subs(op).evalf().tolist(), dtype=float)
        # the state [q, u]: a held angle's column is zero (cyclic); a driven rate is held, so its row and
        # column go too; a free rate stays (its momentum is held by the dynamics themselves)
        drop = [i for i in held] + [n + i for i in held if names[i] not in st.free]
        keep = [i for i in range(2 * n) if i not in drop]
        theirs = np.linalg.eigvals(a[np.ix_(keep, keep)])
        ours = _reduced_eigenvalues(d, state, values)
        # a free rate adds one zero eigenvalue (the momentum's level): set it aside
        theirs = sorted(theirs, key=abs)[len(theirs) - len(ours) :]
        for lam in ours:
            assert min(abs(lam - z) for z in theirs) < 1e-6 * max(1.0, abs(lam)), (state.at, ours, theirs)
        stable = all(z.real <= 1e-9 for z in theirs)
        where = all(_num(d, w.lhs - w.rhs, values) > 0 for w in state.stable_where)
        assert stable == (
            state.verdict in ("stable", "asymptotically stable") or (state.verdict == "conditional" and where)
        )
        checked += 1
    assert checked >= 2


def test_bead_on_driven_hoop_closed_forms() -> None:
    system, d, doc = solved(DRIVEN)
    m, big_r, g, w = sp.symbols("m R g omega", positive=True)
    st = d.analysis.steady
    sym = {p.symbol: sp.Symbol(p.name, positive=True) for p in system.parameters}
    assert st.cyclic == ("phi",) and st.free == () and st.held == "rate"
    values = {str(v) for state in st.states for _, v in state.at}
    assert values == {"0", "pi", "acos(g/(R*omega**2))", "-acos(g/(R*omega**2))"}
    tilted = [x for x in st.states if x.exists_where]
    assert len(tilted) == 2
    for x in tilted:
        assert [str(r) for r in x.exists_where] == ["g <= R*omega**2"]
        assert x.verdict == "stable"
        assert sp.simplify(x.stiffness[0, 0].xreplace(sym) - (m * big_r**2 * w**2 - m * g**2 / w**2)) == 0
    bottom = next(x for x in st.states if x.at[0][1] == 0)
    assert bottom.verdict == "conditional" and [str(r) for r in bottom.stable_where] == ["g > R*omega**2"]
    assert all([(str(u), v) for u, v in x.inputs] == [("tau", 0)] for x in st.states)
    steady = doc["results"]["steady_motion"]
    assert steady["held"] == "rate" and len(steady["states"]) == 4


def test_conical_pendulum_frequency_by_hand() -> None:
    _, d, _ = solved(CONE)
    st = d.analysis.steady
    g, l_, omega = 9.81, 0.8, 5.0
    theta = np.arccos(g / (l_ * omega**2))
    expected = omega * np.sqrt(1 + 3 * np.cos(theta) ** 2)
    cones = [x for x in st.states if x.exists_where]
    assert len(cones) == 2
    for x in cones:
        assert x.exists is True and x.verdict == "stable"
        assert abs(abs(x.eigenvalues[0]) - expected) < 1e-9
    assert st.check.passed


def _cartesian_pendulum_eigenvalues(up: bool, g: float, l_: float) -> np.ndarray:
    """The spherical pendulum in coordinates regular on the vertical axis, x and y of the bob (z from
    the rod's length), linearised about the axis by Kane's method: the independent reference at the
    pole theta = 0 (or pi, ``up``) of the spherical coordinates."""
    from sympy.physics.mechanics import KanesMethod, Particle, Point, ReferenceFrame, dynamicsymbols

    x, y, ux, uy = dynamicsymbols("x y u_x u_y")
    n = ReferenceFrame("N")
    o = Point("O")
    o.set_vel(n, 0)
    z = (1 if up else -1) * sp.sqrt(l_**2 - x**2 - y**2)
    bob = o.locatenew("P", x * n.x + y * n.y + z * n.z)
    bob.set_vel(n, bob.pos_from(o).dt(n).subs({x.diff(): ux, y.diff(): uy}))
    km = KanesMethod(n, q_ind=[x, y], u_ind=[ux, uy], kd_eqs=[x.diff() - ux, y.diff() - uy])
    m = 0.5
    km.kanes_equations([Particle("bob", bob, m)], [(bob, -m * g * n.z)])
    op = {x: 0, y: 0, ux: 0, uy: 0, ux.diff(): 0, uy.diff(): 0}
    a, _, _ = km.linearize(op_point=op, A_and_B=True, simplify=False)
    return np.linalg.eigvals(np.array(sp.Matrix(a).subs(op).evalf().tolist(), dtype=float))


def test_pole_of_spherical_coordinates_is_decided_as_the_rest_state_on_the_axis() -> None:
    """theta = 0 and pi of the conical pendulum: the azimuth is undefined there (its momentum is 0 at
    any rate), so Routh's reduction does not exist; the steady motion is the pendulum at rest on the
    axis, stable hanging and unstable upright, with the frequencies of the Cartesian linearisation."""
    _, d, _ = solved(CONE)
    g, l_ = 9.81, 0.8
    poles = {float(dict(x.at)["theta"]): x for x in d.analysis.steady.states if x.pole}
    assert sorted(poles) == [0.0, pytest.approx(np.pi)]
    for value, state in poles.items():
        up = value != 0.0
        theirs = _cartesian_pendulum_eigenvalues(up, g, l_)
        ours = np.array(state.eigenvalues)
        for lam in ours:
            assert min(abs(lam - z) for z in theirs) < 1e-9, (value, ours, theirs)
        assert state.verdict == ("unstable" if up else "stable")
        assert "the coordinates are singular at theta = " in state.reason
        assert "at rest on the axis" in state.reason


def test_pole_with_a_spin_says_why_it_is_not_decided() -> None:
    """The heavy top at theta = 0 spins about its own axis (its momenta are not 0): the verdict is not
    decided, and the reason says what would decide it."""
    d = derive(_with(TOP, ask=["equations_of_motion", "steady_motion"]))
    poles = [x for x in d.analysis.steady.states if x.pole]
    assert poles
    for x in poles:
        assert x.verdict in ("undetermined", "stable", "unstable")
        if x.verdict == "undetermined":
            assert "spinning about its own axis" in x.reason and "sleeping top" in x.reason


def test_rate_without_steady_motion_is_a_result_not_an_error() -> None:
    data = yaml.safe_load(open(CONE, encoding="utf-8").read())
    data["analysis"] = {"steady": {"phi": "3 rad/s"}}  # g/(l Omega^2) = 1.36 > 1: no cone
    d = derive(system_of(data))
    cones = [x for x in d.analysis.steady.states if x.exists_where]
    assert cones and all(x.exists is False and x.verdict == "none" for x in cones)


def test_named_coordinate_that_is_not_cyclic_is_a_located_spec_error() -> None:
    text = open(DRIVEN, encoding="utf-8").read().replace("steady: {phi: omega}", "steady: {theta: omega}")
    from tutgen.spec.validate import load_system_text

    system = load_system_text(text, path="hoop.yaml")
    with pytest.raises(SpecErrors) as err:
        derive(system)
    line = next(i for i, t in enumerate(text.splitlines(), start=1) if "steady: {theta" in t)
    message = str(err.value)
    assert f"hoop.yaml:{line}:12: error: 'theta' is not a cyclic coordinate: H and G contain theta" in message
    assert "hint: the cyclic coordinates are: phi" in message


def test_steady_without_ask_is_a_spec_error() -> None:
    text = (
        open(FREE, encoding="utf-8")
        .read()
        .replace("ask: [equations_of_motion, steady_motion]", "ask: [equations_of_motion]")
    )
    from tutgen.spec.validate import load_system_text

    with pytest.raises(SpecErrors) as err:
        load_system_text(text, path="hoop.yaml")
    assert "`analysis.steady` gives the cyclic coordinates and rates of `steady_motion`" in str(err.value)


def test_unnamed_cyclic_coordinates_are_found_and_held_at_their_own_rate() -> None:
    """The heavy top: psi and phi are cyclic; at the rates psi_dot, phi_dot the nutation's row gives
    the classic steady precession, cos theta linear in the rates."""
    d = derive(_with(TOP, ask=["equations_of_motion", "steady_motion"]))
    st = d.analysis.steady
    assert st.cyclic == ("psi", "phi") and st.free == ("psi", "phi") and st.others == ("theta",)
    assert st.check.passed
    assert len(st.states) >= 3  # theta = 0, pi and the precessing cone(s)


def test_rotor_is_all_cyclic_and_needs_no_torque() -> None:
    d = derive(_with(ROTOR, ask=["equations_of_motion", "steady_motion"]))
    st = d.analysis.steady
    assert st.cyclic == ("phi",) and st.others == () and st.free == ()
    (state,) = st.states
    assert state.required == (("phi", 0),) and state.verdict == "neutral"
    assert [str(u) for u, _ in state.inputs] == ["tau"] and state.inputs[0][1] == 0


def test_free_hoop_reduced_stiffness_is_printed_as_a_textbook_fraction() -> None:
    """The tilted bead's K_r: its value is the expression Routh's reduction gave before it was tidied,
    and its form is the textbook's, m (Omega^4 R^2 - g^2)((M + 2m) Omega^4 R^2 + 6 m g^2) over
    Omega^2 ((M + 2m) Omega^4 R^2 - 2 m g^2): the conjugate pair multiplied out, M + 2m collected."""
    from tutgen.engine.analysis.steady import textbook

    system, d, _ = solved(FREE)
    sym = {p.symbol: sp.Symbol(p.name, positive=True) for p in system.parameters}
    m, big_m, big_r, g, w = (sp.Symbol(n, positive=True) for n in ("m", "M", "R", "g", "Omega"))
    old = (
        m
        * (w**2 * big_r - g)
        * (w**2 * big_r + g)
        * (big_m * w**4 * big_r**2 + 2 * w**4 * big_r**2 * m + 6 * g**2 * m)
        / (w**2 * (big_m * w**4 * big_r**2 + 2 * w**4 * big_r**2 * m - 2 * g**2 * m))
    )
    tilted = [x for x in d.analysis.steady.states if x.exists_where]
    assert len(tilted) == 2
    for x in tilted:
        k = x.stiffness[0, 0].xreplace(sym)
        assert sp.cancel(k - old) == 0
        num, den = sp.fraction(k)
        assert set(sp.Mul.make_args(num)) >= {m, w**4 * big_r**2 - g**2}
        assert (big_m + 2 * m) * w**4 * big_r**2 - 2 * m * g**2 in sp.Mul.make_args(den)
    # the tidying keeps every value: a sign turned into a bracket, a sum collected, a product left alone
    for v in (-m * big_r * (w**2 * big_r - g), m * w * big_r**2 + big_m * w * big_r**2 / 2 - m * g**2 / w**3, m * g):
        assert sp.cancel(textbook(v) - v) == 0
    assert textbook(-m * big_r * (w**2 * big_r - g)) == m * big_r * (g - w**2 * big_r)


def test_steady_motion_of_a_closed_loop_is_refused_at_its_ask_item() -> None:
    """A four-bar's loop-closing joint: the steady states would have to satisfy the loop too, and its
    constraint forces enter every row, so `steady_motion` is a spec error at the `ask` item."""
    text = open(SPECS / "examples" / "n-four-bar-crank-rocker.yaml", encoding="utf-8").read()
    text += "\nask: [equations_of_motion, steady_motion]\n"
    from tutgen.spec.validate import load_system_text

    with pytest.raises(SpecErrors) as err:
        load_system_text(text, path="four-bar.yaml")
    line = len(text.splitlines())
    message = str(err.value)
    assert f"four-bar.yaml:{line}:28: error: `steady_motion` applies to an unconstrained system" in message
    assert "the loop-closing joint 'B'" in message
