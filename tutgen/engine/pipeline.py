"""One derivation, stage by stage in teaching order: the engine's only orchestrator.

:func:`derive` runs the stages of a worked solution, each a function of the values of the ones before:

1. inertia: each body's mass, centre of mass and inertia tensors (:mod:`~tutgen.engine.inertia`);
2. kinematics: positions, rotations and velocity Jacobians (:mod:`~tutgen.engine.kinematics`);
3. energies and forces: T, U and H (:func:`~tutgen.engine.lagrange.energies`), the springs' energy and
   the generalized forces Q (:mod:`~tutgen.engine.forces`);
4. Lagrange's equations term by term (:func:`~tutgen.engine.lagrange.lagrange_equations`);
5. the matrix form H q_ddot + C + G = Q, with 6. the Christoffel symbols of H that give C
   (:mod:`~tutgen.engine.matrix_form`);
7. checks: the matrix form against Lagrange's equations, H_dot - 2 C skew, H positive semi-definite,
   dimensions (:mod:`~tutgen.engine.checks`), and the remarks (:mod:`~tutgen.engine.remarks`);
8. Newton-Euler, checked against Lagrange (:mod:`~tutgen.engine.newton_euler`), whenever the equations of
   motion are derived and the system has bodies; presented only when ``methods`` asks for it;
8b. a spec's prescribed coordinates substituted: the free coordinates' equations and the drive forces
   (:mod:`~tutgen.engine.prescribed`);
9. the step records (:mod:`~tutgen.engine.steps`): which steps ``ask`` and ``methods`` call for, in
   teaching order; the checks about steps not derived are left out.

and chooses the route: a serial arm of ``LARGE`` (4) or more coordinates
(:func:`~tutgen.engine.serial.is_large_serial_chain`) takes the route of :mod:`~tutgen.engine.serial`
instead of stages 2-6 and 8 (H, C and G as exact trigonometric polynomials, checked numerically).
Every stage records itself with :func:`~tutgen.limits.checkpoint`, so a timeout names it.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import sympy as sp

from tutgen.engine.checks import dimension_checks, matrix_form_checks, verify
from tutgen.engine.derivation import Derivation
from tutgen.engine.forces import generalized_forces, rotors, spring_energies
from tutgen.engine.inertia import BodyInertia, BodyPrincipal, body_inertia, body_principal
from tutgen.engine.kinematics import Kinematics
from tutgen.engine.lagrange import energies, lagrange_equations
from tutgen.engine.lazytable import LazyMatrix, LazyTable
from tutgen.engine.matrix_form import christoffel_symbols, coriolis_terms, equations_of_motion, gravity_vector
from tutgen.engine.potential import potential_sources
from tutgen.engine.remarks import REMARK_CONSTANT_MASS_MATRIX, degeneracy_remarks, rotor_remark, zero_remarks
from tutgen.engine.serial import REMARK_FAST_PATH, is_large_serial_chain, serial_checks, serial_dynamics
from tutgen.engine.steps import StepKind, plan_steps, record_steps, reported_checks
from tutgen.engine.tidy import tidy
from tutgen.errors import DerivationError, DerivationTimeout
from tutgen.limits import DEFAULT_TIMEOUT, checkpoint, deadline, stage
from tutgen.model.system import Method, System

__all__ = ["METHODS", "derive", "derive_with_deadline", "presented_methods"]

#: the values of ``--method``: which formulations to present, overriding the spec's ``methods:``
METHODS = ("both", "lagrange", "newton-euler")
_OVERRIDES = {
    "both": (Method.LAGRANGE, Method.NEWTON_EULER),
    "lagrange": (Method.LAGRANGE,),
    "newton-euler": (Method.NEWTON_EULER,),
}


def presented_methods(system: System, method: str | None = None) -> tuple[Method, ...]:
    """The formulations a worked solution presents: ``method`` ("both", "lagrange", "newton-euler")
    when given, else the spec's ``methods:`` (default Lagrange). Newton-Euler frees bodies, so a spec
    that gives its energy presents Lagrange's (the spec itself may not ask for Newton-Euler then: a
    spec error; an override on the command line falls back to Lagrange)."""
    if method is not None and method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, not {method!r}")
    methods = system.methods if method is None else _OVERRIDES[method]
    if system.kinetic_energy is not None or not system.bodies:
        methods = tuple(m for m in methods if m is not Method.NEWTON_EULER) or (Method.LAGRANGE,)
    return methods


def _method_name(methods: tuple[Method, ...]) -> str:
    if len(methods) > 1:
        return "both"
    return "newton-euler" if methods[0] is Method.NEWTON_EULER else "lagrange"


def derive(system: System, method: str | None = None) -> Derivation:
    """Derive everything a spec asks for, in teaching order.

    ``method`` ("both", "lagrange" or "newton-euler") overrides the formulations the spec's ``methods:``
    presents (default: Lagrange). Lagrange's route always runs, and Newton-Euler is derived whenever
    the equations of motion are and the spec has bodies (not a given energy), for its agreement check;
    its working is a step of the solution only when presented.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> block = load_system_text('''
    ... {tutgen: 1, title: block on a spring, parameters: [m, k], coordinates: [x], bodies: {block: {mass: m}},
    ...  joints: {slide: {type: prismatic, parent: ground, child: block, axis: x, coordinate: x}},
    ...  springs: {wall: {stiffness: k, extension: x}}}
    ... ''')
    >>> derive(block).equations_of_motion[0]
    k*x + m*x_ddot

    See ``tests/models.py`` for more named example systems (cart-pole, double pendulum).
    """
    methods = presented_methods(system, method)
    inertia, principal = mass_properties(system)
    if not system.coordinates:
        d = Derivation(system=system, inertia=inertia, principal=principal, methods=methods)
        return dataclasses.replace(d, steps=record_steps(d, plan_steps(system, methods)))
    large = is_large_serial_chain(system) and not system.is_constrained  # issue 8: the expansions run to pages
    plan = plan_steps(system, methods, large)
    if large:
        d = _serial_route(system, methods, inertia, principal)
    else:
        d = _general_route(system, methods, inertia, principal, {kind for kind, _ in plan})
    if StepKind.PRESCRIBED_MOTION in {kind for kind, _ in plan} and d.equations_of_motion is not None:
        d = _prescribed(d)
    if {kind for kind, _ in plan} & {
        StepKind.EQUILIBRIA,
        StepKind.LINEARIZATION,
        StepKind.MOMENTUM,
        StepKind.STEADY_MOTION,
    }:
        d = _analysis(d, {kind for kind, _ in plan})
    if system.is_constrained and d.mass_matrix is not None:
        d = _constrained(d, {kind for kind, _ in plan})
    checkpoint("steps")
    kinds = [kind for kind, _ in plan]
    return dataclasses.replace(d, checks=reported_checks(d.checks, kinds), steps=record_steps(d, plan, large))


def _analysis(d: Derivation, kinds: set[StepKind]) -> Derivation:
    """Issue 18's stage after the equations of motion: equilibria and linear models
    (:mod:`~tutgen.engine.analysis`), with the finite-difference check of each linear model."""
    from tutgen.engine.analysis import analyse

    a = analyse(
        d,
        StepKind.EQUILIBRIA in kinds,
        StepKind.LINEARIZATION in kinds,
        StepKind.MOMENTUM in kinds,
        StepKind.STEADY_MOTION in kinds,
    )
    models = {id(m): m for m in (*a.classified, *a.linear)}.values()
    checks = tuple(m.check for m in models if m.check is not None)
    if a.steady is not None:
        checks = (*checks, a.steady.check)
    for check in checks:
        if not check.passed:
            raise DerivationError(
                f"internal check failed: {check.detail}; please report this spec as a tutgen bug", d.system.origin
            )
    linear = [ch for ch in checks if ch.name != "steady_motion_satisfies_equations"][:1]
    steady = [ch for ch in checks if ch.name == "steady_motion_satisfies_equations"]
    return dataclasses.replace(d, analysis=a, checks=(*d.checks, *linear, *steady))


def _prescribed(d: Derivation) -> Derivation:
    """The spec's prescribed coordinates (issue 18): the motion substituted into the equations of every
    coordinate as free, giving the free coordinates' equations and each drive force, with their checks."""
    from tutgen.engine.prescribed import prescribed_motion  # imported by the specs that prescribe (issue 17)

    checkpoint("prescribed motion")
    pm = prescribed_motion(d)
    return dataclasses.replace(d, prescribed=pm, checks=(*d.checks, *pm.checks))


