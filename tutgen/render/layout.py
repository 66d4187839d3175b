"""Laying out displayed maths on the page: how wide a formula is when typeset, and where a long one breaks.

Nothing here is ever scaled to fit. A display that is wider than the line is broken the way a person (or
amsmath's ``split``/``multlined``) breaks it by hand, decided by the typeset WIDTH of each line, estimated
from the LaTeX (the widths of Computer Modern at 11 pt; see :func:`tex_width`), against
:data:`LINE_WIDTH_PT` (a margin inside the text width :data:`TEXT_WIDTH`):

1. a list of equations ``a = …,\\quad b = …`` that does not fit on one line is set one equation a line,
   every relation sign aligned;
2. an equation too wide for its line breaks before a top-level ``+`` or ``−`` of its right-hand side;
   continuation lines start a ``\\quad`` right of the relation sign (``&\\quad + …``);
3. a single term too wide even for a line of its own breaks inside its largest bracket, which then becomes
   a ``\\bigl( … \\bigr)`` pair that may span lines (``\\left``/``\\right`` cannot), the inner lines
   indented one more ``\\quad``;
4. a matrix or vector too wide for the line is given entry by entry (``H_{11} = …``; only the upper
   triangle of a symmetric matrix), each entry then laid out by 2 and 3;
5. an equation whose left-hand side is wider than a third of the line starts with it alone and puts
   ``= …`` on the next line.

The result is a list of *rows* of one alignment: each row holds exactly one ``&`` (the alignment point,
before the relation sign), ready for ``align*`` in LaTeX (which may break across pages under
``\\allowdisplaybreaks``) or ``aligned`` in Markdown, so both formats show the same lines.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

#: the text width of the documents tutgen writes (A4, 2.2 cm margins) in TeX points
TEXT_WIDTH = 471.0
#: the widest a displayed line is made; the rest is a margin for the error of the width estimate
LINE_WIDTH_PT = 440.0
#: a boxed display loses its rule and padding (2 × (\fboxsep + \fboxrule)) and is kept a little narrower
BOXED_WIDTH_PT = 420.0

_EM = 10.95  # 11pt article: the maths fonts' em, in pt
_MU = _EM / 18

# glyph widths at 11 pt (Computer Modern: cmmi10/cmr10 × 1.095), a fair average per class
_W_LOWER = 5.5
_W_UPPER = 8.0
_W_DIGIT = 5.48
_W_GREEK = 6.2
_W_ROMAN = 5.3  # upright letters of \sin, \mathrm, \text
_BIN = 8.52 + 8 * _MU  # + or − with \medmuskip on each side
_REL = 8.52 + 10 * _MU  # = with \thickmuskip on each side
_WIDE = {"m": 9.6, "w": 7.9, "M": 10.6, "W": 11.3, "l": 3.3, "i": 3.8, "j": 4.5, "t": 4.0, "r": 4.9, "f": 5.4}
_SPACES = {
    "quad": _EM,
    "qquad": 2 * _EM,
    ",": 3 * _MU,
    ":": 4 * _MU,
    ";": 5 * _MU,
    "!": -3 * _MU,
    " ": 3.65,
}
_OPERATORS = {"sin", "cos", "tan", "cot", "sec", "csc", "det", "log", "exp", "ln", "max", "min"}
_ZERO = {
    "hline",
    "left",
    "right",
    "textstyle",
    "displaystyle",
    "limits",
    "nolimits",
    "big",
    "Big",
    "bigl",
    "bigr",
    "Bigl",
    "Bigr",
    "biggl",
    "biggr",
}
_RELATIONS = {"approx": _REL, "le": _REL, "ge": _REL, "equiv": _REL, "Rightarrow": _REL + 3, "to": _REL}
_BINARIES = {"cdot": 2.7 + 8 * _MU, "times": 8.5 + 8 * _MU, "pm": _BIN, "mp": _BIN}
_SYMBOLS = {"partial": 6.2, "infty": 10.9, "ell": 4.6, "sum": 11.6, "prod": 10.0, "int": 6.0, "circ": 5.5}


@dataclass
class _Cursor:
    """A position in a formula (the scanners read ``text[pos]`` directly: a method call per character
    was most of their time)."""

    text: str
    pos: int = 0


_COMMAND = re.compile(r"\\([A-Za-z]+|.)", re.S)

#: how many distinct formulas (and script pieces) the memoised measurements below remember: a sheet of a
#: hundred variants measures the same pieces (\dot{\theta}_{1}, a bracket, a row) thousands of times
_MEMO = 1 << 15


#: what changes a braced group's depth: an escaped character (skipped with its backslash) and the braces
_BRACE = re.compile(r"[\\{}]")


def _group(cur: _Cursor) -> str:
    """The next argument: a braced group's contents, a command, or one character."""
    text, n, pos = cur.text, len(cur.text), cur.pos
    while pos < n and text[pos] == " ":
        pos += 1
    if pos >= n:
        cur.pos = pos
        return ""
    ch = text[pos]
    if ch == "{":
        # from brace to brace (not character by character: a group is a whole row of a matrix)
        depth, start, i = 0, pos, pos
        while True:
            m = _BRACE.search(text, i)
            if m is None:
                cur.pos = max(i, n)
                return text[start + 1 :]
            j = m.start()
            c = text[j]
            if c == "\\":
                i = j + 2
                continue
            depth += 1 if c == "{" else -1
            i = j + 1
            if depth == 0:
                cur.pos = i
                return text[start + 1 : i - 1]
    if ch == "\\":
        # a command, or a control symbol (\, \; \{); a backslash that ends the text (a piece cut just
        # after the thin space of ``\right)\,``) is taken as it is, never an error
        m = _COMMAND.match(text, pos)
        cur.pos = m.end() if m is not None else n
        return m.group(0) if m is not None else "\\"
    cur.pos = pos + 1
    return ch


