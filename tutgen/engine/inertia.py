"""Mass, centre of mass and inertia tensors of primitive and composite bodies.

Convention: J_ab = integral (r^2 delta_ab - a b) dm, so the diagonal holds the moments of inertia
and the off-diagonal entries are the *negated* products of inertia (J_xy = -integral x y dm).
The parallel-axis theorem in tensor form: J_O = J_G + m (|d|^2 E - d d^T), with d from O to G.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath
import sympy as sp

from tutgen.errors import DerivationError
from tutgen.model.system import Body, Part, Shape

E3 = sp.ImmutableMatrix(sp.eye(3))
ZERO3 = sp.ImmutableMatrix.zeros(3, 1)


@dataclass(frozen=True)
class PartInertia:
    """One part's contribution, with the numbers a worked solution shows."""

    name: str
    shape: Shape
    volume: sp.Expr | None
    mass: sp.Expr
    centroid: sp.ImmutableMatrix  # in the body frame
    inertia_centroid: sp.ImmutableMatrix  # about the part's centroid, body axes
    axis_distances: tuple[sp.Expr, sp.Expr, sp.Expr]  # from the centroid to the body's x, y, z axes
    inertia_origin: sp.ImmutableMatrix  # about the body frame's origin (parallel-axis theorem)


@dataclass(frozen=True)
class BodyInertia:
    """A body's mass properties, about its frame's origin and about its centre of mass."""

    name: str
    mass: sp.Expr
    com: sp.ImmutableMatrix  # in the body frame
    inertia_origin: sp.ImmutableMatrix
    inertia_com: sp.ImmutableMatrix
    parts: tuple[PartInertia, ...]


def shift_inertia(inertia: sp.MatrixBase, mass: sp.Expr, d: sp.MatrixBase) -> sp.ImmutableMatrix:
    """Parallel-axis theorem: the inertia about a point at -d from the centroid (d from the point to G).

    Examples
    ========
    >>> import sympy as sp
    >>> m, l = sp.symbols("m l", positive=True)
    >>> shift_inertia(sp.zeros(3), m, sp.Matrix([l, 0, 0]))[1, 1]
    l**2*m
    """
    d = sp.Matrix(d)
    return sp.ImmutableMatrix((sp.Matrix(inertia) + mass * ((d.T * d)[0] * sp.eye(3) - d * d.T)).applyfunc(sp.expand))


def _axisymmetric(axial: sp.Expr, transverse: sp.Expr, axis: sp.MatrixBase) -> sp.ImmutableMatrix:
    """I = I_t (E - a a^T) + I_a a a^T for a unit axis a."""
    a = sp.Matrix(axis)
    aat = a * a.T
    return sp.ImmutableMatrix((transverse * (sp.eye(3) - aat) + axial * aat).applyfunc(sp.expand))


def part_volume(part: Part) -> sp.Expr | None:
    """The volume of a solid part, or None for idealised parts (points, rods, discs, shells)."""
    dims = dict(part.dimensions)
    if part.shape is Shape.BOX:
        a, b, c = dims["size"]  # type: ignore[misc]
        return a * b * c
    if part.shape is Shape.CYLINDER:
        return sp.pi * dims["radius"] ** 2 * dims["length"]  # type: ignore[operator]
    if part.shape is Shape.HOLLOW_CYLINDER:
        ro, ri = dims["outer_radius"], dims["inner_radius"]
        return sp.pi * (ro**2 - ri**2) * dims["length"]  # type: ignore[operator]
    if part.shape is Shape.SPHERE:
        return sp.Rational(4, 3) * sp.pi * dims["radius"] ** 3  # type: ignore[operator]
    return None


def part_mass(part: Part) -> tuple[sp.Expr, sp.Expr | None]:
    """(mass, volume): the given mass, or density x volume."""
    volume = part_volume(part)
    if part.mass is not None:
        return part.mass, volume
    if part.density is None or volume is None:  # validate.py guarantees this cannot happen
        raise DerivationError(f"part '{part.name}' needs a mass", part.origin)
    return part.density * volume, volume


