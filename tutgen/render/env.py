"""The only place Jinja environments are built."""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

import jinja2


def template_root() -> Path:
    """The templates shipped with tutgen: the top-level `templates/` of the repository, installed
    as the package data `tutgen.templates` (in a source checkout, the folder itself)."""
    try:
        return Path(str(files("tutgen.templates")))
    except ModuleNotFoundError:  # running from a source checkout, not installed
        return Path(__file__).resolve().parents[2] / "templates"


def markdown_env(template_dir: Path | None = None) -> jinja2.Environment:
    """A strict environment for Markdown templates (user text is escaped by the views)."""
    search = [str(template_dir)] if template_dir else []
    search.append(str(template_root() / "markdown"))
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(search),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=False,
    )
