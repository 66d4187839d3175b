"""Text for the reader that may carry inline maths: a spec's ``statement`` and ``description``s.

A spec writes maths between dollars in its own expression grammar (``$T = (3/2 + cos(theta2))
theta1_dot^2$``); validation parses each span through the whitelist parser and keeps the text as a
:class:`RichText`: a ``str`` (the text exactly as written, so every consumer that wants plain text keeps
working) that also knows its parts, plain text and :class:`MathSpan` in order. Renderers typeset the
spans with the same printer as the results and escape the text between them; nothing of it reaches TeX
or Markdown raw. ``\\$`` in the spec is a literal dollar (kept as ``$`` in the text parts).

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> text = RichText("the cart at $x$", ("the cart at ", MathSpan("x", (x,), ())))
>>> str(text), text.parts[1].terms
('the cart at $x$', (x,))
>>> text.upper()  # still a str
'THE CART AT $X$'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

#: the relations a span may chain its expressions with, as written in the spec
RELATIONS = ("=", "!=", "<=", ">=", "<", ">")


@dataclass(frozen=True)
class MathSpan:
    """One ``$…$`` span: expressions chained by relations (``T = a + b``, ``0 < theta < pi``).

    ``terms`` has one more element than ``relations``; each relation is one of :data:`RELATIONS`.
    ``source`` is the span's text between the dollars, as written."""

    source: str
    terms: tuple[sp.Basic, ...]
    relations: tuple[str, ...] = ()


@dataclass(frozen=True)
class Placeholder:
    """``{m}`` in a statement: the value of parameter ``name`` with its unit, filled in when the text is
    printed, so that each variant of a tutorial sheet quotes its own number (``{{`` and ``}}`` are literal
    braces)."""

    name: str


class RichText(str):
    """A reader's text: the ``str`` as written, with its parts (``str``, :class:`MathSpan` and, in a
    statement, :class:`Placeholder`) in order."""

    parts: tuple[str | MathSpan | Placeholder, ...]

    def __new__(cls, raw: str, parts: tuple[str | MathSpan | Placeholder, ...] | None = None) -> RichText:
        self = super().__new__(cls, raw)
        self.parts = parts if parts is not None else ((raw,) if raw else ())
        return self

    def __reduce__(self) -> tuple[Any, ...]:  # sheet workers pickle systems
        return (RichText, (str(self), self.parts))

    @property
    def has_math(self) -> bool:
        return any(isinstance(part, MathSpan) for part in self.parts)
