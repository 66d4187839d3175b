"""Generated code against tutgen's symbolic results, against Pinocchio, and compiled (issue 19).

- The NumPy code of small specs equals the derivation's H, C q_dot, C, G, Q, U (evaluated by sympy
  with the same random parameter values), inverse and forward dynamics, to 1e-10 relative, at random
  states; one call on a batch equals the calls state by state.
- The C code compiles with ``gcc -O2 -Wall -Wextra -std=c99 -Werror`` and, called through ctypes,
  equals the NumPy code (so, the derivation) to 1e-10.
- For every spec Pinocchio can model (tests/engine/pinocchio_model.py), H equals ``crba`` and
  inverse dynamics (with Q and the springs taken back off) equals ``rnea``; the numeric PUMA 560 also
  through the C code.
- Names: spec names that are keywords of a language are renamed and listed in the header; no title,
  statement or description text reaches the code.
"""

from __future__ import annotations

import random
import sys
import types
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from tests.codegen.compiled import GCC, CModel, code, compile_c, derived, python_module
from tests.conftest import ROOT, all_specs
from tutgen.codegen.printers import LANGUAGES, generate_code
from tutgen.codegen.program import build_program, module_name
from tutgen.engine.pipeline import derive
from tutgen.spec.validate import load_system_text

RTOL = 1e-10
SMALL = [
    "specs/tutorial-1/p03-cart-pendulum.yaml",
    "specs/tutorial-1/p04-rp-arm.yaml",
    "specs/tutorial-1/p05-rr-arm.yaml",
    "specs/tutorial-1/p08-spatial-rr.yaml",
    "specs/examples/e-bead-in-rotating-tube.yaml",
    "specs/examples/f-two-mass-chain.yaml",
]
PUMA = "specs/arms/puma560-numeric.yaml"


def _path(rel: str) -> str:
    return str(ROOT / rel)


def relative(ours: np.ndarray, theirs: np.ndarray) -> float:
    """max |ours - theirs| over max(1, max |theirs|)."""
    return float(np.max(np.abs(np.asarray(ours) - np.asarray(theirs))) / max(1.0, float(np.max(np.abs(theirs)))))


def random_values(system, seed: int) -> dict[str, float]:
    rng = random.Random(seed)
    return {p.name: float(p.value) if p.value is not None else rng.uniform(0.5, 2.0) for p in system.parameters}


def _params(module, values: dict[str, float]):
    """The generated Parameters from values by spec name (a keyword of Python gets its '_')."""
    fields = {f.name for f in module.Parameters.__dataclass_fields__.values()}
    named = {k if k in fields else k + "_": v for k, v in values.items()}
    return module.Parameters(**{k: v for k, v in named.items() if k in fields})


def _symbolic(derivation, values: dict[str, float], q, qd, qdd):
    """H, C q_dot, C, G, Q, U from the derivation itself, by sympy substitution."""
    system = derivation.system
    subs = {p.symbol: sp.Float(values[p.name], 30) for p in system.parameters}
    for c, a, b, d in zip(system.coordinates, q, qd, qdd, strict=True):
        subs |= {c.q: sp.Float(a, 30), c.qd: sp.Float(b, 30), c.qdd: sp.Float(d, 30)}

    def num(m):
        return np.array(sp.Matrix(m).xreplace(subs).evalf(30), dtype=float)

    return {
        "mass_matrix": num(derivation.mass_matrix),
        "coriolis_vector": num(derivation.coriolis_vector).ravel(),
        "coriolis_matrix": num(derivation.coriolis_matrix) if derivation.coriolis_matrix is not None else None,
        "gravity_vector": num(derivation.gravity_vector).ravel(),
        "generalized_forces": num(derivation.generalized_forces).ravel(),
        "potential_energy": float(num(sp.Matrix([[derivation.potential_energy]]))[0, 0]),
    }


def _states(n: int, seed: int, count: int = 3):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        yield rng.uniform(-np.pi, np.pi, n), rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)


@pytest.mark.parametrize("rel", [pytest.param(s, id=Path(s).stem) for s in SMALL])
def test_python_code_matches_the_derivation(rel: str) -> None:
    system, derivation = derived(_path(rel))
    module = python_module(_path(rel))
    n = len(system.coordinates)
    values = random_values(system, 1)
    p = _params(module, values)
    for q, qd, qdd in _states(n, 2):
        ref = _symbolic(derivation, values, q, qd, qdd)
        assert relative(module.mass_matrix(q, p), ref["mass_matrix"]) < RTOL
        assert relative(module.coriolis_vector(q, qd, p), ref["coriolis_vector"]) < RTOL
        assert relative(module.coriolis_matrix(q, qd, p), ref["coriolis_matrix"]) < RTOL
        assert relative(module.gravity_vector(q, p), ref["gravity_vector"]) < RTOL
        assert relative(module.generalized_forces(q, qd, p), ref["generalized_forces"]) < RTOL
        assert relative(module.potential_energy(q, p), ref["potential_energy"]) < RTOL
        h = ref["mass_matrix"]
        tau = h @ qdd + ref["coriolis_vector"] + ref["gravity_vector"] - ref["generalized_forces"]
        assert relative(module.inverse_dynamics(q, qd, qdd, p), tau) < RTOL
        assert relative(module.forward_dynamics(q, qd, tau, p), qdd) < 1e-8  # through H^-1: its condition


