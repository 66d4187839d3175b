"""Derivation -> Markdown worked solution: the view of ``views.py`` through ``templates/markdown``."""

from __future__ import annotations

from pathlib import Path

from tutgen.engine.derivation import Derivation

_MD_SPECIALS = str.maketrans({c: "\\" + c for c in "\\`*_{}[]<>#|$"})


def md_escape(text: str) -> str:
    """User text in Markdown: no markup, no maths, no HTML from it."""
    return text.translate(_MD_SPECIALS)


def render_markdown(d: Derivation, template_dir: Path | None = None) -> str:
    from tutgen.render.env import markdown_env
    from tutgen.render.views import solution_view

    return markdown_env(template_dir).get_template("solution.md.j2").render(**solution_view(d))
