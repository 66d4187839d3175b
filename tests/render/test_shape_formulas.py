"""A part's moments about its centroid are printed as a textbook writes its shape's formulas (the
tutorial: ``\\tfrac1{12} m (3r^2 + h^2)``, ``\\tfrac1{12}(15)(1.5)^2``), not in sympy's order
(``m (h^2 + 3 r^2)/12``, ``l^2 m/12``); the printed form is the formula itself."""

from __future__ import annotations

import pytest
import sympy as sp

from tutgen.engine.inertia import ShapeFormula, shape_formula
from tutgen.errors import Location
from tutgen.model.system import Part, Shape
from tutgen.render.sections.inertia import shape_tex

_DIMENSIONS = {
    Shape.BOX: (("size", (sp.Integer(1), sp.Integer(2), sp.Integer(3))),),
    Shape.CYLINDER: (("radius", sp.Integer(1)), ("length", sp.Integer(4))),
    Shape.HOLLOW_CYLINDER: (
        ("outer_radius", sp.Integer(2)),
        ("inner_radius", sp.Integer(1)),
        ("length", sp.Integer(4)),
    ),
    Shape.THIN_CYLINDER: (("radius", sp.Integer(1)), ("length", sp.Integer(4))),
    Shape.ROD: (("length", sp.Integer(3)),),
    Shape.DISC: (("radius", sp.Integer(1)),),
    Shape.SPHERE: (("radius", sp.Integer(1)),),
    Shape.SPHERICAL_SHELL: (("radius", sp.Integer(1)),),
}

#: each shape's moments as printed, in the order of its formula's labels
_PRINTED = {
    Shape.BOX: [
        r"\tfrac{1}{12} m \left(b^{2} + c^{2}\right)",
        r"\tfrac{1}{12} m \left(a^{2} + c^{2}\right)",
        r"\tfrac{1}{12} m \left(a^{2} + b^{2}\right)",
    ],
    Shape.CYLINDER: [r"\tfrac{1}{2} m r^{2}", r"\tfrac{1}{12} m \left(3 r^{2} + h^{2}\right)"],
    Shape.HOLLOW_CYLINDER: [
        r"\tfrac{1}{2} m \left(r_{o}^{2} + r_{i}^{2}\right)",
        r"\tfrac{1}{12} m \left(3 r_{o}^{2} + 3 r_{i}^{2} + h^{2}\right)",
    ],
    Shape.THIN_CYLINDER: [r"m r^{2}", r"\tfrac{1}{12} m \left(6 r^{2} + h^{2}\right)"],
    Shape.ROD: [r"\tfrac{1}{12} m l^{2}"],  # its axial moment is 0, printed as 0
    Shape.DISC: [r"\tfrac{1}{2} m r^{2}", r"\tfrac{1}{4} m r^{2}"],
    Shape.SPHERE: [r"\tfrac{2}{5} m r^{2}"],
    Shape.SPHERICAL_SHELL: [r"\tfrac{2}{3} m r^{2}"],
}


def _formula(shape: Shape) -> ShapeFormula:
    axis = None if shape in (Shape.BOX, Shape.SPHERE, Shape.SPHERICAL_SHELL) else sp.ImmutableMatrix([1, 0, 0])
    part = Part(
        "p", shape, sp.Integer(2), None, _DIMENSIONS[shape], sp.ImmutableMatrix([0, 0, 0]), axis,
        sp.ImmutableMatrix(sp.eye(3)), None, Location("<test>"),
    )  # fmt: skip
    found = shape_formula(part, sp.Integer(2))
    assert found is not None
    return found


m, r, h, a, b, c, ell, ro, ri = sp.symbols("m r h a b c l r_o r_i")
#: the same formulas as sympy expressions, as a handbook gives them
_HANDBOOK = {
    Shape.BOX: [m * (b**2 + c**2) / 12, m * (a**2 + c**2) / 12, m * (a**2 + b**2) / 12],
    Shape.CYLINDER: [m * r**2 / 2, m * (3 * r**2 + h**2) / 12],
    Shape.HOLLOW_CYLINDER: [m * (ro**2 + ri**2) / 2, m * (3 * ro**2 + 3 * ri**2 + h**2) / 12],
    Shape.THIN_CYLINDER: [m * r**2, m * (6 * r**2 + h**2) / 12],
    Shape.ROD: [m * ell**2 / 12],
    Shape.DISC: [m * r**2 / 2, m * r**2 / 4],
    Shape.SPHERE: [2 * m * r**2 / 5],
    Shape.SPHERICAL_SHELL: [2 * m * r**2 / 3],
}


@pytest.mark.parametrize("shape", list(_PRINTED), ids=lambda s: s.value)
def test_each_shapes_moments_print_as_a_textbook_writes_them(shape: Shape) -> None:
    """Each printed form is the handbook's formula written as the handbook writes it; the engine's formula
    is the handbook's (so the printed one is the engine's)."""
    f = _formula(shape)
    moments = [formula for _, formula in f.moments if formula != 0]
    assert moments == _HANDBOOK[shape]
    assert [shape_tex(f, formula) for formula in moments] == _PRINTED[shape]


def test_the_numbers_go_in_where_the_symbols_were() -> None:
    """Tutorial problem 2: ``\tfrac1{12}(15)(1.5)^2``; a number that is not a plain decimal is bracketed
    before its power."""
    f = _formula(Shape.CYLINDER)
    transverse = f.moments[1][1]
    numbers = {m: "1.233", r: "0.025", h: "0.08"}
    assert shape_tex(f, transverse, numbers) == (
        r"\tfrac{1}{12} \cdot 1.233 \cdot \left(3 \cdot 0.025^{2} + 0.08^{2}\right)"
    )
    numbers = {m: "15", r: r"375 \times 10^{-6}", h: "2"}
    assert shape_tex(f, f.moments[0][1], numbers) == r"\tfrac{1}{2} \cdot 15 \cdot \left(375 \times 10^{-6}\right)^{2}"


def test_a_tables_cell_sets_the_fraction_over_the_whole() -> None:
    f = _formula(Shape.CYLINDER)
    assert shape_tex(f, f.moments[1][1], stacked=True) == r"\frac{m \left(3 r^{2} + h^{2}\right)}{12}"
    sphere = _formula(Shape.SPHERE)
    assert shape_tex(sphere, sphere.moments[0][1], stacked=True) == r"\frac{2 m r^{2}}{5}"
    thin = _formula(Shape.THIN_CYLINDER)
    assert shape_tex(thin, thin.moments[0][1], stacked=True) == r"m r^{2}"


def test_a_formula_of_another_form_is_printed_by_sympy() -> None:
    f = _formula(Shape.CYLINDER)
    odd = m * sp.sin(r) / 2 + h
    assert shape_tex(f, odd) == sp.latex(odd)
