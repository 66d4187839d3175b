"""A constrained spec's simulation: the consistent initial state, and the residuals and multipliers along
the run (docs/simulate.md, "Constrained specs").

The integration itself is that of every spec (tutgen/sim/integrate.py) on the state (q, q_dot) of all n
coordinates, with the accelerations of the index-reduced DAE H q_ddot + C + G = Q + A^T lambda,
A q_ddot + b = 0 stabilised after Baumgarte (:meth:`tutgen.sim.model.NumericModel.accelerations`).

The initial state: the independent coordinates and their rates as given; the dependent coordinates that
the position constraints fix are solved from them by the engine's solver,
:func:`tutgen.engine.constraints.kinematics.solve_positions` (the damped Gauss-Newton that also finds the
derivation's consistent states), starting from the values given for them, if any (which picks the
branch: a four-bar's open or crossed assembly). Without a value given, the start is the branch the
figure shows (:func:`tutgen.figure.build.drawn_branch`: for a four-bar the same assembly, open or
crossed, at the simulation's lengths; for another loop the same sign of its closed form), or, when the
position analysis has no closed form, the figure's values of those coordinates. The dependent rates
follow from A q_dot = 0, A_d q_dot_d = -A_i q_dot_i.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping

import numpy as np
import sympy as sp

from tutgen.engine.constraints.kinematics import solve_positions
from tutgen.engine.constraints.positions import branch_values
from tutgen.engine.derivation import Derivation
from tutgen.sim.model import NumericModel

__all__ = ["BAUMGARTE", "baumgarte_rate", "consistent_start", "position_unknowns", "residuals_and_multipliers"]

#: The Baumgarte rate alpha is this many over the interval's length: the residual's errors decay over a
#: tenth of the run, slowly enough that the stabilisation never makes the system stiff (alpha (t1 - t0)
#: = 10, far below the stiffness test's 10^4), fast enough that they cannot accumulate.
BAUMGARTE = 10.0


def baumgarte_rate(t0: float, t1: float) -> float:
    """alpha (1/s) for a run from t0 to t1."""
    return BAUMGARTE / (t1 - t0)


def position_unknowns(derivation: Derivation) -> tuple[int, ...]:
    """The coordinates (indices) that the position constraints fix: the dependent ones they use, as many as
    there are position constraints (the engine's choice, tutgen/engine/constraints/kinematics.py)."""
    assert derivation.constraints is not None
    ck = derivation.constraints.kinematics
    coords = derivation.system.coordinates
    position = [f for f, c in zip(ck.functions, ck.constraints, strict=True) if c.kind.value == "position"]
    used = [j for j in ck.dependent if any(coords[j].q in f.free_symbols for f in position)]
    return tuple(used[: len(position)])


def consistent_start(
    derivation: Derivation,
    model: NumericModel,
    t0: float,
    q: np.ndarray,
    qd: np.ndarray,
    values: Mapping[str, float] | None = None,
    guessed: Collection[str] = (),
) -> tuple[np.ndarray, np.ndarray] | None:
    """(q, q_dot) with the position-fixed coordinates solved and the dependent rates from A q_dot = 0;
    None when the position constraints have no root from the start.

    ``values`` are the parameters' numbers (by name; default: those of the numeric model), ``guessed``
    the coordinates whose entry of ``q`` was not given (their start is then the figure's branch, see the
    module's docstring); the others start from their entries of ``q``."""
    assert derivation.constraints is not None and model.constraint_jacobian is not None
    ck = derivation.constraints.kinematics
    system = derivation.system
    coords = system.coordinates
    q, qd = np.array(q, dtype=float), np.array(qd, dtype=float)
    numbers: dict[sp.Symbol, float] = {}
    by_name = dict(values) if values is not None else {}
    for par in system.parameters:
        if par.name in by_name:
            numbers[par.symbol] = float(by_name[par.name])
    numbers |= {c.q: float(q[j]) for j, c in enumerate(coords)}
    fixed = list(position_unknowns(derivation))
    if fixed:
        start = {coords[j].q: float(q[j]) for j in fixed}
        if all(coords[j].name in guessed for j in fixed):
            start |= _figure_start(derivation, numbers, fixed)
        try:
            solved = solve_positions(system, ck, numbers, start)
        except KeyError:  # a number is missing (a parameter that is an input): no root from here
            return None
        if solved is None:
            return None
        for j in fixed:
            q[j] = solved[coords[j].q]
    p = model.parameters(t0, q, qd)
    a = np.asarray(model.constraint_jacobian(q, p), dtype=float)
    dep, ind = list(ck.dependent), list(ck.independent)
    qd[dep] = np.linalg.solve(a[:, dep], -a[:, ind] @ qd[ind])
    return q, qd


def _figure_start(
    derivation: Derivation, numbers: Mapping[sp.Symbol, float], fixed: list[int]
) -> dict[sp.Symbol, float]:
    """Where the solve starts for the coordinates ``fixed`` when no value is given for them: on the
    branch the figure shows (see the module's docstring); empty when there is none to follow."""
    from tutgen.figure.build import drawn_branch, drawn_values

    assert derivation.constraints is not None
    ck = derivation.constraints.kinematics
    system = derivation.system
    coords = [c.q for c in system.coordinates]
    if ck.positions:  # solved in closed form, one branch: any start reaches it
        return {}
    if ck.loop is None:
        drawn = drawn_values(system)
        return {coords[j]: drawn[coords[j]] for j in fixed if coords[j] in drawn}
    shown = drawn_branch(system, ck.loop)
    if shown is None:
        return {}
    sign, assembly = shown
    return branch_values(ck.loop, numbers, coords, sign, assembly) or {}


def residuals_and_multipliers(
    model: NumericModel, t: np.ndarray, q: np.ndarray, qd: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The constraints' residuals (samples x m: f_k(q) or a_k(q) . q_dot) and the multipliers lambda of the
    integrated (stabilised) accelerations at each sample."""
    assert model.residual is not None
    n, m = q.shape[1], len(model.constraints)
    residuals = np.empty((len(t), m))
    multipliers = np.empty((len(t), m))
    for k in range(len(t)):
        p = model.parameters(float(t[k]), q[k], qd[k])
        residuals[k] = model.residual(q[k], qd[k], p)
        h, rhs = model.accelerations(float(t[k]), q[k], qd[k])
        multipliers[k] = np.linalg.solve(h, rhs)[n:]
    return residuals, multipliers
