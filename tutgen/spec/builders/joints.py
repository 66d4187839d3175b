"""`joints`: the joints of a kinematic tree (with their motors), each placing a child body on its parent."""

from __future__ import annotations

import difflib

import sympy as sp

from tutgen.model.system import GROUND, Joint, JointKind
from tutgen.spec import schema as S
from tutgen.spec.builders.context import Context, rotation_matrix
from tutgen.spec.builders.words import article
from tutgen.spec.loader import KeyPath
from tutgen.spec.units import DIMENSIONS


def build_joints(
    ctx: Context, bodies: set[str], arm: list[Joint], used: dict[str, str]
) -> tuple[list[Joint], dict[str, str]]:
    """The joints of `joints`, and which joint places each body (``{body: joint}``).

    ``bodies`` are the declared bodies, ``arm`` the joints of the DH table (already built) and
    ``used`` the coordinates they drive (``{coordinate: joint}``; the joints here are added to it).
    """
    out: list[Joint] = []
    # body -> the joint that places it
    children: dict[str, str] = {j.child: j.name for j in arm}
    # (joint, parent, child) of every well-formed link
    links: list[tuple[str, str, str]] = [(j.name, j.parent, j.child) for j in arm]
    arm_joints = {j.name for j in arm}
    consts = ctx.symbols()
    known = sorted(bodies | {GROUND})
    for name, spec in ctx.doc.joints.items():
        if spec.closes_loop:  # a loop-closing joint places nothing (builders/loops.py)
            continue
        path: KeyPath = ("joints", name)
        ctx.check_name(path, name, "joint")
        if spec.child_origin is not None:
            ctx.error(
                (*path, "child_origin"),
                f"joint '{name}' does not close a loop, so it has no `child_origin`",
                "add `closes_loop: true`, or remove it",
                key=True,
            )
        ok = True
        if name in arm_joints:
            ctx.error(
                path,
                f"joint '{name}' is also the name of a joint of the arm; give one of them another name",
                "an arm row's joint is called joint<i> unless its `joint` key names it",
                key=True,
            )
            ok = False
        if spec.child == GROUND:
            ctx.error(
                (*path, "child"),
                f"joint '{name}' has the ground as its child; expected the body that the joint moves "
                f"(known: {', '.join(sorted(bodies)) or 'none'})",
            )
            ok = False
        for role in ("parent", "child"):
            target = getattr(spec, role)
            if target in bodies or (target == GROUND and (role == "parent" or not ok)):
                continue
            unknown_body(ctx, (*path, role), name, target, known)
            ok = False
        if ok and spec.parent == spec.child:
            ctx.error(
                (*path, "child"),
                f"joint '{name}' connects body '{spec.child}' to itself; expected a child other than its parent",
            )
            ok = False
        elif ok and spec.child in children:
            ctx.error(
                (*path, "child"),
                f"body '{spec.child}' is already placed by joint '{children[spec.child]}'; "
                "expected one joint from each body to its parent",
            )
            ok = False
        elif ok:
            children[spec.child] = name
            links.append((name, spec.parent, spec.child))
        kind = JointKind(spec.type)
        coord = None
        if kind is JointKind.FIXED:
            if spec.coordinate is not None:
                ctx.error(
                    (*path, "coordinate"),
                    f"joint '{name}' is fixed, so it has no coordinate; found coordinate '{spec.coordinate}'",
                    "remove `coordinate`, or make the joint revolute or prismatic",
                )
                ok = False
        elif spec.coordinate is None:
            ctx.error(
                path,
                f"joint '{name}' is {kind.value} and needs a `coordinate` "
                f"(declared: {', '.join(ctx.coords) or 'none'}); found none",
                key=True,
            )
            ok = False
        elif spec.coordinate not in ctx.coords:
            close = difflib.get_close_matches(spec.coordinate, list(ctx.coords), n=1)
            ctx.error(
                (*path, "coordinate"),
                f"joint '{name}' uses '{spec.coordinate}', which is not a "
                f"declared coordinate (declared: {', '.join(ctx.coords) or 'none'})",
                f"did you mean '{close[0]}'?" if close else None,
            )
            ok = False
        else:
            coord = ctx.coords[spec.coordinate]
            if spec.coordinate in used:
                ctx.error(
                    (*path, "coordinate"),
                    f"coordinate '{spec.coordinate}' already drives joint '{used[spec.coordinate]}'; "
                    "expected one joint per coordinate",
                )
                ok = False
            used[spec.coordinate] = name
            expected = "angle" if kind is JointKind.REVOLUTE else "length"
            if coord.dimension is not None and coord.dimension != expected:
                ctx.error(
                    (*path, "coordinate"),
                    f"joint '{name}' is {kind.value}, so its coordinate must be {article(expected)} {expected}; "
                    f"found '{coord.name}', declared as {article(coord.dimension)} {coord.dimension}",
                )
                ok = False
            ctx.dims.setdefault(coord.q, DIMENSIONS[expected])
        if spec.angle == "absolute" and kind is not JointKind.REVOLUTE:
            ctx.error(
                (*path, "angle"),
                f"joint '{name}' is {kind.value}; only a revolute joint can measure an absolute angle",
                "remove `angle: absolute`",
            )
            ok = False
        axis = ctx.axis((*path, "axis"), spec.axis, {})
        origin = ctx.vector((*path, "origin"), spec.origin, consts, "length")
        offset_dim = "angle" if kind is JointKind.REVOLUTE else "length"
        offset = (
            ctx.expr((*path, "offset"), spec.offset, consts, offset_dim) if spec.offset is not None else sp.Integer(0)
        )
        rots = ctx.rotations((*path, "orientation"), spec.orientation, consts)
        rotation = rotation_matrix(rots or ())
        motor = build_motor(ctx, (*path, "motor"), spec.motor, kind, f"joint '{name}'")
        if not ok or axis is None or origin is None or offset is None or rots is None or motor is None:
            continue
        out.append(
            Joint(
                name,
                kind,
                spec.parent,
                spec.child,
                coord,
                axis,
                origin,
                rotation,
                offset,
                spec.angle == "absolute",
                ctx.smap.key_location(path),
                rotor_inertia=motor[0],
                gear_ratio=motor[1],
            )
        )
    _check_loops(ctx, links)
    return out, dict(children)


