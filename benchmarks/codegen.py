"""Speed of the generated code against Pinocchio, in the same run (issue 19).

Run from the repository root:  python benchmarks/codegen.py [--states N] [--repeat R]

For the numeric PUMA 560 (specs/arms/puma560-numeric.yaml), H(q) and inverse dynamics
tau(q, q_dot, q_ddot) per call:

- C: `tutgen code --lang c`, compiled with gcc -O2 -std=c99 into a shared library with a small timing
  driver appended (a loop over N states, timed inside C with clock_gettime), so the time is the
  generated function's alone; also called once per state through ctypes (what a Python user pays);
- Pinocchio: pin.crba (the upper triangle, as Pinocchio fills it) and pin.rnea, called from Python on
  the same states: its time includes the Python binding's overhead of about a microsecond, so the
  same loop over a no-op binding call (pin.neutral) is measured and reported;
- NumPy: `tutgen code --lang python`, one call on the whole batch of N states, per state.

Before timing, all three are checked to agree to 1e-10 relative on every state. Each time is the
best of R repeats. Targets: C within 2x of Pinocchio, NumPy batch within 10x per state.
"""

from __future__ import annotations

import argparse
import ctypes
import shutil
import subprocess
import sys
import tempfile
import time
import types
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

SPEC = ROOT / "specs/arms/puma560-numeric.yaml"

DRIVER = """
#include <time.h>
static double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
double bench_mass_matrix(const double *qs, int count, const PREFIX_params *p, double *out)
{
    double start = bench_now();
    for (int k = 0; k < count; k++) PREFIX_mass_matrix(qs + 6 * k, p, out + 36 * k);
    return bench_now() - start;
}
double bench_inverse_dynamics(const double *qs, const double *qds, const double *qdds, int count,
                              const PREFIX_params *p, double *out)
{
    double start = bench_now();
    for (int k = 0; k < count; k++) PREFIX_inverse_dynamics(qs + 6 * k, qds + 6 * k, qdds + 6 * k, p, out + 6 * k);
    return bench_now() - start;
}
"""


