"""`figure`: how the problem's schematic is drawn, and the instructor's own picture (docs/figures.md)."""

from __future__ import annotations

from tutgen.model.figure import FigureConfig
from tutgen.spec.builders.context import Context
from tutgen.spec.figure import validate_figure


def build_figure(ctx: Context) -> FigureConfig | None:
    """The drawing configuration (``at`` poses of the coordinates, ``sizes`` of symbolic lengths) and the
    checked ``file``; after the coordinates and parameters, whose names it uses."""
    return validate_figure(ctx.doc.figure, ctx.smap, ctx.coords, ctx.params, ctx.errors)
