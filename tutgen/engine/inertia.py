"""Mass, centre of mass and inertia tensors of primitive and composite bodies.

Convention: J_ab = integral (r^2 delta_ab - a b) dm, so the diagonal holds the moments of inertia
and the off-diagonal entries are the *negated* products of inertia (J_xy = -integral x y dm).
The parallel-axis theorem in tensor form: J_O = J_G + m (|d|^2 E - d d^T), with d from O to G.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import mpmath
import sympy as sp

from tutgen.errors import DerivationError
from tutgen.model.system import Body, Part, Shape

E3 = sp.ImmutableMatrix(sp.eye(3))
ZERO3 = sp.ImmutableMatrix.zeros(3, 1)
ZERO33 = sp.ImmutableMatrix.zeros(3, 3)


#: the six independent entries of a symmetric tensor, as (label, row, column)
ENTRIES: tuple[tuple[str, int, int], ...] = (
    ("xx", 0, 0),
    ("yy", 1, 1),
    ("zz", 2, 2),
    ("xy", 0, 1),
    ("yz", 1, 2),
    ("zx", 2, 0),
)
AXES = "xyz"


@dataclass(frozen=True)
class ShapeFormula:
    """A primitive's textbook moments about its centroid, in the shape's own symbols.

    ``symbols`` pairs each symbol of the formulas (``m``, ``a``, ``r``, ...) with the part's value of it;
    ``moments`` are (label, formula): ``("xx", m*(b**2 + c**2)/12)``. A label names body axes (``xx``)
    when the shape's axes are the body's, or the shape's own (``axial``, ``transverse``; a turned box's
    ``x'x'``) when they are not; ``turned`` says the tensor is then turned into the body's axes.
    """

    symbols: tuple[tuple[sp.Symbol, sp.Expr], ...]
    moments: tuple[tuple[str, sp.Expr], ...]
    turned: bool = False
    axis: sp.ImmutableMatrix | None = None  # the symmetry axis in body axes (axisymmetric shapes)


@dataclass(frozen=True)
class AxisShift:
    """One entry of the parallel-axis theorem, J_O,ab = J_G,ab + term.

    For a moment (``xx``) the term is m d^2 with d^2 the squared distance between the parallel axes
    (d_y^2 + d_z^2 for x); for a product entry (``xy``) it is -m d_x d_y (J_ab holds minus the product of
    inertia). ``distance_squared`` is d^2, or d_a d_b for a product entry.
    """

    label: str
    centroidal: sp.Expr
    distance_squared: sp.Expr
    term: sp.Expr
    value: sp.Expr


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
    formula: ShapeFormula | None = None  # None: a point (no own inertia) or a tensor given directly
    shifts: tuple[AxisShift, ...] = ()  # the six entries of the shift to the origin (ENTRIES order)


@dataclass(frozen=True)
class CompositeEntry:
    """One entry of a composite body's tensor about the origin: the parts' values and their sum."""

    label: str
    terms: tuple[sp.Expr, ...]  # per part, in spec order
    total: sp.Expr


@dataclass(frozen=True)
class BodyInertia:
    """A body's mass properties, about its frame's origin and about its centre of mass."""

    name: str
    mass: sp.Expr
    com: sp.ImmutableMatrix  # in the body frame
    inertia_origin: sp.ImmutableMatrix
    inertia_com: sp.ImmutableMatrix
    parts: tuple[PartInertia, ...]
    first_moment: sp.ImmutableMatrix = ZERO3  # sum of m_p r_p, so com = first_moment / mass
    composite: tuple[CompositeEntry, ...] = ()  # J_O entry by entry as the sum of its parts (ENTRIES order)
    # m(|c|^2 E - c c^T), c the centre of mass: J_G = J_O - com_shift (the parallel-axis theorem backwards)
    com_shift: sp.ImmutableMatrix = ZERO33

    @property
    def products_origin(self) -> tuple[tuple[str, sp.Expr], ...]:
        """The products of inertia about the origin, P_ab = integral a b dm = -J_ab (xy, yz, zx)."""
        return tuple((label, -self.inertia_origin[i, j]) for label, i, j in ENTRIES[3:])


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


def _axis_label(axis: sp.MatrixBase | None) -> int | None:
    """The index of the body axis a unit symmetry axis lies along (either sense), or None."""
    if axis is None:
        return None
    a = list(axis)
    hits = [k for k in range(3) if a[k] != 0]
    return hits[0] if len(hits) == 1 else None


def shape_formula(part: Part, mass: sp.Expr) -> ShapeFormula | None:
    """The textbook formulas of a primitive's centroidal moments, in its own symbols (None for a point,
    whose own inertia is zero, and for a tensor given directly).

    Examples
    ========
    >>> from tutgen.model.system import Part, Shape
    >>> from tutgen.errors import Location
    >>> box = Part("b", Shape.BOX, sp.Integer(2), None, (("size", (1, 2, 3)),), sp.ImmutableMatrix([0, 0, 0]),
    ...            None, sp.ImmutableMatrix(sp.eye(3)), None, Location("<t>"))
    >>> shape_formula(box, sp.Integer(2)).moments[0]
    ('xx', m*(b**2 + c**2)/12)
    """
    dims = dict(part.dimensions)
    m = sp.Symbol("m")
    shape = part.shape
    if shape in (Shape.POINT, Shape.GENERAL):
        return None
    if shape is Shape.BOX:
        a, b, c = sp.symbols("a b c")
        sizes = dims["size"]
        turned = sp.Matrix(part.rotation) != sp.eye(3)
        names = ("x'x'", "y'y'", "z'z'") if turned else ("xx", "yy", "zz")
        moments = (m * (b**2 + c**2) / 12, m * (a**2 + c**2) / 12, m * (a**2 + b**2) / 12)
        return ShapeFormula(
            ((m, mass), (a, sizes[0]), (b, sizes[1]), (c, sizes[2])),  # type: ignore[index]
            tuple(zip(names, moments, strict=True)),
            turned,
        )
    r = sp.Symbol("r")
    if shape is Shape.SPHERE:
        return ShapeFormula(((m, mass), (r, dims["radius"])), (("xx = yy = zz", sp.Rational(2, 5) * m * r**2),))  # type: ignore[arg-type]
    if shape is Shape.SPHERICAL_SHELL:
        return ShapeFormula(((m, mass), (r, dims["radius"])), (("xx = yy = zz", sp.Rational(2, 3) * m * r**2),))  # type: ignore[arg-type]
    h = sp.Symbol("h")
    if shape is Shape.CYLINDER:
        symbols = ((m, mass), (r, dims["radius"]), (h, dims["length"]))
        axial, transverse = m * r**2 / 2, m * (3 * r**2 + h**2) / 12
    elif shape is Shape.HOLLOW_CYLINDER:
        ro, ri = sp.symbols("r_o r_i")
        symbols = ((m, mass), (ro, dims["outer_radius"]), (ri, dims["inner_radius"]), (h, dims["length"]))
        axial, transverse = m * (ro**2 + ri**2) / 2, m * (3 * (ro**2 + ri**2) + h**2) / 12
    elif shape is Shape.THIN_CYLINDER:
        symbols = ((m, mass), (r, dims["radius"]), (h, dims["length"]))
        axial, transverse = m * r**2, m * (6 * r**2 + h**2) / 12
    elif shape is Shape.ROD:
        ell = sp.Symbol("l")
        symbols = ((m, mass), (ell, dims["length"]))
        axial, transverse = sp.Integer(0), m * ell**2 / 12
    elif shape is Shape.DISC:
        symbols = ((m, mass), (r, dims["radius"]))
        axial, transverse = m * r**2 / 2, m * r**2 / 4
    else:  # pragma: no cover
        raise AssertionError(f"unhandled shape {shape}")
    k = _axis_label(part.axis)
    if k is None:
        labels = ("axial", "transverse")
    else:
        others = [AXES[i] * 2 for i in range(3) if i != k]
        labels = (AXES[k] * 2, f"{others[0]} = {others[1]}")
    return ShapeFormula(symbols, ((labels[0], axial), (labels[1], transverse)), k is None, part.axis)  # type: ignore[arg-type]


def axis_shifts(j_c: sp.MatrixBase, mass: sp.Expr, d: sp.MatrixBase) -> tuple[AxisShift, ...]:
    """The parallel-axis theorem entry by entry (ENTRIES order): J_O,aa = J_G,aa + m (d_b^2 + d_c^2) and
    J_O,ab = J_G,ab - m d_a d_b, with d from the origin to the centroid."""
    out = []
    for label, i, j in ENTRIES:
        if i == j:
            d2 = sp.Add(*[d[k] ** 2 for k in range(3) if k != i])
            term = mass * d2
        else:
            d2 = d[i] * d[j]
            term = -mass * d2
        out.append(AxisShift(label, j_c[i, j], d2, term, sp.expand(j_c[i, j] + term)))
    return tuple(out)


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
        formula=shape_formula(part, mass),
        shifts=axis_shifts(j_c, mass, part.at),
    )


@functools.lru_cache(maxsize=1024)
def body_inertia(body: Body) -> BodyInertia:
    """Sum the parts about the body frame's origin, then shift to the centre of mass.

    Cached (bodies are frozen values): the serial route and its numeric checks ask for the same body's
    inertia up to eight times, a third of a second each on the symbolic PUMA's six links (issue 17)."""
    parts = tuple(part_inertia(p) for p in body.parts)
    mass = sp.expand(sum((p.mass for p in parts), sp.Integer(0)))
    first_moment = sp.ImmutableMatrix(sum((p.mass * sp.Matrix(p.centroid) for p in parts), sp.zeros(3, 1)))
    if mass == 0:
        com = ZERO3
    else:
        com = sp.ImmutableMatrix((first_moment / mass).applyfunc(sp.factor_terms))
    j_o = sp.ImmutableMatrix(sum((sp.Matrix(p.inertia_origin) for p in parts), sp.zeros(3, 3)))
    composite = tuple(
        CompositeEntry(label, tuple(p.inertia_origin[i, j] for p in parts), j_o[i, j]) for label, i, j in ENTRIES
    )
    # J_O = J_G + m(|c|^2 E - c c^T)  =>  J_G = J_O - m(|c|^2 E - c c^T)
    c = sp.Matrix(com)
    shift = (mass * ((c.T * c)[0] * sp.eye(3) - c * c.T)).applyfunc(lambda e: sp.cancel(sp.expand(e)))
    j_g = sp.ImmutableMatrix((sp.Matrix(j_o) - shift).applyfunc(lambda e: sp.cancel(sp.expand(e))))
    return BodyInertia(
        name=body.name,
        mass=mass,
        com=com,
        inertia_origin=j_o,
        inertia_com=j_g,
        parts=parts,
        first_moment=first_moment,
        composite=composite,
        com_shift=sp.ImmutableMatrix(shift),
    )


