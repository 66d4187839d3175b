"""Generated code of constrained specs (issue 19 with issue 21's constraints) against the derivation.

The generated ``forward_dynamics`` solves the augmented system [[H, -A^T], [A, 0]] [q_ddot; lambda] =
[tau + Q - C q_dot - G; -b]. The reference is the other route the derivation holds: the reduced equations
H_r q_ddot_i + C_r + G_r = Q_r solved for q_ddot_i, q_ddot = T q_ddot_i + T_dot q_dot_i, and lambda from the
dependent rows (tutgen/engine/constraints/dynamics.py), evaluated by sympy at consistent states that the
engine's own solve finds (``consistent_states``). A, b and the residuals are compared with the kinematics'
entries; the C code compiles warning-free and equals the NumPy code.
"""

from __future__ import annotations

import random
import shutil
import subprocess
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import sympy as sp

from tests.codegen.compiled import GCC, CModel, compile_c, derived_lagrange
from tests.conftest import ROOT
from tutgen.codegen.printers import LANGUAGES, generate_code
from tutgen.codegen.program import build_program
from tutgen.engine.constraints import with_loop_closures
from tutgen.engine.constraints.kinematics import consistent_states
from tutgen.sim.model import _compile

SPECS = {
    "disc": "specs/examples/l-disc-rolling-down-incline.yaml",
    "coin": "specs/examples/m-vertical-rolling-coin.yaml",
    "slider-crank": "specs/examples/o-slider-crank.yaml",
}
STATES = 3
RTOL = 1e-9


_derived = derived_lagrange


@cache
def _source(rel: str, language: str) -> str:
    return generate_code(_derived(rel), language, Path(rel).name)


def _states(rel: str) -> list[dict[sp.Symbol, float]]:
    """Consistent states: the engine's solve of the position constraints, random independent rates, the
    dependent rates from B (q_dot_d = B q_dot_i)."""
    d = _derived(rel)
    system = with_loop_closures(d.system, d.kinematics)
    ck = d.constraints.kinematics
    rng = random.Random(11)
    out = []
    for state in consistent_states(system, ck.functions, ck.dependent, STATES):
        values = {k: float(v) for k, v in state.values.items()}
        for j in ck.independent:
            values[system.coordinates[j].qd] = rng.uniform(-2, 2)
        for rate, e in ck.rates.items():
            values[rate] = float(e.xreplace(values))
        out.append(values)
    assert len(out) == STATES
    return out


def _reference(rel: str, values: dict[sp.Symbol, float]) -> tuple[np.ndarray, np.ndarray]:
    """q_ddot and lambda by the reduced route, evaluated by sympy."""
    d = _derived(rel)
    cd = d.constraints
    coords = d.system.coordinates
    ind = cd.kinematics.independent

    def num(m: sp.MatrixBase, extra: dict | None = None) -> np.ndarray:
        return np.array(sp.Matrix(m).xreplace({**values, **(extra or {})}).evalf(30), dtype=float)

    qdd_i = [coords[j].qdd for j in ind]
    zero = {s: 0 for s in qdd_i}
    h_r = num(cd.mass_matrix)
    rest = num(cd.equations_of_motion, zero).ravel()
    acc_i = np.linalg.solve(h_r, -rest)
    qdd = num(cd.kinematics.velocity_map) @ acc_i + num(cd.velocity_terms).ravel()
    acc = {c.qdd: float(v) for c, v in zip(coords, qdd, strict=True)}
    lam = np.array(
        [float(sp.sympify(e).xreplace({**values, **acc}).evalf(30)) for e in cd.multipliers_in_accelerations]
    )
    return qdd, lam


def _arguments(rel: str, values: dict[sp.Symbol, float]) -> tuple[np.ndarray, np.ndarray, dict[str, float]]:
    system = _derived(rel).system
    q = np.array([values[c.q] for c in system.coordinates])
    qd = np.array([values[c.qd] for c in system.coordinates])
    params = {p.name: float(values[p.symbol]) if p.symbol in values else float(p.value) for p in system.parameters}
    return q, qd, params


def _python(rel: str) -> dict[str, Any]:
    return _compile(_source(rel, "python"), f"constrained_{Path(rel).stem.replace('-', '_')}")


def _parameters(module: dict[str, Any], params: dict[str, float]) -> Any:
    fields = set(module["Parameters"].__dataclass_fields__)
    return module["Parameters"](**{k if k in fields else k + "_": v for k, v in params.items()})


def _relative(ours: np.ndarray, theirs: np.ndarray) -> float:
    return float(np.max(np.abs(ours - theirs)) / max(1.0, float(np.max(np.abs(theirs)))))


