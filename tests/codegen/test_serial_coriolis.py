"""The matrix C(q, q_dot) on the serial route (four or more joints, issue 19): generated from the
recursive program's H differentiated forward (tutgen/codegen/coriolis.py), it equals the derivation's
own C, which the serial engine builds from the exact Christoffel symbols of the expanded H (an
independent route), C q_dot equals the generated Coriolis vector, and H_dot - 2C is skew; the C code
compiles warning-free and agrees."""

from __future__ import annotations

import sys
import types
from functools import cache
from pathlib import Path

import numpy as np
import pytest

from tests.codegen.compiled import GCC, CModel, compile_c
from tests.codegen.test_codegen import _params, _states, _symbolic, random_values, relative
from tests.conftest import ROOT
from tutgen.codegen.printers import LANGUAGES, generate_code
from tutgen.codegen.program import build_program
from tutgen.engine.pipeline import derive
from tutgen.spec.validate import load_system

ARM = ROOT / "specs/arms/planar-4r.yaml"


@cache
def arm():
    derivation = derive(load_system(ARM))
    assert derivation.program is not None  # the serial route
    module = types.ModuleType("serial_coriolis")
    sys.modules[module.__name__] = module
    exec(compile(generate_code(derivation, "python", ARM.name), "arm", "exec"), module.__dict__)
    return derivation, module


def test_serial_route_coriolis_matrix_equals_the_christoffel_one() -> None:
    derivation, module = arm()
    values = random_values(derivation.system, 31)
    p = _params(module, values)
    for q, qd, qdd in _states(4, 32):
        ref = _symbolic(derivation, values, q, qd, qdd)
        c = module.coriolis_matrix(q, qd, p)
        assert c.shape == (4, 4)
        assert relative(c, ref["coriolis_matrix"]) < 1e-10
        assert relative(c @ qd, module.coriolis_vector(q, qd, p)) < 1e-10
        # H_dot - 2C is skew: H_dot by central differences of the generated H along qd
        h = 1e-6
        h_dot = (module.mass_matrix(q + h * qd, p) - module.mass_matrix(q - h * qd, p)) / (2 * h)
        skew = h_dot - 2 * c
        assert relative(skew + skew.T, np.zeros((4, 4))) < 1e-6


def test_serial_route_coriolis_matrix_vectorises() -> None:
    derivation, module = arm()
    p = _params(module, random_values(derivation.system, 33))
    rng = np.random.default_rng(34)
    q, qd = rng.uniform(-2, 2, (5, 4)), rng.uniform(-2, 2, (5, 4))
    batch = module.coriolis_matrix(q, qd, p)
    assert batch.shape == (5, 4, 4)
    for k in range(5):
        assert relative(batch[k], module.coriolis_matrix(q[k], qd[k], p)) < 1e-14


@pytest.mark.skipif(GCC is None, reason="gcc is not installed")
def test_serial_route_c_code_has_the_coriolis_matrix(tmp_path: Path) -> None:
    derivation, module = arm()
    source = generate_code(derivation, "c", ARM.name)
    prefix = "planar_4r"
    assert f"{prefix}_coriolis_matrix" in source
    lib = compile_c(source, tmp_path, prefix)
    program = build_program(derivation, "c", LANGUAGES["c"][1](), ARM.name)
    model = CModel(lib, prefix, 4, [(prm.spec_name, prm.name) for prm in program.parameters])
    values = random_values(derivation.system, 35)
    cp, pp = model.params(values), _params(module, values)
    for q, qd, _ in _states(4, 36, count=2):
        ours, _ = model.call("coriolis_matrix", cp, q, qd, size=16)
        assert relative(ours, np.ravel(module.coriolis_matrix(q, qd, pp))) < 1e-10