def test_python_code_vectorises_over_a_batch() -> None:
    path = _path("specs/tutorial-1/p05-rr-arm.yaml")
    system, _ = derived(path)
    module = python_module(path)
    p = _params(module, random_values(system, 3))
    rng = np.random.default_rng(4)
    q, qd, qdd = (rng.uniform(-2, 2, (7, 2)) for _ in range(3))
    tau = module.inverse_dynamics(q, qd, qdd, p)
    assert tau.shape == (7, 2)
    assert module.mass_matrix(q, p).shape == (7, 2, 2)
    for k in range(7):
        assert relative(tau[k], module.inverse_dynamics(q[k], qd[k], qdd[k], p)) < 1e-14
    assert relative(module.forward_dynamics(q, qd, tau, p), qdd) < 1e-10


needs_gcc = pytest.mark.skipif(GCC is None, reason="gcc is not installed")


def _c_model(rel: str, tmp_path: Path) -> tuple[CModel, object]:
    system, derivation = derived(_path(rel))
    source = code(_path(rel), "c")
    prefix = module_name(Path(rel).stem)
    lib = compile_c(source, tmp_path, prefix)
    program = build_program(derivation, "c", LANGUAGES["c"][1](), Path(rel).name)
    fields = [(p.spec_name, p.name) for p in program.parameters]  # the struct's field order is the spec's
    return CModel(lib, prefix, len(system.coordinates), fields), system


@needs_gcc
@pytest.mark.parametrize("rel", [pytest.param(s, id=Path(s).stem) for s in SMALL[:4]])
def test_c_code_compiles_warning_free_and_matches_python(rel: str, tmp_path: Path) -> None:
    model, system = _c_model(rel, tmp_path)
    module = python_module(_path(rel))
    n = model.n
    values = random_values(system, 5)
    cp, pp = model.params(values), _params(module, values)
    for q, qd, qdd in _states(n, 6):
        for name, args, size in [
            ("mass_matrix", (q,), n * n),
            ("coriolis_vector", (q, qd), n),
            ("coriolis_matrix", (q, qd), n * n),
            ("gravity_vector", (q,), n),
            ("generalized_forces", (q, qd), n),
            ("potential_energy", (q,), 1),
            ("inverse_dynamics", (q, qd, qdd), n),
        ]:
            ours, _ = model.call(name, cp, *args, size=size)
            theirs = np.ravel(getattr(module, name)(*args, pp))
            assert relative(ours, theirs) < RTOL, name
        tau, _ = model.call("inverse_dynamics", cp, q, qd, qdd, size=n)
        qdd_back, status = model.call("forward_dynamics", cp, q, qd, tau, size=n)
        assert status == 0
        assert relative(qdd_back, qdd) < 1e-8


@needs_gcc
def test_c_forward_dynamics_reports_a_singular_mass_matrix(tmp_path: Path) -> None:
    # a point mass on a prismatic arm with zero mass: H is zero, so Cholesky fails and the status says so
    model, system = _c_model("specs/tutorial-1/p05-rr-arm.yaml", tmp_path)
    p = model.params({p.name: 0.0 for p in system.parameters})
    _, status = model.call("forward_dynamics", p, np.zeros(2), np.zeros(2), np.zeros(2), size=2)
    assert status == 1


# ---------------------------------------------------------------------------------------------
# Pinocchio
# ---------------------------------------------------------------------------------------------


def _pinocchio_cases() -> list:
    cases = []
    for path in all_specs():
        cases.append(pytest.param(str(path), id=path.stem))
    return cases


