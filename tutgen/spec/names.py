"""How a spec name is typeset when the spec gives no ``latex:``: ``Ixx1`` is I_{xx,1}, never I·x·x₁.

sympy's own rule (``sp.latex(Symbol("Ixx1"))`` is ``Ixx_{1}``) prints a name of several letters as a
product of letters. A reader of a mechanics text expects one letter with subscripts, and Greek names as
Greek letters. The rule, applied to the parts of the name between underscores (docs/spec-format.md,
"Display names"):

1. The first part is the symbol: a Greek letter's name (``theta``, ``Omega``, ``varphi``) is that
   letter; one letter is itself; a Greek name followed by one or two letters is the Greek letter with
   those letters as a subscript (``mus`` μ_s, ``omegan`` ω_n); two or three letters are the first
   letter with the rest as a subscript (``Ixx`` I_{xx}, ``Jz`` J_z, ``lc`` l_c); capitals only
   (``EI``) and longer words (``mass``) are one italic word. Digits that end the first part are one
   more subscript (``m1`` m_1, ``Ixx1`` I_{xx,1}, ``theta12`` θ_{12}).
2. Each further part (after an underscore) is one more subscript, a Greek name again a Greek letter
   and digits that end it again a subscript of their own: ``l_AB`` l_{AB}, ``theta_m`` θ_m,
   ``k_theta`` k_{θ}, ``I_zz3`` I_{zz,3}.
3. Several subscripts are separated by commas; a subscript of one character has no braces.

A name that fits none of this (digits inside letters, empty parts as in ``a__b``) is printed as written,
in one italic word. A coordinate's rates (``theta1_dot``) are the renderer's: it dots the coordinate's
display name. Other names ending in ``_dot`` or ``_ddot`` (free symbols of a text's maths, such as the
generic ``q_dot``) are dotted here the same way, on the base letter: ``\\dot{q}``, ``\\ddot{\\theta}_1``.

Examples
--------
>>> [default_latex(n) for n in ("m1", "Ixx1", "Jz3", "theta_m", "theta1", "l_AB", "rho", "Omega")]
['m_1', 'I_{xx,1}', 'J_{z,3}', '\\\\theta_m', '\\\\theta_1', 'l_{AB}', '\\\\rho', '\\\\Omega']
"""

from __future__ import annotations

import re

__all__ = ["GREEK", "default_latex"]

_LOWER_GREEK = (
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi omicron pi rho sigma tau "
    "upsilon phi chi psi omega"
).split()
#: Capitals that TeX has a command for; the others look like Latin capitals (Alpha is A).
_TEX_CAPITALS = frozenset("Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi Psi Omega".split())
_LATIN_CAPITALS = dict(
    zip(
        "Alpha Beta Epsilon Zeta Eta Iota Kappa Mu Nu Omicron Rho Tau Chi".split(),
        "A B E Z H I K M N O P T X".split(),
        strict=True,
    )
)

#: Greek letter names (as a spec may write them) -> their LaTeX. ``lamda`` is sympy's spelling, as
#: ``lambda`` is a Python keyword and cannot name a parameter on its own.
GREEK: dict[str, str] = {name: f"\\{name}" for name in _LOWER_GREEK if name != "omicron"}
GREEK.update({"omicron": "o", "lamda": r"\lambda", "Lamda": r"\Lambda"})
GREEK.update({f"var{name}": f"\\var{name}" for name in ("epsilon", "theta", "pi", "rho", "sigma", "phi")})
GREEK.update({name: f"\\{name}" for name in sorted(_TEX_CAPITALS)})
GREEK.update(_LATIN_CAPITALS)

# the longest Greek names first, so that "theta" is found before "eta" and "upsilon" before "psi"
_GREEK_BY_LENGTH = sorted(GREEK, key=lambda name: (-len(name), name))
_HEAD = re.compile(r"([A-Za-z]+)([0-9]*)")
_PART = re.compile(r"[A-Za-z0-9]+")
#: Most letters after a Greek name or a first letter that still read as its subscript (I_{xx}, ω_n):
#: ``Fmax`` or ``mass`` are words, not a letter with a three-letter subscript.
_MAX_SUBSCRIPT_LETTERS = 2


def _greek_prefix(letters: str) -> tuple[str, str] | None:
    """(LaTeX of a Greek name that starts ``letters``, the one or two letters after it), or None."""
    for name in _GREEK_BY_LENGTH:
        rest = letters[len(name) :]
        if letters.startswith(name) and 1 <= len(rest) <= _MAX_SUBSCRIPT_LETTERS:
            return GREEK[name], rest
    return None


def _symbol(letters: str) -> tuple[str, list[str]]:
    """The base symbol of a run of letters and the subscripts it brings."""
    if letters in GREEK:
        return GREEK[letters], []
    if len(letters) == 1:
        return letters, []
    prefix = _greek_prefix(letters)
    if prefix is not None:
        return prefix[0], [prefix[1]]
    if letters.isupper():
        return f"\\mathit{{{letters}}}", []
    if len(letters) <= 1 + _MAX_SUBSCRIPT_LETTERS:
        return letters[0], [letters[1:]]
    return f"\\mathit{{{letters}}}", []


def _subscripts(part: str) -> list[str]:
    """The subscripts of one part written after an underscore: a Greek name is its letter, digits that
    end letters are one more subscript (``zz3``: zz, 3), anything else is as written."""
    split = _HEAD.fullmatch(part)
    if split is None or not split[2]:
        return [GREEK.get(part, part)]
    return [GREEK.get(split[1], split[1]), split[2]]


def default_latex(name: str) -> str:
    """The LaTeX a spec name is typeset as when the spec gives no ``latex:`` (see the module docstring).

    The result is always valid maths-mode LaTeX made of letters, digits, ``_``, braces, commas and the
    commands of :data:`GREEK` and ``\\mathit``.
    """
    for suffix, accent in (("_ddot", r"\ddot"), ("_dot", r"\dot")):
        if name.endswith(suffix) and len(name) > len(suffix):
            return _dotted(default_latex(name[: -len(suffix)]), accent)
    parts = name.split("_")
    head = _HEAD.fullmatch(parts[0])
    if head is None or not all(_PART.fullmatch(p) for p in parts[1:]):
        return _verbatim(name)
    base, subscripts = _symbol(head[1])
    if head[2]:
        subscripts.append(head[2])
    for part in parts[1:]:
        subscripts += _subscripts(part)
    if not subscripts:
        return base
    sub = ",".join(subscripts)
    return f"{base}_{sub}" if len(sub) == 1 else f"{base}_{{{sub}}}"


def _dotted(latex: str, accent: str) -> str:
    """The accent on the base symbol, not on its subscript (as the renderer dots a coordinate)."""
    if latex.startswith("\\mathit"):
        return f"{accent}{{{latex}}}"
    base, sep, sub = latex.partition("_")
    return f"{accent}{{{base}}}{sep}{sub}"


def _verbatim(name: str) -> str:
    """A name that the rule does not cover, as written in one italic word (underscores shown)."""
    return "\\mathit{" + name.replace("_", r"\_") + "}"
