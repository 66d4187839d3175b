"""The one object every section builder shares: what the spec has declared so far, and every problem found.

Each builder of :mod:`tutgen.spec.builders` reads its part of the :class:`~tutgen.spec.schema.SpecDoc`,
declares what it names (parameters, coordinates, their dimensions) in the :class:`Context`, and
records each problem with its place instead of raising, so that the whole spec is checked and
reported at once. The helpers below read the kinds of value that every section has: names,
expressions and quantities (through the whitelist parser of :mod:`tutgen.spec.expr`; nothing here
evaluates user text as code), vectors, axes and rotations.
"""

from __future__ import annotations

import keyword
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from tutgen.errors import SpecError
from tutgen.model.system import GROUND, Coordinate
from tutgen.spec import schema as S
from tutgen.spec.builders.words import expected_dimension, found_dimension
from tutgen.spec.expr import FUNCTIONS, ExprError, parse_expression
from tutgen.spec.loader import KeyPath, SourceMap
from tutgen.spec.places import ARM_LINKS, NAMED_SECTIONS, where
from tutgen.spec.units import DIMENSIONS, Dimension, DimensionMismatch, dimension_of, parse_quantity

#: Names a spec may not declare: the world frame, the constant pi, time and the functions of expressions.
RESERVED_NAMES = frozenset({GROUND, "pi", "t", *FUNCTIONS})
#: The axes an axis may be written as (``x``, ``-y``, ``+z``), as unit vectors.
AXES = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}

#: A rotation as the spec gives it: a unit axis and an angle.
Rotation = tuple[sp.ImmutableMatrix, sp.Expr]


