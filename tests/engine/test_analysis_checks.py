"""Issue 18 point 6 and "How it is measured": the checks of the linear models.

- Energy: a linear model without damping and with K symmetric conserves
  E = 1/2 dq_dot^T M dq_dot + 1/2 dq^T K dq, exactly (A^T W + W A = 0 with W = diag(K, M), so dE/dt =
  1/2 x^T (A^T W + W A) x = 0) and along a numerical integration of x_dot = A x (scipy), which can fail:
  a model given damping drifts.
- Every spec in specs/ that has an equilibrium: tutgen's state matrix A about each equilibrium against
  ``KanesMethod.linearize`` of a sympy.physics.mechanics twin built from the validated model alone
  (tests/engine/test_mechanics_generic.py), parameters without a value at random positive numbers and
  the inputs at 0. The specs that ask for equilibria or a linear model run by default; the others
  (their equilibria searched for here) under ``-m slow``; a spec without bodies, with constraints, or
  with no isolated equilibrium is skipped with its reason.
"""

from __future__ import annotations

import dataclasses
import random
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import sympy as sp
import yaml

from tests.conftest import HEAVY_SPECS, ROOT, all_specs, solved
from tests.engine.test_mechanics_generic import MechanicsModel
from tutgen.engine.pipeline import derive
from tutgen.model.system import Ask
from tutgen.spec.validate import load_system


def _values(system: Any, seed: int = 6) -> dict[str, float]:
    """By name: each parameter's value, else a random positive number (an input, a force's symbol that
    is not declared positive, at 0: as tutgen holds it at an equilibrium)."""
    rng = random.Random(seed)
    out = {}
    for p in system.parameters:
        if p.value is not None:
            out[p.name] = float(p.value)
        else:
            out[p.name] = rng.uniform(0.7, 1.6) if p.symbol.is_positive else 0.0
    return out


def _array(d: Any, m: sp.MatrixBase, values: dict[str, float]) -> np.ndarray:
    subs = {p.symbol: values[p.name] for p in d.system.parameters}
    return np.array(sp.Matrix(d.numeric(m)).xreplace(subs).evalf().tolist(), dtype=float)


# ---------------------------------------------------------------------------------------------
# Energy of the linear model
# ---------------------------------------------------------------------------------------------


def _energy_drift(m: np.ndarray, k: np.ndarray, a: np.ndarray, x0: np.ndarray, t: float = 2.0) -> float:
    """max |E(t) - E(0)| along x_dot = A x, relative to the largest of the two terms of E seen."""
    from scipy.integrate import solve_ivp

    n = m.shape[0]
    sol = solve_ivp(lambda _, x: a @ x, (0.0, t), x0, rtol=1e-12, atol=1e-14, dense_output=False, max_step=t / 200)
    energies, scale = [], 0.0
    for x in sol.y.T:
        dq, dv = x[:n], x[n:]
        kinetic, potential = 0.5 * dv @ m @ dv, 0.5 * dq @ k @ dq
        energies.append(kinetic + potential)
        scale = max(scale, abs(kinetic), abs(potential))
    return max(abs(e - energies[0]) for e in energies) / scale


CONSERVATIVE = [
    str(ROOT / "specs" / "examples" / name)
    for name in ("h-inverted-pendulum-cart.yaml", "i-bead-spinning-hoop.yaml", "j-two-mass-chain-modes.yaml")
]


@pytest.mark.parametrize("path", CONSERVATIVE, ids=lambda p: Path(p).stem)
def test_linear_model_conserves_its_energy(path: str) -> None:
    _, d, _ = solved(path)
    models = {id(m): m for m in (*d.analysis.classified, *d.analysis.linear)}.values()
    checked = 0
    for model in models:
        damping = sp.Matrix(d.numeric(model.damping))
        stiffness = sp.Matrix(d.numeric(model.stiffness))
        if damping != sp.zeros(*damping.shape) or (stiffness - stiffness.T).applyfunc(sp.simplify) != sp.zeros(
            *stiffness.shape
        ):
            continue
        n = stiffness.shape[0]
        w = sp.diag(stiffness, sp.Matrix(d.numeric(model.mass)))
        a = sp.Matrix(d.numeric(model.state_matrix))
        assert (a.T * w + w * a).applyfunc(sp.simplify) == sp.zeros(2 * n), model.about
        values = _values(d.system)
        m_, k_, a_ = (_array(d, x, values) for x in (model.mass, model.stiffness, model.state_matrix))
        x0 = np.random.default_rng(3).uniform(-0.1, 0.1, 2 * n)
        assert _energy_drift(m_, k_, a_, x0) < 1e-8, model.about
        # the check can fail: the same model with damping loses energy
        damped = a_.copy()
        damped[n:, n:] -= np.linalg.solve(m_, 0.3 * np.eye(n))
        assert _energy_drift(m_, k_, damped, x0) > 1e-4
        checked += 1
    assert checked


