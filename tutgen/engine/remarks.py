"""What a worked solution says about a spec besides its results: motors, degenerate coordinates, zeros.

Each function returns sentences (plain text with ASCII names such as H_11 and q_dot) in the order the
solution prints them; :mod:`tutgen.engine.pipeline` collects them into ``Derivation.remarks``.
"""

from __future__ import annotations

import sympy as sp

from tutgen.engine.derivation import BodyEnergy
from tutgen.engine.inertia import BodyInertia
from tutgen.model.system import Ask, System

__all__ = ["REMARK_CONSTANT_MASS_MATRIX", "degeneracy_remarks", "rotor_remark", "zero_remarks"]

REMARK_CONSTANT_MASS_MATRIX = "H does not depend on q, so every Christoffel symbol vanishes and C = 0."


def rotor_remark(system: System, i: int, reflected: sp.Expr) -> str:
    """The sentence on the motor of coordinate i and the reflected inertia it adds to H_ii."""
    coord = system.coordinates[i]
    joint = next(j for j in system.joints if j.coordinate is not None and j.coordinate.name == coord.name)

    def show(e: sp.Expr) -> str:
        """A symbolic value as written; a number that is not whole to 6 significant digits."""
        return f"{float(e):.6g}" if e.is_number and not e.is_Integer else sp.sstr(e)

    values = system.values
    value = sp.Matrix([reflected]).subs(values)[0] if values else reflected
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


def zero_remarks(
    system: System,
    inertia: tuple[BodyInertia, ...],
    u: sp.Expr,
    forces: list[sp.Expr],
    energies: tuple[BodyEnergy, ...] = (),
) -> list[str]:
    """Bodies without mass, springs without stiffness, dampers without damping, no gravity: valid, but worth
    a word, since each is usually a slip in the spec.

    What a massless body adds is read off the results it comments on: its kinetic energy among
    ``energies`` (when the route has them; the serial route does not) and its inertia about its centre of
    mass. A flywheel (``mass: 0, inertia: {zz: J}``) that turns adds J w^2 / 2 to T, so it is not said to
    add nothing.
    """
    values = system.values

    def is_zero_value(e: sp.Expr | None) -> bool:
        return e is not None and sp.sympify(e).subs(values) == 0

    def is_zero_expr(e: sp.Expr) -> bool:
        value = sp.sympify(e).subs(values) if values else sp.sympify(e)
        return value == 0 or sp.simplify(value) == 0

    # a massless body that carries others is a device of the kinematics (a gimbal frame), not a slip
    parents = {j.parent for j in system.joints}
    by_name = {e.name: e for e in energies}
    out: list[str] = []
    for bi in inertia:
        if not is_zero_value(bi.mass) or bi.name in parents:
            continue
        energy = by_name.get(bi.name)
        no_inertia = all(is_zero_expr(x) for x in bi.inertia_com)
        if no_inertia:
            out.append(f"Body '{bi.name}' has zero mass and no moment of inertia, so it adds nothing to T, U or H.")
        elif energy is not None and is_zero_expr(energy.kinetic):
            out.append(f"Body '{bi.name}' has zero mass and does not turn, so it adds nothing to T, U or H.")
        elif energy is not None:
            out.append(
                f"Body '{bi.name}' has zero mass, so it adds nothing to U; its moment of inertia still adds "
                f"{_ascii(energy.kinetic)} to T, and so to H."
            )
        else:
            out.append(
                f"Body '{bi.name}' has zero mass, so it adds nothing to U; its moment of inertia still adds "
                "its rotational energy to T, and so to H."
            )
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


def degeneracy_remarks(
    system: System,
    h: sp.MatrixBase,
    det: sp.Expr | None,
    t: sp.Expr,
    u: sp.Expr,
    forces: list[sp.Expr],
    eom: sp.MatrixBase,
) -> list[str]:
    """Coordinates without inertia or without any role, and a singular H (``det`` None: not computed)."""
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


def _ascii(e: sp.Expr) -> str:
    """An expression in the sentences' ASCII notation (``J phi_dot^2/2``), which the renderers typeset."""
    return sp.sstr(e).replace("**", "^").replace("*", " ")
