"""The figure as the renderers and the JSON output see it: plain strings and numbers.

The Markdown solution refers to the SVG by a relative name, :func:`svg_name` (``<spec>.figure.svg``,
written beside the ``.md`` by :mod:`tutgen.api`); the LaTeX solution holds the TikZ picture inline.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tutgen.figure.build import draw_system
from tutgen.figure.scene import Drawing
from tutgen.model.figure import ImageKind
from tutgen.model.system import System

if TYPE_CHECKING:
    from tutgen.figure.freebody import BodyForce

_PLAIN = re.compile(r"[A-Za-z0-9._/-]+")


def svg_name(system: System) -> str:
    """The file name of a spec's figure beside its Markdown solution."""
    # only characters that need no quoting in a Markdown link or a file system
    stem = re.sub(r"[^A-Za-z0-9._-]", "_", Path(system.source).stem) or "figure"
    return f"{stem}.figure.svg"


def drawing_of(system: System) -> Drawing | None:
    """The generated drawing, or None when the spec asks for its own picture only."""
    cfg = system.figure
    if cfg is not None and not cfg.generated:
        return None
    return draw_system(system)


def figure_view(system: System, drawing: Drawing | None = None) -> dict[str, Any]:
    """The template context of the figure (``figure`` in tutgen/render/views.py).

    ``tikz``: the picture for LaTeX ("" without a generated drawing); ``svg``: the SVG's relative
    name for Markdown; ``file``/``file_kind``: the instructor's picture, as written in the spec
    (``file_tex``: whether pdflatex can include it, PNG, JPEG or PDF; ``file_tex_name``: the safe name
    it is copied in under when tutgen compiles the PDF, :func:`tutgen.figure.picture.picture_name`;
    ``file_plain``: whether the path as written may also go into TeX, for a ``.tex`` compiled beside
    the spec; ``file_md``: whether a browser shows it, PNG, JPEG or SVG); ``caption``: raw text;
    ``remarks``: what the drawing adjusted.
    """
    from tutgen.figure.picture import TEX_EXTENSIONS, picture_name
    from tutgen.figure.tikz import to_tikz

    drawing = drawing if drawing is not None else drawing_of(system)
    cfg = system.figure
    file = cfg.file if cfg is not None else None
    return {
        "generated": drawing is not None,
        "tikz": to_tikz(drawing) if drawing is not None else "",
        "svg": svg_name(system) if drawing is not None else "",
        "file": file.path if file is not None else "",
        "file_kind": file.kind.value if file is not None else "",
        # pdflatex includes PNG, JPEG and PDF, by a name tutgen makes (copied into the compile folder)
        "file_tex": file is not None and file.kind in TEX_EXTENSIONS,
        "file_tex_name": picture_name(file) if file is not None and file.kind in TEX_EXTENSIONS else "",
        # the path as written goes into TeX only when it is plain and its extension says its kind
        "file_plain": file is not None and file.kind in TEX_EXTENSIONS and _is_plain(file.path, file.kind),
        "file_md": file is not None and file.kind is not ImageKind.PDF,
        "caption": system.title,
        "remarks": list(drawing.remarks) if drawing is not None else [],
    }


def _is_plain(path: str, kind: ImageKind) -> bool:
    """Whether ``path`` can be written in TeX as it is: plain characters, and an extension pdflatex
    reads as the file's kind (it picks the graphics driver by the extension)."""
    suffix = path.rsplit(".", 1)[-1].lower() if "." in path.rsplit("/", 1)[-1] else ""
    wanted = {ImageKind.PNG: ("png",), ImageKind.JPEG: ("jpg", "jpeg"), ImageKind.PDF: ("pdf",)}
    return _PLAIN.fullmatch(path) is not None and suffix in wanted.get(kind, ())


