"""The SVG back end: the same drawing written directly as SVG 1.1, for Markdown.

Written by hand rather than through TeX and ``dvisvgm`` so that it is fast (a solve must not wait for
LaTeX) and byte-identical on every machine: numbers are rounded to 0.01 px, elements come in the
drawing's order, and labels are text in a serif font, their TeX read by
:func:`tutgen.figure.texlabel.svg_runs` (Greek letters as Unicode, sub- and superscripts as shifted
``tspan`` elements). Every piece of text is XML-escaped.
"""

from __future__ import annotations

from xml.sax.saxutils import escape

from tutgen.figure.scene import Circle, Drawing, Fill, Polyline, Stroke
from tutgen.figure.texlabel import svg_runs

PX_PER_CM = 37.795
FONT_PX = 13.33  # 10 pt, the size of the TikZ labels
_WIDTH = {  # px, as the TikZ widths in points (1 pt = 1.333 px)
    Stroke.BAR: 2.13,
    Stroke.OUTLINE: 1.07,
    Stroke.THIN: 0.53,
    Stroke.DASHED: 0.53,
    Stroke.AXIS: 0.53,
    Stroke.ARROW: 0.93,
}
_DASH = {Stroke.DASHED: "2.67 2", Stroke.AXIS: "5.33 2 1.07 2"}
#: A label run's style (:func:`tutgen.figure.texlabel.svg_runs`) as (italic, bold), the way pdflatex
#: sets it: ``\\mathbf`` upright bold, ``\\boldsymbol`` bold italic.
_FONT_STYLE = {
    "italic": (True, False),
    "upright": (False, False),
    "bold": (False, True),
    "bolditalic": (True, True),
}
_FILL = {Fill.NONE: "none", Fill.WHITE: "#ffffff", Fill.BLACK: "#000000", Fill.GRAY: "#bfbfbf"}


def _n(v: float) -> str:
    text = f"{v:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def to_svg(drawing: Drawing, title: str = "") -> str:
    """The drawing as a standalone SVG document (text)."""
    b = drawing.bbox
    w, h = (b.x1 - b.x0) * PX_PER_CM, (b.y1 - b.y0) * PX_PER_CM

    def X(x: float) -> str:
        return _n((x - b.x0) * PX_PER_CM)

    def Y(y: float) -> str:
        return _n((b.y1 - y) * PX_PER_CM)

    def style(stroke: Stroke, fill: Fill) -> str:
        out = f'fill="{_FILL[fill]}"'
        if stroke is Stroke.NONE:
            return out + ' stroke="none"'
        out += f' stroke="#000000" stroke-width="{_n(_WIDTH[stroke])}"'
        if stroke in _DASH:
            out += f' stroke-dasharray="{_DASH[stroke]}"'
        return out

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{_n(w)}" height="{_n(h)}" '
        f'viewBox="0 0 {_n(w)} {_n(h)}" stroke-linecap="round" stroke-linejoin="round">',
    ]
    if title:
        out.append(f"<title>{escape(title)}</title>")
    out.append(f'<rect x="0" y="0" width="{_n(w)}" height="{_n(h)}" fill="#ffffff"/>')
    for prim in drawing.primitives:
        if isinstance(prim, Circle):
            out.append(
                f'<circle cx="{X(prim.center[0])}" cy="{Y(prim.center[1])}" r="{_n(prim.radius * PX_PER_CM)}" '
                f"{style(prim.stroke, prim.fill)}/>"
            )
            continue
        assert isinstance(prim, Polyline)
        pts = " ".join(f"{X(x)},{Y(y)}" for x, y in prim.points)
        tag = "polygon" if prim.closed else "polyline"
        out.append(f'<{tag} points="{pts}" {style(prim.stroke, prim.fill)}/>')
    for lb in drawing.labels:
        spans = []
        shift = 0.0
        for text, font, place in svg_runs(lb.tex):
            target = {"base": 0.0, "sub": 0.3 * FONT_PX, "sup": -0.4 * FONT_PX}[place]
            attrs = []
            if target != shift:
                attrs.append(f'dy="{_n(target - shift)}"')
                shift = target
            if place != "base":
                attrs.append(f'font-size="{_n(FONT_PX * 0.7)}"')
            italic, bold = _FONT_STYLE[font]
            attrs.append(f'font-style="{"italic" if italic else "normal"}"')
            if bold:
                attrs.append('font-weight="bold"')
            spans.append(f"<tspan {' '.join(attrs)}>{escape(text)}</tspan>")
        out.append(
            f'<text x="{X(lb.at[0])}" y="{_n((b.y1 - lb.at[1]) * PX_PER_CM + 0.33 * FONT_PX)}" font-family="serif" '
            f'font-size="{_n(FONT_PX)}" text-anchor="middle">{"".join(spans)}</text>'
        )
    out.append("</svg>")
    return "\n".join(out) + "\n"
