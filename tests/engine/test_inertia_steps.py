"""The mass-property steps a teacher shows (issue 15 item 4): shape formulas, parallel-axis shifts with
their m d^2 terms, the composite sum, the centre of mass, J about it and the principal axes about O and G,
against the tutorial's answer key (problem 1) and against numpy computed independently."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tests.seed import problems
from tutgen.engine.inertia import ENTRIES, body_inertia
from tutgen.model.system import Shape
from tutgen.spec.validate import load_system_text

P01 = str(SPECS / "tutorial-1" / "p01-composite-inertia.yaml")


def _p01():
    system, d, _ = solved(P01)
    bi = d.inertia[0]
    parts = {p.name: p for p in bi.parts}
    return system, d, bi, parts


def _num(system, expr) -> float:
    return float(sp.N(sp.sympify(expr).subs(system.values)))


def _answer(key: str):
    found = problems().get(1)
    if found is None:
        pytest.skip("the tutorial's answer key is missing")
    return found["answers"][key]["value"]


@pytest.mark.parametrize(
    ("part", "key", "label"),
    [
        pytest.param("block", "block_Ixx", "xx", id="block-xx"),
        pytest.param("block", "block_Iyy", "yy", id="block-yy"),
        pytest.param("block", "block_Izz", "zz", id="block-zz"),
    ],
)
def test_inertia_shape_formula_gives_tutorial_value(part: str, key: str, label: str) -> None:
    system, _, _, parts = _p01()
    f = parts[part].formula
    assert f is not None
    formula = dict(f.moments)[label]
    value = _num(system, formula.subs(dict(f.symbols)))
    assert value == pytest.approx(_answer(key), rel=2e-3)


def test_inertia_box_formula_is_written_in_its_symbols() -> None:
    _, _, _, parts = _p01()
    f = parts["block"].formula
    m, a, b, c = sp.symbols("m a b c")
    assert sp.simplify(dict(f.moments)["xx"] - m * (b**2 + c**2) / 12) == 0
    assert sp.simplify(dict(f.moments)["yy"] - m * (a**2 + c**2) / 12) == 0
    # the cylinder's axis is x: its axial moment is labelled xx, the transverse ones yy = zz
    cyl = parts["cylinder"].formula
    assert [label for label, _ in cyl.moments] == ["xx", "yy = zz"]
    assert parts["point"].formula is None


@pytest.mark.parametrize(
    ("label", "key", "distance_squared"),
    [
        pytest.param("xx", "cylinder_Ixx", 0.05**2, id="xx"),
        pytest.param("yy", "cylinder_Iyy", 0.065**2, id="yy"),
        pytest.param("zz", "cylinder_Izz", 0.065**2 + 0.05**2, id="zz"),
    ],
)
def test_inertia_parallel_axis_shift_has_its_m_d2_term(label: str, key: str, distance_squared: float) -> None:
    """The tutorial's distances (0.05, 0.065, sqrt(0.065^2 + 0.05^2) m) and its shifted values."""
    system, _, _, parts = _p01()
    cyl = parts["cylinder"]
    shift = next(s for s in cyl.shifts if s.label == label)
    mass = _num(system, cyl.mass)
    assert _num(system, shift.distance_squared) == pytest.approx(distance_squared, rel=1e-12)
    assert _num(system, shift.term) == pytest.approx(mass * distance_squared, rel=1e-12)
    assert _num(system, shift.value) == pytest.approx(_answer(key), rel=5e-3)
    assert _num(system, shift.centroidal) + _num(system, shift.term) == pytest.approx(_num(system, shift.value))


def test_inertia_product_shift_is_minus_m_dx_dy() -> None:
    system, _, bi, parts = _p01()
    cyl = parts["cylinder"]
    xy = next(s for s in cyl.shifts if s.label == "xy")
    mass = _num(system, cyl.mass)
    assert _num(system, xy.term) == pytest.approx(-mass * 0.065 * 0.05, rel=1e-12)
    products = dict(bi.products_origin)
    assert _num(system, products["xy"]) == pytest.approx(_answer("product_of_inertia_xy"), rel=2e-3)
    assert _num(system, products["yz"]) == 0 and _num(system, products["zx"]) == 0