@pytest.mark.parametrize("path", _pinocchio_cases())
def test_generated_code_agrees_with_pinocchio(path: str) -> None:
    pin = pytest.importorskip("pinocchio")
    from tests.engine.pinocchio_model import build_model, parameter_values, serial_skip_reason, spring_gradient

    system, derivation = derived(path)
    reason = serial_skip_reason(system)
    if reason is not None:
        pytest.skip(reason)
    values = parameter_values(system, seed=11)
    rebuilt = build_model(system, values)
    module = python_module(path)
    p = _params(module, {s.name: v for s, v in values.items()})
    springs = spring_gradient(system, derivation.spring_energies)
    q_syms = [c.q for c in system.coordinates]
    spring_f = sp.lambdify(q_syms, springs.xreplace(values), modules="numpy")
    data = rebuilt.model.createData()
    idx = list(rebuilt.v_index)
    for q, qd, qdd in _states(len(q_syms), 12):
        m = np.array(pin.crba(rebuilt.model, data, rebuilt.to_pin(q)))
        m = (np.triu(m) + np.triu(m, 1).T)[np.ix_(idx, idx)]
        assert relative(module.mass_matrix(q, p), m) < RTOL
        rnea = rebuilt.from_pin(
            pin.rnea(rebuilt.model, data, rebuilt.to_pin(q), rebuilt.to_pin(qd), rebuilt.to_pin(qdd))
        )
        ours = module.inverse_dynamics(q, qd, qdd, p) + module.generalized_forces(q, qd, p)
        ours = ours - np.ravel(np.array(spring_f(*q), dtype=float))
        assert relative(ours, rnea) < RTOL


@pytest.mark.slow  # 6-14 s: gcc -O2 on 1500 lines (the NumPy code of the same arm is checked in the default run)
@needs_gcc
def test_c_code_of_the_numeric_puma_agrees_with_pinocchio(tmp_path: Path) -> None:
    pin = pytest.importorskip("pinocchio")
    from tests.engine.pinocchio_model import build_model

    model, system = _c_model(PUMA, tmp_path)
    values = {p.symbol: float(p.value) if p.value is not None else 0.0 for p in system.parameters}
    rebuilt = build_model(system, values)
    data = rebuilt.model.createData()
    cp = model.params({})
    idx = list(rebuilt.v_index)
    for q, qd, qdd in _states(6, 13, count=5):
        h, _ = model.call("mass_matrix", cp, q, size=36)
        m = np.array(pin.crba(rebuilt.model, data, rebuilt.to_pin(q)))
        m = (np.triu(m) + np.triu(m, 1).T)[np.ix_(idx, idx)]
        assert relative(h.reshape(6, 6), m) < RTOL
        tau, _ = model.call("inverse_dynamics", cp, q, qd, qdd, size=6)
        rnea = rebuilt.from_pin(
            pin.rnea(rebuilt.model, data, rebuilt.to_pin(q), rebuilt.to_pin(qd), rebuilt.to_pin(qdd))
        )
        assert relative(tau, rnea) < RTOL
        back, status = model.call("forward_dynamics", cp, q, qd, tau, size=6)
        assert status == 0 and relative(back, qdd) < 1e-8


# ---------------------------------------------------------------------------------------------
# Names
# ---------------------------------------------------------------------------------------------

MARKER = "ZQX marker */ system('rm')"
NAMES_SPEC = f"""
tutgen: 1
title: "{MARKER} title"
statement: "{MARKER} statement"
parameters:
  double: {{value: 2 kg, description: "{MARKER} description"}}
  end: 0.5 m
  H: 9.81 m/s^2
  shape: 40 N/m
  p: {{dimension: force}}
coordinates: {{int: {{dimension: length, description: "{MARKER}"}}}}
gravity: [-H, 0, 0]
bodies: {{block: {{mass: double}}}}
joints: {{slide: {{type: prismatic, parent: ground, child: block, axis: x, coordinate: int}}}}
springs: {{s: {{stiffness: shape, extension: int - end}}}}
generalized_forces: {{int: p}}
"""


@pytest.fixture(scope="module")
def names_derivation():
    return derive(load_system_text(NAMES_SPEC))


@pytest.mark.parametrize("language", list(LANGUAGES))
def test_code_holds_no_spec_text_but_declared_names(names_derivation, language: str) -> None:
    text = generate_code(names_derivation, language, "bad name\n*/ evil.yaml")
    assert "ZQX" not in text and "marker" not in text and "*/ evil" not in text
    assert "bad_name____evil.yaml" in text  # the file name, reduced to safe characters
    header = text[:3000]
    expected = {"python": "H -> H_", "c": "double -> double_", "matlab": "end -> end_", "julia": "end -> end_"}
    assert expected[language] in header
    assert "shape -> shape_" in header  # a local of the generated functions


@needs_gcc
def test_c_with_keyword_names_compiles_and_runs(names_derivation, tmp_path: Path) -> None:
    source = generate_code(names_derivation, "c", "names.yaml")
    lib = compile_c(source, tmp_path, "names")
    fields = [("double", "double_"), ("end", "end"), ("H", "H_"), ("shape", "shape_"), ("p", "p_")]
    model = CModel(lib, "names", 1, fields)
    params = model.params({"p": 3.0})
    # m x_ddot + k (x - end) - m H... : gravity along -x, G = m H + k (x - end), Q = p
    tau, _ = model.call("inverse_dynamics", params, np.array([1.0]), np.array([0.0]), np.array([0.5]), size=1)
    assert tau[0] == pytest.approx(2 * 0.5 + 2 * 9.81 + 40 * (1.0 - 0.5) - 3.0, rel=1e-12)


