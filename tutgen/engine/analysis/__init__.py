"""Beyond the equations of motion (issue 18): equilibria, the linear model about each, momentum and
steady motion (:mod:`.steady`).

:func:`analyse` reads a :class:`~tutgen.engine.derivation.Derivation` whose equations of motion are
derived and returns an :class:`Analysis`: the rest configurations (:mod:`.equilibria`) and the linear
model about the spec's `analysis.about` or about each equilibrium found (:mod:`.linear`), each with its
stability verdict. The pipeline stores it in ``Derivation.analysis`` when ``ask`` names `equilibria` or
`linearization`.
"""

from __future__ import annotations

from dataclasses import dataclass

from tutgen.engine.analysis.equilibria import Equilibria, check_given, find_equilibria, rest_residual
from tutgen.engine.analysis.linear import LinearModel, Mode, linearize
from tutgen.engine.analysis.momentum import Momentum, momentum
from tutgen.engine.analysis.steady import SteadyMotion, SteadyState, steady_motion
from tutgen.engine.derivation import Derivation

__all__ = [
    "MAX_LINEARIZED",
    "Analysis",
    "Equilibria",
    "LinearModel",
    "Mode",
    "Momentum",
    "SteadyMotion",
    "SteadyState",
    "analyse",
]

#: at most this many equilibria found are linearised (a spec names the one it wants with `about`)
MAX_LINEARIZED = 6


@dataclass(frozen=True)
class Analysis:
    """The equilibria (None when not asked for) with the linear model that classifies each
    (``classified``, in the order of ``equilibria.solutions``), and the linear models of
    `linearization` (``linear``: about the spec's `about`, or about each equilibrium found)."""

    equilibria: Equilibria | None
    classified: tuple[LinearModel, ...]
    linear: tuple[LinearModel, ...]
    momentum: Momentum | None = None  # `ask: [momentum]`
    steady: SteadyMotion | None = None  # `ask: [steady_motion]`


def analyse(
    d: Derivation, equilibria: bool, linearization: bool, with_momentum: bool = False, steady: bool = False
) -> Analysis:
    """The equilibria, the linear models, the momenta and the steady motions a derivation asks for (see
    the module's docstring)."""
    system = d.system
    mo = momentum(d) if with_momentum else None
    st = steady_motion(d) if steady else None
    if not (equilibria or linearization):
        return Analysis(None, (), (), mo, st)
    about = system.analysis.about if system.analysis is not None else None
    found = find_equilibria(d) if equilibria or about is None else None
    if found is None:
        check_given(d, rest_residual(d))
    classified = tuple(linearize(d, p) for p in found.solutions[:MAX_LINEARIZED]) if found is not None else ()
    linear: tuple[LinearModel, ...] = ()
    if linearization:
        linear = (linearize(d, about),) if about is not None else classified
    return Analysis(found if equilibria else None, classified if equilibria else (), linear, mo, st)
