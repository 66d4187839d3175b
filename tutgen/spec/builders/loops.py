"""Loop-closing joints (`closes_loop: true` in `joints`): the joints that close a four-bar or a slider-crank.

The tree of joints places every body; a loop-closing joint places nothing and has no coordinate: it says
that a point of its parent and a point of its child coincide, which the engine turns into the
loop-closure equations (tutgen/engine/constraints/loops.py). Only revolute joints close loops.
"""

from __future__ import annotations

import sympy as sp

from tutgen.model.system import GROUND, LoopJoint
from tutgen.spec.builders.context import Context
from tutgen.spec.builders.joints import unknown_body
from tutgen.spec.loader import KeyPath


def build_loop_joints(ctx: Context, bodies: set[str]) -> list[LoopJoint]:
    """The loop-closing joints, in spec order; ``bodies`` are the declared bodies."""
    out: list[LoopJoint] = []
    consts = ctx.symbols()
    known = sorted(bodies | {GROUND})
    for name, spec in ctx.doc.joints.items():
        if not spec.closes_loop:
            continue
        path: KeyPath = ("joints", name)
        ctx.check_name(path, name, "joint")
        ok = True
        if spec.type != "revolute":
            ctx.error(
                (*path, "type"),
                f"joint '{name}' closes a loop and is {spec.type}; expected a revolute loop-closing joint "
                "(a slider is closed by a revolute joint on its slide block)",
            )
            ok = False
        if spec.coordinate is not None:
            ctx.error(
                (*path, "coordinate"),
                f"joint '{name}' closes a loop, so it has no coordinate of its own; found '{spec.coordinate}'",
                "its angle follows from the loop: remove `coordinate`",
            )
            ok = False
        for role in ("parent", "child"):
            target = getattr(spec, role)
            if target in known:
                continue
            unknown_body(ctx, (*path, role), name, target, known)
            ok = False
        if ok and spec.parent == spec.child:
            ctx.error((*path, "child"), f"joint '{name}' connects body '{spec.child}' to itself")
            ok = False
        parent_at = ctx.vector((*path, "origin"), spec.origin, consts, "length")
        child_at = ctx.vector((*path, "child_origin"), spec.child_origin, consts, "length")
        if not ok or parent_at is None or child_at is None:
            continue
        out.append(
            LoopJoint(
                name,
                spec.parent,
                spec.child,
                sp.ImmutableMatrix(parent_at),
                sp.ImmutableMatrix(child_at),
                ctx.smap.key_location(path),
            )
        )
    return out