def derive_with_deadline(
    system: System, method: str | None = None, seconds: float | None = DEFAULT_TIMEOUT
) -> Derivation:
    """:func:`derive`, stopped after ``seconds`` (None or 0: no limit) by :func:`tutgen.limits.deadline`.

    ``derive`` is looked up when called, so a test that replaces it is honoured. A timeout is located at
    the spec (``file:1:1``), like every other error about it.
    """
    try:
        with deadline(seconds):
            stage("derivation")
            return derive(system, method)
    except DerivationTimeout as exc:
        if exc.location is None:
            exc.location = system.origin
        raise


def mass_properties(system: System) -> tuple[tuple[BodyInertia, ...], tuple[BodyPrincipal, ...]]:
    """Stage 1: each body's inertia, and its principal axes about the body frame's origin and about its
    centre of mass (with the parameters' numeric values, where they have them)."""
    checkpoint("inertia")
    inertia = tuple(body_inertia(b) for b in system.bodies)
    principal = tuple(body_principal(bi, system.values) for bi in inertia)
    return inertia, principal


def _general_route(
    system: System,
    methods: tuple[Method, ...],
    inertia: tuple[BodyInertia, ...],
    principal: tuple[BodyPrincipal, ...],
    kinds: set[StepKind],
) -> Derivation:
    """Stages 2-8 for any tree of joints, bodies placed by position, or a given T and U."""
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    qdd = [c.qdd for c in system.coordinates]

    # 2. kinematics: a spec that gives T and U has none
    kin: Kinematics | None = None
    if system.kinetic_energy is None:
        checkpoint("kinematics")
        kin = Kinematics(system, {bi.name: bi.com for bi in inertia})

    # 3. energies and forces
    energy = energies(system, inertia, kin)
    remarks = [rotor_remark(system, i, reflected) for i, reflected in rotors(system)] if kin is not None else []
    checkpoint("energies of springs")
    springs = spring_energies(system, kin)
    t_total = energy.kinetic_energy
    u_total = tidy(energy.potential_energy + sum((e for _, e in springs), sp.Integer(0)))
    lagrangian = t_total - u_total
    checkpoint("generalized forces")
    forces = generalized_forces(system, kin, q, qd)

    # 4. Lagrange's equations, term by term
    terms, eom_lagrange = lagrange_equations(system, lagrangian, forces)

    # 5.-6. the matrix form, C from the Christoffel symbols of H
    checkpoint("mass matrix")
    hm = sp.ImmutableMatrix(energy.mass_matrix)
    checkpoint("Christoffel symbols")
    first, tutorial = christoffel_symbols(energy.mass_matrix, q)
    checkpoint("Coriolis and gravity terms")
    c_vec, c_mat = coriolis_terms(first, qd)
    g_vec = gravity_vector(u_total, q)
    q_vec = sp.ImmutableMatrix(forces)
    eom = equations_of_motion(hm, c_vec, g_vec, q_vec, qd, qdd)

    # 7. checks and remarks
    checkpoint("checks")
    checks = matrix_form_checks(system, hm, c_mat, eom, eom_lagrange)
    det = tidy(hm.det(method="berkowitz")) if len(q) <= 4 else None
    # the remarks on H and on the equations only where they are derived (p02 asks for T alone)
    if kinds & {StepKind.MASS_MATRIX, StepKind.EQUATIONS_OF_MOTION, StepKind.LAGRANGE_EQUATIONS}:
        remarks += degeneracy_remarks(system, hm, det, t_total, u_total, forces, eom)
    remarks += zero_remarks(system, inertia, u_total, forces, energy.bodies)
    if all(first[key] == 0 for key in first) and kinds & {StepKind.MASS_MATRIX, StepKind.CHRISTOFFEL}:
        remarks.append(REMARK_CONSTANT_MASS_MATRIX)
    derivation = Derivation(
        system=system,
        inertia=inertia,
        principal=principal,
        kinematics=energy.kinematics,
        energies=energy.bodies,
        spring_energies=springs,
        potential_sources=potential_sources(system, energy.bodies, springs, kin),
        kinetic_energy=t_total,
        potential_energy=u_total,
        lagrangian=lagrangian,
        lagrange_terms=terms,
        generalized_forces=q_vec,
        mass_matrix=hm,
        coriolis_vector=c_vec,
        coriolis_matrix=c_mat,
        gravity_vector=g_vec,
        equations_of_motion=eom,
        christoffel=tutorial,
        christoffel_first_kind=first,
        mass_matrix_determinant=det,
        remarks=tuple(remarks),
        checks=tuple(checks),
        method=_method_name(methods),
        methods=methods,
    )
    checkpoint("checks: mass matrix and dimensions")
    derivation = dataclasses.replace(derivation, checks=(*derivation.checks, *verify(system, derivation)))

    # 8. Newton-Euler, for bodies (a given T has no bodies to free), whenever the equations of motion are
    # derived: its agreement with Lagrange's is one of the checks even when its working is not shown
    wanted = {StepKind.EQUATIONS_OF_MOTION, StepKind.LAGRANGE_EQUATIONS, StepKind.NEWTON_EULER}
    if not kinds & wanted or kin is None or not system.bodies or system.is_constrained:
        return derivation  # a constrained spec's, with its constraint reactions: in _constrained
    checkpoint("Newton-Euler")
    from tutgen.engine.newton_euler import derive_newton_euler  # not on a large serial arm's route (issue 17)

    # the planar working (free bodies, eliminations: a quarter more time) only when it is printed
    ne = derive_newton_euler(system, derivation, kin, planar=Method.NEWTON_EULER in methods)
    return dataclasses.replace(derivation, newton_euler=ne, checks=(*derivation.checks, ne.agreement))


