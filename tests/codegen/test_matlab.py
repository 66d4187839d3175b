"""The generated MATLAB runs (issue 19): under GNU Octave (`octave-cli`, Debian's `octave`), every
function of the file, called at random states, equals the generated NumPy code (itself checked
against the derivation in test_codegen.py) to 1e-10: a small arm by `sympy.cse`, the cart-pendulum
with a spring and its generalized force, and a 4R arm on the serial route (the recursive program,
with the C matrix of tutgen/codegen/coriolis.py). Skipped where `octave-cli` is not installed."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from tests.codegen.compiled import code, derived, python_module
from tests.codegen.test_codegen import _params, _states, random_values, relative
from tests.conftest import ROOT
from tutgen.codegen.printers import LANGUAGES
from tutgen.codegen.program import build_program, module_name

OCTAVE = shutil.which("octave-cli")
pytestmark = pytest.mark.skipif(OCTAVE is None, reason="octave-cli is not installed (Debian: apt-get install octave)")

SPECS = [
    pytest.param("specs/tutorial-1/p05-rr-arm.yaml", id="p05-rr-arm"),
    pytest.param("specs/tutorial-1/p03-cart-pendulum.yaml", id="p03-cart-pendulum"),
    pytest.param("specs/arms/planar-4r.yaml", id="planar-4r", marks=pytest.mark.slow),  # ~7 s: the 4R derivation
]


def _vector(x: np.ndarray) -> str:
    return "[" + "; ".join(repr(float(v)) for v in x) + "]"


@pytest.mark.parametrize("rel", SPECS)
def test_generated_matlab_runs_in_octave_and_matches_python(rel: str, tmp_path: Path) -> None:
    path = str(ROOT / rel)
    system, derivation = derived(path)
    name = module_name(Path(rel).stem)
    (tmp_path / f"{name}.m").write_text(code(path, "matlab"), encoding="utf-8")
    program = build_program(derivation, "matlab", LANGUAGES["matlab"][1](), Path(rel).name)
    module = python_module(path)
    values = random_values(system, 41)
    pp = _params(module, values)
    n = len(system.coordinates)
    states = list(_states(n, 42, count=2))
    calls = [
        ("mass_matrix", (0,)),
        ("coriolis_vector", (0, 1)),
        ("coriolis_matrix", (0, 1)),
        ("gravity_vector", (0,)),
        ("generalized_forces", (0, 1)),
        ("potential_energy", (0,)),
        ("inverse_dynamics", (0, 1, 2)),
        ("forward_dynamics", (0, 1, 2)),  # the third vector as tau
    ]
    lines = [f"dyn = {name}();", "p = dyn.params;"]
    lines += [f"p.{prm.name} = {values[prm.spec_name]!r};" for prm in program.parameters]
    for k, (q, qd, qdd) in enumerate(states):
        lines += [f"s{{1}} = {_vector(q)};", f"s{{2}} = {_vector(qd)};", f"s{{3}} = {_vector(qdd)};"]
        for fn, args in calls:
            call = f"dyn.{fn}({', '.join(f's{{{a + 1}}}' for a in args)}, p)"
            lines.append(f"r = {call}; printf('{k} {fn}'); printf(' %.17g', reshape(r.', 1, [])); printf('\\n');")
    (tmp_path / "driver.m").write_text("\n".join(lines) + "\n", encoding="utf-8")
    run = subprocess.run(
        [OCTAVE, "--no-gui", "--norc", "--no-history", "--quiet", "--eval", "driver"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0 and not run.stderr.strip(), run.stderr
    got = {}
    for line in run.stdout.splitlines():
        k, fn, *numbers = line.split()
        got[int(k), fn] = np.array([float(x) for x in numbers])
    assert len(got) == len(states) * len(calls)
    for k, (q, qd, qdd) in enumerate(states):
        vectors = (q, qd, qdd)
        for fn, args in calls:
            theirs = np.ravel(getattr(module, fn)(*(vectors[a] for a in args), pp))
            assert relative(got[k, fn], theirs) < (1e-8 if fn == "forward_dynamics" else 1e-10), (k, fn)