def _environment(cur: _Cursor, name: str) -> str:
    """The body of ``\\begin{name}`` (the cursor after the ``\\begin{name}``), nested ones included."""
    depth, start = 1, cur.pos
    pattern = re.compile(r"\\(begin|end)\{" + re.escape(name) + r"\}")
    for m in pattern.finditer(cur.text, cur.pos):
        depth += 1 if m.group(1) == "begin" else -1
        if depth == 0:
            cur.pos = m.end()
            return cur.text[start : m.start()]
    cur.pos = len(cur.text)
    return cur.text[start:]


def split_top(tex: str, separator: str) -> list[str]:
    """``tex`` cut at every top-level occurrence of ``separator`` (``&`` or ``\\\\``): not inside braces or
    an inner environment."""
    pieces: list[str] = []
    depth, env, start, i, n = 0, 0, 0, 0, len(tex)
    special = _SPECIAL.get(separator[:1])
    if special is None:
        special = _SPECIAL[separator[:1]] = re.compile("[\\\\{}" + re.escape(separator[:1]) + "]")
    while i < n:
        # only a backslash, a brace or the separator's first character changes anything: jump to the next
        found = special.search(tex, i)
        if found is None:
            break
        i = found.start()
        if tex.startswith("\\begin{", i):
            env += 1
        elif tex.startswith("\\end{", i):
            env -= 1
        if depth == 0 and env == 0 and tex.startswith(separator, i):
            pieces.append(tex[start:i])
            i += len(separator)
            start = i
            continue
        ch = tex[i]
        if ch == "\\":
            i += 2
            continue
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        i += 1
    pieces.append(tex[start:])
    return pieces


#: by a separator's first character: what :func:`split_top` stops at
_SPECIAL: dict[str, re.Pattern[str]] = {}


def _matrix_width(body: str, scale: float) -> float:
    rows = [split_top(r, "&") for r in split_top(body, "\\\\")]
    cols = max(len(r) for r in rows)
    widths = [
        max((tex_width(r[c], scale, display=False) for r in rows if c < len(r)), default=0.0) for c in range(cols)
    ]
    return sum(widths) + (cols - 1) * 10.0 * scale + 2 * 4.5 * scale