def _constrained(d: Derivation, kinds: set[StepKind]) -> Derivation:
    """The spec's constraints (issue 21): their kinematics, then the equations with Lagrange's multipliers
    and reduced to the independent coordinates, checked against each other."""
    from tutgen.engine.constraints import constrained_dynamics, constraint_kinematics, with_loop_closures

    checkpoint("constraints: kinematics")
    system = with_loop_closures(d.system, d.kinematics)  # the loop joints' equations join the constraints
    ck = constraint_kinematics(system)
    checkpoint("constraints: multipliers and reduction")
    assert d.coriolis_vector is not None and d.gravity_vector is not None and d.generalized_forces is not None
    cd = constrained_dynamics(system, ck, d.mass_matrix, d.coriolis_vector, d.gravity_vector, d.generalized_forces)
    d = dataclasses.replace(d, constraints=cd, checks=(*d.checks, cd.check))
    if kinds & {StepKind.EQUATIONS_OF_MOTION, StepKind.LAGRANGE_EQUATIONS, StepKind.NEWTON_EULER} and d.kinematics:
        # (d.kinematics: bodies placed by the spec, not a given kinetic energy)
        checkpoint("Newton-Euler")  # with the constraint reactions (tutgen.engine.newton_euler)
        from tutgen.engine.newton_euler import derive_newton_euler

        ne = derive_newton_euler(system, d, planar=Method.NEWTON_EULER in d.methods, constraints=cd)
        checks = (*d.checks, ne.agreement, *((ne.reduction,) if ne.reduction else ()))
        d = dataclasses.replace(d, newton_euler=ne, checks=checks)
    return d


