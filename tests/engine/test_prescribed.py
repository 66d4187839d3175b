"""Prescribed (driven) coordinates (issue 18, point 4): the free coordinates' equations and the drive force,
against sympy.physics.mechanics built independently, and by hand.

Each reference builds the system with sympy's frames twice: with the driven angle or position written as
its function of time before ``LagrangesMethod`` runs (so L depends on t explicitly and sympy's d/dt takes
that dependence: the free coordinates' equations), and with every coordinate free, its Lagrange equation of
the driven coordinate then evaluated along the motion (the drive force). tutgen substitutes the motion into
its own matrix form instead; the two must agree term by term.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import pytest
import sympy as sp
from sympy.physics.mechanics import (
    LagrangesMethod,
    Particle,
    Point,
    ReferenceFrame,
    RigidBody,
    dynamicsymbols,
    inertia,
)

from tests.conftest import SPECS, solved
from tutgen.engine.pipeline import derive
from tutgen.engine.prescribed import prescribed_motion
from tutgen.errors import DerivationError
from tutgen.model.system import TIME
from tutgen.render.jsonout import derivation_to_json
from tutgen.spec.expr import parse_expression
from tutgen.spec.validate import load_system_text

BEAD = str(SPECS / "examples" / "p-bead-on-rotating-rod.yaml")
CRANK = str(SPECS / "examples" / "q-pendulum-driven-support.yaml")

#: a pendulum whose support slides along x with a prescribed oscillation: a driven length, so a drive force
SHAKEN = """
tutgen: 1
title: pendulum on a shaken support
parameters: [M, m, l, g, a, w]
coordinates:
  x: {prescribed: 'a*sin(w*t)'}
  theta: {}
gravity: [0, -g, 0]
bodies:
  cart: {mass: M}
  bob: {parts: {p: {shape: point, mass: m, at: [0, -l, 0]}}}
joints:
  slide: {type: prismatic, parent: ground, child: cart, axis: x, coordinate: x}
  pin: {type: revolute, parent: cart, child: bob, axis: z, coordinate: theta}
