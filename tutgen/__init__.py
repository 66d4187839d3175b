"""tutgen: worked solutions for rigid-body and robot dynamics problems from a YAML spec.

The Python API is the command line's pipeline, one function a stage (docs/api.md):

- :func:`load` (a spec file) or :func:`loads` (a spec's text) -> a validated ``System``, or
  :class:`tutgen.errors.SpecErrors` naming each problem at its file:line:col;
- :func:`derive` -> a ``Derivation``: every intermediate result, as sympy expressions;
- :func:`render` -> the worked solution as Markdown, LaTeX, JSON (text) or PDF (bytes);
- :func:`check` -> the marks of answers files against a spec (a ``CheckRun``).

>>> import tutgen
>>> system = tutgen.loads('''
... tutgen: 1
... title: Block on a spring
... parameters: [m, k]
... coordinates: [x]
... bodies: {block: {mass: m}}
... joints: {slide: {type: prismatic, parent: ground, child: block, axis: x, coordinate: x}}
... springs: {wall: {stiffness: k, extension: x}}
... ''')
>>> d = tutgen.derive(system)
>>> d.mass_matrix
Matrix([[m]])
>>> d.equations_of_motion
Matrix([[k*x + m*x_ddot]])
>>> import json
>>> json.loads(tutgen.render(d, "json"))["results"]["kinetic_energy"]
'm*x_dot**2/2'

The names are imported on first use, so ``import tutgen`` (and ``tutgen --help``) stays fast.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from tutgen.version import __version__

__all__ = ["__version__", "check", "derive", "load", "loads", "render"]

if TYPE_CHECKING:  # pragma: no cover
    from tutgen.api import derive, load, loads


def __getattr__(name: str) -> Any:
    """``load``, ``loads`` and ``derive`` on first use. ``render`` and ``check`` are the subpackages
    tutgen.render and tutgen.check themselves, made callable (a function of the same name would be
    replaced by the subpackage as soon as it is imported): calling them calls tutgen.api's functions."""
    if name in ("derive", "load", "loads"):
        from tutgen import api

        return getattr(api, name)
    if name in ("check", "render"):
        import importlib

        return importlib.import_module(f"tutgen.{name}")
    raise AttributeError(f"module 'tutgen' has no attribute {name!r}")
