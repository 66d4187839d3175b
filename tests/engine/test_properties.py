"""Properties of the engine's results on random systems (Hypothesis), checked numerically.

Random planar chains (tests/models.py, ``planar_chain``) go through the whole pipeline, spec dict
to Derivation; their results are evaluated at random states with mpmath, because simplifying
symbolically would be too slow:

- H is symmetric and positive definite;
- H_dot - 2 C is skew-symmetric (C = ``coriolis_matrix``, from the Christoffel symbols);
- the Christoffel symbols of the first kind are symmetric in their two velocity indices, and both
  they and the tutorial's symbols h_ijk rebuild C (``coriolis_vector``), as does C(q, q_dot) q_dot;
- along the equations of motion, d/dt (T + U) = 0 for a conservative chain, and = q_dot . Q with
  dampers and applied forces;
- parallel-axis shifts there and back are the identity, and a body's inertia about its origin is
  its inertia about the centre of mass shifted by its mass;
- the trace and the eigenvalues of an inertia tensor do not change when the part is turned.

The number of examples and the (absent) deadline come from the profiles in tests/conftest.py.
"""

from __future__ import annotations

import random
from functools import cache
from typing import Any

import mpmath
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from tests.conftest import few_examples
from tests.models import planar_chain, system_of
from tutgen.engine.inertia import body_inertia, shift_inertia
from tutgen.engine.pipeline import derive

DIGITS = 30
TOL = mpmath.mpf(10) ** -20  # relative, at DIGITS digits
STATES = 3

sizes = st.integers(min_value=1, max_value=3)
seeds = st.integers(min_value=0, max_value=2**16)


# ---------------------------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------------------------


@cache
def chain(n: int, seed: int, conservative: bool = True) -> tuple[Any, Any]:
    """(system, derivation) of a random planar chain, derived once (Lagrange's route only)."""
    system = system_of(planar_chain(n, seed, conservative=conservative))
    return system, derive(system, method="lagrange")


def random_states(system: Any, seed: int, count: int = STATES) -> list[dict[sp.Symbol, Any]]:
    """Random states: q in (-pi, pi), q_dot in (-2, 2); symbolic parameters in (0.5, 2)."""
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        state: dict[sp.Symbol, Any] = {}
        for p in system.parameters:
            state[p.symbol] = p.value if p.value is not None else sp.Rational(rng.randint(500, 2000), 1000)
        for c in system.coordinates:
            state[c.q] = sp.Rational(rng.randint(-3141, 3141), 1000)
            state[c.qd] = sp.Rational(rng.randint(-2000, 2000), 1000)
        out.append(state)
    return out


def numeric(expr: Any, state: dict[sp.Symbol, Any]) -> Any:
    """A sympy expression or matrix at a state, as an mpmath number or matrix (DIGITS digits)."""
    with mpmath.workdps(DIGITS):
        if isinstance(expr, sp.MatrixBase):
            return mpmath.matrix([[numeric(expr[i, j], state) for j in range(expr.cols)] for i in range(expr.rows)])
        value = sp.sympify(expr).xreplace(state)
        assert not value.free_symbols, value.free_symbols
        return mpmath.mpf(str(sp.N(value, DIGITS + 5)))


def largest(*matrices: Any) -> Any:
    """The largest magnitude among the entries (at least 1), to scale tolerances."""
    return max([mpmath.mpf(1)] + [abs(x) for m in matrices for x in (m if isinstance(m, mpmath.matrix) else [m])])


def assert_small(value: Any, scale: Any, what: str) -> None:
    assert abs(value) <= TOL * scale, f"{what}: {value} (scale {scale})"


def h_dot(derivation: Any) -> sp.Matrix:
    """dH/dt = sum_k dH/dq_k q_dot_k."""
    h = sp.Matrix(derivation.mass_matrix)
    system = derivation.system
    return sum((h.diff(c.q) * c.qd for c in system.coordinates), sp.zeros(*h.shape))


# ---------------------------------------------------------------------------------------------
# Mass matrix, Coriolis matrix, Christoffel symbols
# ---------------------------------------------------------------------------------------------


