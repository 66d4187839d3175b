"""The TikZ back end: a ``tikzpicture`` for LaTeX/PDF, from a :class:`~tutgen.figure.scene.Drawing`.

Only core TikZ is used (no libraries), because arrow heads are polygons of the drawing already; the
picture's bounding box is the drawing's, so the page layout does not depend on TeX's own estimate.
Label text is the drawing's safe TeX (:mod:`tutgen.figure.texlabel`), set in maths mode.
"""

from __future__ import annotations

from tutgen.figure.scene import Circle, Drawing, Fill, Polyline, Stroke

_STROKE = {
    Stroke.BAR: "line width=1.6pt",
    Stroke.OUTLINE: "line width=0.8pt",
    Stroke.THIN: "line width=0.4pt",
    Stroke.DASHED: "line width=0.4pt, dash pattern=on 2pt off 1.5pt",
    Stroke.AXIS: "line width=0.4pt, dash pattern=on 4pt off 1.5pt on 0.8pt off 1.5pt",
    Stroke.ARROW: "line width=0.7pt",
}
_FILL = {Fill.WHITE: "white", Fill.BLACK: "black", Fill.GRAY: "black!25"}


def _n(v: float) -> str:
    text = f"{v:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _pt(p: tuple[float, float]) -> str:
    return f"({_n(p[0])},{_n(p[1])})"


def _options(stroke: Stroke, fill: Fill) -> str:
    opts = []
    if stroke is Stroke.NONE:
        opts.append("draw=none")
    else:
        opts.append(_STROKE[stroke])
    if fill is not Fill.NONE:
        opts.append(f"fill={_FILL[fill]}")
    return ", ".join(opts)


def to_tikz(drawing: Drawing) -> str:
    """The drawing as a ``tikzpicture`` environment (needs only ``\\usepackage{tikz}``)."""
    b = drawing.bbox
    lines = [
        "\\begin{tikzpicture}[x=1cm, y=1cm, line cap=round, line join=round]",
        f"\\path[use as bounding box] {_pt((b.x0, b.y0))} rectangle {_pt((b.x1, b.y1))};",
    ]
    for prim in drawing.primitives:
        if isinstance(prim, Circle):
            cmd = "\\filldraw" if prim.fill is not Fill.NONE else "\\draw"
            lines.append(
                f"{cmd}[{_options(prim.stroke, prim.fill)}] {_pt(prim.center)} circle[radius={_n(prim.radius)}];"
            )
            continue
        assert isinstance(prim, Polyline)
        cmd = (
            "\\filldraw"
            if prim.fill is not Fill.NONE and prim.stroke is not Stroke.NONE
            else ("\\fill" if prim.fill is not Fill.NONE else "\\draw")
        )
        opts = _options(prim.stroke, prim.fill) if cmd != "\\fill" else f"{_FILL[prim.fill]}"
        path = " -- ".join(_pt(p) for p in prim.points) + (" -- cycle" if prim.closed else "")
        lines.append(f"{cmd}[{opts}] {path};")
    for lb in drawing.labels:
        lines.append(f"\\node[inner sep=0pt] at {_pt(lb.at)} {{$\\vphantom{{(}}{lb.tex}$}};")
    lines.append("\\end{tikzpicture}")
    return "\n".join(lines) + "\n"


def tikz_document(drawing: Drawing) -> str:
    """A LaTeX document holding only the figure, its one page exactly the picture's size (for
    ``tutgen figure``): the picture is boxed and shipped out alone, so no page layout intervenes."""
    return (
        "\\documentclass{article}\n"
        "\\ifdefined\\pdftrailerid\\pdftrailerid{}\\fi\n"
        "\\usepackage{amsmath}\n"  # \\text and \\boldsymbol of the label vocabulary
        "\\usepackage{tikz}\n"
        "\\begin{document}\n"
        "\\setbox0=\\hbox{%\n" + to_tikz(drawing) + "}\n"
        "\\pdfpagewidth=\\wd0 \\pdfpageheight=\\dimexpr\\ht0+\\dp0\\relax\n"
        "\\hoffset=-1in \\voffset=-1in\n"
        "\\shipout\\box0\n"
        "\\end{document}\n"
    )
