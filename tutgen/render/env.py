"""The only place Jinja environments are built.

Both environments are strict (``StrictUndefined``), trim block lines and keep the trailing newline.
The LaTeX one uses delimiters that cannot clash with braces: ``((* … *))`` blocks, ``((( … )))``
variables, ``((# … #))`` comments. A user's ``--template-dir`` goes first on the search path (a
template there replaces the shipped one of the same name) and then the environment is sandboxed.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path
from typing import Any

import jinja2
import jinja2.sandbox

from tutgen.render.escape import latex_escape, md_escape


def template_root() -> Path:
    """The templates shipped with tutgen: the top-level `templates/` of the repository, installed
    as the package data `tutgen.templates` (in a source checkout, the folder itself)."""
    try:
        return Path(str(files("tutgen.templates")))
    except ModuleNotFoundError:  # running from a source checkout, not installed
        return Path(__file__).resolve().parents[2] / "templates"


def _env(fmt: str, template_dir: Path | None, **delimiters: Any) -> jinja2.Environment:
    search = [str(template_dir)] if template_dir else []
    search.append(str(template_root() / fmt))
    cls = jinja2.sandbox.SandboxedEnvironment if template_dir else jinja2.Environment
    return cls(
        loader=jinja2.FileSystemLoader(search),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=False,
        **delimiters,
    )


def markdown_env(template_dir: Path | None = None) -> jinja2.Environment:
    """Markdown templates; user text goes through the ``md_escape`` filter."""
    env = _env("markdown", template_dir)
    env.filters["md_escape"] = md_escape
    return env


def latex_env(template_dir: Path | None = None) -> jinja2.Environment:
    """LaTeX templates; user text goes through the ``latex_escape`` filter."""
    env = _env(
        "latex",
        template_dir,
        block_start_string="((*",
        block_end_string="*))",
        variable_start_string="(((",
        variable_end_string=")))",
        comment_start_string="((#",
        comment_end_string="#))",
        line_statement_prefix=None,
        line_comment_prefix=None,
    )
    env.filters["latex_escape"] = latex_escape
    return env