# ---------------------------------------------------------------------------------------------
# Every spec with an equilibrium against Kane's linearisation
# ---------------------------------------------------------------------------------------------


def _why_not(data: Any) -> str | None:
    """Why a spec has no linear model to compare, read from its YAML alone (cheap), or None."""
    if not isinstance(data, dict) or not data.get("coordinates"):
        return "no coordinates: nothing moves"
    if not (data.get("bodies") or data.get("arm")):
        return "no bodies (the spec gives its energy): no mechanics twin to compare with"
    if data.get("constraints") or any(
        isinstance(j, dict) and j.get("closes_loop") for j in (data.get("joints") or {}).values()
    ):
        return "constrained: its equilibria live on the constraint manifold (docs/constraints.md)"
    return None


def _specs() -> list[Any]:
    out = []
    for path in all_specs():
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
        reason = _why_not(data)
        asked = set(data.get("ask") or []) & {"equilibria", "linearization"} if isinstance(data, dict) else set()
        marks: Any = ()
        if (reason is None and not asked) or path.stem in HEAVY_SPECS or path.stem == "puma560-numeric":
            marks = pytest.mark.slow
        name = path.relative_to(ROOT / "specs").with_suffix("").as_posix()
        out.append(pytest.param(path, reason, id=name, marks=marks))
    return out


def _kane_state_matrix(system: Any, about: dict[str, float], values: dict[str, float]) -> np.ndarray:
    from sympy.physics.mechanics import KanesMethod

    model = MechanicsModel(system)
    bodies, loads = model.bodies_and_loads()
    if any(e != 0 for e in model.extra_forces()):
        pytest.skip("a force the twin cannot apply as a load (a generalized force)")
    kd = [q.diff(model.t) - u for q, u in zip(model.qs, model.us, strict=True)]
    km = KanesMethod(model.n_frame, q_ind=model.qs, u_ind=model.us, kd_eqs=kd)
    km.kanes_equations(bodies, loads)
    op = {q: about[c.name] for q, c in zip(model.qs, system.coordinates, strict=True)}
    op |= {u: 0 for u in model.us} | {u.diff(model.t): 0 for u in model.us}
    a, _, _ = km.linearize(op_point=op, A_and_B=True, simplify=False)
    ref = {sp.Symbol(k): v for k, v in values.items()}
    return np.array(sp.Matrix(a).xreplace(ref).subs(op).evalf().tolist(), dtype=float)


@pytest.mark.parametrize(("path", "reason"), _specs())
def test_linear_model_matches_kane_for_every_spec_with_an_equilibrium(path: Path, reason: str | None) -> None:
    if reason is not None:
        pytest.skip(reason)
    system = load_system(path)
    if not system.ask & {Ask.EQUILIBRIA, Ask.LINEARIZATION}:
        system = dataclasses.replace(system, ask=system.ask | {Ask.EQUILIBRIA})
    d = derive(system)
    models = {id(m): m for m in (*d.analysis.classified, *d.analysis.linear)}.values()
    values = _values(system)
    subs = {p.symbol: values[p.name] for p in system.parameters}
    compared = 0
    for model in models:
        try:
            about = {name: float(sp.N(d.numeric(sp.sympify(v)).xreplace(subs))) for name, v in model.about}
        except TypeError:
            continue  # an equilibrium that does not exist at these values (acos of more than 1)
        if model.state_matrix.shape == (0, 0):  # H(q0) singular (the top's pole): Kane's linearize fails too
            assert model.verdict == "undetermined"
            continue
        theirs = _kane_state_matrix(system, about, values)
        ours = _array(d, model.state_matrix, values)
        assert np.allclose(ours, theirs, rtol=1e-9, atol=1e-9), (model.about, ours, theirs)
        compared += 1
    if not compared:
        pytest.skip("no isolated equilibrium to linearise about")
