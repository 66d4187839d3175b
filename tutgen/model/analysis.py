"""The spec's `analysis:` section as a model value: where equilibria and linear models are taken."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from tutgen.errors import Location


@dataclass(frozen=True)
class Analysis:
    """The equilibrium a linearisation is taken about and the inputs, as the spec gives them.

    ``about`` maps every coordinate name to its value at the equilibrium (the coordinates the spec does
    not name are at 0), or is None when the spec names none (each equilibrium found is linearised).
    ``inputs`` are the parameters without a value that are inputs u, with their value at the
    equilibrium (SI, exact; parameters with values may appear). ``origin`` is where the section was
    written; ``places`` where each entry was, by ``"about.theta"``, ``"inputs.F"``, ``"steady.phi"``.
    """

    about: tuple[tuple[str, sp.Expr], ...] | None
    inputs: tuple[tuple[sp.Symbol, sp.Expr], ...]
    origin: Location
    places: tuple[tuple[str, Location], ...] = ()
    # `steady`: the cyclic coordinates of `ask: [steady_motion]` by name with their constant rate (SI,
    # exact), or None when the spec names none (every cyclic coordinate, at its own rate symbol)
    steady: tuple[tuple[str, sp.Expr], ...] | None = None

    def place(self, key: str) -> Location:
        """Where ``key`` ("about.theta") was written, or the section itself."""
        return dict(self.places).get(key, self.origin)