@few_examples
@given(n=sizes, seed=seeds, state_seed=seeds)
def test_properties_mass_matrix_symmetric_positive_definite(n: int, seed: int, state_seed: int) -> None:
    system, derivation = chain(n, seed)
    for state in random_states(system, state_seed):
        h = numeric(derivation.mass_matrix, state)
        with mpmath.workdps(DIGITS):
            for i in range(n):
                for j in range(n):
                    assert_small(h[i, j] - h[j, i], largest(h), f"H[{i},{j}] - H[{j},{i}]")
            eigenvalues, _ = mpmath.eigsy(h)
            assert min(eigenvalues) > TOL * largest(h), f"H is not positive definite: eigenvalues {eigenvalues}"


@few_examples
@given(n=sizes, seed=seeds, state_seed=seeds)
def test_properties_hdot_minus_2c_skew_symmetric(n: int, seed: int, state_seed: int) -> None:
    system, derivation = chain(n, seed)
    skew = h_dot(derivation) - 2 * sp.Matrix(derivation.coriolis_matrix)
    for state in random_states(system, state_seed):
        s = numeric(skew, state)
        with mpmath.workdps(DIGITS):
            for i in range(n):
                for j in range(i, n):
                    assert_small(s[i, j] + s[j, i], largest(s), f"(H_dot - 2C)[{i},{j}] + [{j},{i}]")


@few_examples
@given(n=sizes, seed=seeds, state_seed=seeds)
def test_properties_christoffel_symbols_rebuild_c(n: int, seed: int, state_seed: int) -> None:
    system, derivation = chain(n, seed)
    qd = sp.Matrix([c.qd for c in system.coordinates])
    first, tutorial = derivation.christoffel_first_kind, derivation.christoffel
    assert set(first) == set(tutorial) == {(i, j, k) for i in range(n) for j in range(n) for k in range(n)}
    rebuilt = {
        "first kind": sp.Matrix(
            [sum(first[i, j, k] * qd[j] * qd[k] for j in range(n) for k in range(n)) for i in range(n)]
        ),
        "tutorial": sp.Matrix(
            [sum(tutorial[i, j, k] * qd[j] * qd[k] for j in range(n) for k in range(n)) for i in range(n)]
        ),
        "C(q, q_dot) q_dot": sp.Matrix(derivation.coriolis_matrix) * qd,
    }
    symmetry = sp.Matrix([first[i, j, k] - first[i, k, j] for i in range(n) for j in range(n) for k in range(n)])
    for state in random_states(system, state_seed):
        c = numeric(derivation.coriolis_vector, state)
        for how, expr in rebuilt.items():
            value = numeric(expr, state)
            with mpmath.workdps(DIGITS):
                for i in range(n):
                    assert_small(value[i] - c[i], largest(c, value), f"C[{i}] from {how}")
        with mpmath.workdps(DIGITS):
            for x in numeric(symmetry, state):
                assert_small(x, largest(c), "Gamma_ijk - Gamma_ikj")


# ---------------------------------------------------------------------------------------------
# Energy along the equations of motion
# ---------------------------------------------------------------------------------------------


def power_balance(system: Any, derivation: Any, state_seed: int) -> None:
    """d/dt (T + U) = q_dot . Q along the motion, with q_ddot = H^-1 (Q - C - G)."""
    energy = derivation.kinetic_energy + derivation.potential_energy
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    grad_q = sp.Matrix([energy.diff(x) for x in q])
    grad_qd = sp.Matrix([energy.diff(x) for x in qd])
    rhs = derivation.generalized_forces - derivation.coriolis_vector - derivation.gravity_vector
    for state in random_states(system, state_seed):
        h, f = numeric(derivation.mass_matrix, state), numeric(rhs, state)
        gq, gqd = numeric(grad_q, state), numeric(grad_qd, state)
        rates, forces = numeric(sp.Matrix(qd), state), numeric(derivation.generalized_forces, state)
        with mpmath.workdps(DIGITS):
            qdd = mpmath.lu_solve(h, f)
            de_dt = sum(gq[i] * rates[i] + gqd[i] * qdd[i] for i in range(len(q)))
            power = sum(forces[i] * rates[i] for i in range(len(q)))
            scale = largest(gq, gqd, qdd, forces)
            assert_small(de_dt - power, scale, f"dE/dt - q_dot.Q (dE/dt = {de_dt}, power = {power})")


