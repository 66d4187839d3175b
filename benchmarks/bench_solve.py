"""How fast `tutgen solve` is, against sympy.physics.mechanics measured in the same run.

Run from the repository root:  python benchmarks/bench_solve.py [--repeat N]

It prints
- the wall time of `tutgen --help` and of solving all ten tutorial specs to JSON in ONE call
  (interpreter start included), and of each spec alone, as a user would run them;
- per spec, the in-process derivation time of tutgen (H, C, G, Christoffel symbols, Lagrange's
  terms) next to sympy.physics.mechanics' LagrangesMethod and KanesMethod given the same bodies
  (point-mass positions as functions of the coordinates), and the ratios.
Targets from the issue: all ten in one call < 5 s, any single one < 2 s, --help < 0.3 s.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # run from a checkout without installing
SPECS = sorted((ROOT / "specs" / "tutorial-1").glob("p*.yaml"))


def wall(cmd: list[str], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(cmd, check=True, cwd=ROOT, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def mechanics_times(system, derivation) -> tuple[float, float] | None:
    """Seconds for LagrangesMethod and KanesMethod to form mass matrix and forcing from the same
    point masses (None when a body has rotational inertia: this reference handles particles)."""
    import sympy as sp
    from sympy.physics.mechanics import KanesMethod, LagrangesMethod, Particle, Point, ReferenceFrame, dynamicsymbols

    if not derivation.kinematics or any(not (bi.inertia_com == sp.zeros(3, 3)) for bi in derivation.inertia):
        return None
    qs = [dynamicsymbols(c.name + "_m") for c in system.coordinates]
    us = [dynamicsymbols(c.name + "_u") for c in system.coordinates]
    to_dyn = {c.q: qm for c, qm in zip(system.coordinates, qs, strict=True)}
    gravity = sp.Matrix(system.gravity) if system.gravity is not None else sp.zeros(3, 1)
    out = []
    for method in ("lagrange", "kane"):
        start = time.perf_counter()
        frame = ReferenceFrame("N")
        origin = Point("O")
        origin.set_vel(frame, 0)
        particles, loads, potential = [], [], sp.Integer(0)
        for bk, bi in zip(derivation.kinematics, derivation.inertia, strict=True):
            r = [e.subs(to_dyn) for e in bk.com]
            point = origin.locatenew(bk.name, r[0] * frame.x + r[1] * frame.y + r[2] * frame.z)
            vel = point.pos_from(origin).dt(frame)
            if method == "kane":
                vel = vel.subs({qm.diff(): u for qm, u in zip(qs, us, strict=True)})
            point.set_vel(frame, vel)
            particles.append(Particle("P" + bk.name, point, bi.mass))
            g = gravity[0] * frame.x + gravity[1] * frame.y + gravity[2] * frame.z
            loads.append((point, bi.mass * g))
            potential -= bi.mass * (gravity.T * sp.Matrix(r))[0]
        if method == "lagrange":
            kinetic = sum((p.kinetic_energy(frame) for p in particles), sp.Integer(0))
            lm = LagrangesMethod(kinetic - potential, qs)
            lm.form_lagranges_equations()
            _ = (lm.mass_matrix, lm.forcing)
        else:
            km = KanesMethod(frame, q_ind=qs, u_ind=us, kd_eqs=[qm.diff() - u for qm, u in zip(qs, us, strict=True)])
            km.kanes_equations(particles, loads)
            _ = (km.mass_matrix, km.forcing)
        out.append(time.perf_counter() - start)
    return out[0], out[1]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per wall-time figure (median)")
    args = parser.parse_args()
    exe = [sys.executable, "-m", "tutgen"]

    help_time = wall([*exe, "--help"], args.repeat)
    with tempfile.TemporaryDirectory() as out:
        all_time = wall([*exe, "solve", *map(str, SPECS), "--format", "json", "-o", out, "--force"], args.repeat)
    singles = {spec.name: wall([*exe, "solve", str(spec), "--format", "json"], args.repeat) for spec in SPECS}

    print(f"command-line wall time (median of {args.repeat}, interpreter start included)")
    print(f"  tutgen --help                              {help_time:7.3f} s   (target < 0.3 s)")
    print(f"  tutgen solve <10 tutorial specs> --format json  {all_time:7.3f} s   (target < 5 s)")
    for name, t in singles.items():
        print(f"  tutgen solve {name:<34} {t:7.3f} s   (target < 2 s)")

    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    print("\nin-process derivation, tutgen vs sympy.physics.mechanics (same bodies, same run)")
    print(f"  {'spec':<34} {'tutgen':>8} {'Lagrange':>9} {'Kane':>8} {'L/tutgen':>9} {'K/tutgen':>9}")
    for spec in SPECS:
        system = load_system(spec)
        start = time.perf_counter()
        derivation = derive(system)
        ours = time.perf_counter() - start
        ref = mechanics_times(system, derivation)
        if ref is None:
            print(f"  {spec.name:<34} {ours:8.3f} {'-':>9} {'-':>8} {'-':>9} {'-':>9}")
            continue
        lag, kane = ref
        print(f"  {spec.name:<34} {ours:8.3f} {lag:9.3f} {kane:8.3f} {lag / ours:9.2f} {kane / ours:9.2f}")
    print("\ntutgen's figure includes H, C (vector and matrix), G, both Christoffel tables, Lagrange's")
    print("intermediate terms and its self-checks; mechanics' includes only the mass matrix and forcing,")
    print("unsimplified. A ratio above 1 means tutgen is faster.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
