"""`ask`: what the worked solution derives."""

from __future__ import annotations

from tutgen.model.system import OPT_IN_ASK, Ask
from tutgen.spec.builders.context import Context


def build_ask(ctx: Context, dynamic: bool) -> frozenset[Ask]:
    """What to derive: the items of `ask`, or by default everything that applies (only the inertia of a
    spec that has nothing that moves, ``dynamic`` False).

    An item that does not apply is a problem at its place: anything but `inertia` without coordinates
    (nothing moves), `inertia` without bodies (a system given by its energy), `simulation` without a
    `simulate` section that gives every coordinate its initial value; so is an `analysis` section when
    `ask` names neither `equilibria` nor `linearization`. `simulation` (it runs an integration,
    docs/simulate.md) and the analysis items are never asked by default.
    """
    if ctx.doc.ask is not None:
        # coordinates set aside for a shape error (already reported) may be what is missing: no cascade
        unsure = bool(ctx.dropped_keys & {"coordinates", "arm", "joints"})
        asked: set[Ask] = set()
        for i, item in enumerate(ctx.doc.ask):
            a = Ask(item)
            if a is not Ask.INERTIA and not dynamic and not unsure:
                ctx.error(
                    ("ask", i),
                    f"`{item}` needs generalized coordinates, and the spec has no `coordinates`; "
                    "expected `inertia` only, or coordinates that say what moves",
                )
            elif a is Ask.INERTIA and ctx.doc.energy is not None and not ctx.doc.bodies:
                ctx.error(
                    ("ask", i),
                    "`inertia` needs bodies, and the spec gives its energy (`energy`) instead; expected "
                    "the bodies, or no `inertia` in `ask`",
                )
            elif a is Ask.SIMULATION and (missing := _without_initial_value(ctx)) is not None:
                ctx.error(("ask", i), missing[0], missing[1])
            elif a is Ask.MOMENTUM and ctx.doc.energy is not None and not ctx.doc.bodies:
                ctx.error(
                    ("ask", i),
                    "`momentum` needs bodies, and the spec gives its energy (`energy`) instead; expected "
                    "the bodies, or no `momentum` in `ask`",
                )
            elif a is Ask.STEADY_MOTION and (refused := _steady_refused(ctx)) is not None:
                ctx.error(("ask", i), refused[0], refused[1])
            else:
                asked.add(a)
        if ctx.doc.analysis is not None and ctx.doc.analysis.steady is not None and Ask.STEADY_MOTION not in asked:
            ctx.error(
                ("analysis", "steady"),
                "`analysis.steady` gives the cyclic coordinates and rates of `steady_motion`, and `ask` does not "
                "name it",
                "add `steady_motion` to `ask`, or remove `steady`",
                key=True,
            )
        elif (
            ctx.doc.analysis is not None
            and dynamic
            and not asked
            & {
                Ask.EQUILIBRIA,
                Ask.LINEARIZATION,
                Ask.STEADY_MOTION,
            }
        ):
            ctx.error(
                ("analysis",),
                "`analysis` gives the equilibrium and inputs of `equilibria` and `linearization`, and `ask` "
                "names neither",
                "add `linearization` (or `equilibria`) to `ask`, or remove `analysis`",
                key=True,
            )
        return frozenset(asked)
    if not dynamic:
        return frozenset({Ask.INERTIA})
    everything = set(Ask) - OPT_IN_ASK  # the integration and the analysis after the equations of motion: by name
    if not ctx.doc.bodies:
        everything.discard(Ask.INERTIA)
    return frozenset(everything)


def _steady_refused(ctx: Context) -> tuple[str, str] | None:
    """Why `ask: [steady_motion]` does not apply (message, hint), or None. Its rows are those of the
    unconstrained H q_ddot + C + G = Q, and a cyclic coordinate is one absent from H, G and Q: with
    constraints the steady state must also satisfy them and their multipliers enter every row, and a
    prescribed coordinate is not a degree of freedom whose rate the analysis could hold."""
    doc = ctx.doc
    loops = [name for name, j in (doc.joints or {}).items() if j.closes_loop]
    if doc.constraints or loops:
        why = "`constraints`" if doc.constraints else f"the loop-closing joint '{loops[0]}'"
        return (
            f"`steady_motion` applies to an unconstrained system, and this spec has {why}: its steady states "
            "would have to satisfy the constraints too, and the constraint forces enter every equation of motion",
            "remove `steady_motion` from `ask` (the reduced equations of a constrained system are its "
            "`equations_of_motion`)",
        )
    driven = [name for name, c in (doc.coordinates or {}).items() if c.prescribed is not None or c.rate is not None]
    if driven:
        name = driven[0]
        return (
            f"`steady_motion` holds the rate of a free cyclic coordinate, and '{name}' is prescribed: it is no "
            "degree of freedom, so there is no rate left to hold",
            f"drop `prescribed`/`rate` of '{name}' and give its rate as `analysis: {{steady: {{{name}: ...}}}}`, "
            "or ask for `equilibria` of the driven system",
        )
    return None


def _without_initial_value(ctx: Context) -> tuple[str, str] | None:
    """Why `ask: [simulation]` cannot run (message, hint), or None: the plots of the worked solution
    are a run of the spec's own `simulate` section, so it must hold every coordinate's `q0`."""
    sim = ctx.doc.simulate
    if sim is None:
        return (
            "`simulation` needs the spec's `simulate` section, and the spec has none; expected the initial "
            "values to start from",
            "add e.g. `simulate: {t: [0, 10], q0: {" + ", ".join(f"{c}: 0.5" for c in ctx.coords) + "}}`",
        )
    missing = [c for c in ctx.coords if c not in sim.q0]
    if ctx.doc.independent_coordinates and (
        ctx.doc.constraints or any(j.closes_loop for j in (ctx.doc.joints or {}).values())
    ):
        # a constrained spec: the run solves the dependent coordinates from the constraints (a coordinate
        # only velocity constraints tie still needs a value: the run says so, at the `simulate` section)
        missing = [c for c in missing if c in ctx.doc.independent_coordinates]
    if missing:
        return (
            f"`simulation` needs every coordinate's initial value in `simulate.q0`; missing: {', '.join(missing)}",
            "add e.g. `q0: {" + ", ".join(f"{c}: 0.5" for c in missing) + "}` to `simulate`",
        )
    return None
