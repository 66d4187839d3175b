"""`springs` and `dampers`: linear elements between two points, or along an `extension` of the coordinates."""

from __future__ import annotations

import difflib

import sympy as sp

from tutgen.model.system import GROUND, Damper, Endpoint, Spring
from tutgen.spec import schema as S
from tutgen.spec.builders.context import Context
from tutgen.spec.loader import KeyPath
from tutgen.spec.places import where


def _endpoints(
    ctx: Context, path: KeyPath, between: list[S.EndpointSpec] | None, bodies: set[str]
) -> tuple[Endpoint, Endpoint] | None:
    """The two attachment points of `between`; None if not given or bad."""
    if between is None:
        return None
    out = []
    known = sorted(bodies | {GROUND})
    for i, ep in enumerate(between):
        at = ctx.vector((*path, i, "at"), ep.at, ctx.symbols(), "length")
        if ep.body not in known:
            close = difflib.get_close_matches(ep.body, known, n=1)
            epath = (*path, i, "body") if isinstance(ctx.written((*path, i)), dict) else (*path, i)
            ctx.error(
                epath,
                f"{where(path[:2])} refers to unknown body '{ep.body}' (known: {', '.join(known)})",
                f"did you mean '{close[0]}'?" if close else None,
            )
            continue
        if at is not None:
            out.append(Endpoint(ep.body, at))
    if len(out) != 2:
        return None
    return (out[0], out[1])


def build_elements(ctx: Context, bodies: set[str]) -> tuple[list[Spring], list[Damper]]:
    """The springs and dampers, in spec order; ``bodies`` are the declared bodies."""
    springs: list[Spring] = []
    dampers: list[Damper] = []
    kin_names = ctx.symbols(coords=True)
    consts = ctx.symbols()
    for section, specs in (("springs", ctx.doc.springs), ("dampers", ctx.doc.dampers)):
        what = section[:-1]
        for name, spec in specs.items():
            path: KeyPath = (section, name)
            ctx.check_name(path, name, what)
            ok = True
            if spec.between is not None and spec.extension is not None:
                ctx.error(
                    (*path, "extension"),
                    f"{what} '{name}' gives both `between` and `extension`; expected one of them",
                    key=True,
                )
                ok = False
            elif spec.between is None and spec.extension is None:
                ctx.error(
                    path,
                    f"{what} '{name}' needs `between` (two attachment points) or `extension` "
                    "(an expression of the coordinates); found neither",
                    key=True,
                )
                ok = False
            between = _endpoints(ctx, (*path, "between"), spec.between, bodies)
            ok &= spec.between is None or between is not None
            ext = None
            if spec.extension is not None:
                ext = ctx.expr((*path, "extension"), spec.extension, kin_names)
                ok &= ext is not None
            # with `between`, the elongation is a length and the units of k and c follow
            physical = between is not None
            if section == "springs":
                k = ctx.expr(
                    (*path, "stiffness"), spec.stiffness, consts, "stiffness" if physical else None, "a stiffness"
                )
                l0 = (
                    ctx.expr((*path, "free_length"), spec.free_length, consts, "length")
                    if spec.free_length is not None
                    else sp.Integer(0)
                )
                if spec.free_length is not None and spec.extension is not None and spec.between is None:
                    ctx.error(
                        (*path, "free_length"),
                        f"spring '{name}' gives `free_length` with `extension`; `free_length` goes with "
                        "`between`: with `extension`, write the elongation itself (e.g. 'x - L0')",
                        key=True,
                    )
                    ok = False
                if ok and k is not None and l0 is not None:
                    springs.append(Spring(name, k, l0, between, ext, ctx.smap.key_location(path)))
            else:
                c = ctx.expr(
                    (*path, "coefficient"),
                    spec.coefficient,
                    consts,
                    "damping" if physical else None,
                    "a damping coefficient",
                )
                if ok and c is not None:
                    dampers.append(Damper(name, c, between, ext, ctx.smap.key_location(path)))
    return springs, dampers
