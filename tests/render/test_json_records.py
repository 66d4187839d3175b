"""Records of the worked solution in the JSON output (docs/json-output.md): the principal axes about the
centre of mass, and planar Newton-Euler as taught (free bodies, balances, elimination, reactions)."""

from __future__ import annotations

import numpy as np
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.spec.expr import ExpressionParser

TUTORIAL = SPECS / "tutorial-1"


def _reader(doc):
    names = {p: sp.Symbol(p) for p, v in doc["parameters"].items() if v is None}
    for c in doc["coordinates"]:
        for suffix in ("", "_dot", "_ddot"):
            names[c + suffix] = sp.Symbol(c + suffix)
    return lambda v: ExpressionParser(v, names).parse() if isinstance(v, str) else sp.nsimplify(v)


def test_principal_axes_about_the_centre_of_mass_are_the_eigenvectors_of_the_tensor_about_it():
    """p01: the JSON's principal moments and axes about G diagonalise its own inertia_tensor_com, and
    differ from those about the origin (the block is not centred there)."""
    doc = solved(str(TUTORIAL / "p01-composite-inertia.yaml"))[2]
    (body,) = doc["results"]["bodies"].values()
    j_g = np.array(body["inertia_tensor_com"], dtype=float)
    moments = np.array(body["principal_moments_com"])
    axes = np.array(body["principal_axes_com"])  # one axis per row or per column: test both readings
    assert np.allclose(np.sort(moments), np.linalg.eigvalsh(j_g), rtol=1e-9)
    by_column = np.allclose(j_g @ axes, axes * moments, atol=1e-9)
    by_row = np.allclose(j_g @ axes.T, axes.T * moments, atol=1e-9)
    assert by_column or by_row
    assert not np.allclose(moments, body["principal_moments"], rtol=1e-3)


def test_planar_newton_euler_records_name_every_force_and_eliminate_to_lagranges_equations():
    """p03 (methods: both): the cart's free body holds the spring and the applied force, its x balance
    the spring's -k x; each eliminated equation is Lagrange's equation of its coordinate."""
    doc = solved(str(TUTORIAL / "p03-cart-pendulum.yaml"))[2]
    results = doc["results"]
    planar = results["newton_euler"]["planar"]
    read = _reader(doc)
    cart = next(b for b in planar["balances"] if b["body"] == "cart")
    kinds = [f["kind"] for f in cart["forces"]]
    assert {"gravity", "load", "spring", "reaction", "inertial_force"} <= set(kinds)
    spring = next(f for f in cart["forces"] if f["kind"] == "spring")
    k, x = sp.symbols("k x")
    assert sp.expand(read(spring["force"][0]) + k * x) == 0
    assert "k*x" in cart["sum_fx"] and "F" in cart["sum_fx"]
    pendulum = next(b for b in planar["balances"] if b["body"] == "pendulum")
    assert "joint 'pivot'" in pendulum["about"]
    order = doc["coordinates"]
    assert sorted(s["coordinate"] for s in planar["elimination"]) == sorted(order)
    for s in planar["elimination"]:
        lagrange = read(results["equations_of_motion"][order.index(s["coordinate"])])
        assert sp.simplify(read(s["equation"]) - lagrange) == 0, s["coordinate"]
    # the reaction at the pivot is the pendulum's: solved, in the coordinates only (no unknowns left)
    pivot = planar["reactions"]["pivot"]
    assert pivot["child"] == "pendulum" and set(pivot["unknowns"]) == {"R[pivot].x", "R[pivot].y"}
    for v in pivot["unknowns"].values():
        assert "R[" not in str(v)
        read(v)


def test_planar_records_are_absent_where_newton_euler_is_not_presented():
    """p05 asks for Lagrange's working only: its Newton-Euler is the agreement check, with no planar
    working in the JSON."""
    doc = solved(str(TUTORIAL / "p05-rr-arm.yaml"))[2]
    assert "planar" not in doc["results"].get("newton_euler", {})