@dataclass(eq=False)
class Context:
    """The spec being built, the names declared so far, and the problems found.

    ``dropped`` are the parts of the spec set aside for shape errors (already reported): their names
    still count as declared, so that nothing else is reported because of them.
    """

    doc: S.SpecDoc
    data: dict[str, Any]  # the spec as loaded, for how something was written (a list shorthand, ...)
    smap: SourceMap
    dropped: set[KeyPath] = field(default_factory=set)
    errors: list[SpecError] = field(default_factory=list)
    params: dict[str, sp.Symbol] = field(default_factory=dict)
    coords: dict[str, Coordinate] = field(default_factory=dict)
    # the dimension of each symbol, where known (a joint may give its coordinate one)
    dims: dict[sp.Symbol, Dimension | None] = field(default_factory=dict)
    # the numeric values of the parameters that have one, once the parameters are built
    values: dict[sp.Symbol, sp.Expr] = field(default_factory=dict)

    @property
    def dropped_keys(self) -> set[str]:
        """The top-level keys set aside for shape errors."""
        return {str(u[0]) for u in self.dropped if len(u) == 1}

    def dropped_names(self, section: str) -> list[str]:
        """Names of the entries of ``section`` set aside for shape errors."""
        return sorted(str(u[1]) for u in self.dropped if len(u) == 2 and u[0] == section and isinstance(u[1], str))

    def dropped_arm_links(self) -> list[str]:
        """Names of the rows of the arm's table set aside for shape errors."""
        return sorted(str(u[2]) for u in self.dropped if len(u) == 3 and tuple(u[:2]) == ARM_LINKS)

    # -- problems ------------------------------------------------------------------------
    def error(self, path: KeyPath, message: str, hint: str | None = None, key: bool = False) -> None:
        """Record a problem at the value at ``path`` (at its key, with ``key``)."""
        loc = self.smap.key_location(path) if key else self.smap.location(path)
        self.errors.append(SpecError(loc, message, hint))

    def expr_error(self, path: KeyPath, exc: ExprError, hint: str | None = None) -> None:
        """Record a parse error at the character of the text at ``path`` where it was found."""
        self.errors.append(SpecError(self.smap.expr_location(path, exc.offset), exc.message, hint or exc.hint))

    # -- how the spec was written --------------------------------------------------------
    def written(self, path: KeyPath) -> Any:
        """The value at ``path`` in the spec as loaded (before shorthands are expanded); None if absent."""
        node: Any = self.data
        for key in path:
            if isinstance(node, dict):
                node = node.get(key)
            elif isinstance(node, list) and isinstance(key, int) and 0 <= key < len(node):
                node = node[key]
            else:
                return None
        return node

    def name_path(self, section: str, name: str) -> KeyPath:
        """Where a declared name was written: its key, or its item in a list shorthand ``[m1, m2]``."""
        written = self.written((section,))
        if isinstance(written, list) and name in written:
            return (section, written.index(name))
        return (section, name)

    # -- names ---------------------------------------------------------------------------
    def check_listed_twice(self, section: str) -> None:
        """A list shorthand ``[m, l, m]`` would silently merge the two ``m``: report the second one."""
        written = self.written((section,))
        if not isinstance(written, list):
            return
        first: dict[str, int] = {}
        for i, name in enumerate(written):
            if not isinstance(name, str):
                continue
            if name in first:
                where_first = self.smap.location((section, first[name]))
                self.error(
                    (section, i),
                    f"{NAMED_SECTIONS[section]} '{name}' is listed twice in '{section}' "
                    f"(first at line {where_first.line}, column {where_first.col})",
                    "a name may appear once; remove one of them",
                    key=True,
                )
            else:
                first[name] = i

    def check_name(self, path: KeyPath, name: str, what: str) -> bool:
        """Report a name that cannot be used; False if it must not even be declared (it would hide a function).

        A bad name is reported once, here: the object is still declared under it, so that whatever
        refers to it is not reported again as referring to something unknown.
        """
        if not name.isidentifier() or not name.isascii():
            self.error(
                path,
                f"{what} name '{name}' is not a valid name; expected letters, digits and _, "
                "starting with a letter (e.g. m1, theta_2)",
                key=True,
            )
            return True
        if keyword.iskeyword(name):
            self.error(
                path,
                f"{what} name '{name}' is a reserved word; choose another name (e.g. '{name}1')",
                key=True,
            )
            return True
        if name in FUNCTIONS or name in ("pi", "t"):
            kind = "a function" if name in FUNCTIONS else "the constant pi" if name == "pi" else "time"
            self.error(path, f"{what} name '{name}' is reserved: it is {kind} in expressions", key=True)
            return False
        if name == GROUND:
            self.error(path, f"{what} name '{name}' is reserved: it is the fixed world frame", key=True)
            return True
        if name.endswith(("_dot", "_ddot")):
            self.error(
                path,
                f"{what} name '{name}' is reserved: NAME_dot and NAME_ddot are the velocity and acceleration "
                "of a coordinate",
                key=True,
            )
            return True
        return True

    def check_name_free(self, path: KeyPath, name: str, what: str) -> bool:
        """Report a body (or link) named like a parameter or coordinate; False if it is."""
        if name not in self.params and name not in self.coords:
            return True
        self.error(
            path,
            f"'{name}' is already the name of a {'parameter' if name in self.params else 'coordinate'}"
            f"; give the {what} another name",
            key=True,
        )
        return False

    def symbols(self, *, coords: bool = False, rates: bool = False, accel: bool = False) -> dict[str, sp.Expr]:
        """The names an expression may use: the parameters, and on request the coordinates, their rates
        (``NAME_dot``) and accelerations (``NAME_ddot``)."""
        table: dict[str, sp.Expr] = dict(self.params)
        if coords:
            for c in self.coords.values():
                table[c.name] = c.q
                if rates:
                    table[f"{c.name}_dot"] = c.qd
                if accel:
                    table[f"{c.name}_ddot"] = c.qdd
        return table

    # -- values --------------------------------------------------------------------------
    def expr(
        self,
        path: KeyPath,
        value: Any,
        names: Mapping[str, sp.Expr],
        dimension: str | None = None,
        what: str = "",
    ) -> sp.Expr | None:
        """Parse one expression (or quantity) at ``path``; record an error and return None if bad.

        ``what`` names the value in a message when its dimension alone does not ("gravity").
        """
        expected = ""
        if dimension is not None:
            expected = expected_dimension(dimension)
            if what and what.split(" ", 1)[-1] != dimension.replace("_", " "):
                expected += f" for {what}"
        if isinstance(value, str):
            try:
                quantity = parse_quantity(value)
            except ExprError as exc:
                self.expr_error(path, exc)
                return None
            if quantity is not None:
                if dimension is not None and quantity.dimension != DIMENSIONS[dimension]:
                    found_words = found_dimension(quantity.dimension)
                    self.error(path, f"expected {expected}, found '{value}', which is {found_words}")
                    return None
                return quantity.value
        try:
            result = parse_expression(value, names)
        except ExprError as exc:
            self.expr_error(path, exc, self._name_hint(exc))
            return None
        if dimension is not None:
            try:
                found = dimension_of(result, self.dims)
            except DimensionMismatch as exc:
                self.error(path, f"the units in '{value}' do not agree: {exc.args[0] if exc.args else exc}")
                return None
            if found is not None and found != DIMENSIONS[dimension] and not result.is_number:
                self.error(path, f"expected {expected}, found '{value}', which is {found_dimension(found)}")
                return None
        return result

    def _name_hint(self, exc: ExprError) -> str | None:
        """Why a declared name is unknown here: a coordinate in a constant, a velocity outside T and forces."""
        match = re.fullmatch(r"unknown name '([A-Za-z_][A-Za-z0-9_]*)'", exc.message)
        if match is None:
            return None
        name = match[1]
        base = re.sub(r"_d?dot$", "", name)
        if name in self.coords:
            return f"'{name}' is a coordinate; this value must be constant (parameters and numbers only)"
        if name in self.params:
            return f"'{name}' is a parameter; this value must be given by numbers only"
        if base != name and base in self.coords:
            if name.endswith("_ddot"):
                return f"'{name}' is the acceleration of coordinate '{base}'; no value in a spec may depend on it"
            return (
                f"'{name}' is the velocity of coordinate '{base}'; velocities may appear only in "
                "`energy.kinetic`, `loads` and `generalized_forces`"
            )
        return None

    def vector(
        self, path: KeyPath, values: list[Any] | None, names: Mapping[str, sp.Expr], dimension: str | None = None
    ) -> sp.ImmutableMatrix | None:
        """A column vector of expressions (zero when not given); None if a component is bad."""
        if values is None:
            return sp.ImmutableMatrix.zeros(3, 1)
        comps = [self.expr((*path, i), v, names, dimension) for i, v in enumerate(values)]
        if any(c is None for c in comps):
            return None
        return sp.ImmutableMatrix(comps)

    def axis(self, path: KeyPath, value: Any, names: Mapping[str, sp.Expr]) -> sp.ImmutableMatrix | None:
        """A unit direction: ``x``, ``-y``, ... or a constant vector, normalised exactly."""
        if isinstance(value, str):
            sign = -1 if value.startswith("-") else 1
            return sp.ImmutableMatrix([sign * v for v in AXES[value.lstrip("+-")]])
        vec = self.vector(path, value, names)
        if vec is None:
            return None
        norm2 = sp.expand(sum((v**2 for v in vec), sp.Integer(0)))
        if norm2 == 0:
            self.error(path, f"{where(path)} must be a direction; found the zero vector")
            return None
        if norm2.free_symbols:
            self.error(path, "expected a constant direction (numbers), found one that depends on symbols")
            return None
        return sp.ImmutableMatrix([sp.nsimplify(v / sp.sqrt(norm2)) for v in vec])

    def rotations(
        self, path: KeyPath, specs: list[S.RotationSpec] | None, names: Mapping[str, sp.Expr]
    ) -> tuple[Rotation, ...] | None:
        """An ``orientation``: its rotations in the order written; None if one is bad."""
        out = []
        for i, r in enumerate(specs or []):
            axis = self.axis((*path, i, "axis"), r.axis, {})
            angle = self.expr((*path, i, "angle"), r.angle, names, "angle", "an angle")
            if axis is None or angle is None:
                return None
            out.append((axis, angle))
        return tuple(out)


def rotation_matrix(rotations: tuple[Rotation, ...]) -> sp.ImmutableMatrix:
    """The product of ``rotations`` in the order written (each about an axis of the frame so far)."""
    if not rotations:
        return sp.ImmutableMatrix(sp.eye(3))
    # imported here, not at the top: spec/ comes before engine/ in the pipeline and borrows only this
    # one formula from it
    from tutgen.engine.kinematics import rotation_about

    r = sp.eye(3)
    for axis, angle in rotations:
        r = r * rotation_about(axis, angle)
    return sp.ImmutableMatrix(r)