@pytest.mark.parametrize("rel", list(SPECS.values()), ids=list(SPECS))
def test_forward_dynamics_solves_the_augmented_system_as_the_reduced_route(rel: str) -> None:
    """q_ddot and lambda of the generated NumPy code = the reduced route's; A, b, residuals = the kinematics'."""
    module = _python(rel)
    ck = _derived(rel).constraints.kinematics
    n, m = len(_derived(rel).system.coordinates), ck.jacobian.rows
    for values in _states(rel):
        q, qd, params = _arguments(rel, values)
        p = _parameters(module, params)
        out = module["forward_dynamics"](q, qd, np.zeros(n), p)
        assert out.shape == (n + m,)
        qdd, lam = _reference(rel, values)
        assert _relative(out[:n], qdd) < RTOL
        assert _relative(out[n:], lam) < RTOL
        a = np.array(ck.jacobian.xreplace(values).evalf(30), dtype=float)
        assert _relative(module["constraint_jacobian"](q, p), a) < RTOL
        b = np.array(ck.bias.xreplace(values).evalf(30), dtype=float).ravel()
        assert _relative(module["constraint_bias"](q, qd, p), b) < RTOL
        # a consistent state: every residual (position f(q), velocity A q_dot) vanishes
        assert np.max(np.abs(module["constraint_residual"](q, qd, p))) < 1e-12
        assert np.max(np.abs(a @ qd)) < 1e-12
        # the constrained accelerations keep the acceleration constraint A q_ddot + b = 0
        assert np.max(np.abs(a @ out[:n] + b)) < 1e-9 * max(1.0, float(np.max(np.abs(out))))


def test_forward_dynamics_vectorises_over_a_batch() -> None:
    rel = SPECS["slider-crank"]
    module = _python(rel)
    states = [_arguments(rel, v) for v in _states(rel)]
    p = _parameters(module, states[0][2])  # the parameters of the first state for all
    q = np.array([s[0] for s in states])
    qd = np.array([s[1] for s in states])
    batch = module["forward_dynamics"](q, qd, np.zeros_like(q), p)
    for k in range(len(states)):
        assert np.allclose(batch[k], module["forward_dynamics"](q[k], qd[k], np.zeros(3), p), rtol=1e-13, atol=0)


@pytest.mark.skipif(GCC is None, reason="gcc is not installed")
@pytest.mark.parametrize("rel", list(SPECS.values()), ids=list(SPECS))
def test_c_forward_dynamics_compiles_warning_free_and_equals_numpy(rel: str, tmp_path: Path) -> None:
    """gcc -O2 -Wall -Wextra -std=c99 -Werror; the pivoted elimination's (q_ddot, lambda) = NumPy's."""
    derivation = _derived(rel)
    lib = compile_c(_source(rel, "c"), tmp_path, "constrained")
    c_program = build_program(derivation, "c", _c_reserved(), Path(rel).name)
    fields = [(prm.spec_name, prm.name) for prm in c_program.parameters]
    model = CModel(lib, c_program.module, c_program.n, fields)
    module = _python(rel)
    n, m = c_program.n, len(c_program.constraints)
    for values in _states(rel):
        q, qd, params = _arguments(rel, values)
        p_c = model.params(params)
        p_py = _parameters(module, params)
        out, status = model.call("forward_dynamics", p_c, q, qd, np.zeros(n), size=n + m)
        assert status == 0
        assert _relative(out, module["forward_dynamics"](q, qd, np.zeros(n), p_py)) < 1e-12
        jac, _ = model.call("constraint_jacobian", p_c, q, size=m * n)
        assert _relative(jac.reshape(m, n), module["constraint_jacobian"](q, p_py)) < 1e-13
        bias, _ = model.call("constraint_bias", p_c, q, qd, size=m)
        assert _relative(bias, module["constraint_bias"](q, qd, p_py)) < 1e-13


def _c_reserved() -> frozenset[str]:
    return LANGUAGES["c"][1]()


def test_header_names_the_constraints_and_the_augmented_system() -> None:
    for language in ("python", "c", "matlab", "julia"):
        text = _source(SPECS["slider-crank"], language)
        assert (
            "Constraints (the rows of A, the entries of lambda, in this order): B_x (position), B_y (position)." in text
        )
        assert "[[H, -A^T], [A, 0]] [q_ddot; lambda] = [tau + Q - C q_dot - G; -b]" in text, language


OCTAVE = shutil.which("octave-cli")


