"""The files a sheet's problem brings beside the sheet besides its figure: the free-body diagrams of
its Newton–Euler step (Markdown sheets; the LaTeX sheets draw them inline in TikZ) and the plots of
its simulation (``ask: [simulation]``; Markdown and LaTeX sheets name them, the PDF includes them).

They exist only once a problem is derived (which bodies the planar step frees, whether the run is
planar enough for snapshots), so a sheet's plan is made twice: before deriving without them, to refuse
bad outputs early, and after deriving with them (:func:`asset_names`, from the nominal derivations),
before anything is built. Each file is named after its problem's key, so that no two problems and no
two variants write the same file, and each is written once, under the sheet that shows it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from tutgen.engine.derivation import Derivation

__all__ = ["ProblemAssets", "asset_names", "problem_assets"]


def _fbd_name(key: str, body: str) -> str:
    return f"figures/{key}.fbd-{body}.svg"


def _plot_name(key: str, kind: str) -> str:
    return f"figures/{key}.{'simulation' if kind == 'plot' else kind}.png"


def _tex_name(number: int, kind: str) -> str:
    # tutgen.render.pdf.INPUT_NAME: lowercase, digits and hyphens; one sheet holds several problems
    return f"p{number}-simulation-{kind}.png"


def _free_bodies(d: Derivation) -> list[dict[str, Any]]:
    from tutgen.render.sections.newton_euler import free_bodies

    return free_bodies(d)


def asset_names(key: str, d: Derivation, formats: tuple[str, ...] | list[str]) -> list[str]:
    """The files of one problem's assets, relative to its sheet, in the order :func:`problem_assets`
    gives them."""
    from tutgen.render.sections.newton_euler import free_body_names

    names = [_fbd_name(key, body) for body in free_body_names(d)] if "md" in formats else []
    if d.simulation is not None and ("md" in formats or "tex" in formats):
        names += [_plot_name(key, p.kind) for p in d.simulation.plots]
    return names


@dataclass(frozen=True)
class ProblemAssets:
    """One problem's asset files (name relative to the sheet, content), its plots by their names in
    the PDF compile, and what its view's blocks must be told (their names as the sheet writes them)."""

    files: tuple[tuple[str, str | bytes], ...]
    tex_files: tuple[tuple[str, bytes], ...]
    fbd: tuple[tuple[str, str], ...]  # body -> file
    plots: tuple[tuple[str, str, str], ...]  # kind -> (file, tex name)

    def view(self, view: dict[str, Any], md: bool) -> dict[str, Any]:
        """The problem's view with its blocks naming the sheet's files: the plots always, the free
        bodies' SVGs for a Markdown sheet (whose free bodies the sheet has no file for are left out)."""
        fbd = dict(self.fbd)
        plots = {kind: (file, tex) for kind, file, tex in self.plots}

        def block(b: dict[str, Any]) -> dict[str, Any] | None:
            if b["kind"] == "plot":
                for kind, (file, tex) in plots.items():
                    if b["tex_name"].endswith(f"-{kind}.png"):
                        return {**b, "file": file, "tex_name": tex}
                return None
            if b["kind"] == "freebody" and md:
                return {**b, "svg": fbd[b["body"]]} if b["body"] in fbd else None
            if b["kind"] == "beside":  # a free-body diagram set beside its forces (tutgen/sheet/compact.py)
                left = block(b["left"])
                return {**b, "left": left} if left is not None else b["right"]
            return b

        solution = view.get("solution")
        if not solution:
            return view
        sections = [
            {**sec, "blocks": [nb for b in sec["blocks"] if (nb := block(b)) is not None]}
            for sec in solution["sections"]
        ]
        return {**view, "solution": {**solution, "sections": sections}}


def problem_assets(key: str, number: int, d: Derivation, formats: tuple[str, ...] | list[str]) -> ProblemAssets:
    """The assets of problem ``key`` (number ``number`` on its sheet) from its derivation ``d`` (a
    variant's, with its own run); the files in the order of :func:`asset_names`."""
    files: list[tuple[str, str | bytes]] = []
    fbd: list[tuple[str, str]] = []
    if "md" in formats:
        for v in _free_bodies(d):
            name = _fbd_name(key, v["body"])
            fbd.append((v["body"], name))
            files.append((name, v["svg_text"]))
    plots: list[tuple[str, str, str]] = []
    tex_files: list[tuple[str, bytes]] = []
    if d.simulation is not None:
        for p in d.simulation.plots:
            plots.append((p.kind, _plot_name(key, p.kind), _tex_name(number, p.kind)))
            tex_files.append((_tex_name(number, p.kind), p.png))
            if "md" in formats or "tex" in formats:
                files.append((_plot_name(key, p.kind), p.png))
    return ProblemAssets(tuple(files), tuple(tex_files), tuple(fbd), tuple(plots))
