"""Answers as students write them: Unicode maths and juxtaposition, rewritten into the spec grammar.

A student copies ``0.2109 θ̇₁² + m·g·l cos θ₁`` from a worked solution, or types ``θ1'``-free text on a
phone keyboard. :func:`ascii_answer` rewrites such text into the ASCII grammar of the whitelist
parser (:mod:`tutgen.spec.expr`), which then reads it as always: the result is text, never code.

- Greek letters are their names (``θ`` ``theta``, ``ω`` ``omega``, ``ϕ`` ``phi``), subscript digits are
  digits (``θ₁`` ``theta1``), a combining dot or diaeresis above a name is a rate (``θ̇₁``
  ``theta1_dot``, ``ẍ`` ``x_ddot``), superscripts are powers (``θ̇²`` ``theta_dot**2``, ``⁻¹``).
- ``·`` ``⋅`` ``×`` are ``*``; ``−`` (minus sign) and ``–`` are ``-``; ``÷`` is ``/``; ``√`` is ``sqrt``;
  ``½ ⅓ ¼ ¾ ⅔`` are fractions; ``π`` is ``pi``; non-breaking spaces are spaces.
- Juxtaposition is a product (``2 m g`` ``2*m*g``, ``2θ`` ``2*theta``), and a function written without
  parentheses takes the one factor after it (``cos θ₁ θ̇₂`` ``cos(theta1)*theta2_dot``,
  ``sin²θ`` ``sin(theta)**2``, ``cos 2θ`` ``cos(2*theta)``), as a textbook prints them.

Every character of the rewritten text remembers the character of the answer it came from, so a parse
error still points at the right place in the answers file (:attr:`Rewritten.source_offset`).
"""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass

from tutgen.spec.expr import FUNCTIONS

__all__ = ["GREEK", "Rewritten", "ascii_answer"]