@lru_cache(maxsize=_MEMO)
def tex_width(tex: str, scale: float = 1.0, display: bool = True) -> float:
    """The typeset width of a formula in TeX points, estimated from the LaTeX tutgen writes: glyph widths of
    Computer Modern at 11 pt, scripts at 70 %, a fraction as wide as its wider part, a matrix as its columns
    and gaps, an ``aligned`` block as its widest row, the spacing of binary operators and relations.
    ``display`` is the display style (fractions at full size), ``scale`` the font size relative to the text."""
    cur = _Cursor(tex)
    n = len(tex)
    total = 0.0
    last_script = 0.0  # width of the script just set, so a sub- and superscript pair counts once
    after_operand = False  # a + or − is binary only after an operand
    while cur.pos < n:
        ch = tex[cur.pos]
        glyph = _GLYPHS.get(ch)
        if glyph is not None:  # a plain character, most of a formula: as at the end of this loop
            cur.pos += 1
            last_script = 0.0
            total += glyph[0] * scale
            if glyph[1] is not None:
                after_operand = glyph[1]
            continue
        if ch in " \n":
            cur.pos += 1
            continue
        if ch in "_^":
            cur.pos += 1
            arg = _group(cur)
            w = tex_width(arg, scale * (0.7 if scale > 0.6 else 0.71), display=False)
            if last_script:
                total += max(0.0, w - last_script)
                last_script = 0.0
            else:
                total += w + 0.5 * scale
                last_script = w
            continue
        last_script = 0.0
        if ch == "{":
            total += tex_width(_group(cur), scale, display)
            after_operand = True
            continue
        if ch in "}":
            cur.pos += 1
            continue
        if ch == "&":
            cur.pos += 1
            after_operand = False
            continue
        if ch == "\\":
            cmd = _group(cur)
            name = cmd[1:]
            if name in ("frac", "tfrac", "dfrac"):
                num, den = _group(cur), _group(cur)
                inner = scale if (display and name != "tfrac") or name == "dfrac" else scale * 0.7
                sub_display = False
                total += max(tex_width(num, inner, sub_display), tex_width(den, inner, sub_display)) + 2.4 * scale
                after_operand = True
            elif name == "begin":
                env = _group(cur)
                body = _environment(cur, env)
                if env == "array":  # its column specification first, then cells as a matrix's
                    spec = _Cursor(body)
                    _group(spec)
                    total += _matrix_width(body[spec.pos :], scale)
                elif env.endswith("matrix"):
                    total += _matrix_width(body, scale)
                elif env in ("aligned", "gathered", "split", "align*", "gather*"):
                    total += max((tex_width(r, scale, True) for r in split_top(body, "\\\\")), default=0.0)
                else:
                    total += tex_width(body, scale, display)
                after_operand = True
            elif name in ("dot", "ddot", "hat", "bar", "vec", "tilde", "mathbf", "boldsymbol", "mathit", "bm"):
                total += tex_width(_group(cur), scale, display) * (1.1 if name in ("mathbf", "boldsymbol") else 1.0)
                after_operand = True
            elif name in ("mathrm", "text", "textrm", "textit", "operatorname"):
                arg = _group(cur)
                total += len(re.sub(r"\\.|[{}]", "x", arg)) * _W_ROMAN * scale
                after_operand = True
            elif name == "boxed":
                total += tex_width(_group(cur), scale, display) + 7.0
                after_operand = True
            elif name in ("phantom", "mathrlap", "mathllap", "llap", "rlap"):
                w = tex_width(_group(cur), scale, display)
                total += w if name == "phantom" else 0.0
            elif name in ("sqrt",):
                total += tex_width(_group(cur), scale, display) + 9.0 * scale
                after_operand = True
            elif name in _SPACES:
                total += _SPACES[name] * scale
            elif name in _OPERATORS:
                total += (len(name) * _W_ROMAN + 1.8) * scale
                after_operand = False  # what follows is its argument, not a binary operator's
            elif name in _ZERO:
                if name in ("left", "right", "bigl", "bigr", "Bigl", "Bigr", "biggl", "biggr", "big", "Big"):
                    delim = _group(cur)
                    total += (0.0 if delim == "." else 5.0 if name.startswith(("B", "bigg")) else 4.5) * scale
                    after_operand = name in ("right", "bigr", "Bigr", "biggr")
            elif name in _RELATIONS:
                total += _RELATIONS[name] * scale
                after_operand = False
            elif name in _BINARIES:
                total += _BINARIES[name] * scale
                after_operand = False
            elif name in _SYMBOLS:
                w = _SYMBOLS[name]
                total += (w * 1.4 if name in ("sum", "prod", "int") and display else w) * scale
                after_operand = name not in ("sum", "prod", "int")
            elif name in ("{", "}", "|"):
                total += 5.5 * scale
                after_operand = name == "}"
            elif name == "\\":
                after_operand = False  # a row break (the caller measures rows apart)
            elif len(name) > 1:  # \theta, \omega, \Gamma, \tau …
                total += (_W_GREEK if name[0].islower() else _W_UPPER) * scale
                after_operand = True
            continue
        cur.pos += 1
        if ch in "+-" or ch == "\u2212":
            total += (_BIN if after_operand else 8.52) * scale
            after_operand = False
            continue
        w, operand = _glyph(ch)
        total += w * scale
        if operand is not None:
            after_operand = operand
    return total


