"""`title`, `statement` and the descriptions: the reader's texts of a problem, with their `$…$` maths."""

from __future__ import annotations

from tutgen.model.text import RichText
from tutgen.spec.builders.context import Context
from tutgen.spec.loader import KeyPath
from tutgen.spec.richtext import read_texts


def build_title(ctx: Context) -> str:
    """The problem's title, without the blank space around it."""
    return ctx.doc.title.strip()


def build_question_title(ctx: Context) -> str | None:
    """The title on a tutorial's question sheet, when the spec gives one that differs from ``title`` (a
    solution's title may name what the question asks the student to find)."""
    return ctx.doc.question_title.strip() if ctx.doc.question_title else None


def build_statement(ctx: Context) -> str | None:
    """The problem statement shown in the worked solution, if the spec gives one."""
    return ctx.doc.statement.strip() if ctx.doc.statement else None


def build_texts(ctx: Context) -> dict[KeyPath, RichText]:
    """Every text of the spec read with its maths (:mod:`tutgen.spec.richtext`), by key path; built after
    the parameters and coordinates, whose names (and rates) the maths may use."""
    texts, errors = read_texts(ctx.data, ctx.smap, ctx.symbols(coords=True, rates=True, accel=True), ctx.params)
    ctx.errors += errors
    return texts
