"""`given`: what a question states besides its statement and data."""

from __future__ import annotations

from tutgen.model.system import Given
from tutgen.spec.builders.context import Context


def build_given(ctx: Context) -> Given:
    """``given: {coordinates: false}`` leaves the generalized coordinates out of the question sheet, for the
    student to propose (the worked solution still states them). The shape (a true/false value) is checked
    by the schema."""
    spec = ctx.doc.given
    return Given() if spec is None else Given(coordinates=spec.coordinates)
