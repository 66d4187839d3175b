"""`arm`: a serial arm as a Denavit-Hartenberg table, desugared into one body and one joint per row."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import sympy as sp

from tutgen.model.system import GROUND, ArmTable, Body, Coordinate, DHRow, Joint, JointKind, Part
from tutgen.spec import schema as S
from tutgen.spec.builders.bodies import lumped_part
from tutgen.spec.builders.context import Context
from tutgen.spec.builders.joints import build_motor
from tutgen.spec.builders.words import article
from tutgen.spec.loader import KeyPath
from tutgen.spec.places import ARM_LINKS
from tutgen.spec.units import DIMENSIONS


def build_arm(ctx: Context, used: dict[str, str]) -> tuple[list[Body], list[Joint], ArmTable | None]:
    """One body and one joint per row of `arm.links`, placed exactly as the DH matrices place them.

    modified (Craig), A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i): the row's joint has
    origin (a_{i-1}, 0, 0) + Rx(alpha_{i-1}) (0, 0, d_i), the fixed rotation Rx(alpha_{i-1}) and axis
    z (a prismatic row: origin (a_{i-1}, 0, 0), rotation Rx(alpha_{i-1}) Rz(theta_i), sliding along z),
    and the body frame is DH frame i.

    standard (Spong, Paul), A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i): a joint cannot put fixed
    transforms after its motion, so the body frame of link i is the frame after Rz(theta_i) Tz(d_i)
    (on joint axis i, where Craig puts frame i), and DH frame i = body frame Tx(a_i) Rx(alpha_i). The
    link's centre of mass and inertia, given in DH frame i, are moved into the body frame exactly:
    c' = (a_i, 0, 0) + Rx(alpha_i) c and J' = Rx(alpha_i) J Rx(alpha_i)^T; the next row's joint then
    starts from (a_i, 0, 0) turned by Rx(alpha_i), as a modified row would.
    """
    spec = ctx.doc.arm
    if spec is None:
        return [], [], None
    if not spec.links and not ctx.dropped_arm_links():
        ctx.error(("arm", "links"), "the arm has no links; expected one row per link, from the base outward")
        return [], [], None
    # imported here, as in context.rotation_matrix: spec/ borrows only this formula from engine/
    from tutgen.engine.kinematics import rotation_about

    x_axis = sp.ImmutableMatrix([1, 0, 0])
    z_axis = sp.ImmutableMatrix([0, 0, 1])

    def rot(axis: sp.ImmutableMatrix, angle: sp.Expr) -> sp.Matrix:
        return sp.eye(3) if angle == 0 else rotation_about(axis, angle)

    consts = ctx.symbols()
    kin_names = ctx.symbols(coords=True)
    by_q = {c.q: c for c in ctx.coords.values()}
    standard = spec.convention == "standard"
    other_joints = set(ctx.doc.joints)
    bodies: list[Body] = []
    joints: list[Joint] = []
    table: list[DHRow] = []  # the rows as written, for the worked solution's table
    names: dict[str, str] = {}  # joint name -> its row
    parent = GROUND
    before = (sp.Integer(0), sp.Integer(0))  # standard: the previous row's (a, alpha); frame 0 is the world
    for i, (name, row) in enumerate(spec.links.items(), start=1):
        path: KeyPath = (*ARM_LINKS, name)
        where = f"arm link '{name}'"
        ctx.check_name(path, name, "link")
        ok = ctx.check_name_free(path, name, "link")
        if name in ctx.doc.bodies:
            ctx.error(
                path,
                f"'{name}' is both a link of the arm and a body in `bodies`; give one of them another name",
                key=True,
            )
            ok = False
        joint_name = row.joint if row.joint is not None else f"joint{i}"
        jpath: KeyPath = (*path, "joint") if row.joint is not None else path
        if row.joint is not None:
            ctx.check_name(jpath, joint_name, "joint")
        if joint_name in names or joint_name in other_joints:
            first = f"the joint of arm link '{names[joint_name]}'" if joint_name in names else "a joint in `joints`"
            ctx.error(
                jpath,
                f"the joint of {where} is called '{joint_name}', which is already {first}; expected a new name",
                "name it with the row's `joint` key",
                key=row.joint is None,
            )
            ok = False
        names.setdefault(joint_name, name)
        theta = ctx.expr((*path, "theta"), row.theta, kin_names, "angle")
        d = ctx.expr((*path, "d"), row.d, kin_names, "length")
        a = ctx.expr((*path, "a"), row.a, consts, "length")
        alpha = ctx.expr((*path, "alpha"), row.alpha, consts, "angle")
        kind, coord, offset = _joint_variable(ctx, path, where, row, theta, d, by_q, used, joint_name)
        ok &= kind is not None
        body = _link_body(ctx, path, name, row, consts)
        motor = build_motor(ctx, (*path, "motor"), row.motor, kind or JointKind.REVOLUTE, where)
        here_a, here_alpha = before if standard else (a, alpha)
        if standard:
            before = (a, alpha)
        if not ok or None in (theta, d, a, alpha, here_a, here_alpha, body, motor, offset):
            parent = name
            continue
        assert kind is not None and body is not None and motor is not None and coord is not None
        table.append(DHRow(name, theta, d, a, alpha))
        rx = rot(x_axis, here_alpha)
        if kind is JointKind.REVOLUTE:
            origin = sp.Matrix([here_a, 0, 0]) + rx * sp.Matrix([0, 0, d])
            rotation = rx
        else:
            origin = sp.Matrix([here_a, 0, 0])
            rotation = rx * rot(z_axis, theta)
        if standard:  # the link's data, given in DH frame i, into the body frame (see the docstring)
            body = _moved(body, a, rot(x_axis, alpha))
        bodies.append(body)
        joints.append(
            Joint(
                joint_name,
                kind,
                parent,
                name,
                coord,
                z_axis,
                sp.ImmutableMatrix(origin.applyfunc(sp.expand)),
                sp.ImmutableMatrix(sp.Matrix(rotation).applyfunc(sp.expand)),
                offset,
                False,
                ctx.smap.key_location(path),
                rotor_inertia=motor[0],
                gear_ratio=motor[1],
            )
        )
        parent = name
    return bodies, joints, ArmTable(spec.convention, tuple(table))


def _joint_variable(
    ctx: Context,
    path: KeyPath,
    where: str,
    row: S.DHLinkSpec,
    theta: sp.Expr | None,
    d: sp.Expr | None,
    by_q: dict[sp.Expr, Coordinate],
    used: dict[str, str],
    joint_name: str,
) -> tuple[JointKind | None, Coordinate | None, sp.Expr | None]:
    """The joint variable of a DH row: which of theta and d holds a coordinate, and the constant beside it."""
    if theta is None or d is None:
        return None, None, None
    found = {key: sorted(e.free_symbols & by_q.keys(), key=str) for key, e in (("theta", theta), ("d", d))}
    declared = ", ".join(ctx.coords) or "none"
    if found["theta"] and found["d"]:
        ctx.error(
            (*path, "d"),
            f"{where} uses a coordinate in both `theta` ('{row.theta}') and `d` ('{row.d}'); expected one "
            "joint variable: in `theta` (a revolute joint) or in `d` (a prismatic joint), the other a constant",
        )
        return None, None, None
    if not found["theta"] and not found["d"]:
        ctx.error(
            path,
            f"{where} has no joint variable: neither `theta` nor `d` uses a coordinate (declared: {declared}); "
            "expected a coordinate in `theta` (revolute) or in `d` (prismatic)",
            "e.g. theta: q1; a link that does not move goes in `bodies`, with a fixed joint",
            key=True,
        )
        return None, None, None
    key = "theta" if found["theta"] else "d"
    kind = JointKind.REVOLUTE if key == "theta" else JointKind.PRISMATIC
    value, written = (theta, row.theta) if key == "theta" else (d, row.d)
    if row.type is not None and row.type != kind.value:
        ctx.error(
            (*path, "type"),
            f"{where} is declared {row.type}, but its coordinate is in `{key}`, which makes it {kind.value}; "
            f"expected the coordinate in `{'theta' if row.type == 'revolute' else 'd'}`",
        )
        return None, None, None
    q = found[key][0]
    offset = sp.expand(value - q)
    if len(found[key]) > 1 or offset.free_symbols & by_q.keys():
        ctx.error(
            (*path, key),
            f"expected `{key}` of {where} to be one coordinate plus a constant (e.g. 'q2 + pi/2'), found '{written}'",
        )
        return None, None, None
    coord = by_q[q]
    if coord.name in used:
        ctx.error(
            (*path, key),
            f"coordinate '{coord.name}' already drives joint '{used[coord.name]}'; expected one joint per coordinate",
        )
        return None, None, None
    used[coord.name] = joint_name
    expected = "angle" if kind is JointKind.REVOLUTE else "length"
    if coord.dimension is not None and coord.dimension != expected:
        ctx.error(
            (*path, key),
            f"{where} is {kind.value}, so its coordinate must be {article(expected)} {expected}; "
            f"found '{coord.name}', declared as {article(coord.dimension)} {coord.dimension}",
        )
        return None, None, None
    ctx.dims.setdefault(coord.q, DIMENSIONS[expected])
    return kind, coord, offset


def _link_body(ctx: Context, path: KeyPath, name: str, row: S.DHLinkSpec, consts: Mapping[str, sp.Expr]) -> Body | None:
    """The link as a body given by mass, centre of mass and inertia (in DH frame i), or massless."""
    parts: list[Part] = []
    if row.mass is not None:
        part = lumped_part(ctx, path, name, row, consts)
        if part is None:
            return None
        parts.append(part)
    elif row.inertia is not None or row.com is not None:
        given = "`com`" if row.com is not None else "`inertia`"
        ctx.error(path, f"arm link '{name}' gives {given} but no `mass`; expected a `mass` with it", key=True)
        return None
    return Body(name, tuple(parts), None, None, (), ctx.smap.key_location(path), True)


def _moved(body: Body, a: sp.Expr, rx: sp.Matrix) -> Body:
    """A standard-convention link's data from DH frame i into its body frame: c' = (a, 0, 0) + Rx c,
    J' = Rx J Rx^T (DH frame i is the body frame moved by a along x and turned by Rx)."""
    parts = []
    for p in body.parts:
        at = (sp.Matrix([a, 0, 0]) + rx * sp.Matrix(p.at)).applyfunc(sp.expand)
        inertia = None if p.inertia is None else (rx * sp.Matrix(p.inertia) * rx.T).applyfunc(sp.expand)
        parts.append(
            dataclasses.replace(
                p,
                at=sp.ImmutableMatrix(at),
                inertia=None if inertia is None else sp.ImmutableMatrix(inertia),
            )
        )
    return dataclasses.replace(body, parts=tuple(parts))
