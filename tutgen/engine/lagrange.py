"""Lagrange's method, from the bodies to the matrix form H(q) q_ddot + C(q, q_dot) + G(q) = Q.

The order follows a worked solution: mass properties, kinematics, T and U, the Lagrangian, the
three terms of Lagrange's equation for each coordinate, then H, the Christoffel symbols, C and G.
H is assembled from the velocity Jacobians (H = sum m J_v^T J_v + J_w^T R J_G R^T J_w), one
small entry at a time, and C from the Christoffel symbols of H, so no step needs a global simplify.
The equations of Lagrange's route and the matrix form are then checked against each other.
"""

from __future__ import annotations

import dataclasses

import sympy as sp

from tutgen.engine.checks import verify
from tutgen.engine.derivation import BodyEnergy, Check, Derivation, LagrangeTerms
from tutgen.engine.inertia import BodyInertia, body_inertia, principal_axes
from tutgen.engine.kinematics import Kinematics
from tutgen.engine.newton_euler import derive_newton_euler
from tutgen.engine.tidy import is_zero, tidy, tidy_rates
from tutgen.errors import DerivationError
from tutgen.limits import checkpoint
from tutgen.model.system import GROUND, Ask, Damper, Spring, System

METHODS = ("both", "lagrange", "newton-euler")