#: a plain character's width and what it makes of a following + or − (an operand: True, not: False, as
#: it was: None), by :func:`_glyph`; every character but white space, scripts, braces, ``&``, ``\\`` and signs
_GLYPHS: dict[str, tuple[float, bool | None]] = {}


def _glyph(ch: str) -> tuple[float, bool | None]:
    found = _GLYPHS.get(ch)
    if found is not None:
        return found
    if ch in "=<>":
        found = (_REL, False)
    elif ch in "([":
        found = (4.3, False)
    elif ch in ")]":
        found = (4.3, True)
    elif ch in ",;":
        found = (3.0 + 3 * _MU, False)
    elif ch in ".'|":
        found = (3.0, None)
    elif ch == "/":
        found = (5.5, None)
    elif ch.isdigit():
        found = (_W_DIGIT, True)
    elif ch.isalpha():
        found = (_WIDE.get(ch, _W_UPPER if ch.isupper() else _W_LOWER), True)
    else:
        found = (5.5, True)
    if len(_GLYPHS) < 4096:
        _GLYPHS[ch] = found
    return found


# --- cutting a formula at its top-level operators -------------------------------------------------------


#: what :func:`_scan` stops at: a command, a bracket, ``=``, ``+``, ``-``
_SCANNED = re.compile(r"[\\{}()\[\]=+\-]")


@lru_cache(maxsize=_MEMO)
def _scan(tex: str) -> tuple[tuple[int, str], ...]:
    """Positions of the top-level break points of a formula: ``("rel", i)`` at a relation ``=`` and
    ``("add", i)`` before a binary ``+`` or ``-`` (sympy prints them with a space on each side)."""
    points: list[tuple[int, str]] = []
    depth = 0
    i, n = 0, len(tex)
    while i < n:
        found = _SCANNED.search(tex, i)  # nothing else changes the depth or makes a break point
        if found is None:
            break
        i = found.start()
        if tex.startswith("\\left", i) and not tex[i + 5 : i + 6].isalpha():
            depth += 1
            i += 6
            continue
        if tex.startswith("\\right", i) and not tex[i + 6 : i + 7].isalpha():
            depth -= 1
            i += 7
            continue
        if tex.startswith("\\begin{", i):
            depth += 1
        elif tex.startswith("\\end{", i):
            depth -= 1
        ch = tex[i]
        if ch == "\\":
            i += 2
            continue
        if ch in "{([":
            depth += 1
        elif ch in "})]":
            depth -= 1
        elif depth == 0 and i > 0 and tex[i - 1] == " " and tex[i + 1 : i + 2] == " ":
            end = i  # the end of what comes before, trailing white space left out (no copy: long formulas)
            while end > 0 and tex[end - 1].isspace():
                end -= 1
            if ch == "=":
                points.append((i, "rel"))
            elif (
                ch in "+-"
                and end > 0
                and tex[end - 1] not in "=&(,{"
                and not tex.endswith(("\\quad", "\\left("), 0, end)
            ):
                points.append((i, "add"))
        i += 1
    return tuple(points)