def test_inertia_composite_sum_is_the_tutorial_total() -> None:
    system, _, bi, _ = _p01()
    by_label = {e.label: e for e in bi.composite}
    assert [e.label for e in bi.composite] == [label for label, _, _ in ENTRIES]
    for label, key in (("xx", "Ixx"), ("yy", "Iyy"), ("zz", "Izz")):
        entry = by_label[label]
        assert sum(_num(system, t) for t in entry.terms) == pytest.approx(_num(system, entry.total), rel=1e-12)
        assert _num(system, entry.total) == pytest.approx(_answer(key), rel=5e-3)
    tensor = np.array(_answer("inertia_tensor"))
    mine = np.array([[_num(system, bi.inertia_origin[i, j]) for j in range(3)] for i in range(3)])
    assert np.allclose(mine, tensor, atol=2e-5)


def _hand_com_tensor() -> tuple[np.ndarray, float, np.ndarray]:
    """p01 worked by hand with numpy: masses, centroids, centroidal tensors -> r_G and J_G."""
    rho = 7849.0
    m_b, m_c, m_p = rho * 0.05 * 0.15 * 0.05, rho * np.pi * 0.025**2 * 0.08, 1.0
    r = np.array([[0, 0, 0], [0.065, 0.05, 0], [0.1, 0, 0]])
    masses = np.array([m_b, m_c, m_p])
    j_b = np.diag([m_b * (0.15**2 + 0.05**2), m_b * (0.05**2 + 0.05**2), m_b * (0.05**2 + 0.15**2)]) / 12
    tr = m_c * (3 * 0.025**2 + 0.08**2) / 12
    j_c = np.diag([m_c * 0.025**2 / 2, tr, tr])
    own = [j_b, j_c, np.zeros((3, 3))]
    total = masses.sum()
    com = (masses[:, None] * r).sum(axis=0) / total
    j_g = np.zeros((3, 3))
    for m, ri, ji in zip(masses, r, own, strict=True):
        d = ri - com
        j_g += ji + m * (d @ d * np.eye(3) - np.outer(d, d))
    return com, total, j_g


def test_inertia_centre_of_mass_and_tensor_about_it() -> None:
    system, _, bi, _ = _p01()
    com, total, j_g = _hand_com_tensor()
    assert _num(system, bi.mass) == pytest.approx(total, rel=1e-12)
    assert [_num(system, x) for x in bi.com] == pytest.approx(list(com), rel=1e-10, abs=1e-15)
    assert [_num(system, x) / total for x in bi.first_moment] == pytest.approx(list(com), rel=1e-10, abs=1e-15)
    mine = np.array([[_num(system, bi.inertia_com[i, j]) for j in range(3)] for i in range(3)])
    assert np.allclose(mine, j_g, rtol=1e-10, atol=1e-15)
    shift = np.array([[_num(system, bi.com_shift[i, j]) for j in range(3)] for i in range(3)])
    j_o = np.array([[_num(system, bi.inertia_origin[i, j]) for j in range(3)] for i in range(3)])
    assert np.allclose(j_o - shift, j_g, rtol=1e-10, atol=1e-15)


def _check_principal(found, tensor: np.ndarray) -> None:
    values, vectors = np.linalg.eigh(tensor)
    assert list(found.moments) == pytest.approx(list(values), rel=1e-9)
    for moment, axis, reference in zip(found.moments, found.axes, vectors.T, strict=True):
        axis = np.array(axis)
        assert np.linalg.norm(axis) == pytest.approx(1.0, rel=1e-9)
        assert np.allclose(tensor @ axis, moment * axis, atol=1e-12)
        assert abs(axis @ reference) == pytest.approx(1.0, rel=1e-9)  # the same line, either sense