#: Greek letters and the names they are read as (both forms of theta, phi, epsilon).
GREEK = {
    "α": "alpha", "β": "beta", "γ": "gamma", "δ": "delta", "ε": "epsilon", "ϵ": "epsilon", "ζ": "zeta",
    "η": "eta", "θ": "theta", "ϑ": "theta", "ι": "iota", "κ": "kappa", "λ": "lambda", "μ": "mu", "µ": "mu",
    "ν": "nu", "ξ": "xi", "ρ": "rho", "σ": "sigma", "τ": "tau", "υ": "upsilon", "φ": "phi", "ϕ": "phi",
    "χ": "chi", "ψ": "psi", "ω": "omega", "Γ": "Gamma", "Δ": "Delta", "Θ": "Theta", "Λ": "Lambda",
    "Ξ": "Xi", "Π": "Pi", "Σ": "Sigma", "Φ": "Phi", "Ψ": "Psi", "Ω": "Omega",
}  # fmt: skip
_SUBSCRIPTS = dict(zip("₀₁₂₃₄₅₆₇₈₉", "0123456789", strict=True))
_SUPERSCRIPTS = dict(zip("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+", strict=True))
_OPERATORS = {"·": "*", "⋅": "*", "×": "*", "∗": "*", "−": "-", "–": "-", "÷": "/"}
_FRACTIONS = {"½": "(1/2)", "⅓": "(1/3)", "¼": "(1/4)", "¾": "(3/4)", "⅔": "(2/3)"}
_SPACES = frozenset(" \t\r\n\f\v\u00a0\u2009\u202f\u2002\u2003")
_DOT, _DDOT = "\u0307", "\u0308"  # combining dot above, combining diaeresis
_NUMBER = re.compile(r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")


@dataclass(frozen=True)
class _Token:
    kind: str  # name, number, open, close, pow, op, other
    text: str
    at: int  # offset in the answer as written


@dataclass(frozen=True)
class Rewritten:
    """The answer in the spec grammar, and for each of its characters the offset it came from."""

    text: str
    origins: tuple[int, ...]
    length: int  # of the answer as written

    def source_offset(self, offset: int) -> int:
        """The offset in the answer as written of the rewritten text's character at ``offset``."""
        if 0 <= offset < len(self.origins):
            return self.origins[offset]
        return self.length


def _is_name_start(ch: str) -> bool:
    return (ch.isascii() and (ch.isalpha() or ch == "_")) or ch in GREEK


def _is_name_part(ch: str) -> bool:
    return _is_name_start(ch) or (ch.isascii() and ch.isdigit()) or ch in _SUBSCRIPTS or ch in (_DOT, _DDOT)


def _tokens(chars: list[tuple[str, int]]) -> list[_Token]:
    """The answer (NFD characters with their offsets) as tokens, Unicode already read as ASCII."""
    out: list[_Token] = []
    text = "".join(c for c, _ in chars)
    i, n = 0, len(chars)
    while i < n:
        ch, at = chars[i]
        if ch in _SPACES:
            i += 1
            continue
        if (ch.isascii() and ch.isdigit()) or (ch == "." and i + 1 < n and text[i + 1].isdigit()):
            match = _NUMBER.match(text, i)
            assert match is not None
            out.append(_Token("number", match.group(), at))
            i = match.end()
            continue
        if _is_name_start(ch):
            parts: list[str] = []
            dots = 0
            while i < n and _is_name_part(chars[i][0]):
                c = chars[i][0]
                if c == _DOT:
                    dots += 1
                elif c == _DDOT:
                    dots += 2
                else:
                    parts.append(GREEK.get(c) or _SUBSCRIPTS.get(c) or c)
                i += 1
            name = "".join(parts)
            if dots == 1:
                name += "_dot"
            elif dots >= 2:
                name += "_ddot"
            out.append(_Token("name", name, at))
            continue
        if ch in _SUPERSCRIPTS:
            digits = ""
            while i < n and chars[i][0] in _SUPERSCRIPTS:
                digits += _SUPERSCRIPTS[chars[i][0]]
                i += 1
            out.append(_Token("pow", f"**({digits})" if not digits.isdigit() else f"**{digits}", at))
            continue
        i += 1
        if ch == "*" and i < n and chars[i][0] == "*":
            out.append(_Token("op", "**", at))
            i += 1
        elif ch in _FRACTIONS:
            out.append(_Token("number", _FRACTIONS[ch], at))
        elif ch == "√":
            out.append(_Token("name", "sqrt", at))
        elif ch == "π":
            out.append(_Token("name", "pi", at))
        elif ch == "(":
            out.append(_Token("open", "(", at))
        elif ch == ")":
            out.append(_Token("close", ")", at))
        elif ch in _OPERATORS or ch in "+-*/^,=":
            out.append(_Token("op", _OPERATORS.get(ch, ch), at))
        else:
            out.append(_Token("other", ch, at))
    return out


def _is_function(tok: _Token) -> bool:
    return tok.kind == "name" and tok.text in FUNCTIONS


def _ends_operand(tok: _Token) -> bool:
    return tok.kind in ("number", "close", "pow") or (tok.kind == "name" and not _is_function(tok))


def _starts_operand(tok: _Token) -> bool:
    return tok.kind in ("number", "name", "open")


def _with_calls(tokens: list[_Token]) -> list[_Token]:
    """A function followed by a factor instead of ``(``: its argument in parentheses (``cos θ`` is
    ``cos(θ)``; ``sin²θ`` is ``sin(θ)**2``; ``cos 2θ`` is ``cos(2*θ)``; ``cos θ²`` is ``cos(θ**2)``)."""
    out: list[_Token] = []
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        out.append(tok)
        i += 1
        if not _is_function(tok):
            continue
        power = tokens[i] if i < len(tokens) and tokens[i].kind == "pow" else None
        j = i + (power is not None)
        if j >= len(tokens) or tokens[j].kind not in ("name", "number") or _is_function(tokens[j]):
            continue
        argument = [tokens[j]]
        j += 1
        if (
            argument[0].kind == "number"
            and j < len(tokens)
            and tokens[j].kind == "name"
            and not _is_function(tokens[j])
        ):
            argument.append(tokens[j])  # cos 2θ
            j += 1
        if j < len(tokens) and tokens[j].kind == "pow":
            argument.append(tokens[j])  # cos θ²
            j += 1
        out.append(_Token("open", "(", argument[0].at))
        out += argument
        out.append(_Token("close", ")", argument[-1].at))
        if power is not None:
            out.append(power)
        i = j
    return out


def _with_products(tokens: list[_Token]) -> list[_Token]:
    """A ``*`` between two factors written side by side (``2 m g``, ``2θ``, ``(a)(b)``), never between
    a function and its parenthesis."""
    out: list[_Token] = []
    for tok in tokens:
        if out and _ends_operand(out[-1]) and _starts_operand(tok):
            out.append(_Token("op", "*", tok.at))
        out.append(tok)
    return out


def ascii_answer(text: str) -> Rewritten:
    """``text`` in the ASCII spec grammar (see the module's docstring), with the offsets it came from."""
    chars = [(c, i) for i, ch in enumerate(text) for c in unicodedata.normalize("NFD", ch)]
    tokens = _with_products(_with_calls(_tokens(chars)))
    pieces: list[str] = []
    origins: list[int] = []
    for k, tok in enumerate(tokens):
        if k and tok.kind in ("name", "number") and tokens[k - 1].kind in ("name", "number"):
            pieces.append(" ")  # never glue two words into one (only if no product was put between)
            origins.append(tok.at)
        pieces.append(tok.text)
        origins += [tok.at] * len(tok.text)
    return Rewritten("".join(pieces), tuple(origins), len(text))
