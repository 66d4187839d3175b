"""Derivation -> Markdown worked solution: the view of ``views.py`` through ``templates/markdown``."""

from __future__ import annotations

from pathlib import Path

from tutgen.engine.derivation import Derivation
from tutgen.render.env import markdown_env
from tutgen.render.escape import md_escape
from tutgen.render.views import solution_view

__all__ = ["md_escape", "render_markdown"]


def render_markdown(d: Derivation, template_dir: Path | None = None) -> str:
    return markdown_env(template_dir).get_template("solution.md.j2").render(**solution_view(d))
