"""tutgen's own sentences (checks, remarks) with their maths typeset.

The engine words its checks and remarks in plain text with the spec's ASCII notation (``H q_ddot + C + G
- Q``, ``theta1``, ``n^2 J_m q6_dot^2 / 2``), which suits a terminal and the JSON output. A worked solution
prints the same sentence with typeset maths (``H\\ddot q + C + G - Q``, ``\\theta_1``): this module finds
the maths in such a sentence and returns it as parts (text, and maths in LaTeX) for the templates:

1. the engine's fixed notations (:data:`PHRASES`, longest first);
2. the system's own names: a coordinate, its rate ``<name>_dot`` and acceleration ``<name>_ddot``, a
   parameter (a quoted ``'theta'`` too), with a power ``^2`` after it;
3. other ASCII maths: a power ``n^2``, an indexed ``H_11``/``J_m``, a number in e-notation, a Greek name,
   and the one-letter names of the results (``H``, ``C``, ``G``, ``Q``, ``T``, ``U``, and the linear
   model's ``M``, ``D``, ``K``);
4. neighbouring maths joined with the operators and numbers between them (``n^2 J_m q6_dot^2 / 2`` is
   one formula), and a minus sign in front of one taken in.

Everything else stays text, which the templates escape.
"""

from __future__ import annotations

import re

from tutgen.render.printer import TexPrinter, format_number

Part = dict[str, str]

#: the fixed notations of the engine's sentences, as LaTeX
PHRASES = {
    "H q_ddot + C + G - Q": r"H\ddot q + C + G - Q",
    "H q_ddot + C + G": r"H\ddot q + C + G",
    "q_ddot = H^-1 (Q - C - G)": r"\ddot q = H^{-1}(Q - C - G)",
    "H = H^T": r"H = H^{T}",
    "H_dot - 2 C": r"\dot H - 2C",
    "det H = 0": r"\det H = 0",
    "C = 0": r"C = 0",
    "-dU/dq_i": r"-\partial U/\partial q_i",
    "-dD/dq_dot_i": r"-\partial D/\partial \dot q_i",
    "-m a_G": r"-m\mathbf a_G",
    "-(I_G alpha + omega x I_G omega)": r"-(I_G\alpha + \omega\times I_G\omega)",
    "dv_G/dq_dot_i": r"\partial \mathbf v_G/\partial \dot q_i",
    "domega/dq_dot_i": r"\partial \omega/\partial \dot q_i",
    "Q_i": "Q_i",
    "q_i": "q_i",
}