@few_examples
@given(n=sizes, seed=seeds, state_seed=seeds)
def test_properties_energy_conserved_without_forces(n: int, seed: int, state_seed: int) -> None:
    system, derivation = chain(n, seed)
    assert not system.loads and not system.dampers and not system.generalized_forces
    assert all(e == 0 for e in derivation.generalized_forces)
    power_balance(system, derivation, state_seed)


@few_examples
@given(n=sizes, seed=seeds, state_seed=seeds)
def test_properties_energy_rate_is_power_of_forces(n: int, seed: int, state_seed: int) -> None:
    system, derivation = chain(n, seed, conservative=False)
    assert system.dampers and system.loads
    power_balance(system, derivation, state_seed)


# ---------------------------------------------------------------------------------------------
# Inertia tensors
# ---------------------------------------------------------------------------------------------


def rationals(low: int, high: int, denominator: int = 100) -> st.SearchStrategy[sp.Rational]:
    return st.integers(min_value=low, max_value=high).map(lambda k: sp.Rational(k, denominator))


symmetric_tensors = st.lists(rationals(-300, 300), min_size=6, max_size=6).map(
    lambda v: sp.ImmutableMatrix([[v[0], v[3], v[4]], [v[3], v[1], v[5]], [v[4], v[5], v[2]]])
)
vectors = st.lists(rationals(-300, 300), min_size=3, max_size=3).map(sp.ImmutableMatrix)


@given(inertia=symmetric_tensors, mass=rationals(1, 500), there=vectors, elsewhere=vectors)
def test_properties_shift_inertia_there_and_back(inertia: Any, mass: Any, there: Any, elsewhere: Any) -> None:
    # G -> O (d from O to G) and back: shifting with -m removes exactly the term that +m added
    at_o = shift_inertia(inertia, mass, there)
    assert shift_inertia(at_o, -mass, there) == inertia
    # the shift depends on d only through d d^T: O and its mirror image through G agree
    assert at_o == shift_inertia(inertia, mass, -there)
    # G -> A -> G -> B is G -> B
    at_b = shift_inertia(shift_inertia(shift_inertia(inertia, mass, there), -mass, there), mass, elsewhere)
    assert at_b == shift_inertia(inertia, mass, elsewhere)


def _exact(hundredths: int) -> str:
    """A number in hundredths, written as an exact expression of the spec grammar."""
    return f"{hundredths}/100"


def _part(kind: str, mass: int, size: list[int], at: list[int], axis: Any) -> dict[str, Any]:
    """A part spec from whole hundredths (mass, sizes and position)."""
    part: dict[str, Any] = {"shape": kind, "mass": _exact(mass), "at": [_exact(a) for a in at]}
    a, b, c = (_exact(x) for x in size)
    if kind == "box":
        part["size"] = [a, b, c]
    elif kind in ("cylinder", "thin_cylinder"):
        part |= {"radius": a, "length": b, "axis": axis}
    elif kind == "hollow_cylinder":
        part |= {"outer_radius": _exact(size[0] + size[2]), "inner_radius": a, "length": b, "axis": axis}
    elif kind == "rod":
        part |= {"length": b, "axis": axis}
    elif kind == "disc":
        part |= {"radius": a, "axis": axis}
    elif kind in ("sphere", "spherical_shell"):
        part["radius"] = a
    return part


positives = st.integers(min_value=1, max_value=300)  # hundredths
places = st.lists(st.integers(min_value=-300, max_value=300), min_size=3, max_size=3)
parts = st.builds(
    _part,
    kind=st.sampled_from(
        ["point", "box", "cylinder", "hollow_cylinder", "thin_cylinder", "rod", "disc", "sphere", "spherical_shell"]
    ),
    mass=positives,
    size=st.lists(positives, min_size=3, max_size=3),
    at=places,
    axis=st.sampled_from(["x", "y", "z", "-x"]),
)


