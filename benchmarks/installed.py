"""The environment of a measured command: the tutgen of a source tree, run as ``pip install`` leaves it.

``pip install .`` byte-compiles the package (``.pyc`` files beside the modules), so an installed tutgen
does not compile its 200 modules on every start. A source tree measured with ``PYTHONPATH`` does, when
nothing has written its ``__pycache__`` yet or when ``PYTHONDONTWRITEBYTECODE`` is set (as it is on
the machines these figures were taken on): about 0.15-0.2 s more for every fresh process. The
benchmarks compile the tree first and let each command read the compiled modules, so that the figures
are those of the installed tool, for the tree measured and for a ``--baseline`` alike.
"""

from __future__ import annotations

import compileall
import os
from pathlib import Path


def installed_env(tree: Path) -> dict[str, str]:
    """``os.environ`` with ``tree`` first on the module path and its ``tutgen`` package byte-compiled."""
    compileall.compile_dir(str(tree / "tutgen"), quiet=1)
    env = {**os.environ, "PYTHONPATH": str(tree)}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env
