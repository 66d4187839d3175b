"""The figure as the renderers and the JSON output see it: plain strings and numbers.

The Markdown solution refers to the SVG by a relative name, :func:`svg_name` (``<spec>.figure.svg``,
written beside the ``.md`` by :mod:`tutgen.api`); the LaTeX solution holds the TikZ picture inline.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tutgen.model.figure import ImageKind
from tutgen.model.system import System

if TYPE_CHECKING:
    from tutgen.figure.freebody import BodyForce
    from tutgen.figure.scene import Drawing

_PLAIN = re.compile(r"[A-Za-z0-9._/-]+")


def svg_name(system: System) -> str:
    """The file name of a spec's figure beside its Markdown solution."""
    # only characters that need no quoting in a Markdown link or a file system
    stem = re.sub(r"[^A-Za-z0-9._-]", "_", Path(system.source).stem) or "figure"
    return f"{stem}.figure.svg"


def drawing_of(system: System) -> Drawing | None:
    """The generated drawing, or None when the spec asks for its own picture only."""
    if not is_generated(system):
        return None
    from tutgen.figure.build import draw_system  # numpy: only when a figure is drawn

    return draw_system(system)


def is_generated(system: System) -> bool:
    """Whether the spec has a generated drawing (without drawing it): unless it asks for its own picture only."""
    cfg = system.figure
    return cfg is None or cfg.generated


class FigureView(Mapping[str, Any]):
    """The keys of :func:`figure_view`; those that need the drawing (``tikz``, ``remarks``) are drawn on
    first read, so a Markdown solution on stdout, which names the SVG only, never draws (issue 17).
    Pickled, it is a plain dict."""

    _DRAWN_KEYS = ("tikz", "remarks")

    def __init__(self, system: System, drawing: Drawing | None, plain: dict[str, Any]) -> None:
        self._system = system
        self._drawing = drawing
        self._plain = plain

    def _drawn(self) -> None:
        from tutgen.figure.tikz import to_tikz

        drawing = self._drawing if self._drawing is not None else drawing_of(self._system)
        self._plain["tikz"] = to_tikz(drawing) if drawing is not None else ""
        self._plain["remarks"] = list(drawing.remarks) if drawing is not None else []

    def __getitem__(self, key: str) -> Any:
        if key in self._DRAWN_KEYS and key not in self._plain:
            self._drawn()
        return self._plain[key]

    def __iter__(self) -> Iterator[str]:
        return iter(FIGURE_KEYS)

    def __len__(self) -> int:
        return len(FIGURE_KEYS)

    def __reduce__(self) -> tuple[type, tuple[dict[str, Any]]]:
        return (dict, (dict(self.items()),))


#: The keys of :func:`figure_view`, in order.
FIGURE_KEYS = (
    "generated",
    "tikz",
    "svg",
    "file",
    "file_kind",
    "file_tex",
    "file_tex_name",
    "file_plain",
    "file_md",
    "caption",
    "remarks",
)


def figure_view(system: System, drawing: Drawing | None = None) -> Mapping[str, Any]:
    """The template context of the figure (``figure`` in tutgen/render/views.py).

    ``tikz``: the picture for LaTeX ("" without a generated drawing); ``svg``: the SVG's relative
    name for Markdown; ``file``/``file_kind``: the instructor's picture, as written in the spec
    (``file_tex``: whether pdflatex can include it, PNG, JPEG or PDF; ``file_tex_name``: the safe name
    it is copied in under when tutgen compiles the PDF, :func:`tutgen.figure.picture.picture_name`;
    ``file_plain``: whether the path as written may also go into TeX, for a ``.tex`` compiled beside
    the spec; ``file_md``: whether a browser shows it, PNG, JPEG or SVG); ``caption``: raw text;
    ``remarks``: what the drawing adjusted. ``tikz`` and ``remarks`` are drawn when first read
    (:class:`FigureView`).
    """
    from tutgen.figure.picture import TEX_EXTENSIONS, picture_name

    generated = drawing is not None or is_generated(system)
    cfg = system.figure
    file = cfg.file if cfg is not None else None
    plain = {
        "generated": generated,
        "svg": svg_name(system) if generated else "",
        "file": file.path if file is not None else "",
        "file_kind": file.kind.value if file is not None else "",
        # pdflatex includes PNG, JPEG and PDF, by a name tutgen makes (copied into the compile folder)
        "file_tex": file is not None and file.kind in TEX_EXTENSIONS,
        "file_tex_name": picture_name(file) if file is not None and file.kind in TEX_EXTENSIONS else "",
        # the path as written goes into TeX only when it is plain and its extension says its kind
        "file_plain": file is not None and file.kind in TEX_EXTENSIONS and _is_plain(file.path, file.kind),
        "file_md": file is not None and file.kind is not ImageKind.PDF,
        "caption": system.title,
    }
    return FigureView(system, drawing, plain)


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


def free_body_bodies(system: System) -> list[str]:
    """The bodies :func:`free_body_views` draws, in its order, without drawing them: every body with
    a mass when the system is drawn in the plane (a sheet plans its files from these names)."""
    from tutgen.figure.build import draw_system

    if not system.bodies or draw_system(system).view != "planar":
        return []
    return [body.name for body in system.bodies if body.parts]


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

    stem = svg_name(system).removesuffix(".figure.svg")
    out = []
    for name in free_body_bodies(system):
        body = system.body(name)
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
    from tutgen.figure.build import draw_system
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