def relation_parts(tex: str) -> list[str]:
    """A chain ``a = b = c`` cut at its top-level ``=`` signs: ``["a", "b", "c"]``."""
    cuts = [i for i, kind in _scan(tex) if kind == "rel"]
    parts, start = [], 0
    for i in cuts:
        parts.append(tex[start:i].strip())
        start = i + 1
    parts.append(tex[start:].strip())
    return parts


def terms(tex: str) -> list[str]:
    """A sum cut before each top-level binary ``+``/``-``: ``["a", "+ b", "- c"]``."""
    cuts = [i for i, kind in _scan(tex) if kind == "add"]
    out, start = [], 0
    for i in cuts:
        out.append(tex[start:i].strip())
        start = i
    out.append(tex[start:].strip())
    return [t for t in out if t]


_BMATRIX = re.compile(r"^\\begin\{bmatrix\}(.*)\\end\{bmatrix\}$", re.S)


def _matrix_cells(tex: str) -> list[list[str]] | None:
    m = _BMATRIX.match(tex.strip())
    if m is None or "\\begin{bmatrix}" in m.group(1):
        return None
    return [[c.strip() for c in split_top(r, "&")] for r in split_top(m.group(1), "\\\\")]


def _indexed(name: str, index: str) -> str:
    """The entry ``index`` of a named matrix: ``H`` -> ``H_{12}``, ``\\mathbf v_{G}`` -> ``(\\mathbf v_{G})_{1}``."""
    name = name.strip()
    if re.fullmatch(r"\\?[A-Za-z]+", name):
        return f"{name}_{{{index}}}"
    if name in ("\\mathbf 0", "0"):
        return "0"
    return f"\\left({name}\\right)_{{{index}}}"


# --- breaking a long sum into lines ---------------------------------------------------------------------


def _bracket(term: str) -> tuple[str, str, str] | None:
    """The largest ``\\left( … \\right)`` (or ``\\left[ … \\right]``) group of a term that is not inside
    braces (a fraction's parts, a script): (before and its opening, inside, its closing and after)."""
    best: tuple[str, str, str] | None = None
    depth, braces, start = 0, 0, -1
    i = 0
    envs = 0  # inside a matrix or other environment: not a bracket of the term's own
    while i < len(term):
        if term.startswith("\\begin{", i) or term.startswith("\\end{", i):
            envs += 1 if term.startswith("\\begin{", i) else -1
            i += 6
            continue
        if envs:
            i += 1
            continue
        if term.startswith("\\left", i) or term.startswith("\\right", i):
            opening = term.startswith("\\left", i)
            if opening and braces == 0 and depth == 0 and term.startswith(("\\left(", "\\left["), i):
                start = i
            depth += 1 if opening else -1
            closing = term.startswith(("\\right)", "\\right]"), i)
            if not opening and depth == 0 and braces == 0 and start >= 0 and closing:
                inner = term[start + 6 : i]
                if best is None or len(inner) > len(best[1]):
                    best = (term[:start] + term[start + 5], inner, term[i + 6 :])
                start = -1
            i += 6 if opening else 7
            continue
        if term[i] == "\\":
            i += 2
            continue
        braces += {"{": 1, "}": -1}.get(term[i], 0)
        i += 1
    return best


def _fraction(term: str) -> tuple[str, str, str] | None:
    """A term that is one fraction ``[sign] \\frac{A}{B}``: (sign, A, B)."""
    m = re.match(r"^([+-]?\s*)\\frac\{", term)
    if m is None:
        return None
    cur = _Cursor(term, m.end() - 1)
    num = _group(cur)
    den = _group(cur)
    if term[cur.pos :].strip():
        return None
    return m.group(1), num, den


def _fill(pieces: list[str], first: float, rest: float) -> list[str]:
    """Greedy lines of ``pieces`` (each begins with its sign): at most ``first`` points on the first line,
    ``rest`` on the others. A piece too wide for a line of its own is broken inside its largest bracket."""
    lines: list[str] = []
    current = ""
    for piece in pieces:
        room = first if not lines else rest
        candidate = f"{current} {piece}".strip()
        if not current or tex_width(candidate) <= room:
            if current or tex_width(piece) <= room:
                current = candidate
                continue
        if current:
            lines.append(current)
            current = ""
            room = rest
        if tex_width(piece) <= room:
            current = piece
            continue
        broken = _break_term(piece, room, rest)
        lines += broken[:-1]
        current = broken[-1]
    if current:
        lines.append(current)
    return lines


