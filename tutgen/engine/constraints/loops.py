"""Loop-closing joints as constraints: the loop-closure equations from the geometry.

A loop-closing revolute joint says that the point ``parent_at`` of its parent and ``child_at`` of its
child are the same point. With each body's frame from the tree (its position r and rotation R, world from
body), the loop-closure equations are the world components of

    r_parent + R_parent parent_at - (r_child + R_child child_at) = 0,

each a position constraint named ``<joint>_x``, ``<joint>_y``, ``<joint>_z``; a component that is
identically zero (the z of a planar loop) says nothing and is left out. The revolute joint's axis is
assumed to be the loop's normal (a planar mechanism): the rotations about the other axes are not
constrained.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import sympy as sp

from tutgen.engine.kinematics import BodyKinematics
from tutgen.engine.tidy import tidy
from tutgen.errors import DerivationError
from tutgen.model.system import GROUND, Constraint, ConstraintKind, System

__all__ = ["loop_closure_equations", "with_loop_closures"]


def _point(kin: dict[str, BodyKinematics], body: str, at: sp.MatrixBase) -> sp.Matrix:
    if body == GROUND:
        return sp.Matrix(at)
    k = kin[body]
    return sp.Matrix(k.position) + sp.Matrix(k.rotation) * sp.Matrix(at)


def loop_closure_equations(system: System, kinematics: Sequence[BodyKinematics]) -> tuple[Constraint, ...]:
    """The loop-closure equations of every loop-closing joint, in spec order (the module's conventions)."""
    kin = {k.name: k for k in kinematics}
    out: list[Constraint] = []
    for joint in system.loop_joints:
        gap = _point(kin, joint.parent, joint.parent_at) - _point(kin, joint.child, joint.child_at)
        for axis, e in zip("xyz", gap, strict=True):
            e = tidy(sp.expand(e))
            if e != 0:
                out.append(Constraint(f"{joint.name}_{axis}", ConstraintKind.POSITION, e, joint.origin))
    return tuple(out)


def with_loop_closures(system: System, kinematics: Sequence[BodyKinematics]) -> System:
    """The system with its loop-closure equations first among its constraints, and its independent
    coordinates resolved: as the spec lists them (their count checked: n minus the number of equations),
    or the first n - m coordinates."""
    if not system.loop_joints:
        return system
    closures = loop_closure_equations(system, kinematics)
    constraints = (*closures, *system.constraints)
    n, m = len(system.coordinates), len(constraints)
    if m >= n:
        raise DerivationError(
            f"the loop-closing joints give {len(closures)} equation(s) and the spec {len(system.constraints)} "
            f"constraint(s): {m} on {n} coordinate(s) leave no motion; expected fewer than {n}",
            system.loop_joints[0].origin,
        )
    independent = system.independent_coordinates
    if not independent:
        independent = tuple(c.name for c in system.coordinates[: n - m])
    elif len(independent) != n - m:
        raise DerivationError(
            f"{n} coordinates with {m} loop-closure equation(s) and constraint(s) leave {n - m} independent "
            f"coordinate(s); `independent_coordinates` lists {len(independent)} ({', '.join(independent)})",
            system.loop_joints[0].origin,
        )
    return dataclasses.replace(system, constraints=constraints, independent_coordinates=independent)