def test_serial_route_code_keeps_springs_and_dampers() -> None:
    # a 4R arm takes the serial route (H, C q_dot, G from the recursive program); its spring and damper
    # come from the derivation's spring energies and Q
    text = (ROOT / "specs/arms/planar-4r.yaml").read_text()
    text += "springs: {back: {stiffness: k, extension: q2 - q20}}\ndampers: {joint3: {coefficient: c, extension: q3}}\n"
    text = text.replace("parameters: [m1,", "parameters: [k, q20, c, m1,")
    derivation = derive(load_system_text(text))
    assert derivation.program is not None
    module = types.ModuleType("serial_springs")
    sys.modules[module.__name__] = module
    exec(compile(generate_code(derivation, "python", "arm.yaml"), "arm", "exec"), module.__dict__)
    values = random_values(derivation.system, 21)
    p = _params(module, values)
    for q, qd, qdd in _states(4, 22, count=2):
        ref = _symbolic(derivation, values, q, qd, qdd)
        assert relative(module.gravity_vector(q, p), ref["gravity_vector"]) < RTOL
        assert relative(module.mass_matrix(q, p), ref["mass_matrix"]) < RTOL
        assert relative(module.coriolis_vector(q, qd, p), ref["coriolis_vector"]) < RTOL
        assert relative(module.generalized_forces(q, qd, p), ref["generalized_forces"]) < RTOL


def test_python_with_keyword_names_runs(names_derivation) -> None:
    module = types.ModuleType("names_python")
    sys.modules[module.__name__] = module
    exec(compile(generate_code(names_derivation, "python", "names.yaml"), "names", "exec"), module.__dict__)
    p = module.Parameters(p_=3.0)
    tau = module.inverse_dynamics(np.array([1.0]), np.array([0.0]), np.array([0.5]), p)
    assert tau[0] == pytest.approx(2 * 0.5 + 2 * 9.81 + 40 * (1.0 - 0.5) - 3.0, rel=1e-12)


LINEAR_SPEC = """
tutgen: 1
title: damped pendulum on a spring-loaded slider
parameters: {m: 0.7 kg, M: 2 kg, l: 0.9 m, g: 9.81 m/s^2, c: 0.3 N*m*s, b: 1.5 N*s/m, k: 20 N/m}
coordinates: {x: {dimension: length}, theta: {dimension: angle}}
gravity: [0, -g, 0]
bodies: {cart: {mass: M}, bob: {mass: m, com: [0, -l, 0]}}
joints:
  slide: {type: prismatic, parent: ground, child: cart, axis: x, coordinate: x}
  pin: {type: revolute, parent: cart, child: bob, axis: z, coordinate: theta}
springs: {wall: {stiffness: k, extension: x}}
dampers: {hinge: {coefficient: c, extension: theta}, rail: {coefficient: b, extension: x}}
"""


@pytest.mark.parametrize("language", ["python", "c"])
def test_linear_model_is_the_hand_derived_one(language: str, tmp_path: Path) -> None:
    # by hand: U = k x^2/2 - m g l cos(theta), Q = (-b x_dot, -c theta_dot):
    # K = diag(k, m g l cos(theta)), D = diag(b, c)
    derivation = derive(load_system_text(LINEAR_SPEC))
    theta = 0.4
    k_hand = np.diag([20.0, 0.7 * 9.81 * 0.9 * np.cos(theta)])
    d_hand = np.diag([1.5, 0.3])
    q = np.array([0.1, theta])
    source = generate_code(derivation, language, "lin.yaml", linear=True)
    if language == "python":
        module = types.ModuleType("linear_python")
        sys.modules[module.__name__] = module
        exec(compile(source, "lin", "exec"), module.__dict__)
        p = module.Parameters()
        stiffness, damping = module.linear_stiffness(q, p), module.linear_damping(q, p)
    else:
        if GCC is None:
            pytest.skip("gcc is not installed")
        model = CModel(compile_c(source, tmp_path, "lin"), "lin", 2, [(s, s) for s in "mMlgcbk"])
        p = model.params({})
        stiffness = model.call("linear_stiffness", p, q, size=4)[0].reshape(2, 2)
        damping = model.call("linear_damping", p, q, size=4)[0].reshape(2, 2)
    assert relative(stiffness, k_hand) < 1e-12
    assert relative(damping, d_hand) < 1e-12