def _ptr(a: np.ndarray) -> ctypes.c_void_p:
    return a.ctypes.data_as(ctypes.c_void_p)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--states", type=int, default=20000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()

    import pinocchio as pin

    from tests.engine.pinocchio_model import build_model
    from tutgen.codegen.printers import generate_code
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    t0 = time.perf_counter()
    system = load_system(SPEC)
    derivation = derive(system, "lagrange")
    t1 = time.perf_counter()
    c_source = generate_code(derivation, "c", SPEC.name)
    t2 = time.perf_counter()
    py_source = generate_code(derivation, "python", SPEC.name)
    prefix = "puma560_numeric"
    print(f"derive {t1 - t0:.2f} s, C code {t2 - t1:.2f} s, NumPy code {time.perf_counter() - t2:.2f} s")
    print(
        f"code size: C {len(c_source.splitlines())} lines / {len(c_source)} bytes, "
        f"NumPy {len(py_source.splitlines())} lines / {len(py_source)} bytes"
    )

    gcc = shutil.which("gcc")
    if gcc is None:
        print("gcc not found")
        return 1
    work = Path(tempfile.mkdtemp(prefix="tutgen-bench-"))
    c_file = work / "puma.c"
    c_file.write_text("#define _POSIX_C_SOURCE 199309L\n" + c_source + DRIVER.replace("PREFIX", prefix))
    lib_file = work / "libpuma.so"
    subprocess.run(
        [
            gcc,
            "-O2",
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-shared",
            "-fPIC",
            str(c_file),
            "-o",
            str(lib_file),
            "-lm",
        ],
        check=True,
    )
    obj_size = lib_file.stat().st_size
    lib = ctypes.CDLL(str(lib_file))
    lib.bench_mass_matrix.restype = ctypes.c_double
    lib.bench_inverse_dynamics.restype = ctypes.c_double
    from tutgen.codegen.printers import LANGUAGES
    from tutgen.codegen.program import build_program

    fields = [p.name for p in build_program(derivation, "c", LANGUAGES["c"][1](), SPEC.name).parameters]
    params_t = type("P", (ctypes.Structure,), {"_fields_": [(f, ctypes.c_double) for f in fields]})
    cp = params_t()
    getattr(lib, f"{prefix}_default_params")(ctypes.byref(cp))

    module = types.ModuleType("puma_generated")
    sys.modules[module.__name__] = module
    exec(compile(py_source, "puma_generated", "exec"), module.__dict__)
    pp = module.Parameters(**{f"tau{i}": 0.0 for i in range(1, 7)})

    values = {p.symbol: float(p.value) if p.value is not None else 0.0 for p in system.parameters}
    rebuilt = build_model(system, values)
    model, data = rebuilt.model, rebuilt.model.createData()
    idx = list(rebuilt.v_index)
    assert idx == list(range(6)), "the PUMA's coordinates are Pinocchio's in order"

    n = args.states
    rng = np.random.default_rng(1)
    qs, qds, qdds = (np.ascontiguousarray(rng.uniform(-np.pi, np.pi, (n, 6))) for _ in range(3))
    h_c, tau_c = np.zeros((n, 36)), np.zeros((n, 6))

    # agreement first
    lib.bench_mass_matrix(_ptr(qs), n, ctypes.byref(cp), _ptr(h_c))
    lib.bench_inverse_dynamics(_ptr(qs), _ptr(qds), _ptr(qdds), n, ctypes.byref(cp), _ptr(tau_c))
    h_np, tau_np = module.mass_matrix(qs, pp), module.inverse_dynamics(qs, qds, qdds, pp)
    worst = 0.0
    for k in range(0, n, max(1, n // 200)):
        m = np.array(pin.crba(model, data, qs[k]))
        m = np.triu(m) + np.triu(m, 1).T
        tau = np.array(pin.rnea(model, data, qs[k], qds[k], qdds[k]))
        for ours, theirs in ((h_c[k].reshape(6, 6), m), (h_np[k], m), (tau_c[k], tau), (tau_np[k], tau)):
            worst = max(worst, float(np.max(np.abs(ours - theirs)) / max(1.0, float(np.max(np.abs(theirs))))))
    print(f"agreement with Pinocchio (C and NumPy, H and tau): worst relative difference {worst:.2e}")
    if worst > 1e-10:
        print("DISAGREE")
        return 1

    def best(f) -> float:
        return min(f() for _ in range(args.repeat))

    def timed(f) -> float:
        start = time.perf_counter()
        f()
        return time.perf_counter() - start

    c_h = best(lambda: lib.bench_mass_matrix(_ptr(qs), n, ctypes.byref(cp), _ptr(h_c))) / n
    c_tau = (
        best(lambda: lib.bench_inverse_dynamics(_ptr(qs), _ptr(qds), _ptr(qdds), n, ctypes.byref(cp), _ptr(tau_c))) / n
    )
    mm = getattr(lib, f"{prefix}_mass_matrix")
    out = np.zeros(36)
    rows = [_ptr(qs[k]) for k in range(n)]
    ref_p, out_p = ctypes.byref(cp), _ptr(out)
    c_h_ctypes = best(lambda: timed(lambda: [mm(r, ref_p, out_p) for r in rows])) / n
    pin_h = best(lambda: timed(lambda: [pin.crba(model, data, q) for q in qs])) / n
    pin_tau = (
        best(lambda: timed(lambda: [pin.rnea(model, data, q, v, a) for q, v, a in zip(qs, qds, qdds, strict=True)])) / n
    )
    pin_call = best(lambda: timed(lambda: [pin.neutral(model) for _ in qs])) / n
    np_h = best(lambda: timed(lambda: module.mass_matrix(qs, pp))) / n
    np_tau = best(lambda: timed(lambda: module.inverse_dynamics(qs, qds, qdds, pp))) / n

    us = 1e6
    print(f"\nper call, best of {args.repeat}, {n} random states (microseconds)")
    print(f"{'':28s}{'H(q)':>10s}{'tau(q,qd,qdd)':>16s}")
    print(f"{'C (timed in C)':28s}{c_h * us:10.3f}{c_tau * us:16.3f}")
    print(f"{'C through ctypes':28s}{c_h_ctypes * us:10.3f}{'':>16s}")
    print(f"{'Pinocchio crba / rnea':28s}{pin_h * us:10.3f}{pin_tau * us:16.3f}")
    print(f"{'  (binding call, no-op)':28s}{pin_call * us:10.3f}")
    print(f"{'NumPy batch, per state':28s}{np_h * us:10.3f}{np_tau * us:16.3f}")
    print("\nratios (ours / Pinocchio; target C <= 2, NumPy <= 10)")
    print(
        f"C H {c_h / pin_h:.2f}, C tau {c_tau / pin_tau:.2f}; "
        f"against Pinocchio less its binding overhead: C H {c_h / max(pin_h - pin_call, 1e-12):.2f}, "
        f"C tau {c_tau / max(pin_tau - pin_call, 1e-12):.2f}"
    )
    print(f"NumPy H {np_h / pin_h:.2f}, NumPy tau {np_tau / pin_tau:.2f}")
    print(f"shared library {obj_size} bytes")
    met = c_h / pin_h <= 2 and c_tau / pin_tau <= 2 and np_h / pin_h <= 10 and np_tau / pin_tau <= 10
    print("targets: " + ("met" if met else "missed"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