def derive(system: System, method: str = "both") -> Derivation:
    """Derive everything a spec asks for, in teaching order.

    ``method`` is "both" (the default) or "newton-euler" to add the Newton-Euler derivation and its
    agreement check when the spec has bodies (not a given energy), or "lagrange" to skip it. Lagrange's
    route always runs: Newton-Euler is checked against it.

    Examples
    ========
    See ``tests/models.py`` for named example systems (simple pendulum, cart-pole, double pendulum).
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, not {method!r}")
    checkpoint("inertia")
    inertia = tuple(body_inertia(b) for b in system.bodies)
    principal = tuple(principal_axes(system_subs(system, bi.inertia_origin)) for bi in inertia)
    if not system.coordinates:
        return Derivation(system=system, inertia=inertia, principal=principal)
    # serial arms of LARGE (4) or more coordinates: the fast route of tutgen/engine/serial.py (issue 8)
    from tutgen.engine.serial import derive_serial, is_large_serial_chain

    if is_large_serial_chain(system):
        return derive_serial(system, method, inertia, principal)

    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    qdd = [c.qdd for c in system.coordinates]
    n = len(q)
    remarks: list[str] = []

    kin: Kinematics | None = None
    energies: list[BodyEnergy] = []
    if system.kinetic_energy is not None:
        t_total = sp.expand(system.kinetic_energy)
        h = sp.Matrix(n, n, lambda i, j: tidy(sp.diff(t_total, qd[i], qd[j])))
        rest = sp.expand(t_total - (sp.Matrix([qd]) * h * sp.Matrix(qd))[0] / 2)
        if rest != 0 or any(h_ij.has(*qd) for h_ij in h):
            raise DerivationError(
                "the kinetic energy must be a quadratic form in the velocities, T = q_dot^T H(q) q_dot / 2; "
                f"this one has the extra terms {rest}",
                system.origin,
            )
        u_total = sp.expand(system.potential_energy) if system.potential_energy is not None else sp.Integer(0)
        bodies_kin = ()
    else:
        checkpoint("kinematics")
        kin = Kinematics(system, {bi.name: bi.com for bi in inertia})
        h = sp.zeros(n, n)
        u_total = sp.Integer(0)
        qd_vec = sp.Matrix(qd)
        g_vec = sp.Matrix(system.gravity) if system.gravity is not None else None
        for bi in inertia:
            checkpoint(f"energies of body '{bi.name}'")
            bk = kin.bodies[bi.name]
            if len(bi.parts) > 1:
                # part by part (sum of m_p J_p^T J_p, each part's own inertia): the centre of mass,
                # a quotient by the total mass, then never enters the expressions
                h_trans = sp.zeros(n, n)
                grav = sp.Integer(0)
                for part in bi.parts:
                    r_p = kin.point(bi.name, part.centroid)
                    j_p = r_p.jacobian(q)
                    h_trans += (j_p.T * j_p).applyfunc(lambda e, m=part.mass: tidy(m * e))
                    if g_vec is not None:
                        grav += -part.mass * (g_vec.T * r_p)[0]
                own = sum((sp.Matrix(part.inertia_centroid) for part in bi.parts), sp.zeros(3, 3))
                h_rot = _rotational_block(own, bk.rotation, bk.jw)
                grav = tidy(grav)
            else:
                h_trans = (bk.jv.T * bk.jv).applyfunc(lambda e, m=bi.mass: tidy(m * e))
                h_rot = _rotational_block(bi.inertia_com, bk.rotation, bk.jw)
                grav = tidy(-bi.mass * (g_vec.T * sp.Matrix(bk.com))[0]) if g_vec is not None else sp.Integer(0)
            h += h_trans + h_rot
            v2 = tidy_rates((qd_vec.T * (bk.jv.T * bk.jv).applyfunc(tidy) * qd_vec)[0], qd)
            t_trans = tidy_rates((qd_vec.T * h_trans * qd_vec)[0] / 2, qd)
            t_rot = tidy_rates((qd_vec.T * h_rot * qd_vec)[0] / 2, qd)
            u_total += grav
            energies.append(BodyEnergy(bi.name, v2, t_trans, t_rot, tidy_rates(t_trans + t_rot, qd), grav))
        # motor rotors: each adds its reflected inertia n^2 J_m to H_ii, i.e. n^2 J_m q_dot_i^2 / 2 to T
        # (so L, and Lagrange's equation term by term, carry it too)
        for i, reflected in _rotors(system):
            h = sp.Matrix(h)
            h[i, i] += reflected
            remarks.append(_rotor_remark(system, i, reflected))
        h = h.applyfunc(tidy)
        t_total = tidy_rates((qd_vec.T * h * qd_vec)[0] / 2, qd)
        bodies_kin = tuple(kin.bodies[b.name] for b in system.bodies)

    checkpoint("energies of springs")
    spring_energies = tuple((s.name, _spring_energy(s, kin, system)) for s in system.springs)
    u_total = tidy(u_total + sum((e for _, e in spring_energies), sp.Integer(0)))
    lagrangian = t_total - u_total

    checkpoint("generalized forces")
    forces = _generalized_forces(system, kin, q, qd)

    # Lagrange's equation, term by term: d/dt(dL/dq_dot_i) - dL/dq_i = Q_i
    terms: list[LagrangeTerms] = []
    eom_lagrange: list[sp.Expr] = []
    for i, coord in enumerate(system.coordinates):
        checkpoint(f"Lagrange's equation for {coord.name}")
        p_i = tidy_rates(sp.diff(lagrangian, qd[i]), qd)
        dp_i = tidy_rates(_ddt(p_i, q, qd, qdd), [*qdd, *qd])
        f_i = tidy_rates(sp.diff(lagrangian, q[i]), qd)
        terms.append(LagrangeTerms(coord.name, p_i, dp_i, f_i, forces[i]))
        eom_lagrange.append(dp_i - f_i - forces[i])

    # matrix form
    checkpoint("mass matrix")
    hm = sp.ImmutableMatrix(h)
    checkpoint("Christoffel symbols")
    first = {
        (i, j, k): tidy((sp.diff(h[i, j], q[k]) + sp.diff(h[i, k], q[j]) - sp.diff(h[j, k], q[i])) / 2)
        for i in range(n)
        for j in range(n)
        for k in range(n)
    }
    tutorial = {
        (i, j, k): tidy(sp.diff(h[i, j], q[k]) - sp.diff(h[j, k], q[i]) / 2)
        for i in range(n)
        for j in range(n)
        for k in range(n)
    }
    checkpoint("Coriolis and gravity terms")
    c_vec = sp.ImmutableMatrix(
        [
            tidy_rates(sum((first[i, j, k] * qd[j] * qd[k] for j in range(n) for k in range(n)), sp.Integer(0)), qd)
            for i in range(n)
        ]
    )
    c_mat = sp.ImmutableMatrix(
        n, n, lambda i, j: tidy_rates(sum((first[i, j, k] * qd[k] for k in range(n)), sp.Integer(0)), qd)
    )
    g_vec = sp.ImmutableMatrix([tidy(sp.diff(u_total, qi)) for qi in q])
    q_vec = sp.ImmutableMatrix(forces)
    eom = sp.ImmutableMatrix(
        [tidy_rates((hm * sp.Matrix(qdd))[i] + c_vec[i] + g_vec[i] - q_vec[i], [*qdd, *qd]) for i in range(n)]
    )

    checkpoint("checks")
    checks = [_agreement(eom, eom_lagrange, system)]
    h_dot = hm.applyfunc(lambda e: _ddt(e, q, qd, qdd))
    skew = h_dot - 2 * c_mat
    ok = all(is_zero(skew[i, j] + skew[j, i])[0] for i in range(n) for j in range(i, n))
    checks.append(Check("skew_symmetry", ok, "H_dot - 2 C is skew-symmetric" if ok else "H_dot - 2 C is NOT skew"))
    checks.append(Check("symmetric_mass_matrix", hm == hm.T, "H = H^T"))

    det = tidy(hm.det(method="berkowitz")) if n <= 4 else None
    remarks += _degeneracy_remarks(system, hm, det, t_total, u_total, forces, eom)
    remarks += _zero_remarks(system, inertia, u_total, forces)
    if all(first[key] == 0 for key in first):
        remarks.append("H does not depend on q, so every Christoffel symbol vanishes and C = 0.")

    derivation = Derivation(
        system=system,
        inertia=inertia,
        principal=principal,
        kinematics=bodies_kin,
        energies=tuple(energies),
        spring_energies=spring_energies,
        kinetic_energy=t_total,
        potential_energy=u_total,
        lagrangian=lagrangian,
        lagrange_terms=tuple(terms),
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
        method=method,
    )
    checkpoint("checks: mass matrix and dimensions")
    derivation = dataclasses.replace(derivation, checks=(*derivation.checks, *verify(system, derivation)))
    if method == "lagrange" or kin is None or not system.bodies:
        return derivation
    checkpoint("Newton-Euler")
    ne = derive_newton_euler(system, derivation, kin)
    return dataclasses.replace(derivation, newton_euler=ne, checks=(*derivation.checks, ne.agreement))


def system_subs(system: System, m: sp.MatrixBase) -> sp.MatrixBase:
    values = system.values
    return m.subs(values) if values else m


def _ddt(expr: sp.Expr, q: list[sp.Symbol], qd: list[sp.Symbol], qdd: list[sp.Symbol]) -> sp.Expr:
    """The total time derivative by the chain rule: d/dt f(q, q_dot) = f_q q_dot + f_qdot q_ddot."""
    out = sp.Integer(0)
    for qi, qdi, qddi in zip(q, qd, qdd, strict=True):
        out += sp.diff(expr, qi) * qdi + sp.diff(expr, qdi) * qddi
    return out


def _rotational_block(inertia: sp.MatrixBase, rotation: sp.MatrixBase, jw: sp.MatrixBase) -> sp.Matrix:
    """J_w^T (R J R^T) J_w for an inertia J in body axes, computed as (R^T J_w)^T J (R^T J_w)."""
    n = jw.shape[1]
    if sp.Matrix(inertia) == sp.zeros(3, 3) or n == 0:
        return sp.zeros(n, n)
    jw_body = (sp.Matrix(rotation).T * sp.Matrix(jw)).applyfunc(tidy)
    return (jw_body.T * sp.Matrix(inertia) * jw_body).applyfunc(tidy)


def _rotors(system: System) -> list[tuple[int, sp.Expr]]:
    """(index of the coordinate, reflected inertia n^2 J_m) for every joint driven by a motor's rotor.

    Only the reflected inertia is modelled: the rotor spins at n q_dot_i about its own axis, so its
    kinetic energy is J_m (n q_dot_i)^2 / 2; its gyroscopic coupling with the links (and its own mass,
    part of the link's) are neglected, as in Spong's and Craig's arm models."""
    index = {c.name: i for i, c in enumerate(system.coordinates)}
    out = []
    for joint in system.joints:
        reflected = joint.reflected_inertia
        if reflected is not None and joint.coordinate is not None:
            out.append((index[joint.coordinate.name], reflected))
    return out


def _rotor_remark(system: System, i: int, reflected: sp.Expr) -> str:
    coord = system.coordinates[i]
    joint = next(j for j in system.joints if j.coordinate is not None and j.coordinate.name == coord.name)

    def show(e: sp.Expr) -> str:
        """A symbolic value as written; a number that is not whole to 6 significant digits."""
        return f"{float(e):.6g}" if e.is_number and not e.is_Integer else sp.sstr(e)

    value = system_subs(system, sp.Matrix([reflected]))[0]
    shown = show(reflected) + (f" = {show(value)}" if value != reflected and not reflected.is_number else "")
    k = i + 1
    entry = f"H_{k}{k}" if k < 10 else f"H_{k},{k}"
    ratio = f"gear ratio n = {show(joint.gear_ratio)}" if joint.gear_ratio is not None else "no gearbox, n = 1"
    return (
        f"Joint '{joint.name}' is driven by a motor ({ratio}) whose rotor has the inertia "
        f"J_m = {show(joint.rotor_inertia)}: it adds the reflected inertia n^2 J_m = {shown} to {entry}, "
        f"that is n^2 J_m {coord.name}_dot^2 / 2 to T (the rotor's gyroscopic coupling with the links is "
        "neglected)."
    )


def _length_between(element: Spring | Damper, kin: Kinematics | None) -> sp.Expr:
    assert element.between is not None and kin is not None
    a, b = element.between
    d = kin.point(a.body, a.at) - kin.point(b.body, b.at)
    return tidy((d.T * d)[0])  # the squared length


def _spring_energy(spring: Spring, kin: Kinematics | None, system: System) -> sp.Expr:
    """U = k (L - L0)^2 / 2, with L the distance between the ends or the given elongation."""
    if spring.extension is not None:
        return spring.stiffness * spring.extension**2 / 2
    if kin is None:
        raise DerivationError(f"spring '{spring.name}' needs bodies to attach to", spring.origin)
    length2 = _length_between(spring, kin)
    if spring.free_length == 0:
        return tidy(spring.stiffness * length2 / 2)
    return spring.stiffness * (sp.sqrt(length2) - spring.free_length) ** 2 / 2


def _generalized_forces(
    system: System, kin: Kinematics | None, q: list[sp.Symbol], qd: list[sp.Symbol]
) -> list[sp.Expr]:
    """Q_i from the virtual power of every applied force, torque and damper."""
    n = len(q)
    names = [c.name for c in system.coordinates]
    out = [sp.Integer(0)] * n
    for name, value in system.generalized_forces:
        i = names.index(name)
        out[i] = out[i] + value
    for load in system.loads:
        assert kin is not None
        frame = kin.frames[load.body]
        rot = frame.rotation if load.in_body_frame else sp.eye(3)
        if load.force is not None:
            force = rot * sp.Matrix(load.force)
            where = kin.point(load.body, load.at)
            jac = kin.point_jacobian(load.body, where)
            if load.reaction_body is not None and load.reaction_body != GROUND:
                jac = jac - kin.point_jacobian(load.reaction_body, where)
            for i in range(n):
                out[i] = out[i] + (force.T * jac[:, i])[0]
        if load.torque is not None:
            torque = rot * sp.Matrix(load.torque)
            jw = frame.jw
            if load.reaction_body is not None and load.reaction_body != GROUND:
                jw = jw - kin.frames[load.reaction_body].jw
            for i in range(n):
                out[i] = out[i] + (torque.T * jw[:, i])[0]
    for damper in system.dampers:
        if damper.extension is not None:
            ext = damper.extension
            rate = sum((sp.diff(ext, q[j]) * qd[j] for j in range(n)), sp.Integer(0))
            for i in range(n):
                out[i] = out[i] - damper.coefficient * rate * sp.diff(ext, q[i])
        else:
            length2 = _length_between(damper, kin)
            # L_dot = (dL^2/dt) / (2 L);  Q_i = -c L_dot dL/dq_i = -c (dL^2/dt)(dL^2/dq_i) / (4 L^2)
            rate2 = sum((sp.diff(length2, q[j]) * qd[j] for j in range(n)), sp.Integer(0))
            for i in range(n):
                out[i] = out[i] - damper.coefficient * rate2 * sp.diff(length2, q[i]) / (4 * length2)
    return [tidy_rates(e, qd) if not e.has(sp.Pow) or e.is_polynomial(*qd) else sp.factor_terms(e) for e in out]


def _agreement(eom: sp.MatrixBase, lagrange: list[sp.Expr], system: System) -> Check:
    """Lagrange's equations, as derived term by term, must equal H q_ddot + C + G - Q."""
    for i, coord in enumerate(system.coordinates):
        zero, _ = is_zero(eom[i] - lagrange[i])
        if not zero:
            raise DerivationError(
                f"internal check failed: the matrix form of the equation for '{coord.name}' differs from "
                "Lagrange's equation; please report this spec as a tutgen bug",
                coord.origin,
            )
    return Check("matrix_form_equals_lagrange", True, "H q_ddot + C + G - Q equals Lagrange's equations")


def _zero_remarks(system: System, inertia: tuple[BodyInertia, ...], u: sp.Expr, forces: list[sp.Expr]) -> list[str]:
    """Bodies without mass, springs without stiffness, dampers without damping, no gravity: valid, but worth
    a word, since each is usually a slip in the spec."""
    values = system.values

    def is_zero_value(e: sp.Expr | None) -> bool:
        return e is not None and sp.sympify(e).subs(values) == 0

    # a massless body that carries others is a device of the kinematics (a gimbal frame), not a slip
    parents = {j.parent for j in system.joints}
    out = [
        f"Body '{bi.name}' has zero mass, so it adds nothing to T, U or H."
        for bi in inertia
        if is_zero_value(bi.mass) and bi.name not in parents
    ]
    out += [
        f"Spring '{s.name}' has zero stiffness, so it stores no energy and adds nothing to U or G."
        for s in system.springs
        if is_zero_value(s.stiffness)
    ]
    out += [
        f"Damper '{d.name}' has a zero coefficient, so it adds nothing to the generalized forces."
        for d in system.dampers
        if is_zero_value(d.coefficient)
    ]
    no_gravity = system.gravity is None or all(is_zero_value(g) for g in system.gravity)
    asked = Ask.EQUATIONS_OF_MOTION in system.ask
    if asked and system.bodies and no_gravity and u == 0 and all(is_zero_value(f) for f in forces):
        out.append("There is no gravity and no other force: U = 0, G = 0 and Q = 0, so the motion is force-free.")
    return out


def _degeneracy_remarks(
    system: System,
    h: sp.MatrixBase,
    det: sp.Expr | None,
    t: sp.Expr,
    u: sp.Expr,
    forces: list[sp.Expr],
    eom: sp.MatrixBase,
) -> list[str]:
    out: list[str] = []
    n = h.shape[0]
    for i, coord in enumerate(system.coordinates):
        if all(h[i, j] == 0 for j in range(n)):
            out.append(
                f"The coordinate '{coord.name}' carries no inertia (row {i + 1} of H is zero): its equation is "
                f"not a differential equation but the condition {sp.sstr(eom[i])} = 0."
            )
        involved = any(e.has(coord.q) or e.has(coord.qd) for e in (t, u, *forces))
        if not involved:
            out.append(f"The coordinate '{coord.name}' appears nowhere in T, U or the generalized forces.")
    if det is not None and det == 0:
        out.append(
            "det H = 0: the mass matrix is singular, so q_ddot = H^-1 (Q - C - G) does not exist; "
            "the equations cannot be solved for every acceleration."
        )
    return out