@dataclass(frozen=True)
class Principal:
    """Principal moments (ascending) and unit axes (columns, in body axes), as floats."""

    moments: tuple[float, float, float]
    axes: tuple[tuple[float, float, float], ...]


@dataclass(frozen=True)
class BodyPrincipal:
    """A body's principal moments and axes about its frame's origin O and about its centre of mass G
    (each None when the tensor has symbols)."""

    origin: Principal | None
    com: Principal | None


def body_principal(bi: BodyInertia, values: dict[sp.Symbol, sp.Expr]) -> BodyPrincipal:
    """The principal axes of a body about O and about G, with the parameters' numeric ``values``."""

    def numeric(m: sp.ImmutableMatrix) -> sp.MatrixBase:
        return m.xreplace(values) if values else m  # symbols for numbers: xreplace is subs, many times faster

    return BodyPrincipal(principal_axes(numeric(bi.inertia_origin)), principal_axes(numeric(bi.inertia_com)))


def principal_axes(inertia: sp.MatrixBase, digits: int = 12) -> Principal | None:
    """Principal moments and axes of a numeric tensor (None when it has symbols).

    Computed with mpmath at 40 digits and rounded, so the result is the same on every machine.
    The sign of each axis is fixed so that its largest component is positive.
    """
    if any(sp.Matrix(inertia).free_symbols):
        return None
    with mpmath.workdps(40):
        m = mpmath.matrix([[mpmath.mpf(sp.N(inertia[i, j], 50)) for j in range(3)] for i in range(3)])
        diagonal = [m[k, k] for k in range(3)]
        if len(set(diagonal)) < 3 or any(m[i, j] != 0 for i in range(3) for j in range(3) if i != j):
            return _eigen_principal(m, digits)
        # the axes of the body's own frame (most bodies): eigsy's result without its iteration (a sheet's
        # every variant asks); equal moments are left to eigsy, whose order of their axes rules
        order = sorted(range(3), key=lambda k: diagonal[k])
        moments = tuple(_round(diagonal[k], digits) for k in order)
        axes = tuple(tuple(1.0 if i == k else 0.0 for i in range(3)) for k in order)
    return Principal(moments=moments, axes=axes)  # type: ignore[arg-type]


def _eigen_principal(m: mpmath.matrix, digits: int) -> Principal:
    """:func:`principal_axes` of the mpmath matrix ``m`` by ``mpmath.eigsy`` (at the caller's precision)."""
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
