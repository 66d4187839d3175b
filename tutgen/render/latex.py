"""Derivation -> LaTeX worked solution: the view of ``views.py`` through ``templates/latex``.

The printer (``printer.py``) and the escaping (``escape.py``) live in their own modules, which the view
uses too; their names are re-exported here for callers that import them from this module."""

from __future__ import annotations

from pathlib import Path

from tutgen.engine.derivation import Derivation
from tutgen.render.env import latex_env
from tutgen.render.escape import latex_escape
from tutgen.render.printer import SIGNIFICANT_FIGURES, TexPrinter, format_number, tidy_functions
from tutgen.render.views import solution_view

__all__ = ["SIGNIFICANT_FIGURES", "TexPrinter", "format_number", "latex_escape", "render_latex", "tidy_functions"]


def render_latex(d: Derivation, template_dir: Path | None = None) -> str:
    return latex_env(template_dir).get_template("solution.tex.j2").render(**solution_view(d))