def figure_json(system: System, drawing: Drawing | None = None) -> dict[str, Any]:
    """The figure entry of the JSON output (docs/json-output.md): where the files are, and the
    drawing configuration that was used."""
    drawing = drawing if drawing is not None else drawing_of(system)
    cfg = system.figure
    file = cfg.file if cfg is not None else None
    return {
        "svg": svg_name(system) if drawing is not None else None,
        "file": file.path if file is not None else None,
        "generated": drawing is not None,
        "view": drawing.view if drawing is not None else None,
        "at": {name: round(v, 6) for name, v in drawing.at} if drawing is not None else {},
        "sizes": {name: round(v, 6) for name, v in drawing.sizes} if drawing is not None else {},
        "labels": sorted(drawing.names) if drawing is not None else [],
        "remarks": list(drawing.remarks) if drawing is not None else [],
    }


def svg_file(system: System) -> tuple[str, str] | None:
    """(name, SVG text) of the figure written beside a Markdown solution, or None."""
    from tutgen.figure.svg import to_svg

    drawing = drawing_of(system)
    if drawing is None:
        return None
    return svg_name(system), to_svg(drawing, system.title)


def free_body_views(system: System, forces: Mapping[str, Sequence[BodyForce]] | None = None) -> list[dict[str, Any]]:
    """The free-body diagrams of a planar system's bodies (every body with a mass, in spec order), as
    a template or the file writer needs them: ``body``; ``tikz`` (LaTeX); ``svg``, the relative name
    of the SVG beside a Markdown solution (``<spec>.fbd-<body>.svg``), and ``svg_text``; ``labels`` and
    ``remarks``. ``forces``: per body, the forces to draw instead of the model's own
    (:func:`tutgen.figure.freebody.body_forces`), as the Newton–Euler step names them. A spatial
    system gets none (its diagrams would need the oblique view's care)."""
    from tutgen.figure.freebody import free_body_diagram
    from tutgen.figure.svg import to_svg
    from tutgen.figure.tikz import to_tikz

    if not system.bodies or draw_system(system).view != "planar":
        return []
    stem = svg_name(system).removesuffix(".figure.svg")
    out = []
    for body in system.bodies:
        if not body.parts:
            continue
        drawing = free_body_diagram(system, body.name, (forces or {}).get(body.name))
        out.append(
            {
                "body": body.name,
                "tikz": to_tikz(drawing),
                "svg": f"{stem}.fbd-{body.name}.svg",
                "svg_text": to_svg(drawing, f"{system.title}: {body.name}"),
                "labels": sorted(drawing.names),
                "remarks": list(drawing.remarks),
            }
        )
    return out


#: The formats of ``tutgen figure``, by the output's suffix.
FIGURE_FORMATS = {".svg": "svg", ".tex": "tex", ".pdf": "pdf"}


def render_figure(spec: Path, fmt: str, body: str | None = None) -> str | bytes:
    """A spec's figure alone: ``svg`` (text), ``tex`` (a LaTeX document of the picture) or ``pdf``
    (that document compiled; :class:`tutgen.render.pdf.PdfError` if it cannot be). With ``body``, the
    free-body diagram of that body instead (:mod:`tutgen.figure.freebody`)."""
    from tutgen.errors import UsageError
    from tutgen.figure.svg import to_svg
    from tutgen.figure.tikz import tikz_document
    from tutgen.spec.validate import load_system

    system = load_system(spec)
    if body is not None:
        from tutgen.figure.freebody import free_body_diagram

        try:
            drawing = free_body_diagram(system, body)
        except ValueError as err:
            raise UsageError(f"--body: {err}") from None
    else:
        drawing = draw_system(system)  # also with `generated: false`: asked for by name
    if fmt == "svg":
        return to_svg(drawing, system.title)
    if fmt not in ("tex", "pdf"):
        raise UsageError(f"unknown figure format '{fmt}'; expected one of: svg, tex, pdf")
    tex = tikz_document(drawing)
    if fmt == "tex":
        return tex
    from tutgen.render.pdf import compile_pdf

    return compile_pdf(tex)  # the figure alone: the generated drawing, never the spec's picture