def _break_term(term: str, first: float, rest: float) -> list[str]:
    """A single term too wide for a line, broken inside its largest bracket: ``c\\bigl(a + b`` /
    ``\\quad + d\\bigr)``. A term with no bracket to break stays whole (it is reported by the PDF test)."""
    frac = _fraction(term)
    if frac is not None:  # -\frac{A}{B} = -\frac{1}{B} A, and A breaks (inside its bracket if it is a product)
        sign, num, den = frac
        inner_terms = terms(num)
        rewritten = (
            f"\\frac{{1}}{{{den}}}\\left({num}\\right)" if len(inner_terms) > 1 else f"\\frac{{1}}{{{den}}} {num}"
        )
        return _break_term(f"{sign}{rewritten}", first, rest)
    found = _bracket(term)
    inner_terms = terms(found[1]) if found is not None else []
    if found is None or len(inner_terms) < 2:
        return _break_thin(term, first)
    before, inner, after = found
    before, opening = before[:-1], before[-1]  # ( or [, and after starts with its partner
    closing, after = after[0], after[1:]
    big = "Big" if "\\frac" in inner else "big"
    head = f"{before}\\{big}l{opening}"
    pieces = [head + inner_terms[0], *inner_terms[1:]]
    pieces[-1] = pieces[-1] + f"\\{big}r{closing}" + after
    lines = _fill(pieces, first, rest - _EM)
    return [lines[0], *("\\quad " + ln for ln in lines[1:])]


def _thin_spaces(term: str) -> list[int]:
    """Positions of the top-level thin spaces ``\\,`` of a term (outside braces and brackets): the places
    a product such as ``\\left(…\\right)\\,\\mathbf i`` may break when nothing else can."""
    out: list[int] = []
    depth, i = 0, 0
    while i < len(term):
        if term.startswith("\\left", i) and not term[i + 5 : i + 6].isalpha():
            depth, i = depth + 1, i + 6
            continue
        if term.startswith("\\right", i) and not term[i + 6 : i + 7].isalpha():
            depth, i = depth - 1, i + 7
            continue
        if term.startswith("\\,", i):
            if depth == 0:
                out.append(i)
            i += 2
            continue
        if term[i] == "\\":
            i += 2
            continue
        depth += {"{": 1, "}": -1, "(": 1, ")": -1, "[": 1, "]": -1}.get(term[i], 0)
        i += 1
    return [k for k in out if term[:k].strip() and term[k + 2 :].strip()]


def _break_thin(term: str, first: float) -> list[str]:
    """A term with no bracket to break, broken at its last top-level thin space that leaves a first line
    of at most ``first`` points (the factor after it on the next line, indented); whole if it has none
    (a term too wide for any line is reported by the PDF test)."""
    for k in reversed(_thin_spaces(term)):
        head, tail = term[:k].rstrip(), term[k + 2 :].strip()
        if tex_width(head) <= first:
            return [head, f"\\quad {tail}"]
    return [term]