"""

_t = dynamicsymbols._t


def _symbols(system: Any) -> dict[str, sp.Symbol]:
    return {p.name: p.symbol for p in system.parameters}


def _plain(expr: sp.Expr, coords: dict[str, Any]) -> sp.Expr:
    """A sympy.mechanics expression in tutgen's symbols: q(t) -> q, q' -> q_dot, q'' -> q_ddot, t -> t."""
    out = sp.sympify(expr)
    for f, q, qd, qdd in coords.values():
        out = out.subs({f.diff(_t, 2): qdd}).subs({f.diff(_t): qd}).subs({f: q})
    return out.subs(_t, TIME)


def _bead(system: Any, free_phi: bool) -> tuple[LagrangesMethod, dict[str, Any]]:
    """The rod (J = M L^2/12 about z, turning at phi) and the bead at r along it; gravity -g y."""
    s = _symbols(system)
    r = dynamicsymbols("r")
    phi = dynamicsymbols("phi") if free_phi else s["omega"] * _t
    n = ReferenceFrame("N")
    a = n.orientnew("A", "Axis", [phi, n.z])
    o = Point("O")
    o.set_vel(n, 0)
    rod = RigidBody("rod", o, a, s["M"], (inertia(a, 0, s["M"] * s["L"] ** 2 / 12, s["M"] * s["L"] ** 2 / 12), o))
    p = o.locatenew("P", r * a.x)
    p.set_vel(n, p.pos_from(o).dt(n))
    bead = Particle("bead", p, s["m"])
    for body in (rod, bead):
        body.potential_energy = 0
    bead.potential_energy = s["m"] * s["g"] * p.pos_from(o).dot(n.y)
    from sympy.physics.mechanics import Lagrangian

    lag = Lagrangian(n, rod, bead)
    qs = [phi, r] if free_phi else [r]
    lm = LagrangesMethod(lag, qs)
    lm.form_lagranges_equations()
    coords = {"r": (r, *_c(system, "r"))}
    if free_phi:
        coords["phi"] = (phi, *_c(system, "phi"))
    return lm, coords


def _crank(system: Any, free_phi: bool) -> tuple[LagrangesMethod, dict[str, Any]]:
    """The disc (J = M R^2/2 about z) at phi, the bob at A + l (sin theta, -cos theta), A = a (cos phi, sin phi)."""
    s = _symbols(system)
    theta = dynamicsymbols("theta")
    phi = dynamicsymbols("phi") if free_phi else s["Omega"] * _t
    n = ReferenceFrame("N")
    d = n.orientnew("D", "Axis", [phi, n.z])
    o = Point("O")
    o.set_vel(n, 0)
    disc = RigidBody("disc", o, d, s["M"], (inertia(d, 0, 0, s["M"] * s["R"] ** 2 / 2), o))
    b = o.locatenew("B", s["a"] * d.x + s["l"] * (sp.sin(theta) * n.x - sp.cos(theta) * n.y))
    b.set_vel(n, b.pos_from(o).dt(n))
    bob = Particle("bob", b, s["m"])
    disc.potential_energy = 0
    bob.potential_energy = s["m"] * s["g"] * b.pos_from(o).dot(n.y)
    from sympy.physics.mechanics import Lagrangian

    lm = LagrangesMethod(Lagrangian(n, disc, bob), [phi, theta] if free_phi else [theta])
    lm.form_lagranges_equations()
    coords = {"theta": (theta, *_c(system, "theta"))}
    if free_phi:
        coords["phi"] = (phi, *_c(system, "phi"))
    return lm, coords


def _shaken(system: Any, free_x: bool) -> tuple[LagrangesMethod, dict[str, Any]]:
    """The cart at x along X, the bob at (x + l sin theta, -l cos theta)."""
    s = _symbols(system)
    theta = dynamicsymbols("theta")
    x = dynamicsymbols("x") if free_x else s["a"] * sp.sin(s["w"] * _t)
    n = ReferenceFrame("N")
    o = Point("O")
    o.set_vel(n, 0)
    c = o.locatenew("C", x * n.x)
    c.set_vel(n, c.pos_from(o).dt(n))
    b = c.locatenew("B", s["l"] * (sp.sin(theta) * n.x - sp.cos(theta) * n.y))
    b.set_vel(n, b.pos_from(o).dt(n))
    cart, bob = Particle("cart", c, s["M"]), Particle("bob", b, s["m"])
    cart.potential_energy = 0
    bob.potential_energy = s["m"] * s["g"] * b.pos_from(o).dot(n.y)
    from sympy.physics.mechanics import Lagrangian

    lm = LagrangesMethod(Lagrangian(n, cart, bob), [x, theta] if free_x else [theta])
    lm.form_lagranges_equations()
    coords = {"theta": (theta, *_c(system, "theta"))}
    if free_x:
        coords["x"] = (x, *_c(system, "x"))
    return lm, coords


def _c(system: Any, name: str) -> tuple[sp.Symbol, sp.Symbol, sp.Symbol]:
    c = next(c for c in system.coordinates if c.name == name)
    return c.q, c.qd, c.qdd


def _zero(e: sp.Expr) -> bool:
    return sp.simplify(sp.expand_trig(sp.expand(e))) == 0


@pytest.fixture(scope="module")
def shaken() -> tuple[Any, Any]:
    system = load_system_text(SHAKEN)
    return system, derive(system)


CASES = {"bead": (BEAD, _bead, "phi"), "crank": (CRANK, _crank, "phi"), "shaken": (None, _shaken, "x")}


def _case(name: str, shaken: tuple[Any, Any]) -> tuple[Any, Any, Any, str]:
    path, build, driven = CASES[name]
    if path is None:
        system, d = shaken
    else:
        system, d, _ = solved(path)
    return system, d, build, driven


@pytest.mark.parametrize("name", sorted(CASES))
def test_prescribed_free_equations_match_mechanics_with_the_motion_in_the_lagrangian(
    name: str, shaken: tuple[Any, Any]
) -> None:
    system, d, build, _ = _case(name, shaken)
    lm, coords = build(system, False)
    pm = d.prescribed
    assert pm is not None and len(pm.equations_of_motion) == len(lm.eom) == 1
    reference = _plain(lm.eom[0], coords)
    assert _zero(pm.equations_of_motion[0] - reference), (pm.equations_of_motion[0], reference)


@pytest.mark.parametrize("name", sorted(CASES))
def test_prescribed_drive_matches_mechanics_row_along_the_motion(name: str, shaken: tuple[Any, Any]) -> None:
    system, d, build, driven = _case(name, shaken)
    lm, coords = build(system, True)
    q, qd, qdd = _c(system, driven)
    row = [c.name for c in system.coordinates].index(driven)
    # sympy's order is the order given to LagrangesMethod: the driven coordinate first
    reference = _plain(lm.eom[0], coords)
    motion = next(c.prescribed for c in system.coordinates if c.name == driven)
    along = {q: motion, qd: sp.diff(motion, TIME), qdd: sp.diff(motion, TIME, 2)}
    reference = reference.subs(along)
    x = d.prescribed.driven[0]
    assert x.index == row and x.name == driven
    assert _zero(x.drive - reference), (x.drive, reference)


def test_prescribed_bead_by_hand() -> None:
    """r_ddot - r omega^2 + g sin(omega t) = 0 and tau = 2 m r r_dot omega + m g r cos(omega t): the rod's
    own inertia needs no torque at constant rate."""
    system, d, _ = solved(BEAD)
    s = _symbols(system)
    r, rd, rdd = _c(system, "r")
    m, g, w = s["m"], s["g"], s["omega"]
    pm = d.prescribed
    assert _zero(pm.equations_of_motion[0] - m * (rdd - r * w**2 + g * sp.sin(w * TIME)))
    (x,) = pm.driven
    assert x.kind == "torque" and x.motion == w * TIME and x.rate == w and x.acceleration == 0
    assert _zero(x.drive - (2 * m * r * rd * w + m * g * r * sp.cos(w * TIME)))
    assert x.drive_along_motion is None  # r_ddot does not appear: H_r_phi = 0
    assert pm.is_time_dependent
    assert _zero(pm.driving_vector[0] + m * w**2 * r)  # the centrifugal term comes from the driven rate


def test_prescribed_crank_by_hand() -> None:
    """m l^2 theta_ddot - m a l Omega^2 cos(theta - Omega t) + m g l sin(theta) = 0."""
    system, d, _ = solved(CRANK)
    s = _symbols(system)
    th, _, thdd = _c(system, "theta")
    m, g, a, length, w = s["m"], s["g"], s["a"], s["l"], s["Omega"]
    expected = m * length**2 * thdd - m * a * length * w**2 * sp.cos(th - w * TIME) + m * g * length * sp.sin(th)
    assert _zero(d.prescribed.equations_of_motion[0] - expected)
    (x,) = d.prescribed.driven
    assert x.drive.has(thdd) and x.drive_along_motion is not None and not x.drive_along_motion.has(thdd)
    # along the motion: the drive with theta_ddot from the equation of motion
    solved_thdd = sp.solve(expected, thdd)[0]
    assert _zero(x.drive_along_motion - x.drive.subs(thdd, solved_thdd))


def test_prescribed_shaken_support_is_a_force(shaken: tuple[Any, Any]) -> None:
    """theta_ddot l + g sin(theta) = a w^2 sin(w t) cos(theta): the support's acceleration as a load."""
    system, d = shaken
    s = _symbols(system)
    th, _, thdd = _c(system, "theta")
    m, g, a, length, w = s["m"], s["g"], s["a"], s["l"], s["w"]
    eq = d.prescribed.equations_of_motion[0]
    expected = m * length * (length * thdd + g * sp.sin(th) - a * w**2 * sp.sin(w * TIME) * sp.cos(th))
    assert _zero(eq - expected)
    assert d.prescribed.driven[0].kind == "force"