def body_of(parts_of_body: list[dict[str, Any]]) -> Any:
    """The one body of a spec made of the given parts."""
    spec = {"title": "Random body", "bodies": {"body": {"parts": {f"p{i}": p for i, p in enumerate(parts_of_body)}}}}
    return system_of(spec).bodies[0]


@given(parts_of_body=st.lists(parts, min_size=1, max_size=4), shift=places)
def test_properties_body_inertia_parallel_axis(parts_of_body: list[dict[str, Any]], shift: list[int]) -> None:
    props = body_inertia(body_of(parts_of_body))
    # about the origin = about G shifted by the total mass, and back
    assert shift_inertia(props.inertia_com, props.mass, props.com) == props.inertia_origin
    assert shift_inertia(props.inertia_origin, -props.mass, props.com) == props.inertia_com
    # moving every part by the same vector moves G by it and leaves the inertia about G unchanged
    moved_parts = [
        p | {"at": [f"{a} + {_exact(d)}" for a, d in zip(p["at"], shift, strict=True)]} for p in parts_of_body
    ]
    moved = body_inertia(body_of(moved_parts))
    assert moved.mass == props.mass
    assert moved.inertia_com == props.inertia_com
    assert moved.com - props.com == sp.Matrix([sp.Rational(d, 100) for d in shift])


def _eigenvalues(inertia: Any) -> list[Any]:
    with mpmath.workdps(DIGITS):
        m = mpmath.matrix([[mpmath.mpf(str(sp.N(inertia[i, j], DIGITS + 5))) for j in range(3)] for i in range(3)])
        values, _ = mpmath.eigsy(m)
        return sorted(values)


def assert_same_spectrum(turned: Any, reference: Any) -> None:
    with mpmath.workdps(DIGITS):
        scale = largest(mpmath.mpf(str(sp.N(reference.trace(), DIGITS))))
        assert_small(mpmath.mpf(str(sp.N(turned.trace() - reference.trace(), DIGITS + 5))), scale, "trace")
        for a, b in zip(_eigenvalues(turned), _eigenvalues(reference), strict=True):
            assert_small(a - b, scale, "eigenvalue")


rotation_lists = st.lists(
    st.fixed_dictionaries(
        {
            "axis": st.one_of(
                st.sampled_from(["x", "y", "z", "-y"]),
                st.lists(st.integers(-3, 3), min_size=3, max_size=3).filter(any),
            ),
            "angle": st.integers(-180, 180).map(lambda d: f"{d} deg"),
        }
    ),
    min_size=1,
    max_size=2,  # body_inertia takes seconds for three turns about tilted axes
)


@few_examples
@given(mass=positives, size=st.lists(positives, min_size=3, max_size=3), orientation=rotation_lists)
def test_properties_inertia_invariant_under_rotation(mass: int, size: list[int], orientation: list[Any]) -> None:
    box = _part("box", mass, size, [0, 0, 0], None)
    plain = body_inertia(body_of([box])).inertia_com
    turned = body_inertia(body_of([box | {"orientation": orientation}])).inertia_com
    assert_same_spectrum(turned, plain)


@given(
    kind=st.sampled_from(["cylinder", "hollow_cylinder", "thin_cylinder", "rod", "disc"]),
    mass=positives,
    size=st.lists(positives, min_size=3, max_size=3),
    direction=st.lists(st.integers(-3, 3), min_size=3, max_size=3).filter(any),
)
def test_properties_inertia_of_tilted_axis_same_spectrum(
    kind: str, mass: int, size: list[int], direction: list[int]
) -> None:
    plain = body_inertia(body_of([_part(kind, mass, size, [0, 0, 0], "z")])).inertia_com
    tilted_part = _part(kind, mass, size, [0, 0, 0], "z") | {"axis": direction}
    tilted = body_inertia(body_of([tilted_part])).inertia_com
    assert_same_spectrum(tilted, plain)
