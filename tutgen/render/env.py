"""The only place Jinja environments are built.

Both environments are strict (``StrictUndefined``), trim block lines and keep the trailing newline.
The LaTeX one uses delimiters that cannot clash with braces: ``((* … *))`` blocks, ``((( … )))``
variables, ``((# … #))`` comments. A user's ``--template-dir`` goes first on the search path (a
template there replaces the shipped one of the same name) and then the environment is sandboxed.

A user's templates are read by :class:`TemplateDirLoader`, not Jinja's ``FileSystemLoader``: a name
resolves only to a regular file inside the directory, after every symlink is followed, so a link to
``/`` (or a FIFO, or a device) cannot let a template include ``/proc/self/environ`` or hang the run.
Such a refusal is a :class:`TemplateRefused`, a usage error.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Callable
from importlib.resources import files
from pathlib import Path
from typing import Any

import jinja2
import jinja2.sandbox
from jinja2.loaders import split_template_path

from tutgen.errors import UsageError
from tutgen.render.escape import latex_escape, md_escape

#: The largest template file a user's --template-dir may hold.
MAX_TEMPLATE_BYTES = 1024 * 1024


class TemplateRefused(UsageError):
    """A template name in --template-dir that leads out of the directory or to a non-regular file."""


class TemplateDirLoader(jinja2.BaseLoader):
    """Templates from a user's directory, each resolved (symlinks followed) to a regular file inside
    it; a name that is not there at all is :class:`jinja2.TemplateNotFound`, so the shipped template of
    that name is used (through a ``ChoiceLoader``)."""

    def __init__(self, directory: Path) -> None:
        self.shown = str(directory)
        self.root = Path(os.path.realpath(directory))

    def get_source(self, environment: jinja2.Environment, template: str) -> tuple[str, str, Callable[[], bool]]:
        pieces = split_template_path(template)  # refuses '..' itself
        path = self.root.joinpath(*pieces)
        if not os.path.lexists(path):
            raise jinja2.TemplateNotFound(template)
        real = Path(os.path.realpath(path))
        if real != self.root and self.root not in real.parents:
            raise TemplateRefused(
                f"--template-dir {self.shown}: the template '{template}' leads out of the directory "
                f"(to {real}); templates must be regular files inside it"
            )
        try:
            # O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused just below
            fd = os.open(real, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0))
        except OSError as err:
            raise TemplateRefused(f"--template-dir {self.shown}: cannot read '{template}': {err.strerror}") from None
        with os.fdopen(fd, "rb") as fh:
            info = os.fstat(fh.fileno())
            if not stat.S_ISREG(info.st_mode):
                raise TemplateRefused(f"--template-dir {self.shown}: '{template}' is not a regular file")
            if info.st_size > MAX_TEMPLATE_BYTES:
                raise TemplateRefused(
                    f"--template-dir {self.shown}: '{template}' is larger than {MAX_TEMPLATE_BYTES // 1024} KiB"
                )
            data = fh.read(MAX_TEMPLATE_BYTES + 1)
        try:
            source = data.decode("utf-8")
        except UnicodeDecodeError:
            raise TemplateRefused(f"--template-dir {self.shown}: '{template}' is not UTF-8 text") from None
        mtime = info.st_mtime_ns
        return source, str(path), lambda: _mtime(real) == mtime


def _mtime(path: Path) -> int | None:
    try:
        return os.stat(path).st_mtime_ns
    except OSError:
        return None


def template_root() -> Path:
    """The templates shipped with tutgen: the top-level `templates/` of the repository, installed
    as the package data `tutgen.templates` (in a source checkout, the folder itself)."""
    try:
        return Path(str(files("tutgen.templates")))
    except ModuleNotFoundError:  # running from a source checkout, not installed
        return Path(__file__).resolve().parents[2] / "templates"


def _env(fmt: str, template_dir: Path | None, **delimiters: Any) -> jinja2.Environment:
    shipped = jinja2.FileSystemLoader(str(template_root() / fmt))
    loader: jinja2.BaseLoader = (
        jinja2.ChoiceLoader([TemplateDirLoader(template_dir), shipped]) if template_dir else shipped
    )
    cls = jinja2.sandbox.SandboxedEnvironment if template_dir else jinja2.Environment
    return cls(
        loader=loader,
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