def _serial_route(
    system: System,
    methods: tuple[Method, ...],
    inertia: tuple[BodyInertia, ...],
    principal: tuple[BodyPrincipal, ...],
) -> Derivation:
    """A large serial arm: H, C, G, Q, the equations of motion and the Christoffel symbols, with empty
    ``lagrange_terms`` and no Newton-Euler (see ``REMARK_FAST_PATH``).

    Q, springs and dampers are the general route's (:mod:`~tutgen.engine.forces`); world kinematics are
    built only when a load, or a spring or damper between points, needs them.
    """
    from tutgen.engine.recursive import nested_dynamics  # the program of a large arm only

    checkpoint("mass matrix, Coriolis and gravity terms (serial arm)")
    dyn = serial_dynamics(system)
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    qdd = [c.qdd for c in system.coordinates]
    n = len(q)
    needs_world = bool(system.loads) or any(e.between is not None for e in (*system.springs, *system.dampers))
    kin = Kinematics(system, {bi.name: bi.com for bi in inertia}) if needs_world else None

    checkpoint("energies of springs")
    springs = spring_energies(system, kin)
    u_springs = sp.Add(*[e for _, e in springs])
    u_total = dyn.potential_energy + u_springs
    g_vec = dyn.gravity_vector
    if u_springs != 0:
        g_vec = sp.ImmutableMatrix([g_vec[i] + tidy(sp.diff(u_springs, q[i])) for i in range(n)])
    checkpoint("generalized forces")
    forces = generalized_forces(system, kin, q, qd)
    # the entries are long: sums of their parts as they are, without tidying
    h = dyn.mass_matrix
    t_total = sp.Add(
        *[h[i, i] * qd[i] ** 2 / 2 for i in range(n)],
        *[h[i, j] * qd[i] * qd[j] for i in range(n) for j in range(i + 1, n)],
    )
    q_vec = sp.ImmutableMatrix(forces)
    c_vec = dyn.coriolis_vector

    def equations(c: Sequence[sp.Expr]) -> list[sp.Expr]:
        return [sp.Add(*[h[i, j] * qdd[j] for j in range(n)], c[i], g_vec[i], -q_vec[i]) for i in range(n)]

    # C q_dot, C and so the equations are converted when first read (the JSON, an answer check): a worked
    # solution of a large arm only sizes them (issue 17); see tutgen/engine/lazytable.py
    eom = LazyMatrix(n, 1, lambda: equations(list(c_vec)), dyn.coriolis_min_ops)
    c_mat = LazyMatrix(n, n, lambda: list(dyn.coriolis_matrix), lambda: dyn.coriolis_min_ops(matrix=True))

    # the Christoffel symbols are converted when first read (the JSON, an answer check): a worked
    # solution of a large arm does not print them (issue 17)

    checkpoint("checks")
    checks = serial_checks(system, dyn)
    remarks = [REMARK_FAST_PATH.format(n=n)]
    remarks += [rotor_remark(system, i, reflected) for i, reflected in rotors(system)]
    remarks += degeneracy_remarks(system, h, None, t_total, u_total, forces, eom)
    remarks += zero_remarks(system, inertia, u_total, forces)
    derivation = Derivation(
        system=system,
        inertia=inertia,
        principal=principal,
        spring_energies=springs,
        kinetic_energy=t_total,
        potential_energy=u_total,
        lagrangian=t_total - u_total,
        generalized_forces=q_vec,
        mass_matrix=h,
        coriolis_vector=c_vec,
        coriolis_matrix=c_mat,
        gravity_vector=g_vec,
        equations_of_motion=eom,
        christoffel=LazyTable(n, lambda: dyn.christoffel, lambda: dyn.christoffel_keys, dyn.christoffel_min_ops),
        christoffel_first_kind=LazyTable(
            n,
            lambda: dyn.christoffel_first_kind,
            lambda: sorted(dyn.christoffel_first_kind_polys),
            lambda key: dyn.christoffel_first_kind_polys[key].min_ops(),
        ),
        remarks=tuple(remarks),
        checks=tuple(checks),
        method=_method_name(methods),
        methods=methods,
        program=nested_dynamics(system),
    )
    # the dimensional check of checks.py is cheap; its eigenvalue check lambdifies H (seconds at 6 DOF),
    # so the numeric one of serial_checks replaces it
    # (on the equations with each H_ij's and C_i's terms by their monomials, serial.py's
    # mass_dimension_terms and coriolis_dimension_terms: the same dimensions without walking the entries
    # written out, 37 000 operations of H on the symbolic PUMA)
    checkpoint("checks: dimensions")
    h_sized = dyn.mass_dimension_terms()
    c_sized = dyn.coriolis_dimension_terms()
    sized = sp.ImmutableMatrix(
        [sp.Add(*[h_sized[i][j] * qdd[j] for j in range(n)], c_sized[i], g_vec[i], -q_vec[i]) for i in range(n)]
    )
    dims = dimension_checks(system, dataclasses.replace(derivation, equations_of_motion=sized))
    for check in dims:
        if not check.passed:
            raise DerivationError(
                f"internal check failed: {check.detail}; please report this spec as a tutgen bug", system.origin
            )
    return dataclasses.replace(derivation, checks=(*derivation.checks, *dims))