@pytest.mark.slow
@pytest.mark.skipif(OCTAVE is None, reason="octave-cli is not installed (Debian: apt-get install octave)")
def test_matlab_forward_dynamics_runs_in_octave_and_equals_numpy(tmp_path: Path) -> None:
    """The backslash solve of the augmented system, A, b and the residuals under GNU Octave = NumPy's."""
    rel = SPECS["slider-crank"]
    program = build_program(_derived(rel), "matlab", LANGUAGES["matlab"][1](), Path(rel).name)
    (tmp_path / f"{program.module}.m").write_text(_source(rel, "matlab"), encoding="utf-8")
    module = _python(rel)
    states = [_arguments(rel, v) for v in _states(rel)]
    n = program.n
    calls = [("forward_dynamics", "q, qd, zeros(3, 1)"), ("constraint_jacobian", "q"), ("constraint_bias", "q, qd")]
    lines = [f"dyn = {program.module}();"]
    for k, (q, qd, params) in enumerate(states):
        lines += ["p = dyn.params;"]
        lines += [f"p.{prm.name} = {float(params[prm.spec_name])!r};" for prm in program.parameters]
        lines += [f"q = [{'; '.join(repr(float(v)) for v in q)}];", f"qd = [{'; '.join(repr(float(v)) for v in qd)}];"]
        for fn, args in calls:
            lines.append(
                f"r = dyn.{fn}({args}, p); printf('{k} {fn}'); printf(' %.17g', reshape(r.', 1, [])); printf('\\n');"
            )
    (tmp_path / "driver.m").write_text("\n".join(lines) + "\n", encoding="utf-8")
    run = subprocess.run(
        [OCTAVE, "--no-gui", "--norc", "--no-history", "--quiet", "--eval", "driver"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert run.returncode == 0 and not run.stderr.strip(), run.stderr
    got = {}
    for line in run.stdout.splitlines():
        k, fn, *numbers = line.split()
        got[int(k), fn] = np.array([float(x) for x in numbers])
    assert len(got) == len(states) * len(calls)
    for k, (q, qd, params) in enumerate(states):
        p = _parameters(module, params)
        assert _relative(got[k, "forward_dynamics"], module["forward_dynamics"](q, qd, np.zeros(n), p)) < 1e-12
        assert _relative(got[k, "constraint_jacobian"], module["constraint_jacobian"](q, p).ravel()) < 1e-13
        assert _relative(got[k, "constraint_bias"], module["constraint_bias"](q, qd, p)) < 1e-13


def test_the_linear_model_of_a_constrained_spec_is_refused_not_wrong() -> None:
    from typer.testing import CliRunner

    from tutgen.cli.main import app
    from tutgen.errors import EXIT_CANNOT_DERIVE

    result = CliRunner().invoke(app, ["code", str(ROOT / SPECS["disc"]), "-l", "python", "--linear"])
    assert result.exit_code == EXIT_CANNOT_DERIVE, result.output
    assert "l-disc-rolling-down-incline.yaml:" in result.stderr
    assert "`tutgen code --linear` does not handle `constraints`" in result.stderr
    assert "Traceback" not in result.output


def test_disc_forward_dynamics_equals_sympy_mechanics_lagranges_method() -> None:
    """Independently of tutgen's derivation: the disc built with sympy's frames, ``LagrangesMethod`` with
    ``hol_coneqs``, M_full [q_dot; q_ddot; lambda] = f_full solved at consistent states (sympy's lambda
    is tutgen's for a constraint as written: tests/engine/test_constraints.py)."""
    from sympy.physics.mechanics import (
        LagrangesMethod,
        Lagrangian,
        Point,
        ReferenceFrame,
        RigidBody,
        dynamicsymbols,
        inertia,
    )

    m, r, g, alpha = sp.symbols("m R g alpha", positive=True)
    x, phi = dynamicsymbols("x phi")
    t = dynamicsymbols._t
    frame = ReferenceFrame("N")
    body = frame.orientnew("B", "Axis", (-phi, frame.z))
    o = Point("O")
    o.set_vel(frame, 0)
    c = o.locatenew("C", x * (sp.cos(alpha) * frame.x - sp.sin(alpha) * frame.y))
    c.set_vel(frame, c.pos_from(o).dt(frame))
    disc = RigidBody("disc", c, body, m, (inertia(body, m * r**2 / 4, m * r**2 / 4, m * r**2 / 2), c))
    disc.potential_energy = m * g * c.pos_from(o).dot(frame.y)
    lm = LagrangesMethod(Lagrangian(frame, disc), [x, phi], hol_coneqs=[x - r * phi], frame=frame)
    lm.form_lagranges_equations()
    module = _python(SPECS["disc"])
    rng = random.Random(5)
    for _ in range(3):
        values = {"m": rng.uniform(0.5, 2), "R": rng.uniform(0.5, 2), "g": 9.81, "alpha": rng.uniform(0.1, 1.2)}
        ph, phd = rng.uniform(-2, 2), rng.uniform(-2, 2)
        q = np.array([values["R"] * ph, ph])
        qd = np.array([values["R"] * phd, phd])
        subs = {m: values["m"], r: values["R"], g: values["g"], alpha: values["alpha"]}
        subs |= {x: q[0], phi: q[1], x.diff(t): qd[0], phi.diff(t): qd[1]}
        ref = np.array(lm.mass_matrix_full.subs(subs).LUsolve(lm.forcing_full.subs(subs)), dtype=float).ravel()
        out = module["forward_dynamics"](q, qd, np.zeros(2), _parameters(module, values))
        assert _relative(out, ref[2:]) < RTOL  # q_ddot (x, phi) and lambda