def break_equation(tex: str, width: float = LINE_WIDTH_PT, column: float | None = None) -> list[str]:
    """One equation (or a chain ``a = b = c``) as rows of an alignment, broken to ``width`` points: each
    row has one ``&`` before its relation sign or continuation. ``column`` is the width of the alignment's
    left column when the equation shares it with others (default: its own left-hand side)."""
    parts = relation_parts(tex)
    lhs, rhss = parts[0], parts[1:]
    own = tex_width(lhs)
    if not rhss or own > width / 3:
        width -= column or 0.0
        # no relation, or a left side too wide to align on: the whole chain flows from the left margin,
        # ``= …`` continuing it like any other term
        pieces = terms(lhs)
        for rhs in rhss:
            rhs_terms = terms(rhs)
            pieces += [f"= {rhs_terms[0]}", *rhs_terms[1:]]
        lines = _fill(pieces, width, width - _EM)
        if len(lines) > 1 and len(pieces) > 2 and lines[-1] == pieces[-1] and pieces[-1].startswith("= "):
            # never "= τ_1" alone on the last row: the last term goes down with it
            pieces = [*pieces[:-2], f"{pieces[-2]} {pieces[-1]}"]
            lines = _fill(pieces, width, width - _EM)
        return ["&" + lines[0], *(f"&\\quad {{}}{ln}" for ln in lines[1:])]
    rows: list[str] = []
    start = (own if column is None else column) + _REL
    last = 0.0  # room taken on the last row, for a short "= 0" that ends a chain on it
    for k, rhs in enumerate(rhss):
        if k and rows and last + tex_width(f"= {rhs}") <= width - start:
            rows[-1] += f" = {rhs}"
            last += tex_width(f"= {rhs}")
            continue
        lines = _fill(terms(rhs), width - start, width - start - _EM)
        rows.append((f"{lhs} &= " if k == 0 else "&= ") + lines[0])
        rows += [f"&\\quad {{}}{ln}" for ln in lines[1:]]
        last = tex_width(lines[-1]) + (_EM if len(lines) > 1 else 0.0)
    return rows


def expand_matrices(equation: str, width: float = LINE_WIDTH_PT) -> list[str]:
    """An equation ``name = [matrix]`` (or a chain) too wide for the line, as one equation per entry:
    ``name_{ij} = entry`` (only i ≤ j for a symmetric matrix, whose lower triangle the reader is told
    about), ``(\\mathbf v)_{i}`` for a vector. Equations without such a matrix come back unchanged."""
    if tex_width(equation) <= width:
        return [equation]
    parts = relation_parts(equation)
    grids = [_matrix_cells(p) for p in parts]
    shapes = {(len(g), len(g[0])) for g in grids if g}
    if len(parts) < 2 or not shapes or len(shapes) > 1:
        return [equation]
    nrows, ncols = shapes.pop()
    grid = next(g for g in grids if g)
    symmetric = nrows == ncols > 1 and all(grid[i][j] == grid[j][i] for i in range(nrows) for j in range(ncols))
    out: list[str] = []
    for i in range(nrows):
        for j in range(ncols):
            if symmetric and j < i:
                continue
            index = f"{i + 1}{j + 1}" if ncols > 1 and nrows > 1 else str((i if ncols == 1 else j) + 1)
            chain = [g[i][j] if g else _indexed(p, index) for p, g in zip(parts, grids, strict=True)]
            if chain[0] == "0":
                continue
            out.append(" = ".join(chain))
    return out


def _left_column(items: list[str], width: float) -> float:
    """The width of the left column that the equations share: their widest left side, leaving out
    those too wide to align on (they flow from the margin)."""
    lefts = [tex_width(relation_parts(e)[0]) for e in items if len(relation_parts(e)) > 1]
    return max((w for w in lefts if w <= width / 3), default=0.0)


def layout(equations: list[str], width: float = LINE_WIDTH_PT, stack: bool = False) -> list[str]:
    """Rows of one alignment for a display of ``equations``; ``[]`` when they fit on one line together
    (the caller then prints them as they are, joined by ``,\\quad``) unless ``stack`` asks for one
    equation a line."""
    joined = ",\\quad ".join(equations)
    if not stack and tex_width(joined) <= width:
        return []
    items: list[str] = []
    for eq in equations:
        items += expand_matrices(eq, width)
    for _ in range(2):  # a matrix that fits its own line may not fit beside a wider shared left column
        left = _left_column(items, width)
        wider: list[str] = []
        for eq in items:
            own = relation_parts(eq)
            shift = max(0.0, left - tex_width(own[0])) if len(own) > 1 else 0.0
            wider += expand_matrices(eq, width - shift) if shift else [eq]
        items = wider
    left = _left_column(items, width)
    rows: list[str] = []
    for k, eq in enumerate(items):
        eq_rows = break_equation(eq, width, left)
        if k < len(items) - 1 and len(items) > 1:
            eq_rows[-1] += ","
        rows += eq_rows
    return rows
