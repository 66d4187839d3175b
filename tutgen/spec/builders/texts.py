"""`title` and `statement`: the reader's texts of a problem."""

from __future__ import annotations

from tutgen.spec.builders.context import Context


def build_title(ctx: Context) -> str:
    """The problem's title, without the blank space around it."""
    return ctx.doc.title.strip()


def build_statement(ctx: Context) -> str | None:
    """The problem statement shown in the worked solution, if the spec gives one."""
    return ctx.doc.statement.strip() if ctx.doc.statement else None
