"""Forward dynamics integrated step by step with scipy's ODE solvers, sampled on a fixed grid.

The state is y = (q, q_dot); y' = (q_dot, H(q)^-1 (Q - C q_dot - G)), or for a constrained spec the
q_ddot of the augmented system (:meth:`tutgen.sim.model.NumericModel.accelerations`). The solver is driven one step
at a time (``scipy.integrate`` solver classes, as ``solve_ivp`` drives them) so that a run that must
stop keeps what it has: the samples up to the last accepted step are returned with the reason
(:class:`Trajectory` ``stopped``). It stops when H is singular or badly conditioned at a state the
solver asks for, when the solver fails, and when the time budget (``seconds``) runs out.

``method="auto"`` takes DOP853 (explicit Runge-Kutta of order 8: accurate energy over long runs) unless
the system is stiff at the start, which is judged from the eigenvalues of the Jacobian of y' (by
central differences): a decay rate λ with λ (t_end - t_start) > 10^4 picks Radau (implicit, L-stable).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tutgen.sim.model import NumericModel

__all__ = ["METHODS", "STIFFNESS", "Trajectory", "choose_method", "integrate"]

METHODS = ("auto", "DOP853", "RK45", "Radau", "BDF", "LSODA")
#: λ (t_end - t_start) above which the start is called stiff.
STIFFNESS = 1e4
#: The condition number of H above which the state counts as singular (for one coordinate: H this many
#: times smaller than at the start).
SINGULAR_CONDITION = 1e12


class _Singular(Exception):
    def __init__(self, t: float, q: np.ndarray, condition: float) -> None:
        self.t, self.q, self.condition = t, q, condition
        super().__init__()


@dataclass(frozen=True)
class Trajectory:
    """The samples of a run: times ``t`` (m), ``q`` and ``qd`` (m x n), and the method used.

    ``stopped`` is None for a run that reached the end, else why it stopped early (the samples then
    end at the last accepted step); ``stop_time`` and ``stop_state`` say where.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    method: str
    steps: int
    evaluations: int
    stopped: str | None = None
    stop_kind: str | None = None  # "singular", "failed", "timeout"
    stop_time: float | None = None
    stop_state: tuple[float, ...] | None = None


def _derivative(model: NumericModel, n: int, counter: list[int]):  # noqa: ANN202 - a closure for scipy
    scale: list[float] = []  # |H| at the first state: a 1 x 1 H is singular when it is tiny against it

    def f(t: float, y: np.ndarray) -> np.ndarray:
        counter[0] += 1
        q, qd = y[:n], y[n:]
        h, rhs = model.accelerations(t, q, qd)
        if n > 1:
            condition = np.linalg.cond(h)
        else:
            if not scale:
                scale.append(abs(float(h[0, 0])))
            condition = scale[0] / abs(float(h[0, 0])) if h[0, 0] != 0 else np.inf
        if not np.isfinite(condition) or condition > SINGULAR_CONDITION or not np.all(np.isfinite(rhs)):
            raise _Singular(t, q.copy(), float(condition))
        # a constrained spec's solve gives (q_ddot, lambda): the state needs q_ddot
        return np.concatenate([qd, np.linalg.solve(h, rhs)[:n]])

    return f


def choose_method(model: NumericModel, t0: float, t1: float, y0: np.ndarray) -> str:
    """DOP853, or Radau when the Jacobian of y' at the start has a decay rate λ with λ (t1 - t0) > 10^4."""
    n = len(y0) // 2
    f = _derivative(model, n, [0])
    jac = np.empty((2 * n, 2 * n))
    for k in range(2 * n):
        step = 1e-6 * max(1.0, abs(y0[k]))
        up, down = y0.copy(), y0.copy()
        up[k] += step
        down[k] -= step
        jac[:, k] = (f(t0, up) - f(t0, down)) / (2 * step)
    decay = max(0.0, float(np.max(-np.linalg.eigvals(jac).real)))
    return "Radau" if decay * (t1 - t0) > STIFFNESS else "DOP853"


def integrate(
    model: NumericModel,
    t0: float,
    t1: float,
    q0: np.ndarray,
    qd0: np.ndarray,
    samples: int,
    method: str = "auto",
    rtol: float = 1e-10,
    atol: float = 1e-12,
    seconds: float | None = None,
) -> Trajectory:
    """Integrate from (q0, qd0) at t0 to t1 and sample at ``samples`` equally spaced instants."""
    from scipy import integrate as si

    n = len(q0)
    y0 = np.concatenate([np.asarray(q0, float), np.asarray(qd0, float)])
    grid = np.linspace(t0, t1, samples)
    out = np.empty((samples, 2 * n))
    counter = [0]
    ends = None if not seconds else time.monotonic() + seconds
    try:
        chosen = choose_method(model, t0, t1, y0) if method == "auto" else method
        solver = getattr(si, chosen)(_derivative(model, n, counter), t0, y0, t1, rtol=rtol, atol=atol)
    except _Singular as exc:
        return _stopped(grid[:0], out[:0], n, method, 0, counter[0], exc, model.matrix_name)
    out[0] = y0
    done = 1  # samples filled
    steps = 0
    stop: tuple[str, str, float, tuple[float, ...]] | None = None
    while solver.status == "running":
        if ends is not None and time.monotonic() > ends:
            stop = ("timeout", f"the time limit of {seconds:g} s ran out", solver.t, tuple(solver.y[:n]))
            break
        try:
            message = solver.step()
        except _Singular as exc:
            return _stopped(grid[:done], out[:done], n, chosen, steps, counter[0], exc, model.matrix_name)
        steps += 1
        if solver.status == "failed":
            stop = ("failed", f"the integrator failed: {message}", solver.t, tuple(solver.y[:n]))
            break
        if done < samples and grid[done] <= solver.t:
            dense = solver.dense_output()
            upto = int(np.searchsorted(grid, solver.t, side="right"))
            out[done:upto] = dense(grid[done:upto]).T
            done = upto
    if stop is None and done < samples:  # the last grid point is t1 itself; rounding may leave it out
        out[done:] = solver.y
        done = samples
    t = grid[:done]
    return Trajectory(
        t=t,
        q=out[:done, :n],
        qd=out[:done, n:],
        method=chosen,
        steps=steps,
        evaluations=counter[0],
        stopped=stop[1] if stop else None,
        stop_kind=stop[0] if stop else None,
        stop_time=stop[2] if stop else None,
        stop_state=stop[3] if stop else None,
    )


def _stopped(
    t: np.ndarray,
    y: np.ndarray,
    n: int,
    method: str,
    steps: int,
    evaluations: int,
    exc: _Singular,
    matrix: str = "the mass matrix H",
) -> Trajectory:
    condition = "infinite" if not np.isfinite(exc.condition) else f"{exc.condition:.3g}"
    return Trajectory(
        t=t,
        q=y[:, :n],
        qd=y[:, n:],
        method=method,
        steps=steps,
        evaluations=evaluations,
        stopped=f"{matrix} is singular at t = {exc.t:.6g} s (condition number {condition})",
        stop_kind="singular",
        stop_time=exc.t,
        stop_state=tuple(float(v) for v in exc.q),
    )