def unknown_body(ctx: Context, path: KeyPath, joint: str, target: str, known: list[str]) -> None:
    """The error at a joint's `parent` or `child` naming no body: the names known, and the closest one."""
    close = difflib.get_close_matches(target, known, n=1)
    ctx.error(
        path,
        f"joint '{joint}' refers to unknown body '{target}' (known: {', '.join(known)})",
        f"did you mean '{close[0]}'?" if close else None,
    )


def build_motor(
    ctx: Context, path: KeyPath, spec: S.MotorSpec | None, kind: JointKind, owner: str
) -> tuple[sp.Expr | None, sp.Expr | None] | None:
    """(rotor inertia, gear ratio) of a joint's motor, (None, None) without one; None if bad."""
    if spec is None:
        return None, None
    if kind is JointKind.FIXED:
        ctx.error(path, f"{owner} is fixed, so it has no motor; found `motor`", "remove `motor`", key=True)
        return None
    consts = ctx.symbols()
    inertia = ctx.expr((*path, "rotor_inertia"), spec.rotor_inertia, consts, "inertia", "a rotor inertia")
    ratio: sp.Expr | None = sp.Integer(1)
    if spec.gear_ratio is not None:
        # revolute: rotor turns per joint turn (a plain number); prismatic: rotor radians per metre
        dim = "dimensionless" if kind is JointKind.REVOLUTE else None
        ratio = ctx.expr((*path, "gear_ratio"), spec.gear_ratio, consts, dim, "a gear ratio")
    if inertia is not None and inertia.subs(ctx.values).is_negative:
        ctx.error(
            (*path, "rotor_inertia"),
            f"the rotor inertia of {owner} must not be negative; found '{spec.rotor_inertia}'",
        )
        inertia = None
    if ratio is not None and spec.gear_ratio is not None and ratio.subs(ctx.values).is_nonpositive:
        ctx.error(
            (*path, "gear_ratio"),
            f"the gear ratio of {owner} must be positive (rotor speed / joint speed); found '{spec.gear_ratio}'",
            "a motor turning the other way has the same reflected inertia n^2 J_m: give |n|",
        )
        ratio = None
    if inertia is None or ratio is None:
        return None
    return inertia, (ratio if spec.gear_ratio is not None else None)


def _check_loops(ctx: Context, links: list[tuple[str, str, str]]) -> None:
    """Every chain of parents must end at the ground: report each loop once, at its first joint."""
    parent_of = {child: (parent, joint) for joint, parent, child in links}
    order = {joint: i for i, (joint, _, _) in enumerate(links)}
    reported: set[frozenset[str]] = set()
    for start in parent_of:
        chain = [start]
        node = start
        while node in parent_of:
            node = parent_of[node][0]
            if node in chain:
                loop = chain[chain.index(node) :]
                if frozenset(loop) not in reported:
                    reported.add(frozenset(loop))
                    joints = sorted((parent_of[b][1] for b in loop), key=order.__getitem__)
                    # start the printed chain at the child of the first joint, for a stable message
                    i = next(k for k, b in enumerate(loop) if parent_of[b][1] == joints[0])
                    loop = loop[i:] + loop[:i]
                    ctx.error(
                        ("joints", joints[0]),
                        f"the joints {', '.join(joints)} form a loop (each body's parent, in turn: "
                        + " -> ".join([*loop, loop[0]])
                        + "); expected a tree in which every body leads back to ground",
                        key=True,
                    )
                break
            chain.append(node)


def check_explicit_placement(ctx: Context, placed: dict[str, str]) -> None:
    """A body placed by a joint (``placed``: {body: joint}) cannot also be placed by hand."""
    for name, spec in ctx.doc.bodies.items():
        if name in placed and (spec.position is not None or spec.orientation):
            key = "position" if spec.position is not None else "orientation"
            ctx.error(
                ("bodies", name, key),
                f"body '{name}' is placed by joint '{placed[name]}', so it cannot also have "
                f"a `position` or `orientation`; found `{key}`",
                "remove it, or remove the joint",
                key=True,
            )
