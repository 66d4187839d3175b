"""The Markdown of a question or a worked solution as HTML an LMS page can show, with nothing active in it.

- The Markdown is tutgen's own (templates/markdown), in which every user text is already escaped
  (``md_escape``); it is rendered by markdown-it in CommonMark mode with raw HTML **off**, so any
  ``<img onerror=…>`` that reached it is printed as text, never markup.
- Maths (``$…$`` and ``$$…$$``) is cut out before the Markdown is read (so that ``_`` and ``\\`` inside
  it stay as written) and put back HTML-escaped between ``\\( … \\)`` and ``\\[ … \\]``, the delimiters
  Moodle's MathJax filter and Canvas read.
- :func:`inert` then writes ``{ } [ ] @`` as character references, for the LMSs that read markers in
  the stored HTML before a browser does: Moodle's Cloze ``{1:NUMERICAL:…}``, STACK's CAS text
  ``{@…@}`` and ``[[input:…]]``, Moodle's ``@@PLUGINFILE@@``. A browser (and MathJax after it) sees the
  same characters; the importers see none of their markers.
"""

from __future__ import annotations

import html
import re
from typing import Any

#: The markers tutgen puts into its own Markdown for its figure, replaced after escaping.
FIGURE_MARK = "tutgen-figure:"

_INERT = str.maketrans({"{": "&#123;", "}": "&#125;", "[": "&#91;", "]": "&#93;", "@": "&#64;"})

_MD: list[Any] = []


def _markdown() -> Any:
    if not _MD:
        from markdown_it import MarkdownIt

        md = MarkdownIt("commonmark", {"html": False, "xhtmlOut": True, "linkify": False, "typographer": False})
        md.enable("table")
        _MD.append(md)
    return _MD[0]


def _cut_maths(text: str) -> tuple[str, list[tuple[bool, str]]]:
    """The text with each maths span replaced by a placeholder, and the spans (display?, LaTeX).

    A backslash escapes the next character outside maths (``\\$`` is a dollar sign, as md_escape writes
    it), so only tutgen's own ``$`` open maths."""
    out: list[str] = []
    spans: list[tuple[bool, str]] = []
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        if ch == "\\" and i + 1 < n:
            out.append(text[i : i + 2])
            i += 2
            continue
        if ch == "$":
            display = text.startswith("$$", i)
            close = text.find("$$" if display else "$", i + (2 if display else 1))
            if close >= 0:
                start = i + (2 if display else 1)
                spans.append((display, text[start:close].strip()))
                out.append(f"TUTGENMATH{len(spans) - 1}X")
                i = close + (2 if display else 1)
                continue
        out.append(ch)
        i += 1
    return "".join(out), spans


def markdown_html(text: str, *, inert_markers: bool = False, figure_src: str = "") -> str:
    """tutgen's Markdown as an HTML fragment: raw HTML off, maths as ``\\( … \\)``/``\\[ … \\]``.

    With ``inert_markers``, every ``{ } [ ] @`` of the text and of the maths is a character reference
    (see the module's docstring); the maths delimiters stay as written, since Moodle's MathJax filter
    looks for them in the stored text. The figure marker becomes ``figure_src``."""
    body, spans = _cut_maths(text)
    rendered = str(_markdown().render(body))
    if inert_markers:
        rendered = inert(rendered)

    def put(m: re.Match[str]) -> str:
        display, tex = spans[int(m.group(1))]
        tex = html.escape(tex, quote=False)
        if inert_markers:
            tex = inert(tex)
        return f"\\[{tex}\\]" if display else f"\\({tex}\\)"

    out = re.sub(r"TUTGENMATH(\d+)X", put, rendered).replace(FIGURE_MARK, figure_src)
    return out.strip() + "\n"


def inert(fragment: str) -> str:
    """The fragment with every ``{ } [ ] @`` as a character reference (see the module's docstring)."""
    return fragment.translate(_INERT)
