"""H, C and G of every multi-DOF spec against sympy.physics.mechanics, built independently.

The reference is built from the answer key's own geometry (its particle positions, masses, gravity
and springs in ``shared/seed/answers.yaml``), not from tutgen's kinematics, with both
LagrangesMethod and KanesMethod. tests/engine/test_mechanics_generic.py does the same for every
spec, from the spec's joints.
"""

from __future__ import annotations

from typing import Any

import pytest
import sympy as sp
from sympy.physics.mechanics import (
    KanesMethod,
    LagrangesMethod,
    Particle,
    Point,
    ReferenceFrame,
    dynamicsymbols,
)

from tests.conftest import SPECS, solved
from tests.seed import ANSWERS, problems
from tests.seed import SPEC_OF as ALL_SPECS
from tutgen.engine.tidy import is_zero
from tutgen.spec.expr import parse_expression

SPEC_OF = {pid: name for pid, name in ALL_SPECS.items() if 3 <= pid <= 9}  # the multi-DOF point-mass problems


def _back_to_symbols(expr: Any, qs: list[Any], system: Any) -> Any:
    t = dynamicsymbols._t
    coords = system.coordinates
    for table in (
        {qm.diff(t, 2): c.qdd for qm, c in zip(qs, coords, strict=True)},
        {qm.diff(t): c.qd for qm, c in zip(qs, coords, strict=True)},
        {qm: c.q for qm, c in zip(qs, coords, strict=True)},
    ):
        expr = expr.subs(table)
    return expr


def reference_from_particles(pid: int, system: Any, method: str) -> tuple[sp.Matrix, sp.Matrix]:
    """Mass matrix and forcing (= -(C + G), no applied forces) of the answer key's point masses."""
    prob = problems()[pid]
    model = prob["model"]
    table: dict[str, Any] = {p.name: p.symbol for p in system.parameters}
    qs = [dynamicsymbols(f"{c.name}_ref") for c in system.coordinates]
    us = [dynamicsymbols(f"{c.name}_u") for c in system.coordinates]
    for c, qm in zip(system.coordinates, qs, strict=True):
        table[c.name] = qm
    frame = ReferenceFrame("N")
    origin = Point("O")
    origin.set_vel(frame, 0)
    gravity = [parse_expression(v, table) for v in model["gravity"]]
    particles = []
    potential = sp.Integer(0)
    for pt in model["particles"]:
        r = [parse_expression(v, table) for v in pt["position"]]
        point = origin.locatenew(pt["name"], r[0] * frame.x + r[1] * frame.y + r[2] * frame.z)
        mass = parse_expression(pt["mass"], table)
        particles.append(Particle(f"P_{pt['name']}", point, mass))
        potential -= mass * sum(g * x for g, x in zip(gravity, r, strict=True))
    potential += parse_expression(model.get("potential_extra", "0"), table)
    if method == "lagrange":
        for p in particles:
            p.point.set_vel(frame, p.point.pos_from(origin).dt(frame))
        kinetic = sum((p.kinetic_energy(frame) for p in particles), sp.Integer(0))
        lm = LagrangesMethod(kinetic - potential, qs)
        lm.form_lagranges_equations()
        mass, forcing = lm.mass_matrix, lm.forcing
    else:
        kd = [qm.diff() - u for qm, u in zip(qs, us, strict=True)]
        loads = []
        for p in particles:
            p.point.set_vel(
                frame, p.point.pos_from(origin).dt(frame).subs({qm.diff(): u for qm, u in zip(qs, us, strict=True)})
            )
            loads.append(
                (
                    p.point,
                    sum((g * v for g, v in zip(gravity, (frame.x, frame.y, frame.z), strict=True)), 0 * frame.x)
                    * p.mass,
                )
            )
        extra = parse_expression(model.get("potential_extra", "0"), table)
        km = KanesMethod(frame, q_ind=qs, u_ind=us, kd_eqs=kd)
        km.kanes_equations(particles, loads)
        mass = km.mass_matrix
        # the spring's generalized force -dU/dq is not a body load: add it by hand
        forcing = km.forcing - sp.Matrix([sp.diff(extra, qm) for qm in qs])
        forcing = forcing.subs({u.diff(): qm.diff(dynamicsymbols._t, 2) for u, qm in zip(us, qs, strict=True)})
        forcing = forcing.subs(dict(zip(us, [qm.diff() for qm in qs], strict=True)))
    return _back_to_symbols(mass, qs, system), _back_to_symbols(forcing, qs, system)


@pytest.mark.skipif(not ANSWERS.exists(), reason="the seed answer key is missing")
@pytest.mark.parametrize("method", ["lagrange", "kane"])
@pytest.mark.parametrize("pid", sorted(SPEC_OF))
def test_mechanics_matches_tutorial_spec(pid: int, method: str) -> None:
    system, derivation, _ = solved(str(SPECS / "tutorial-1" / SPEC_OF[pid]))
    mass, forcing = reference_from_particles(pid, system, method)
    n = len(system.coordinates)
    for i in range(n):
        for j in range(n):
            ok, _ = is_zero(mass[i, j] - derivation.mass_matrix[i, j])
            assert ok, f"H[{i + 1},{j + 1}]: mechanics {mass[i, j]}, tutgen {derivation.mass_matrix[i, j]}"
        ours = derivation.coriolis_vector[i] + derivation.gravity_vector[i]
        ok, _ = is_zero(forcing[i] + ours)
        assert ok, f"C+G [{i + 1}]: mechanics {-forcing[i]}, tutgen {ours}"