def centroidal_inertia(part: Part, mass: sp.Expr) -> sp.ImmutableMatrix:
    """The inertia tensor of a primitive about its own centroid, in the body's axes."""
    dims = dict(part.dimensions)
    shape = part.shape
    if shape is Shape.POINT:
        return sp.ImmutableMatrix.zeros(3, 3)
    if shape is Shape.GENERAL:
        assert part.inertia is not None
        return part.inertia
    if shape is Shape.BOX:
        a, b, c = dims["size"]  # type: ignore[misc]
        own = sp.diag(mass * (b**2 + c**2) / 12, mass * (a**2 + c**2) / 12, mass * (a**2 + b**2) / 12)
        r = sp.Matrix(part.rotation)
        return sp.ImmutableMatrix((r * own * r.T).applyfunc(sp.expand))
    assert part.axis is not None or shape in (Shape.SPHERE, Shape.SPHERICAL_SHELL)
    if shape is Shape.SPHERE:
        return sp.ImmutableMatrix(sp.eye(3) * sp.Rational(2, 5) * mass * dims["radius"] ** 2)  # type: ignore[operator]
    if shape is Shape.SPHERICAL_SHELL:
        return sp.ImmutableMatrix(sp.eye(3) * sp.Rational(2, 3) * mass * dims["radius"] ** 2)  # type: ignore[operator]
    axis = part.axis
    assert axis is not None
    if shape is Shape.CYLINDER:
        r, h = dims["radius"], dims["length"]
        return _axisymmetric(mass * r**2 / 2, mass * (3 * r**2 + h**2) / 12, axis)  # type: ignore[operator]
    if shape is Shape.HOLLOW_CYLINDER:
        ro, ri, h = dims["outer_radius"], dims["inner_radius"], dims["length"]
        s = ro**2 + ri**2  # type: ignore[operator]
        return _axisymmetric(mass * s / 2, mass * (3 * s + h**2) / 12, axis)  # type: ignore[operator]
    if shape is Shape.THIN_CYLINDER:
        r, h = dims["radius"], dims["length"]
        return _axisymmetric(mass * r**2, mass * (6 * r**2 + h**2) / 12, axis)  # type: ignore[operator]
    if shape is Shape.ROD:
        length = dims["length"]
        return _axisymmetric(sp.Integer(0), mass * length**2 / 12, axis)  # type: ignore[operator]
    if shape is Shape.DISC:
        r = dims["radius"]
        return _axisymmetric(mass * r**2 / 2, mass * r**2 / 4, axis)  # type: ignore[operator]
    raise AssertionError(f"unhandled shape {shape}")  # pragma: no cover


def part_inertia(part: Part) -> PartInertia:
    mass, volume = part_mass(part)
    j_c = centroidal_inertia(part, mass)
    x, y, z = part.at
    distances = (
        sp.sqrt(sp.expand(y**2 + z**2)),
        sp.sqrt(sp.expand(x**2 + z**2)),
        sp.sqrt(sp.expand(x**2 + y**2)),
    )
    return PartInertia(
        name=part.name,
        shape=part.shape,
        volume=volume,
        mass=mass,
        centroid=part.at,
        inertia_centroid=j_c,
        axis_distances=distances,
        inertia_origin=shift_inertia(j_c, mass, part.at),
    )


def body_inertia(body: Body) -> BodyInertia:
    """Sum the parts about the body frame's origin, then shift to the centre of mass."""
    parts = tuple(part_inertia(p) for p in body.parts)
    mass = sp.expand(sum((p.mass for p in parts), sp.Integer(0)))
    first_moment = sum((p.mass * sp.Matrix(p.centroid) for p in parts), sp.zeros(3, 1))
    if mass == 0:
        com = ZERO3
    else:
        com = sp.ImmutableMatrix((first_moment / mass).applyfunc(sp.factor_terms))
    j_o = sp.ImmutableMatrix(sum((sp.Matrix(p.inertia_origin) for p in parts), sp.zeros(3, 3)))
    # J_O = J_G + m(|c|^2 E - c c^T)  =>  J_G = J_O - m(|c|^2 E - c c^T)
    c = sp.Matrix(com)
    shift = mass * ((c.T * c)[0] * sp.eye(3) - c * c.T)
    j_g = sp.ImmutableMatrix((sp.Matrix(j_o) - shift).applyfunc(lambda e: sp.cancel(sp.expand(e))))
    return BodyInertia(name=body.name, mass=mass, com=com, inertia_origin=j_o, inertia_com=j_g, parts=parts)


@dataclass(frozen=True)
class Principal:
    """Principal moments (ascending) and unit axes (columns, in body axes), as floats."""

    moments: tuple[float, float, float]
    axes: tuple[tuple[float, float, float], ...]


def principal_axes(inertia: sp.MatrixBase, digits: int = 12) -> Principal | None:
    """Principal moments and axes of a numeric tensor (None when it has symbols).

    Computed with mpmath at 40 digits and rounded, so the result is the same on every machine.
    The sign of each axis is fixed so that its largest component is positive.
    """
    if any(sp.Matrix(inertia).free_symbols):
        return None
    with mpmath.workdps(40):
        m = mpmath.matrix([[mpmath.mpf(sp.N(inertia[i, j], 50)) for j in range(3)] for i in range(3)])
        values, vectors = mpmath.eigsy(m)
        order = sorted(range(3), key=lambda k: values[k])
        moments = tuple(_round(values[k], digits) for k in order)
        axes = []
        for k in order:
            col = [vectors[i, k] for i in range(3)]
            big = max(range(3), key=lambda i: (abs(col[i]), -i))
            sign = 1 if col[big] >= 0 else -1
            axes.append(tuple(_round(sign * v, digits) for v in col))
    return Principal(moments=moments, axes=tuple(axes))  # type: ignore[arg-type]


def _round(x: mpmath.mpf, digits: int) -> float:
    value = float(mpmath.nstr(x, digits, strip_zeros=False, min_fixed=-1, max_fixed=-1))
    return 0.0 if abs(value) < 10.0 ** (-digits - 3) else value
