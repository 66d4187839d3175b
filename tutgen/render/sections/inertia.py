"""The mass properties of each body: its parts' inertia about their centroids, moved to the body
frame's origin (parallel-axis theorem), the totals and the principal moments."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.steps import StepKind
from tutgen.render.blocks import (
    SolutionContext,
    as_number,
    boxed,
    chain,
    display,
    math,
    para,
    section,
    subheading,
    text,
)
from tutgen.spec.units import DIMENSIONS, Dimension

MASS, VOLUME, INERTIA, LENGTH = (DIMENSIONS[k] for k in ("mass", "volume", "inertia", "length"))


def quantity(c: SolutionContext, value: Any, dimension: Dimension) -> str:
    """A mass property as a number with its SI unit (``0.006132 \\ \\mathrm{kg\\,m^{2}}``, TexPrinter.unit)."""
    shown = as_number(c.num(value))
    return c.tex(shown) + c.tex.unit(shown, dimension)


def symbolic(c: SolutionContext, value: Any) -> list[str]:
    """A formula before its number (``m = \\tfrac{3}{8000} \\rho = 2.943 kg``); nothing for a plain number."""
    return [c.tex(value)] if sp.sympify(value).free_symbols else []


def mass_properties(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    if not d.has_step(StepKind.INERTIA) or not d.inertia:
        return None
    sec = section(
        "Mass properties",
        "Each part's inertia about its own centroid, then moved to the body "
        "frame's origin by the parallel-axis theorem $J_O = J_G + m(|d|^2 E - d d^T)$.",
    )
    blocks = sec["blocks"]
    for bi, principal in zip(d.inertia, d.principal, strict=True):
        if s.coordinates and all(p.shape.value == "point" for p in bi.parts) and len(bi.parts) <= 1:
            continue  # a lone point mass: its inertia is m r^2 in the energies, nothing to tabulate
        for p in bi.parts:
            blocks.append(subheading(f"{bi.name} / {p.name} ({p.shape.value.replace('_', ' ')})"))
            chains = [chain("m", *symbolic(c, p.mass), quantity(c, p.mass, MASS))]  # "m = m" says nothing: left out
            if p.volume is not None:
                chains.insert(0, chain("V", *symbolic(c, p.volume), quantity(c, p.volume, VOLUME)))
            blocks += [display(ch) for ch in chains if ch]
            blocks.append(para(text("About its centroid:")))
            blocks.append(display(f"J_G = {quantity(c, p.inertia_centroid, INERTIA)}"))
            if any(x != 0 for x in p.centroid):
                blocks.append(
                    para(
                        text("Centroid at "),
                        math(f"d = {quantity(c, p.centroid.T, LENGTH)}"),
                        text("; distances to the axes "),
                        math(f"({', '.join(tex(as_number(num(x))) for x in p.axis_distances)})"),
                        text(":"),
                    )
                )
                blocks.append(display(f"J_O = {quantity(c, p.inertia_origin, INERTIA)}"))
        blocks.append(subheading(f"{bi.name}, total mass and inertia about the origin:"))
        total = [chain("m", quantity(c, bi.mass, MASS)), f"J_O = {quantity(c, bi.inertia_origin, INERTIA)}"]
        blocks.append(boxed(",\\quad ".join(t for t in total if t)))
        if principal is not None:
            moments = ",\\ ".join(tex(sp.Float(x)) for x in principal.moments)
            blocks.append(para(text("Principal moments: "), math(moments), text(".")))
    return sec if blocks else None
