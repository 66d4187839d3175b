"""`conventions`: the notational choices of a worked solution."""

from __future__ import annotations

from tutgen.model.system import Ask, ChristoffelConvention, Conventions
from tutgen.spec.builders.context import Context


def build_conventions(ctx: Context, ask: frozenset[Ask]) -> Conventions:
    """``conventions: {christoffel: asada_slotine | first_kind | both}`` (the shape is the schema's). A
    convention for symbols that ``ask`` does not derive is a problem at its key: it would be silently
    ignored, and the instructor most likely meant to ask for them."""
    spec = ctx.doc.conventions
    if spec is None:
        return Conventions()
    christoffel = ChristoffelConvention(spec.christoffel)
    if "christoffel" in spec.model_fields_set and Ask.CHRISTOFFEL not in ask:
        ctx.error(
            ("conventions", "christoffel"),
            "`conventions.christoffel` chooses how the Christoffel symbols are printed, but `ask` does not ask "
            "for them; expected `christoffel` in `ask`, or no `conventions.christoffel`",
        )
    return Conventions(christoffel=christoffel)
