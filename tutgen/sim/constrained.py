"""A constrained spec's simulation: the consistent initial state, and the residuals and multipliers along
the run (docs/simulate.md, "Constrained specs").

The integration itself is that of every spec (tutgen/sim/integrate.py) on the state (q, q_dot) of all n
coordinates, with the accelerations of the index-reduced DAE H q_ddot + C + G = Q + A^T lambda,
A q_ddot + b = 0 stabilised after Baumgarte (:meth:`tutgen.sim.model.NumericModel.accelerations`).

The initial state: the independent coordinates and their rates as given; the dependent coordinates that
the position constraints fix are solved from them by damped Gauss-Newton (Levenberg-Marquardt) starting
from the values given for them, if any (which picks the branch: a four-bar's open or crossed assembly),
else from 0; the dependent rates follow from A q_dot = 0, A_d q_dot_d = -A_i q_dot_i. The solve works on
the generated functions the run integrates (the residuals and A of :mod:`tutgen.codegen`), in floats, so
the start satisfies the very constraints whose residual the run reports.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from tutgen.engine.derivation import Derivation
from tutgen.sim.model import NumericModel

__all__ = ["BAUMGARTE", "baumgarte_rate", "consistent_start", "position_unknowns", "residuals_and_multipliers"]

#: The Baumgarte rate alpha is this many over the interval's length: the residual's errors decay over a
#: tenth of the run, slowly enough that the stabilisation never makes the system stiff (alpha (t1 - t0)
#: = 10, far below the stiffness test's 10^4), fast enough that they cannot accumulate.
BAUMGARTE = 10.0
#: |f| below this (relative to 1 + max |q|) is a root; the Gauss-Newton solve's steps.
_ROOT_TOLERANCE = 1e-13
_ITERATIONS = 100


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


def _position_rows(model: NumericModel) -> list[int]:
    return [k for k, (_, kind) in enumerate(model.constraints) if kind == "position"]


def consistent_start(
    derivation: Derivation, model: NumericModel, t0: float, q: np.ndarray, qd: np.ndarray
) -> tuple[np.ndarray, np.ndarray] | None:
    """(q, q_dot) with the position-fixed coordinates solved (starting from their entries of ``q``) and the
    dependent rates from A q_dot = 0; None when the position constraints have no root from that start."""
    assert derivation.constraints is not None and model.residual is not None
    assert model.constraint_jacobian is not None
    ck = derivation.constraints.kinematics
    q, qd = np.array(q, dtype=float), np.array(qd, dtype=float)
    p = model.parameters(t0, q, qd)
    rows, unknown = _position_rows(model), list(position_unknowns(derivation))
    if rows:
        solved = _gauss_newton(model, p, q, qd, rows, unknown)
        if solved is None:
            return None
        q = solved
        p = model.parameters(t0, q, qd)
    a = np.asarray(model.constraint_jacobian(q, p), dtype=float)
    dep, ind = list(ck.dependent), list(ck.independent)
    qd[dep] = np.linalg.solve(a[:, dep], -a[:, ind] @ qd[ind])
    return q, qd


def _gauss_newton(
    model: NumericModel, p: Any, q: np.ndarray, qd: np.ndarray, rows: list[int], unknown: list[int]
) -> np.ndarray | None:
    """Damped Gauss-Newton on the position constraints' residuals in the coordinates ``unknown``: each step
    solves (J^T J + mu I) dx = J^T r, mu shrinking after a step that lowers |r| and growing after one that
    does not."""
    assert model.residual is not None and model.constraint_jacobian is not None

    def residual(x: np.ndarray) -> np.ndarray:
        values = model.residual(x, qd, p)
        return np.array([values[k] for k in rows], dtype=float)

    x = q.copy()
    r = residual(x)
    mu = 1e-3
    tolerance = _ROOT_TOLERANCE * (1 + float(np.max(np.abs(q))))
    with np.errstate(all="ignore"):
        for _ in range(_ITERATIONS):
            if not np.all(np.isfinite(r)):
                return None
            if float(np.linalg.norm(r)) <= tolerance:
                return x
            j = np.asarray(model.constraint_jacobian(x, p), dtype=float)[np.ix_(rows, unknown)]
            step = np.linalg.solve(j.T @ j + mu * np.eye(len(unknown)), j.T @ r)
            trial = x.copy()
            trial[unknown] -= step
            r_trial = residual(trial)
            if float(np.linalg.norm(r_trial)) < float(np.linalg.norm(r)):
                x, r, mu = trial, r_trial, mu / 3
            else:
                mu *= 4
    return None


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
