"""The worked solution as an ordered list of steps: which steps a spec's ``ask:`` and ``methods:`` call
for, with the steps they depend on (:func:`plan_steps`), and the record of each (:func:`record_steps`).

A :class:`Step` is the engine's account of one stage of the solution: the quantity derived, the
equations from its definition to its value (sympy pairs, parameters symbolic), one sentence of why,
and the ids of the steps it uses. The renderers walk ``Derivation.steps``: a section of the worked
solution exists only if its step does (tutgen/render/views.py), and the JSON output lists them.

What ``ask`` names decides which steps exist, and the closure over :data:`DEPENDS` adds what they
need, so the output holds what was asked and no more: ``ask: [kinetic_energy]`` gives the kinematics
and T (and the inertia of bodies that have rotational inertia), nothing after them.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from enum import StrEnum
from typing import TYPE_CHECKING

import sympy as sp

from tutgen.engine.tidy import tidy
from tutgen.model.system import Ask, Method, System

if TYPE_CHECKING:  # derivation.py imports this module
    from tutgen.engine.derivation import Check, Derivation

__all__ = [
    "C_SYMBOL",
    "H_ENTRY",
    "H_SYMBOL",
    "ORDER",
    "Equation",
    "Step",
    "StepKind",
    "plan_steps",
    "record_steps",
    "reported_checks",
]


class StepKind(StrEnum):
    """The kinds of step, each the name of one builder of tutgen/render/sections/ (several kinds may
    share a section: T, U and L are the energies section)."""

    INERTIA = "inertia"
    KINEMATICS = "kinematics"
    KINETIC_ENERGY = "kinetic_energy"
    POTENTIAL_ENERGY = "potential_energy"
    LAGRANGIAN = "lagrangian"
    LAGRANGE_EQUATIONS = "lagrange_equations"
    NEWTON_EULER = "newton_euler"
    EQUATIONS_OF_MOTION = "equations_of_motion"
    MASS_MATRIX = "mass_matrix"  # H read off T = 1/2 q_dot^T H q_dot, coefficient by coefficient
    MATRIX_FORM = "matrix_form"  # C, G and Q of H q_ddot + C + G = Q
    MASS_MATRIX_DERIVATIVES = "mass_matrix_derivatives"  # the non-zero dH_ij/dq_k
    CHRISTOFFEL = "christoffel"  # each symbol from its definition, then C as a vector
    PRESCRIBED_MOTION = "prescribed_motion"  # q_p = f(t) substituted: the free coordinates' equations
    DRIVE_FORCE = "drive_force"  # the driven coordinate's row along the motion: the force or torque needed
    SIMULATION = "simulation"  # the equations of motion integrated numerically: plots, energy drift
    EQUILIBRIA = "equilibria"  # the rest configurations G(q) = Q(q, 0), each classified (engine/analysis)
    LINEARIZATION = "linearization"  # M dq_ddot + D dq_dot + K dq = B du about an equilibrium, its modes
    STEADY_MOTION = "steady_motion"  # relative equilibria at constant rates of the cyclic coordinates
    MOMENTUM = "momentum"  # p, H_G, H_O per body and in total, dH_O/dt, conserved quantities
    CONSTRAINTS = "constraints"  # the constraints, their Jacobian A and the velocity analysis q_dot = T q_dot_i
    LAGRANGE_MULTIPLIERS = "lagrange_multipliers"  # H q_ddot + C + G = Q + A^T lambda, lambda solved
    REDUCED_EQUATIONS = "reduced_equations"  # H_r q_ddot_i + C_r + G_r = Q_r in the independent coordinates


#: teaching order: every step comes after the steps it depends on (the serial arm's equations of
#: motion, read from the matrix form below them, are the one exception)
#: teaching order: the enum's, except that the simulation comes last (it integrates the equations the
#: other steps derive, the constrained ones included)
ORDER: tuple[StepKind, ...] = (*(k for k in StepKind if k is not StepKind.SIMULATION), StepKind.SIMULATION)

_WHY = {
    StepKind.INERTIA: "Each body's mass, centre of mass and inertia tensor, which the kinetic energy needs.",
    StepKind.KINEMATICS: "The velocity of each centre of mass and each body's angular velocity, from the "
    "coordinates: the kinetic energy is built from them.",
    StepKind.KINETIC_ENERGY: "T is the sum of each body's translational and rotational kinetic energy.",
    StepKind.POTENTIAL_ENERGY: "U collects the work of gravity and the springs, each from its datum.",
    StepKind.LAGRANGIAN: "Lagrange's equations are written for L = T - U.",
    StepKind.LAGRANGE_EQUATIONS: "Each coordinate's equation is d/dt(dL/dq_dot) - dL/dq = Q, term by term.",
    StepKind.NEWTON_EULER: "The same equations body by body, from each free body's balance of forces "
    "and moments with D'Alembert's inertial terms.",
    StepKind.EQUATIONS_OF_MOTION: "The equations of motion, one per coordinate, with the inputs on the right.",
    StepKind.MASS_MATRIX: "T is a quadratic form in the rates, T = 1/2 q_dot^T H q_dot: H_ii is twice the "
    "coefficient of q_dot_i^2 and H_ij (i != j) the coefficient of q_dot_i q_dot_j.",
    StepKind.MATRIX_FORM: "The equations of motion as H q_ddot + C + G = Q, with G = dU/dq.",
    StepKind.MASS_MATRIX_DERIVATIVES: "The Christoffel symbols are made of the derivatives of H's entries.",
    StepKind.CHRISTOFFEL: "Each Christoffel symbol from its definition; C is their contraction with the rates.",
    StepKind.PRESCRIBED_MOTION: "A prescribed coordinate is not a degree of freedom: its motion, rate and "
    "acceleration are substituted into the equations of the free coordinates, which may then depend on t.",
    StepKind.DRIVE_FORCE: "Along the prescribed motion the driven coordinate's equation no longer decides its "
    "motion: it gives the force or torque the drive must supply, d/dt(dL/dq_dot) - dL/dq - Q.",
    StepKind.SIMULATION: "The equations of motion integrated numerically from the initial state: the "
    "coordinates, their rates and the energy over time.",
    StepKind.EQUILIBRIA: "At rest q_dot = q_ddot = 0, so the equations of motion reduce to G(q) = Q(q, 0).",
    StepKind.LINEARIZATION: "Small motions about an equilibrium obey the first-order expansion of the equations "
    "of motion: M dq_ddot + D dq_dot + K dq = B du.",
    StepKind.STEADY_MOTION: "With the cyclic coordinates turning at constant rates and the others at rest, "
    "the equations of motion of the others reduce to equations in their values alone.",
    StepKind.MOMENTUM: "Each body's momentum and angular momentum from its velocities and inertia; the rate of "
    "change of the total angular momentum about O is the moment of the external forces about O.",
    StepKind.CONSTRAINTS: "The constraints tie the coordinates: their Jacobian A gives A q_dot = 0, and the "
    "dependent rates follow from the independent ones, q_dot = T q_dot_i.",
    StepKind.LAGRANGE_MULTIPLIERS: "Each constraint adds its force A^T lambda to the equations of all the "
    "coordinates; with A q_ddot + b = 0 they determine q_ddot and lambda.",
    StepKind.REDUCED_EQUATIONS: "Since T^T A^T = 0, projecting with T^T removes the multipliers: the equations "
    "in the independent coordinates alone.",
}

_QUANTITY = {
    StepKind.INERTIA: "mass properties",
    StepKind.KINEMATICS: "velocities of the centres of mass",
    StepKind.KINETIC_ENERGY: "T",
    StepKind.POTENTIAL_ENERGY: "U",
    StepKind.LAGRANGIAN: "L",
    StepKind.LAGRANGE_EQUATIONS: "Lagrange's equations",
    StepKind.NEWTON_EULER: "Newton-Euler equations",
    StepKind.EQUATIONS_OF_MOTION: "equations of motion",
    StepKind.MASS_MATRIX: "H",
    StepKind.MATRIX_FORM: "C, G, Q",
    StepKind.MASS_MATRIX_DERIVATIVES: "dH/dq",
    StepKind.CHRISTOFFEL: "Christoffel symbols and C",
    StepKind.PRESCRIBED_MOTION: "equations of the free coordinates",
    StepKind.DRIVE_FORCE: "drive force",
    StepKind.SIMULATION: "q(t), q_dot(t) and the energy",
    StepKind.EQUILIBRIA: "equilibria",
    StepKind.LINEARIZATION: "linear model",
    StepKind.STEADY_MOTION: "steady motion",
    StepKind.MOMENTUM: "momentum",
    StepKind.CONSTRAINTS: "constraint Jacobian and velocity analysis",
    StepKind.LAGRANGE_MULTIPLIERS: "equations with Lagrange's multipliers",
    StepKind.REDUCED_EQUATIONS: "equations in the independent coordinates",
}


@dataclass(frozen=True)
class Equation:
    """``lhs = rhs``: a named quantity (a symbol, or an unevaluated derivative of one) and its value."""

    lhs: sp.Basic
    rhs: sp.Basic


@dataclass(frozen=True)
class Step:
    """One step of a worked solution."""

    id: str  # unique and stable; the kind's name (one step per kind)
    kind: StepKind
    quantity: str  # what the step derives, in words
    equations: tuple[Equation, ...]  # from the definition to the value (parameters symbolic)
    why: str
    depends_on: tuple[str, ...] = ()  # ids of the steps whose results this one uses


def _has_rotational_inertia(system: System) -> bool:
    """A body that is not a lone point mass: its inertia tensor is part of T, worth a step."""
    return any(not (len(b.parts) == 1 and b.parts[0].shape.value == "point") for b in system.bodies)


def _has_potential(system: System) -> bool:
    given = system.potential_energy is not None and system.potential_energy != 0
    return system.gravity is not None or bool(system.springs) or given


def _depends(system: System, methods: tuple[Method, ...], large: bool) -> dict[StepKind, tuple[StepKind, ...]]:
    """What each step uses, for this system (a given energy has no kinematics; a large serial arm has
    no Lagrange's equations term by term: its equations of motion are the rows of its matrix form)."""
    K = StepKind
    moves = system.kinetic_energy is None and not large  # bodies placed by joints or positions
    t_needs = [K.KINEMATICS] if moves else []
    if moves and _has_rotational_inertia(system):  # a large arm's T is 1/2 q_dot^T H q_dot, from the recursion
        t_needs.insert(0, K.INERTIA)
    u_needs = [K.KINEMATICS] if moves and system.gravity is not None else []
    l_needs = [K.KINETIC_ENERGY] + ([K.POTENTIAL_ENERGY] if _has_potential(system) else [])
    eom_needs: list[StepKind] = []
    if large:
        eom_needs = [K.MASS_MATRIX, K.MATRIX_FORM]
    else:
        if Method.LAGRANGE in methods or not _newton_euler_applies(system):
            eom_needs.append(K.LAGRANGE_EQUATIONS)
        if Method.NEWTON_EULER in methods and _newton_euler_applies(system):
            eom_needs.append(K.NEWTON_EULER)
    ne_needs = [K.INERTIA, K.KINEMATICS] if _has_rotational_inertia(system) else [K.KINEMATICS]
    has_about = system.analysis is not None and system.analysis.about is not None
    form_needs = [K.MASS_MATRIX] + ([K.POTENTIAL_ENERGY] if _has_potential(system) else [])
    return {
        K.INERTIA: (),
        K.KINEMATICS: (),
        K.KINETIC_ENERGY: tuple(t_needs),
        K.POTENTIAL_ENERGY: tuple(u_needs),
        K.LAGRANGIAN: tuple(l_needs),
        K.LAGRANGE_EQUATIONS: (K.LAGRANGIAN,),
        K.NEWTON_EULER: tuple(ne_needs),
        K.EQUATIONS_OF_MOTION: tuple(eom_needs),
        K.MASS_MATRIX: (K.KINETIC_ENERGY,),
        K.MATRIX_FORM: tuple(form_needs),
        K.MASS_MATRIX_DERIVATIVES: (K.MASS_MATRIX,),
        K.CHRISTOFFEL: (K.MASS_MATRIX_DERIVATIVES,),
        K.PRESCRIBED_MOTION: (K.EQUATIONS_OF_MOTION,),
        K.DRIVE_FORCE: (K.PRESCRIBED_MOTION,),
        K.SIMULATION: (K.EQUATIONS_OF_MOTION,),  # what is integrated (the run itself: tutgen/sim/solution.py)
        K.EQUILIBRIA: (K.MATRIX_FORM,),
        # about the spec's equilibrium, or about each one found
        K.LINEARIZATION: (K.MATRIX_FORM,) if has_about else (K.EQUILIBRIA,),
        K.STEADY_MOTION: (K.MATRIX_FORM,),
        K.MOMENTUM: (K.LAGRANGIAN,),
        K.CONSTRAINTS: (),
        K.LAGRANGE_MULTIPLIERS: (K.CONSTRAINTS, K.MATRIX_FORM),
        K.REDUCED_EQUATIONS: (K.CONSTRAINTS, K.MATRIX_FORM),
    }


def _newton_euler_applies(system: System) -> bool:
    """Newton-Euler frees bodies: a spec that gives its energy has none."""
    return system.kinetic_energy is None and bool(system.bodies)


#: each item of ``ask`` as the steps it names
_ASKED = {
    Ask.INERTIA: (StepKind.INERTIA,),
    Ask.KINETIC_ENERGY: (StepKind.KINETIC_ENERGY,),
    Ask.POTENTIAL_ENERGY: (StepKind.POTENTIAL_ENERGY,),
    Ask.LAGRANGIAN: (StepKind.LAGRANGIAN,),
    Ask.LAGRANGE_EQUATIONS: (StepKind.LAGRANGE_EQUATIONS,),
    Ask.EQUATIONS_OF_MOTION: (StepKind.EQUATIONS_OF_MOTION,),
    Ask.MATRIX_FORM: (StepKind.MASS_MATRIX, StepKind.MATRIX_FORM),
    Ask.CHRISTOFFEL: (StepKind.CHRISTOFFEL,),
    Ask.SIMULATION: (StepKind.SIMULATION,),
    Ask.EQUILIBRIA: (StepKind.EQUILIBRIA,),
    Ask.LINEARIZATION: (StepKind.LINEARIZATION,),
    Ask.MOMENTUM: (StepKind.MOMENTUM,),
    Ask.STEADY_MOTION: (StepKind.STEADY_MOTION,),
}


def plan_steps(
    system: System, methods: tuple[Method, ...] | None = None, large: bool = False
) -> tuple[tuple[StepKind, tuple[StepKind, ...]], ...]:
    """The steps a spec's ``ask`` calls for, with the steps they depend on, in teaching order: each as
    (kind, the kinds it depends on). ``methods`` defaults to the spec's; ``large`` is the serial arm's
    route (tutgen.engine.serial), which has no kinematics and no Lagrange's equations term by term.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> rod = load_system_text('''
    ... {tutgen: 1, title: rod, parameters: [m, l, g], coordinates: [theta], gravity: [0, -g, 0],
    ...  bodies: {rod: {parts: {bar: {shape: slender_rod, mass: m, length: l, axis: x}}}},
    ...  joints: {pin: {type: revolute, parent: ground, child: rod, axis: z, coordinate: theta}},
    ...  ask: [kinetic_energy]}
    ... ''')
    >>> [str(kind) for kind, _ in plan_steps(rod)]
    ['inertia', 'kinematics', 'kinetic_energy']
    """
    methods = system.methods if methods is None else methods
    if not system.coordinates:
        return ((StepKind.INERTIA, ()),) if Ask.INERTIA in system.ask and system.bodies else ()
    depends = _depends(system, methods, large)
    wanted: set[StepKind] = set()
    todo = [kind for a in sorted(system.ask) for kind in _ASKED[a]]
    if Method.LAGRANGE not in methods and _newton_euler_applies(system) and not large:
        # Lagrange's equations term by term are Lagrange's working: shown only when it is presented
        todo = [kind for kind in todo if kind is not StepKind.LAGRANGE_EQUATIONS]
    if Method.NEWTON_EULER in methods and _newton_euler_applies(system) and not large:
        # Newton-Euler presented: it is how the equations of motion are found
        if Ask.EQUATIONS_OF_MOTION in system.ask or Ask.LAGRANGE_EQUATIONS in system.ask:
            todo.append(StepKind.NEWTON_EULER)
    if system.is_constrained and Ask.EQUATIONS_OF_MOTION in system.ask:
        # a constrained system's equations of motion are those with the multipliers and the reduced ones
        todo += [StepKind.LAGRANGE_MULTIPLIERS, StepKind.REDUCED_EQUATIONS]
    if system.prescribed_coordinates and {Ask.EQUATIONS_OF_MOTION, Ask.MATRIX_FORM} & system.ask:
        # the driven coordinates' motion substituted, and the force that drives them (tutgen.engine.prescribed)
        todo += [StepKind.PRESCRIBED_MOTION, StepKind.DRIVE_FORCE]
    while todo:
        kind = todo.pop()
        if kind in wanted or not _applies(system, kind, large):
            continue
        wanted.add(kind)
        todo += depends[kind]
    return tuple((k, tuple(d for d in depends[k] if d in wanted)) for k in ORDER if k in wanted)


def _applies(system: System, kind: StepKind, large: bool) -> bool:
    """Whether a step can exist for this system at all (no kinematics without bodies to place, no
    Lagrange's equations term by term on the serial arm's route)."""
    if kind is StepKind.INERTIA:  # with coordinates, a lone point mass has nothing to tabulate: m r^2 is in T
        return bool(system.bodies) and (not system.coordinates or _has_rotational_inertia(system))
    if kind is StepKind.KINEMATICS:
        return system.kinetic_energy is None and bool(system.bodies) and not large
    if kind is StepKind.LAGRANGE_EQUATIONS:
        return not large
    if kind is StepKind.NEWTON_EULER:
        return _newton_euler_applies(system) and not large
    if kind is StepKind.POTENTIAL_ENERGY:
        return _has_potential(system)
    if kind is StepKind.MOMENTUM:  # velocities of bodies: not the serial arm's route, not a given T
        return system.kinetic_energy is None and bool(system.bodies) and not large
    if kind in (StepKind.CONSTRAINTS, StepKind.LAGRANGE_MULTIPLIERS, StepKind.REDUCED_EQUATIONS):
        return system.is_constrained and not large
    if kind in (StepKind.PRESCRIBED_MOTION, StepKind.DRIVE_FORCE):
        return bool(system.prescribed_coordinates)
    return True


# ---------------------------------------------------------------------------------------------
# The records
# ---------------------------------------------------------------------------------------------


def _name(text: str) -> sp.Symbol:
    return sp.Symbol(text)


#: the entries of H, the tutorial's Christoffel symbols h_ijk and those of the first kind c_ijk, with
#: 1-based indices (``H[1, 2]``), so that a renderer reads the indices off an equation's side
H_ENTRY = sp.IndexedBase("H")
H_SYMBOL = sp.IndexedBase("h")
C_SYMBOL = sp.IndexedBase("c")


def _pairs(*items: tuple[sp.Basic, sp.Basic | None]) -> tuple[Equation, ...]:
    return tuple(Equation(lhs, rhs) for lhs, rhs in items if rhs is not None)


def mass_matrix_read_off(d: Derivation) -> tuple[Equation, ...]:
    """H read off T: H_ii = 2 x (the coefficient of q_dot_i^2 in T), H_ij = the coefficient of
    q_dot_i q_dot_j (i < j), each as (H_ij, coefficient) with the coefficient taken from T itself,
    so that the record checks H (tests/engine/test_steps.py)."""
    s = d.system
    t = sp.expand(d.kinetic_energy) if d.kinetic_energy is not None else sp.Integer(0)
    qd = [c.qd for c in s.coordinates]
    n = len(qd)
    out: list[Equation] = []
    poly = sp.Poly(t, *qd) if t != 0 else None
    for i in range(n):
        for j in range(i, n):
            monomial = [0] * n
            monomial[i] += 1
            monomial[j] += 1
            coefficient = poly.coeff_monomial(tuple(monomial)) if poly is not None else sp.Integer(0)
            entry = 2 * coefficient if i == j else coefficient
            out.append(Equation(H_ENTRY[i + 1, j + 1], tidy(sp.expand(entry))))
    return tuple(out)


def mass_matrix_derivatives(d: Derivation) -> dict[tuple[int, int, int], sp.Expr]:
    """The non-zero dH_ij/dq_k with i <= j (H is symmetric), 0-based keys, in index order."""
    hm = d.mass_matrix
    if hm is None:
        return {}
    q = [c.q for c in d.system.coordinates]
    n = len(q)
    out: dict[tuple[int, int, int], sp.Expr] = {}
    for i in range(n):
        for j in range(i, n):
            for k in range(n):
                value = tidy(sp.diff(hm[i, j], q[k]))
                if value != 0:
                    out[i, j, k] = value
    return out


def _equations(d: Derivation, kind: StepKind, large: bool) -> tuple[Equation, ...]:
    """The equations of one step, from its definition to its value."""
    s = d.system
    K = StepKind
    if kind is K.INERTIA:
        return tuple(
            e
            for bi in d.inertia
            for e in _pairs((_name(f"m_{bi.name}"), bi.mass), (_name(f"J_O_{bi.name}"), bi.inertia_origin))
        )
    if kind is K.KINEMATICS:
        return tuple(
            e
            for k, en in zip(d.kinematics, d.energies, strict=True)
            for e in _pairs(
                (_name(f"r_{k.name}"), k.com),
                (_name(f"v_{k.name}"), k.velocity),
                (_name(f"v2_{k.name}"), en.speed_squared),
            )
        )
    if kind is K.KINETIC_ENERGY:
        per_body = [(_name(f"T_{e.name}"), e.kinetic) for e in d.energies]
        return _pairs(*per_body, (_name("T"), d.kinetic_energy))
    if kind is K.POTENTIAL_ENERGY:
        parts = [(_name(f"U_{e.name}"), e.gravitational) for e in d.energies if e.gravitational != 0]
        parts += [(_name(f"U_{name}"), u) for name, u in d.spring_energies]
        return _pairs(*parts, (_name("U"), d.potential_energy))
    if kind is K.LAGRANGIAN:
        return _pairs((_name("L"), _name("T") - _name("U")), (_name("L"), d.lagrangian))
    if kind is K.LAGRANGE_EQUATIONS:
        out: list[Equation] = []
        for t, c in zip(d.lagrange_terms, s.coordinates, strict=True):
            out += _pairs(
                (sp.Derivative(_name("L"), c.qd), t.dL_dqd),
                (_name(f"ddt_dL_d{c.qd.name}"), t.ddt_dL_dqd),
                (sp.Derivative(_name("L"), c.q), t.dL_dq),
                (_name(f"Q_{c.name}"), t.generalized_force),
            )
        return tuple(out)
    if kind is K.NEWTON_EULER and d.newton_euler is not None:
        return tuple(
            Equation(_name(f"NE_{c.name}"), e)
            for c, e in zip(s.coordinates, d.newton_euler.equations_of_motion, strict=True)
        )
    if kind is K.EQUATIONS_OF_MOTION and d.equations_of_motion is not None and d.generalized_forces is not None:
        if large:  # too long to restate: the rows of the matrix form
            return ()
        return tuple(Equation(e + f, f) for e, f in zip(d.equations_of_motion, d.generalized_forces, strict=True))
    if kind is K.MASS_MATRIX:
        if large or d.mass_matrix is None:
            return _pairs((_name("H"), d.mass_matrix))
        return (*mass_matrix_read_off(d), Equation(_name("H"), d.mass_matrix))
    if kind is K.MATRIX_FORM:
        return _pairs(
            (_name("C"), d.coriolis_vector), (_name("G"), d.gravity_vector), (_name("Q"), d.generalized_forces)
        )
    if kind is K.MASS_MATRIX_DERIVATIVES:
        if large:
            return ()
        q = [c.q for c in s.coordinates]
        return tuple(
            Equation(sp.Derivative(H_ENTRY[i + 1, j + 1], q[k]), v)
            for (i, j, k), v in mass_matrix_derivatives(d).items()
        )
    if kind in (K.EQUILIBRIA, K.LINEARIZATION, K.MOMENTUM, K.STEADY_MOTION):
        return analysis_equations(d, kind)
    if kind in (K.CONSTRAINTS, K.LAGRANGE_MULTIPLIERS, K.REDUCED_EQUATIONS):
        return constraint_equations(d, kind)
    if kind in (K.PRESCRIBED_MOTION, K.DRIVE_FORCE):
        return prescribed_equations(d, kind)
    if kind is K.CHRISTOFFEL:
        if large:
            return _pairs((_name("C"), d.coriolis_vector))
        return (*christoffel_definitions(d), *_pairs((_name("C"), d.coriolis_vector)))
    return ()


def analysis_equations(d: Derivation, kind: StepKind) -> tuple[Equation, ...]:
    """The equilibria step: G - Q at rest, then each equilibrium q0_i (every coordinate's value); the
    linearization step: M_i, D_i, K_i, B_i and A_i of each linear model, 1-based as the equilibria."""
    a = d.analysis
    if a is None:
        return ()
    if kind is StepKind.MOMENTUM:
        if a.momentum is None:
            return ()
        mo = a.momentum
        out = [
            e
            for b in mo.bodies
            for e in (
                Equation(_name(f"p_{b.name}"), b.linear),
                Equation(_name(f"H_G_{b.name}"), b.angular_com),
                Equation(_name(f"H_O_{b.name}"), b.angular_origin),
            )
        ]
        out += [Equation(_name("p"), mo.linear), Equation(_name("H_O"), mo.angular_origin)]
        out += [Equation(_name("dH_O_dt"), mo.angular_rate), Equation(_name("M_O_supports"), mo.support_moment)]
        out += [Equation(_name(c.name), c.value) for c in mo.conserved]
        return tuple(out)
    if kind is StepKind.STEADY_MOTION:
        if a.steady is None:
            return ()
        st = a.steady
        out = [Equation(_name("steady_residual"), st.residual)]
        for i, state in enumerate(st.states, start=1):
            out.append(Equation(_name(f"q_s_{i}"), sp.ImmutableMatrix([v for _, v in state.at])))
            out += [Equation(_name(f"Q_{name}_{i}"), v) for name, v in state.required]
            out.append(Equation(_name(f"K_r_{i}"), state.stiffness))
        return tuple(out)
    if kind is StepKind.EQUILIBRIA:
        if a.equilibria is None:
            return ()
        out = [Equation(_name("G_minus_Q"), a.equilibria.residual)]
        for i, sol in enumerate(a.equilibria.solutions, start=1):
            out.append(Equation(_name(f"q0_{i}"), sp.ImmutableMatrix([v for _, v in sol])))
        return tuple(out)
    out = []
    for i, m in enumerate(a.linear, start=1):
        out += [
            Equation(_name(f"q0_{i}"), sp.ImmutableMatrix([v for _, v in m.about])),
            Equation(_name(f"M_{i}"), m.mass),
            Equation(_name(f"D_{i}"), m.damping),
            Equation(_name(f"K_{i}"), m.stiffness),
            *([Equation(_name(f"B_{i}"), m.input_matrix)] if m.inputs else []),
            *([Equation(_name(f"A_{i}"), m.state_matrix)] if m.state_matrix.shape != (0, 0) else []),
        ]
    return tuple(out)


def constraint_equations(d: Derivation, kind: StepKind) -> tuple[Equation, ...]:
    """The equations of a constraint step: the constraints, A, B and T; lambda in the accelerations and
    its value; H_r, C_r, G_r, Q_r and the reduced equations (tutgen.engine.constraints)."""
    cd = d.constraints
    if cd is None:
        return ()
    ck = cd.kinematics
    if kind is StepKind.CONSTRAINTS:
        out = [Equation(_name(f"f_{c.name}"), f) for c, f in zip(ck.constraints, ck.functions, strict=True)]
        if ck.loop is not None:  # the loop's position analysis: each branch's closed forms (<coordinate>_plus)
            names = [c.name for c in d.system.coordinates]
            for b in ck.loop.branches:
                side = "plus" if b.sign > 0 else "minus"
                out += [Equation(_name(f"{names[j]}_{side}"), e) for j, e in b.positions]
        return (
            *out,
            *_pairs((_name("A"), ck.jacobian), (_name("B"), ck.velocity_ratios), (_name("T"), ck.velocity_map)),
        )
    if kind is StepKind.LAGRANGE_MULTIPLIERS:
        out = [Equation(_name("Q_lambda"), cd.constraint_forces)]  # A^T lambda, the constraint forces
        out += [Equation(lam, e) for lam, e in zip(cd.multipliers, cd.multipliers_in_accelerations, strict=True)]
        out += [Equation(lam, e) for lam, e in zip(cd.multipliers, cd.multiplier_values, strict=False)]  # may be ()
        return tuple(out)
    return _pairs(
        (_name("H_r"), cd.mass_matrix),
        (_name("C_r"), cd.coriolis_vector),
        (_name("G_r"), cd.gravity_vector),
        (_name("Q_r"), cd.generalized_forces),
        (_name("reduced"), cd.equations_of_motion),
    )


def prescribed_equations(d: Derivation, kind: StepKind) -> tuple[Equation, ...]:
    """The prescribed-motion step: each q_p, q_p_dot, q_p_ddot as a function of t, then H_f, C_f, G_f, D_f,
    Q_f and the free coordinates' equations; the drive step: each Q_drive_p, and along the motion
    (the free accelerations eliminated) where that differs (tutgen.engine.prescribed)."""
    pm = d.prescribed
    if pm is None:
        return ()
    if kind is StepKind.DRIVE_FORCE:
        out = [Equation(_name(f"Q_drive_{x.name}"), x.drive) for x in pm.driven]
        out += [
            Equation(_name(f"Q_drive_{x.name}"), x.drive_along_motion)
            for x in pm.driven
            if x.drive_along_motion is not None
        ]
        return tuple(out)
    out = [Equation(symbol, value) for symbol, value in pm.substitution]
    out += _pairs(
        (_name("H_f"), pm.mass_matrix),
        (_name("C_f"), pm.coriolis_vector),
        (_name("G_f"), pm.gravity_vector),
        (_name("D_f"), pm.driving_vector),
        (_name("Q_f"), pm.generalized_forces),
    )
    out += [Equation(e + f, f) for e, f in zip(pm.equations_of_motion, pm.generalized_forces, strict=True)]
    return tuple(out)


def christoffel_definitions(d: Derivation) -> tuple[Equation, ...]:
    """Each non-zero symbol of the tutorial's convention from its definition,
    h_ijk = dH_ij/dq_k - 1/2 dH_jk/dq_i, then its value; then each non-zero symbol of the first kind,
    c_ijk = 1/2 (dH_ij/dq_k + dH_ik/dq_j - dH_jk/dq_i), likewise."""
    q = [c.q for c in d.system.coordinates]

    def dh(a: int, b: int, k: int) -> sp.Expr:
        a, b = min(a, b), max(a, b)  # H is symmetric: H_ba is written H_ab
        return sp.Derivative(H_ENTRY[a + 1, b + 1], q[k])

    out: list[Equation] = []
    for (i, j, k), v in sorted(d.christoffel.items()):
        if v != 0:
            name = H_SYMBOL[i + 1, j + 1, k + 1]
            # unevaluated, as the definition is written (h_212 = dH_12/dq_2 - 1/2 dH_12/dq_2, not 1/2 dH_12/dq_2)
            definition = sp.Add(dh(i, j, k), sp.Mul(sp.Rational(-1, 2), dh(j, k, i), evaluate=False), evaluate=False)
            out += [Equation(name, definition), Equation(name, v)]
    for (i, j, k), v in sorted(d.christoffel_first_kind.items()):
        if v != 0:
            name = C_SYMBOL[i + 1, j + 1, k + 1]
            terms = sp.Add(dh(i, j, k), dh(i, k, j), sp.Mul(-1, dh(j, k, i), evaluate=False), evaluate=False)
            out += [Equation(name, sp.Mul(sp.Rational(1, 2), terms, evaluate=False)), Equation(name, v)]
    return tuple(out)


def record_steps(
    d: Derivation, plan: Iterable[tuple[StepKind, tuple[StepKind, ...]]], large: bool = False
) -> tuple[Step, ...]:
    """The step records of a derivation, for the kinds of ``plan`` (:func:`plan_steps`), in its order."""
    return tuple(
        Step(
            id=kind.value,
            kind=kind,
            quantity=_QUANTITY[kind],
            equations=_equations(d, kind, large),
            why=_WHY[kind],
            depends_on=tuple(k.value for k in depends),
        )
        for kind, depends in plan
    )


#: which steps a check is about: it is reported only when one of them is derived (p02 asks for T
#: only and is told nothing about equations of motion it was not shown)
_CHECK_ABOUT = {
    "matrix_form_equals_lagrange": (StepKind.MATRIX_FORM, StepKind.EQUATIONS_OF_MOTION),
    "matrix_form_equals_newton_euler": (StepKind.MATRIX_FORM, StepKind.EQUATIONS_OF_MOTION),
    "newton_euler_equals_lagrange": (StepKind.EQUATIONS_OF_MOTION, StepKind.NEWTON_EULER),
    "skew_symmetry": (StepKind.MATRIX_FORM, StepKind.CHRISTOFFEL),
    "symmetric_mass_matrix": (StepKind.MASS_MATRIX,),
    "positive_semidefinite_mass_matrix": (StepKind.MASS_MATRIX,),
    "dimensional_consistency": (StepKind.EQUATIONS_OF_MOTION, StepKind.LAGRANGE_EQUATIONS),
    "linearization_matches_finite_differences": (StepKind.EQUILIBRIA, StepKind.LINEARIZATION),
    "multipliers_equal_reduction": (StepKind.LAGRANGE_MULTIPLIERS, StepKind.REDUCED_EQUATIONS),
    "prescribed_equals_reduced_lagrangian": (StepKind.PRESCRIBED_MOTION,),
    "drive_force_equals_newton_euler": (StepKind.DRIVE_FORCE,),
}


def reported_checks(checks: Iterable[Check], kinds: Iterable[StepKind]) -> tuple[Check, ...]:
    """The checks about steps that were derived (a check tutgen does not know is always reported)."""
    present = set(kinds)
    return tuple(c for c in checks if c.name not in _CHECK_ABOUT or present & set(_CHECK_ABOUT[c.name]))
