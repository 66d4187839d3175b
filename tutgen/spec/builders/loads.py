"""`loads` and `generalized_forces`: the applied forces and torques, on bodies or along coordinates."""

from __future__ import annotations

import difflib

import sympy as sp

from tutgen.model.system import GROUND, Load
from tutgen.spec.builders.context import Context
from tutgen.spec.loader import KeyPath


def build_loads(ctx: Context, bodies: set[str]) -> list[Load]:
    """The applied forces and torques, in spec order; ``bodies`` are the declared bodies."""
    out = []
    names = ctx.symbols(coords=True, rates=True)
    for name, spec in ctx.doc.loads.items():
        path: KeyPath = ("loads", name)
        ctx.check_name(path, name, "load")
        ok = True
        for role in ("body", "reaction_body"):
            target = getattr(spec, role)
            allowed = bodies | ({GROUND} if role == "reaction_body" else set())
            if target is not None and target not in allowed:
                close = difflib.get_close_matches(target, sorted(allowed), n=1)
                ctx.error(
                    (*path, role),
                    f"load '{name}' refers to unknown body '{target}' (known: {', '.join(sorted(allowed)) or 'none'})",
                    f"did you mean '{close[0]}'?" if close else None,
                )
                ok = False
        if spec.force is None and spec.torque is None:
            ctx.error(path, f"load '{name}' needs a `force` or a `torque` (or both); found neither", key=True)
            ok = False
        force = ctx.vector((*path, "force"), spec.force, names) if spec.force is not None else None
        torque = ctx.vector((*path, "torque"), spec.torque, names) if spec.torque is not None else None
        at = ctx.vector((*path, "at"), spec.at, ctx.symbols(), "length")
        if (
            not ok
            or (spec.force is not None and force is None)
            or (spec.torque is not None and torque is None)
            or at is None
        ):
            continue
        out.append(
            Load(
                name,
                spec.body,
                force,
                torque,
                at,
                spec.frame == "body",
                spec.reaction_body,
                ctx.smap.key_location(path),
            )
        )
    return out


def build_generalized_forces(ctx: Context) -> list[tuple[str, sp.Expr]]:
    """The forces that act along a coordinate directly, as (coordinate name, expression)."""
    out = []
    names = ctx.symbols(coords=True, rates=True)
    for cname, value in ctx.doc.generalized_forces.items():
        path: KeyPath = ("generalized_forces", cname)
        if cname not in ctx.coords:
            close = difflib.get_close_matches(cname, list(ctx.coords), n=1)
            ctx.error(
                path,
                f"generalized force on '{cname}': '{cname}' is not a declared coordinate "
                f"(declared: {', '.join(ctx.coords) or 'none'})",
                f"did you mean '{close[0]}'?" if close else None,
                key=True,
            )
            continue
        e = ctx.expr(path, value, names)
        if e is not None:
            out.append((cname, e))
    return out