_GREEK = (
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi pi rho sigma tau upsilon phi chi "
    "psi omega Gamma Delta Theta Lambda Xi Pi Sigma Phi Psi Omega"
).split()
#: single letters that are also words of a sentence: never taken for maths on their own
_WORDS = {"a", "A", "I", "x", "at", "in", "is", "of", "on", "or", "to", "as", "be", "by", "it", "no", "so", "an"}
_JOIN = re.compile(r"^\s*(?:[-+*/=]|\d+(?:\.\d+)?)(?:\s*(?:[-+*/=]|\d+(?:\.\d+)?))*\s*$")
_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def engine_parts(sentence: str, tex: TexPrinter) -> list[Part]:
    """A sentence of tutgen's as parts: ``{"kind": "text"}`` and ``{"kind": "math", "tex": …}``."""
    spans: list[tuple[int, int, str]] = []

    def free(start: int, end: int) -> bool:
        return all(end <= s or start >= e for s, e, _ in spans)

    def add(start: int, end: int, latex: str) -> None:
        if free(start, end):
            spans.append((start, end, latex))

    for phrase in sorted(PHRASES, key=len, reverse=True):
        for m in re.finditer(re.escape(phrase), sentence):
            if _bounded(sentence, m.start(), m.end()):
                add(m.start(), m.end(), PHRASES[phrase])
    names = _system_names(tex)
    for m in re.finditer(r"'([A-Za-z_][A-Za-z0-9_]*)'|([A-Za-z_][A-Za-z0-9_]*)(?:\^(\d+))?", sentence):
        word = m.group(1) or m.group(2)
        if m.group(2) and _after_apostrophe(sentence, m.start()):
            continue  # the s of "Lagrange's", the t of "don't": English, even where s and t are names
        if word in names and (m.group(1) or word not in _WORDS):
            latex = names[word] + (f"^{{{m.group(3)}}}" if m.group(3) else "")
            add(m.start(), m.end(), latex)
    for pattern, make in _OTHER:
        for m in re.finditer(pattern, sentence):
            if _bounded(sentence, m.start(), m.end()):
                add(m.start(), m.end(), make(m))
    spans.sort()
    joined: list[tuple[int, int, str]] = []
    for start, end, latex in spans:
        if joined:
            p_start, p_end, p_latex = joined[-1]
            between = sentence[p_end:start]
            if between.strip() == "" or _JOIN.match(between):
                op = between.strip().replace("*", " ")
                joined[-1] = (p_start, end, f"{p_latex} {op} {latex}".replace("  ", " "))
                continue
        joined.append((start, end, latex))
    parts: list[Part] = []
    pos = 0
    for start, end, latex in joined:
        if start > 0 and sentence[start - 1] == "-" and (start == 1 or sentence[start - 2] in " ("):
            start, latex = start - 1, "-" + latex  # a sign in front belongs to the formula
        tail = re.match(r"\s*(?:/\s*\d+|=\s*-?\d+(?:\.\d+)?(?:e-?\d+)?)(?!\w|\.\d)", sentence[end:])
        if tail:  # "… / 2", "… = 0" closing a formula
            latex += " " + _number_tex(tail.group(0).strip())
            end += tail.end()
        if start > pos:
            parts.append({"kind": "text", "text": sentence[pos:start]})
        parts.append({"kind": "math", "tex": latex})
        pos = end
    if pos < len(sentence):
        parts.append({"kind": "text", "text": sentence[pos:]})
    return parts


def _after_apostrophe(sentence: str, start: int) -> bool:
    return start >= 2 and sentence[start - 1] in "'’" and sentence[start - 2].isalpha()


def _number_tex(text: str) -> str:
    return re.sub(r"\d+(?:\.\d+)?e-?\d+", lambda m: format_number(float(m.group(0))), text)


def _bounded(sentence: str, start: int, end: int) -> bool:
    """The match is a whole word or formula (not inside a longer name)."""
    before = sentence[start - 1] if start else " "
    after = sentence[end] if end < len(sentence) else " "
    return not (before.isalnum() or before == "_") and not (after.isalnum() or after == "_")


def _system_names(tex: TexPrinter) -> dict[str, str]:
    """Spec name -> LaTeX for the coordinates (with ``_dot`` and ``_ddot``) and parameters."""
    names: dict[str, str] = {}
    for symbol, latex in tex.names.items():
        names[str(symbol)] = latex
    for c in tex.system.coordinates:
        names[c.name] = c.latex
        names[f"{c.name}_dot"] = tex.names.get(c.qd, c.latex)
        names[f"{c.name}_ddot"] = tex.names.get(c.qdd, c.latex)
    return {k: v for k, v in names.items() if _TOKEN.fullmatch(k)}


def _indexed(m: re.Match[str]) -> str:
    return f"{_letter(m.group(1))}_{{{m.group(2)}}}"


def _letter(word: str) -> str:
    return f"\\{word}" if word in _GREEK else word


_OTHER = (
    (r"\b(H|J|I|C|G|Q|T|U)_([0-9]+(?:,[0-9]+)?|[a-z])\b", _indexed),
    (r"\b([A-Za-z])\^(\d+|T)\b", lambda m: f"{m.group(1)}^{{{m.group(2)}}}"),
    (r"\b\d+(?:\.\d+)?e-?\d+\b", lambda m: format_number(float(m.group(0)))),
    # the matrices (the linear model's M, D, K too), the energies and q, by one letter
    (r"\b[HCGQTUMDKq]\b(?!')", lambda m: m.group(0)),
    (r"\b(" + "|".join(_GREEK) + r")\b", lambda m: _letter(m.group(1))),
)