def test_prescribed_checks_are_reported(shaken: tuple[Any, Any]) -> None:
    _, d = shaken
    names = {c.name: c.passed for c in d.checks}
    assert names["prescribed_equals_reduced_lagrangian"] is True
    assert names["drive_force_equals_newton_euler"] is True


def test_prescribed_newton_euler_check_can_fail(shaken: tuple[Any, Any]) -> None:
    """A Newton-Euler row that differs from Lagrange's along the motion is a tutgen bug, not a result."""
    _, d = shaken
    ne = d.newton_euler
    wrong = ne.equations_of_motion + sp.ImmutableMatrix([1, 0])
    broken = dataclasses.replace(d, newton_euler=dataclasses.replace(ne, equations_of_motion=wrong))
    with pytest.raises(DerivationError, match="Newton–Euler"):
        prescribed_motion(broken)


def test_prescribed_matrix_form_check_can_fail(shaken: tuple[Any, Any]) -> None:
    """The free coordinates' matrix form is checked against the substituted rows."""
    _, d = shaken
    wrong = d.equations_of_motion + sp.ImmutableMatrix([0, 1])
    with pytest.raises(DerivationError, match="theta"):
        prescribed_motion(dataclasses.replace(d, equations_of_motion=wrong))


def test_prescribed_steps_and_json() -> None:
    system, d, _ = solved(BEAD)
    kinds = [s.kind.value for s in d.steps]
    assert kinds[-2:] == ["prescribed_motion", "drive_force"]
    drive = next(s for s in d.steps if s.kind.value == "drive_force")
    assert [str(e.lhs) for e in drive.equations] == ["Q_drive_phi"]
    out = derivation_to_json(d)["results"]["prescribed"]
    assert out["free_coordinates"] == ["r"]
    assert out["coordinates"]["phi"]["kind"] == "torque"
    assert out["coordinates"]["phi"]["motion"] == "omega*t"
    s = _symbols(system)
    r, rd, _ = _c(system, "r")
    names = {"t": TIME, "r": r, "r_dot": rd, **s}
    drive_json = parse_expression(out["coordinates"]["phi"]["drive"], names)
    assert _zero(drive_json - d.prescribed.driven[0].drive)


def test_prescribed_not_planned_without_equations() -> None:
    """`ask: [kinetic_energy]` derives T only: no substitution, no drive."""
    system = load_system_text(SHAKEN.replace("joints:", "ask: [kinetic_energy]\njoints:"))
    d = derive(system)
    assert d.prescribed is None and not d.has_step("drive_force")
