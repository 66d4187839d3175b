"""`methods`: the formulations a worked solution presents."""

from __future__ import annotations

from tutgen.model.system import Ask, Method
from tutgen.spec.builders.context import Context

#: what Newton-Euler derives: one of these must be asked for when it is listed
_NEWTON_EULER_GIVES = frozenset({Ask.EQUATIONS_OF_MOTION, Ask.LAGRANGE_EQUATIONS})


def build_methods(ctx: Context, ask: frozenset[Ask]) -> tuple[Method, ...]:
    """The items of `methods`, in order (default: Lagrange's alone). A method that does not apply is a
    problem at its item: Newton-Euler for a system given by its energy (it frees bodies, and there are
    none), or when `ask` asks for no equations of motion; a method listed twice; an empty list."""
    given = ctx.doc.methods
    if given is None:
        return (Method.LAGRANGE,)
    if not given:
        ctx.error(("methods",), "`methods` is empty; expected one or both of: lagrange, newton_euler")
        return (Method.LAGRANGE,)
    methods: list[Method] = []
    for i, item in enumerate(given):
        method = Method(item)
        if method in methods:
            ctx.error(("methods", i), f"method '{item}' is listed twice in `methods`")
            continue
        if method is Method.NEWTON_EULER:
            if ctx.doc.energy is not None:
                ctx.error(
                    ("methods", i),
                    "Newton-Euler does not apply to a system given by its energy (`energy`): it balances the "
                    "forces on bodies, and the spec has none; expected methods: [lagrange]",
                )
                continue
            if not ask & _NEWTON_EULER_GIVES:
                ctx.error(
                    ("methods", i),
                    "Newton-Euler derives the equations of motion, which `ask` does not ask for; expected "
                    "`equations_of_motion` in `ask`, or methods: [lagrange]",
                )
                continue
        methods.append(method)
    return tuple(methods) or (Method.LAGRANGE,)