def test_inertia_principal_axes_about_origin_and_com() -> None:
    system, d, bi, _ = _p01()
    principal = d.principal[0]
    j_o = np.array([[_num(system, bi.inertia_origin[i, j]) for j in range(3)] for i in range(3)])
    _check_principal(principal.origin, j_o)
    _check_principal(principal.com, _hand_com_tensor()[2])
    assert list(principal.origin.moments) == pytest.approx(_answer("principal_moments"), rel=5e-3)
    # the tutorial's angle of the axis of least inertia about z, from +x
    least = principal.origin.axes[0]
    assert np.degrees(np.arctan2(least[1], least[0])) == pytest.approx(_answer("principal_axis_angle_deg"), abs=0.05)
    # about G the moments differ: the shift takes m(|r_G|^2 E - r_G r_G^T) off
    assert principal.com.moments[0] < principal.origin.moments[0]


def test_inertia_symbolic_body_has_no_principal_axes() -> None:
    system = load_system_text(
        "{title: t, parameters: [m, l], bodies: {b: {parts: {r: {shape: rod, mass: m, length: l, axis: x}}}}}",
        "t.yaml",
    )
    bi = body_inertia(system.bodies[0])
    f = bi.parts[0].formula
    assert f is not None and f.symbols[0][1] == system.parameters[0].symbol
    assert (
        dict(f.moments)["yy = zz"].subs(dict(f.symbols))
        == system.parameters[0].symbol * system.parameters[1].symbol ** 2 / 12
    )


@pytest.mark.parametrize(
    "shape",
    [
        pytest.param("{shape: cylinder, radius: r, length: h, axis: z}", id="cylinder"),
        pytest.param("{shape: hollow_cylinder, outer_radius: r, inner_radius: q, length: h, axis: y}", id="hollow"),
        pytest.param("{shape: thin_cylinder, radius: r, length: h, axis: x}", id="thin"),
        pytest.param("{shape: disc, radius: r, axis: z}", id="disc"),
        pytest.param("{shape: sphere, radius: r}", id="sphere"),
        pytest.param("{shape: spherical_shell, radius: r}", id="shell"),
        pytest.param("{shape: box, size: [r, q, h]}", id="box"),
    ],
)
def test_inertia_shape_formula_matches_the_tensor(shape: str) -> None:
    """Each formula, with the part's values put in, is the diagonal entry it names."""
    system = load_system_text(
        "{title: t, parameters: [m, r, q, h], bodies: {b: {parts: {p: " + shape[:-1] + ", mass: m}}}}}", "t.yaml"
    )
    part = body_inertia(system.bodies[0]).parts[0]
    f = part.formula
    assert f is not None and not f.turned
    index = {"xx": 0, "yy": 1, "zz": 2}
    for label, formula in f.moments:
        value = formula.subs(dict(f.symbols))
        for name in label.split("="):
            k = index[name.strip()]
            assert sp.simplify(part.inertia_centroid[k, k] - value) == 0
    assert part.shape is not Shape.POINT


@pytest.mark.parametrize(
    "diagonal",
    [
        (sp.Rational(1, 3), 2, 5),
        (7, sp.Rational(1, 12), sp.Rational(13, 12)),
        (0, sp.sqrt(2) / 7, sp.pi / 5),
        (sp.Rational(1, 10**14), 3, sp.Rational(2, 10**13)),
        (2, 2, 5),  # equal moments: eigsy's own order of their axes
        (5, 2, 2),
        (4, 4, 4),
    ],
)
def test_principal_axes_of_a_diagonal_tensor_are_eigsys_to_the_bit(diagonal: tuple[sp.Expr, ...]) -> None:
    """The diagonal short cut (the axes of the body's frame) gives what mpmath's eigsy gives, bit for
    bit, so that a sheet's JSON and keys are those of before; equal moments take eigsy's path itself."""
    import mpmath

    from tutgen.engine.inertia import _eigen_principal, principal_axes

    found = principal_axes(sp.ImmutableMatrix(sp.diag(*diagonal)))
    with mpmath.workdps(40):
        m = mpmath.matrix(
            [[mpmath.mpf(sp.N(x, 50)) if i == j else 0 for j, _ in enumerate(diagonal)] for i, x in enumerate(diagonal)]
        )
        reference = _eigen_principal(m, 12)
    assert found == reference
    assert [repr(x) for x in found.moments] == [repr(x) for x in reference.moments]
    _check_principal(found, np.diag([float(x) for x in diagonal]))
