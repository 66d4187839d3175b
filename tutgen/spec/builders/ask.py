"""`ask`: what the worked solution derives."""

from __future__ import annotations

from tutgen.model.system import Ask
from tutgen.spec.builders.context import Context


def build_ask(ctx: Context, dynamic: bool) -> frozenset[Ask]:
    """What to derive: the items of `ask`, or by default everything that applies (only the inertia of a
    spec that has nothing that moves, ``dynamic`` False)."""
    if ctx.doc.ask is not None:
        return frozenset(Ask(a) for a in ctx.doc.ask)
    if not dynamic:
        return frozenset({Ask.INERTIA})
    everything = set(Ask)
    if not ctx.doc.bodies:
        everything.discard(Ask.INERTIA)
    return frozenset(everything)
