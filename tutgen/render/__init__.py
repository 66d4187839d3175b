"""Rendering: a Derivation as Markdown, LaTeX, PDF or JSON (docs/architecture.md, "render/").

The package is also the API function ``tutgen.render(derivation, fmt="md")`` (:func:`tutgen.api.render`):
a function and a subpackage of one name cannot both be attributes of ``tutgen`` (importing the
subpackage rebinds the name), so the subpackage is made callable.
"""

from __future__ import annotations

import sys
import types
from pathlib import Path
from typing import Any


class _RenderModule(types.ModuleType):
    def __call__(self, derivation: Any, fmt: str = "md", template_dir: Path | None = None) -> str | bytes:
        """:func:`tutgen.api.render`."""
        from tutgen.api import render

        return render(derivation, fmt, template_dir)


sys.modules[__name__].__class__ = _RenderModule
