"""Spec data -> :class:`tutgen.model.System`: shape, names, expressions, units and cross-references.

Every problem is collected with its ``file:line:col`` and reported at once (:class:`SpecErrors`).
Expressions go through the whitelist parser of :mod:`tutgen.spec.expr`; nothing here evaluates
user text as code.
"""

from __future__ import annotations

import difflib
import keyword
import re
from collections.abc import Mapping
from functools import cache
from pathlib import Path
from typing import Any

import sympy as sp
from pydantic import ValidationError

from tutgen.errors import Location, SpecError, SpecErrors
from tutgen.model.system import (
    GROUND,
    Ask,
    Body,
    Coordinate,
    Damper,
    Endpoint,
    Joint,
    JointKind,
    Load,
    Parameter,
    Part,
    Shape,
    Spring,
    System,
)
from tutgen.spec import schema as S
from tutgen.spec.expr import FUNCTIONS, ExprError, parse_expression
from tutgen.spec.loader import KeyPath, SourceMap, load_yaml_file, load_yaml_text
from tutgen.spec.units import DIMENSIONS, Dimension, DimensionMismatch, dimension_of, parse_quantity

RESERVED_NAMES = frozenset({GROUND, "pi", "t", *FUNCTIONS})
MAX_COORDINATES = 12


def load_system(path: str | Path) -> System:
    """Read, check and convert one spec file."""
    data, smap = load_yaml_file(path)
    return validate_spec(data, smap)


def load_system_text(text: str, path: str = "<spec>") -> System:
    data, smap = load_yaml_text(text, path)
    return validate_spec(data, smap)


def validate_spec(data: Any, smap: SourceMap) -> System:
    """Check a loaded spec and build the model; raise SpecErrors listing every problem."""
    if not isinstance(data, dict):
        found = "an empty file" if data is None else S._describe(data)
        raise SpecErrors(
            [SpecError(smap.location(()), f"expected a mapping with a 'title' and the problem, found {found}")]
        )
    try:
        doc = S.SpecDoc.model_validate(data)
    except ValidationError as exc:
        raise SpecErrors(_translate(exc, data, smap)) from None
    return _Builder(doc, data, smap).build()


# ---------------------------------------------------------------------------------------------
# pydantic errors -> located messages
# ---------------------------------------------------------------------------------------------

_TYPE_WORDS = {
    "dict_type": "a mapping",
    "model_type": "a mapping",
    "list_type": "a list",
    "string_type": "a text",
    "int_type": "a whole number",
    "float_type": "a number",
    "bool_type": "true or false",
}


@cache
def _schema() -> dict[str, Any]:
    return S.SpecDoc.model_json_schema()


def _resolve(node: dict[str, Any], defs: dict[str, Any], data: Any) -> list[dict[str, Any]]:
    """The object schemas that may describe ``data`` at this schema node."""
    if "$ref" in node:
        return _resolve(defs[node["$ref"].split("/")[-1]], defs, data)
    if "oneOf" in node or "anyOf" in node:
        options = node.get("oneOf", node.get("anyOf", []))
        if "discriminator" in node and isinstance(data, dict):
            ref = node["discriminator"]["mapping"].get(str(data.get("shape")))
            if ref:
                return _resolve({"$ref": ref}, defs, data)
        out: list[dict[str, Any]] = []
        for option in options:
            out += _resolve(option, defs, data)
        return out
    return [node]


def _allowed_keys(path: tuple[Any, ...], data: Any) -> list[str]:
    """Keys allowed at a data path (walking the JSON Schema alongside the data)."""
    root = _schema()
    defs = root.get("$defs", {})
    nodes = [root]
    node_data = data
    for key in path:
        nxt = []
        for node in nodes:
            for obj in _resolve(node, defs, node_data):
                props = obj.get("properties", {})
                if key in props:
                    nxt.append(props[key])
                elif isinstance(obj.get("additionalProperties"), dict):
                    nxt.append(obj["additionalProperties"])
                elif isinstance(obj.get("items"), dict):
                    nxt.append(obj["items"])
        nodes = nxt
        node_data = node_data[key] if isinstance(node_data, (dict, list)) else None
    keys: list[str] = []
    for node in nodes:
        for obj in _resolve(node, defs, node_data):
            keys += [k for k in obj.get("properties", {}) if k not in keys]
    return keys


def _data_path(loc: tuple[Any, ...], data: Any) -> tuple[tuple[Any, ...], Any, bool]:
    """Drop the parts of a pydantic loc that are not in the data (union tags, shorthand wrappers).

    Returns (path, value at path, whether the whole loc was found)."""
    path: list[Any] = []
    node = data
    found = True
    for i, key in enumerate(loc):
        if isinstance(node, dict) and key in node:
            node = node[key]
            path.append(key)
        elif isinstance(node, list) and isinstance(key, int) and 0 <= key < len(node):
            node = node[key]
            path.append(key)
        elif i == len(loc) - 1:
            found = False
        # else: a tag pydantic added (e.g. the 'box' of a discriminated union): skip it
    return tuple(path), node, found


def _where(path: tuple[Any, ...]) -> str:
    if not path:
        return "the spec"
    parts = [str(p) if not isinstance(p, int) else f"item {p + 1}" for p in path]
    return "'" + ".".join(parts) + "'"


def _translate(exc: ValidationError, data: Any, smap: SourceMap) -> list[SpecError]:
    errors: list[SpecError] = []
    for err in exc.errors():
        loc = tuple(err["loc"])
        kind = err["type"]
        path, value, _ = _data_path(loc, data)
        if kind == "extra_forbidden":
            key = str(loc[-1])
            allowed = _allowed_keys(path[:-1], data)
            close = difflib.get_close_matches(key, allowed, n=1)
            errors.append(
                SpecError(
                    smap.key_location(path),
                    f"unknown key '{key}' in {_where(path[:-1])}; expected one of: " + ", ".join(allowed),
                    f"did you mean '{close[0]}'?" if close else None,
                )
            )
        elif kind == "missing":
            errors.append(
                SpecError(
                    smap.key_location(path) if path else smap.location(()),
                    f"missing required key '{loc[-1]}' in {_where(path)}",
                )
            )
        elif kind == "literal_error":
            expected = err.get("ctx", {}).get("expected", "")
            choices = [c.strip(" '") for c in expected.replace(" or ", ", ").split(",")]
            close = difflib.get_close_matches(str(value), choices, n=1)
            errors.append(
                SpecError(
                    smap.location(path),
                    f"expected one of: {', '.join(choices)} in {_where(path)}; found {S._describe(value)}",
                    f"did you mean '{close[0]}'?" if close else None,
                )
            )
        elif kind == "union_tag_invalid":
            tag = err["ctx"]["tag"]
            choices = list(S.SHAPES)
            close = difflib.get_close_matches(str(tag), choices, n=1)
            errors.append(
                SpecError(
                    smap.location((*path, "shape")),
                    f"unknown shape '{tag}' in {_where(path)}; expected one of: " + ", ".join(choices),
                    f"did you mean '{close[0]}'?" if close else None,
                )
            )
        elif kind == "union_tag_not_found":
            errors.append(
                SpecError(
                    smap.location(path),
                    f"missing required key 'shape' in {_where(path)}; expected one of: " + ", ".join(S.SHAPES),
                )
            )
        elif kind.startswith("tutgen_"):
            errors.append(SpecError(smap.location(path), f"{err['msg']} in {_where(path)}"))
        elif kind in ("too_short", "too_long"):
            errors.append(
                SpecError(
                    smap.location(path), f"expected {_length_words(err)} in {_where(path)}; found {S._describe(value)}"
                )
            )
        else:
            expected = _TYPE_WORDS.get(kind, err["msg"].removeprefix("Input should be ").rstrip("."))
            errors.append(
                SpecError(smap.location(path), f"expected {expected} in {_where(path)}; found {S._describe(value)}")
            )
    # a union reports one error per alternative; keep the first per place
    seen: set[tuple[Location, str]] = set()
    unique = []
    for e in errors:
        key = (e.location, e.message.split(";")[0])
        if key not in seen:
            seen.add(key)
            unique.append(e)
    return unique


def _length_words(err: Any) -> str:
    ctx = err.get("ctx", {})
    if "min_length" in ctx and err["type"] == "too_short":
        return f"at least {ctx['min_length']} items"
    return f"at most {ctx.get('max_length')} items"


# ---------------------------------------------------------------------------------------------
# The builder: names, expressions, units, cross-references
# ---------------------------------------------------------------------------------------------

AXES = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}


class _Builder:
    def __init__(self, doc: S.SpecDoc, data: dict[str, Any], smap: SourceMap) -> None:
        self.doc = doc
        self.data = data
        self.smap = smap
        self.errors: list[SpecError] = []
        self.params: dict[str, sp.Symbol] = {}
        self.coords: dict[str, Coordinate] = {}
        self.dims: dict[sp.Symbol, Dimension | None] = {}

    # -- helpers -------------------------------------------------------------------------
    def error(self, path: KeyPath, message: str, hint: str | None = None, key: bool = False) -> None:
        loc = self.smap.key_location(path) if key else self.smap.location(path)
        self.errors.append(SpecError(loc, message, hint))

    def _check_name(self, path: KeyPath, name: str, what: str) -> bool:
        if not name.isidentifier() or keyword.iskeyword(name) or not name.isascii():
            self.error(
                path,
                f"{what} name '{name}' is not a valid name; use letters, digits and _, "
                "starting with a letter (e.g. m1, theta_2)",
                key=True,
            )
            return False
        if name in RESERVED_NAMES or name.endswith(("_dot", "_ddot")):
            self.error(
                path,
                f"{what} name '{name}' is reserved"
                + (" (a function or constant)" if name in FUNCTIONS or name == "pi" else "")
                + (
                    "; the names NAME_dot and NAME_ddot are the velocity and acceleration of a coordinate"
                    if name.endswith(("_dot", "_ddot"))
                    else ""
                ),
                key=True,
            )
            return False
        return True

    def symbols(self, *, coords: bool = False, rates: bool = False, accel: bool = False) -> dict[str, sp.Expr]:
        table: dict[str, sp.Expr] = dict(self.params)
        if coords:
            for c in self.coords.values():
                table[c.name] = c.q
                if rates:
                    table[f"{c.name}_dot"] = c.qd
                if accel:
                    table[f"{c.name}_ddot"] = c.qdd
        return table

    def expr(
        self,
        path: KeyPath,
        value: Any,
        names: Mapping[str, sp.Expr],
        dimension: str | None = None,
        what: str = "",
    ) -> sp.Expr | None:
        """Parse one expression (or quantity) at ``path``; record an error and return None if bad."""
        if isinstance(value, str):
            try:
                quantity = parse_quantity(value)
            except ExprError as exc:
                self.errors.append(SpecError(self.smap.expr_location(path, exc.offset), exc.message, exc.hint))
                return None
            if quantity is not None:
                if dimension is not None and quantity.dimension != DIMENSIONS[dimension]:
                    self.error(
                        path,
                        f"expected a {dimension.replace('_', ' ')} ({DIMENSIONS[dimension]})"
                        f"{' for ' + what if what else ''}, found '{value}' ({quantity.dimension})",
                    )
                    return None
                return quantity.value
        try:
            result = parse_expression(value, names)
        except ExprError as exc:
            hint = exc.hint
            self.errors.append(SpecError(self.smap.expr_location(path, exc.offset), exc.message, hint))
            return None
        if dimension is not None:
            try:
                found = dimension_of(result, self.dims)
            except DimensionMismatch as exc:
                self.error(path, str(exc.args[0]) if exc.args else "inconsistent units")
                return None
            if found is not None and found != DIMENSIONS[dimension] and not result.is_number:
                self.error(
                    path,
                    f"expected a {dimension.replace('_', ' ')} ({DIMENSIONS[dimension]})"
                    f"{' for ' + what if what else ''}, found '{value}' with the units {found}",
                )
                return None
        return result

    def vector(
        self, path: KeyPath, values: list[Any] | None, names: Mapping[str, sp.Expr], dimension: str | None = None
    ) -> sp.ImmutableMatrix | None:
        if values is None:
            return sp.ImmutableMatrix.zeros(3, 1)
        comps = [self.expr((*path, i), v, names, dimension) for i, v in enumerate(values)]
        if any(c is None for c in comps):
            return None
        return sp.ImmutableMatrix(comps)

    def axis(self, path: KeyPath, value: Any, names: Mapping[str, sp.Expr]) -> sp.ImmutableMatrix | None:
        if isinstance(value, str):
            sign = -1 if value.startswith("-") else 1
            return sp.ImmutableMatrix([sign * v for v in AXES[value.lstrip("+-")]])
        vec = self.vector(path, value, names)
        if vec is None:
            return None
        norm2 = sp.expand(sum((v**2 for v in vec), sp.Integer(0)))
        if norm2 == 0:
            self.error(path, "expected a direction, found the zero vector")
            return None
        if norm2.free_symbols:
            self.error(path, "expected a constant direction (numbers), found one that depends on symbols")
            return None
        return sp.ImmutableMatrix([sp.nsimplify(v / sp.sqrt(norm2)) for v in vec])

    def rotations(
        self, path: KeyPath, specs: list[S.RotationSpec] | None, names: Mapping[str, sp.Expr]
    ) -> tuple[tuple[sp.ImmutableMatrix, sp.Expr], ...] | None:
        out = []
        for i, r in enumerate(specs or []):
            axis = self.axis((*path, i, "axis"), r.axis, {})
            angle = self.expr((*path, i, "angle"), r.angle, names, "angle", "an angle")
            if axis is None or angle is None:
                return None
            out.append((axis, angle))
        return tuple(out)

    # -- sections ------------------------------------------------------------------------
    def build(self) -> System:
        doc = self.doc
        self.build_parameters()
        self.build_coordinates()
        gravity = self.build_gravity()
        bodies = self.build_bodies()
        joints = self.build_joints({b.name for b in bodies})
        springs, dampers = self.build_elements({b.name for b in bodies})
        loads = self.build_loads({b.name for b in bodies})
        gforces = self.build_generalized_forces()
        kinetic, potential = self.build_energy()
        self.check_explicit_placement(bodies, joints)
        if self.errors:
            raise SpecErrors(self.errors)
        ask = self.build_ask(bool(self.coords))
        return System(
            title=doc.title.strip(),
            statement=doc.statement.strip() if doc.statement else None,
            source=self.smap.path,
            parameters=tuple(self.parameters),
            coordinates=tuple(self.coords.values()),
            bodies=tuple(bodies),
            joints=tuple(joints),
            gravity=gravity,
            springs=tuple(springs),
            dampers=tuple(dampers),
            loads=tuple(loads),
            generalized_forces=tuple(gforces),
            kinetic_energy=kinetic,
            potential_energy=potential,
            ask=ask,
            origin=self.smap.location(()),
        )

    def build_parameters(self) -> None:
        self.parameters: list[Parameter] = []
        # parameters that appear in forces are plain real numbers; the rest (masses, lengths,
        # stiffnesses, g) are positive, which lets sqrt(l**2) become l
        force_text = " ".join(str(v) for v in self.doc.generalized_forces.values())
        for load in self.doc.loads.values():
            force_text += " " + " ".join(str(v) for v in (load.force or []) + (load.torque or []))
        for name, spec in self.doc.parameters.items():
            path = ("parameters", name)
            if not self._check_name(path, name, "parameter"):
                continue
            is_force = _mentions(force_text, name)
            symbol = sp.Symbol(name, real=True) if is_force else sp.Symbol(name, positive=True)
            value: sp.Expr | None = None
            unit: str | None = None
            dim: Dimension | None = DIMENSIONS[spec.dimension] if spec.dimension else None
            if spec.value is not None:
                vpath = (*path, "value") if self.smap.has((*path, "value")) else path
                if isinstance(spec.value, str):
                    try:
                        quantity = parse_quantity(spec.value)
                    except ExprError as exc:
                        self.errors.append(SpecError(self.smap.expr_location(vpath, exc.offset), exc.message, exc.hint))
                        continue
                    if quantity is not None:
                        if dim is not None and quantity.dimension != dim:
                            self.error(
                                vpath,
                                f"parameter '{name}' is declared as a {spec.dimension} ({dim}), "
                                f"but its value '{spec.value}' is in {quantity.dimension}",
                            )
                            continue
                        value, unit, dim = quantity.value, quantity.unit, quantity.dimension
                if value is None:
                    value = self.expr(vpath, spec.value, {})
                    if value is None:
                        continue
            latex = spec.latex if spec.latex is not None else sp.latex(symbol)
            self.params[name] = symbol
            self.dims[symbol] = dim
            self.parameters.append(
                Parameter(name, symbol, value, latex, spec.description, unit, self.smap.key_location(path))
            )

    def build_coordinates(self) -> None:
        if len(self.doc.coordinates) > MAX_COORDINATES:
            self.error(
                ("coordinates",),
                f"at most {MAX_COORDINATES} coordinates are supported, found {len(self.doc.coordinates)}",
            )
            return
        for name, spec in self.doc.coordinates.items():
            path = ("coordinates", name)
            if not self._check_name(path, name, "coordinate"):
                continue
            if name in self.params:
                self.error(path, f"'{name}' is declared both as a parameter and as a coordinate", key=True)
                continue
            q = sp.Symbol(name, real=True)
            qd = sp.Symbol(f"{name}_dot", real=True)
            qdd = sp.Symbol(f"{name}_ddot", real=True)
            latex = spec.latex if spec.latex is not None else sp.latex(q)
            self.coords[name] = Coordinate(
                name, q, qd, qdd, latex, spec.description, spec.dimension, self.smap.key_location(path)
            )
            if spec.dimension == "length":
                self.dims[q] = DIMENSIONS["length"]
            elif spec.dimension == "angle":
                self.dims[q] = DIMENSIONS["angle"]

    def build_gravity(self) -> sp.ImmutableMatrix | None:
        spec = self.doc.gravity
        if spec is None:
            return None
        path: KeyPath = ("gravity",)
        names = self.symbols()
        if spec.vector is not None:
            if spec.g is not None or spec.direction is not None:
                self.error(path, "give gravity as a vector, or as `g` and `direction`, not both")
                return None
            vpath = path if isinstance(self.data.get("gravity"), list) else (*path, "vector")
            return self.vector(vpath, spec.vector, names, "acceleration")
        if spec.g is None or spec.direction is None:
            self.error(path, "gravity needs `g` and `direction` (e.g. {g: g, direction: -y}), or a vector")
            return None
        g = self.expr((*path, "g"), spec.g, names, "acceleration", "gravity")
        direction = self.axis((*path, "direction"), spec.direction, {})
        if g is None or direction is None:
            return None
        return sp.ImmutableMatrix([g * d for d in direction])

    # -- bodies ----------------------------------------------------------------------------
    def build_bodies(self) -> list[Body]:
        out = []
        consts = self.symbols()
        kin_names = self.symbols(coords=True)
        for name, spec in self.doc.bodies.items():
            path: KeyPath = ("bodies", name)
            if not self._check_name(path, name, "body"):
                continue
            if name in self.params or name in self.coords:
                self.error(
                    path,
                    f"'{name}' is already the name of a {'parameter' if name in self.params else 'coordinate'}"
                    "; give the body another name",
                    key=True,
                )
                continue
            parts: list[Part] = []
            simple = spec.parts is None
            if spec.parts is not None:
                if spec.mass is not None or spec.inertia is not None or spec.com is not None:
                    self.error(
                        path, f"body '{name}' has both `parts` and `mass`/`com`/`inertia`; give one or the other"
                    )
                    continue
                for pname, pspec in spec.parts.items():
                    part = self.build_part((*path, "parts", pname), pname, pspec, consts)
                    if part is not None:
                        parts.append(part)
            elif spec.mass is not None:
                mass = self.expr((*path, "mass"), spec.mass, consts, "mass", "a mass")
                com = self.vector((*path, "com"), spec.com, consts, "length")
                inertia = self.inertia_matrix((*path, "inertia"), spec.inertia, consts)
                if mass is not None and com is not None and (spec.inertia is None or inertia is not None):
                    shape = Shape.GENERAL if inertia is not None else Shape.POINT
                    parts.append(
                        Part(
                            name,
                            shape,
                            mass,
                            None,
                            (),
                            com,
                            None,
                            sp.ImmutableMatrix(sp.eye(3)),
                            inertia,
                            self.smap.location(path),
                        )
                    )
            elif spec.inertia is not None or spec.com is not None:
                self.error(path, f"body '{name}' gives `com` or `inertia` but no `mass`")
                continue
            position = None
            if spec.position is not None:
                position = self.vector((*path, "position"), spec.position, kin_names, "length")
            rotations = self.rotations((*path, "orientation"), spec.orientation, kin_names)
            if rotations is None:
                continue
            out.append(Body(name, tuple(parts), position, None, rotations, self.smap.key_location(path), simple))
        return out

    def inertia_matrix(
        self, path: KeyPath, spec: S.InertiaSpec | None, names: Mapping[str, sp.Expr]
    ) -> sp.ImmutableMatrix | None:
        if spec is None:
            return None
        vals = {}
        for key in ("xx", "yy", "zz", "xy", "xz", "yz"):
            v = self.expr((*path, key), getattr(spec, key), names, "inertia", "an inertia")
            if v is None:
                return None
            vals[key] = v
        return sp.ImmutableMatrix(
            [
                [vals["xx"], vals["xy"], vals["xz"]],
                [vals["xy"], vals["yy"], vals["yz"]],
                [vals["xz"], vals["yz"], vals["zz"]],
            ]
        )

    def build_part(self, path: KeyPath, name: str, spec: Any, names: Mapping[str, sp.Expr]) -> Part | None:
        if not self._check_name(path, name, "part"):
            return None
        shape = Shape(spec.shape)
        ok = True
        mass = density = None
        if getattr(spec, "mass", None) is not None:
            mass = self.expr((*path, "mass"), spec.mass, names, "mass", "a mass")
            ok &= mass is not None
        if getattr(spec, "density", None) is not None:
            density = self.expr((*path, "density"), spec.density, names, "density", "a density")
            ok &= density is not None
        solid = shape in (Shape.BOX, Shape.CYLINDER, Shape.HOLLOW_CYLINDER, Shape.SPHERE)
        if getattr(spec, "mass", None) is not None and getattr(spec, "density", None) is not None:
            self.error(path, f"part '{name}' gives both `mass` and `density`; give one of them")
            ok = False
        elif getattr(spec, "mass", None) is None and shape is not Shape.POINT:
            if not solid:
                self.error(
                    path,
                    f"part '{name}' is a {shape.value.replace('_', ' ')}, which has no volume; give its `mass`",
                    key=True,
                )
                ok = False
            elif getattr(spec, "density", None) is None:
                self.error(path, f"part '{name}' needs a `mass` or a `density`", key=True)
                ok = False
        dims: list[tuple[str, Any]] = []
        for key in ("size", "radius", "outer_radius", "inner_radius", "length"):
            if not hasattr(spec, key):
                continue
            raw = getattr(spec, key)
            if key == "size":
                vec = self.vector((*path, key), raw, names, "length")
                ok &= vec is not None
                if vec is not None:
                    dims.append((key, tuple(vec)))
            else:
                v = self.expr((*path, key), raw, names, "length", "a length")
                ok &= v is not None
                dims.append((key, v))
        at = self.vector((*path, "at"), spec.at, names, "length")
        ok &= at is not None
        axis = None
        if hasattr(spec, "axis"):
            axis = self.axis((*path, "axis"), spec.axis, {})
            ok &= axis is not None
        rotation = sp.ImmutableMatrix(sp.eye(3))
        if getattr(spec, "orientation", None):
            from tutgen.engine.kinematics import rotation_about

            rots = self.rotations((*path, "orientation"), spec.orientation, names)
            if rots is None:
                return None
            r = sp.eye(3)
            for ax, angle in rots:
                r = r * rotation_about(ax, angle)
            rotation = sp.ImmutableMatrix(r)
        inertia = None
        if shape is Shape.GENERAL:
            inertia = self.inertia_matrix((*path, "inertia"), spec.inertia, names)
            ok &= inertia is not None
        d = dict(dims)
        if shape is Shape.HOLLOW_CYLINDER and ok:
            ro, ri = d["outer_radius"], d["inner_radius"]
            if (ro - ri).is_number and (ro - ri) < 0:
                self.error((*path, "inner_radius"), f"inner radius {ri} is larger than the outer radius {ro}")
                ok = False
        if not ok:
            return None
        return Part(name, shape, mass, density, tuple(dims), at, axis, rotation, inertia, self.smap.key_location(path))

    # -- joints ----------------------------------------------------------------------------
    def build_joints(self, bodies: set[str]) -> list[Joint]:
        out: list[Joint] = []
        children: dict[str, str] = {}
        used: dict[str, str] = {}
        consts = self.symbols()
        for name, spec in self.doc.joints.items():
            path: KeyPath = ("joints", name)
            if not self._check_name(path, name, "joint"):
                continue
            ok = True
            for role in ("parent", "child"):
                target = getattr(spec, role)
                allowed = bodies | ({GROUND} if role == "parent" else set())
                if target not in allowed:
                    close = difflib.get_close_matches(target, sorted(allowed), n=1)
                    self.error(
                        (*path, role),
                        f"joint '{name}' refers to unknown body '{target}' "
                        f"(known: {', '.join(sorted(allowed)) or 'none'})",
                        f"did you mean '{close[0]}'?" if close else None,
                    )
                    ok = False
            if spec.child in children:
                self.error(
                    (*path, "child"),
                    f"body '{spec.child}' is already placed by joint '{children[spec.child]}'; "
                    "each body has one joint to its parent",
                )
                ok = False
            elif ok:
                children[spec.child] = name
            if spec.parent == spec.child:
                self.error((*path, "child"), f"joint '{name}' connects body '{spec.child}' to itself")
                ok = False
            kind = JointKind(spec.type)
            coord = None
            if kind is JointKind.FIXED:
                if spec.coordinate is not None:
                    self.error((*path, "coordinate"), "a fixed joint has no coordinate")
                    ok = False
            elif spec.coordinate is None:
                self.error(path, f"missing required key 'coordinate' in a {kind.value} joint", key=True)
                ok = False
            elif spec.coordinate not in self.coords:
                close = difflib.get_close_matches(spec.coordinate, list(self.coords), n=1)
                self.error(
                    (*path, "coordinate"),
                    f"joint '{name}' uses '{spec.coordinate}', which is not a "
                    f"declared coordinate (declared: {', '.join(self.coords) or 'none'})",
                    f"did you mean '{close[0]}'?" if close else None,
                )
                ok = False
            else:
                coord = self.coords[spec.coordinate]
                if spec.coordinate in used:
                    self.error(
                        (*path, "coordinate"),
                        f"coordinate '{spec.coordinate}' already drives joint '{used[spec.coordinate]}'",
                    )
                    ok = False
                used[spec.coordinate] = name
                expected = "angle" if kind is JointKind.REVOLUTE else "length"
                if coord.dimension is not None and coord.dimension != expected:
                    self.error(
                        (*path, "coordinate"),
                        f"a {kind.value} joint needs a coordinate that is "
                        f"a(n) {expected}, but '{coord.name}' is declared as a(n) {coord.dimension}",
                    )
                    ok = False
                self.dims.setdefault(coord.q, DIMENSIONS[expected])
            if spec.angle == "absolute" and kind is not JointKind.REVOLUTE:
                self.error((*path, "angle"), "only a revolute joint can measure an absolute angle")
                ok = False
            axis = self.axis((*path, "axis"), spec.axis, {})
            origin = self.vector((*path, "origin"), spec.origin, consts, "length")
            offset_dim = "angle" if kind is JointKind.REVOLUTE else "length"
            offset = (
                self.expr((*path, "offset"), spec.offset, consts, offset_dim)
                if spec.offset is not None
                else sp.Integer(0)
            )
            rotation = sp.ImmutableMatrix(sp.eye(3))
            rots = self.rotations((*path, "orientation"), spec.orientation, consts)
            if rots:
                from tutgen.engine.kinematics import rotation_about

                r = sp.eye(3)
                for ax, angle in rots:
                    r = r * rotation_about(ax, angle)
                rotation = sp.ImmutableMatrix(r)
            if not ok or axis is None or origin is None or offset is None or rots is None:
                continue
            out.append(
                Joint(
                    name,
                    kind,
                    spec.parent,
                    spec.child,
                    coord,
                    axis,
                    origin,
                    rotation,
                    offset,
                    spec.angle == "absolute",
                    self.smap.key_location(path),
                )
            )
        # cycles: follow parents from every body
        parent_of = {j.child: (j.parent, j.name) for j in out}
        for start in parent_of:
            seen = [start]
            node = start
            while node in parent_of:
                node = parent_of[node][0]
                if node in seen:
                    jname = parent_of[start][1]
                    self.error(
                        ("joints", jname),
                        "the joints form a loop: "
                        + " -> ".join([*seen, node])
                        + "; a kinematic tree must lead back to ground",
                        key=True,
                    )
                    break
                seen.append(node)
        return out

    def check_explicit_placement(self, bodies: list[Body], joints: list[Joint]) -> None:
        placed = {j.child for j in joints}
        for b in bodies:
            if b.name in placed and (b.position is not None or b.rotation_rates):
                self.error(
                    ("bodies", b.name, "position" if b.position is not None else "orientation"),
                    f"body '{b.name}' is placed by a joint; it cannot also have a `position` or `orientation`",
                    key=True,
                )

    # -- springs, dampers, loads, forces, energy --------------------------------------------
    def _endpoints(
        self, path: KeyPath, between: list[S.EndpointSpec] | None, bodies: set[str]
    ) -> tuple[Endpoint, Endpoint] | None:
        if between is None:
            return None
        out = []
        for i, ep in enumerate(between):
            if ep.body not in bodies | {GROUND}:
                close = difflib.get_close_matches(ep.body, sorted(bodies | {GROUND}), n=1)
                epath = (*path, i, "body") if isinstance(self.smap_get((*path, i)), dict) else (*path, i)
                self.error(
                    epath,
                    f"unknown body '{ep.body}' (known: {', '.join(sorted(bodies | {GROUND}))})",
                    f"did you mean '{close[0]}'?" if close else None,
                )
                return None
            at = self.vector((*path, i, "at"), ep.at, self.symbols(), "length")
            if at is None:
                return None
            out.append(Endpoint(ep.body, at))
        return (out[0], out[1])

    def smap_get(self, path: KeyPath) -> Any:
        node: Any = self.data
        for key in path:
            try:
                node = node[key]
            except (KeyError, IndexError, TypeError):
                return None
        return node

    def build_elements(self, bodies: set[str]) -> tuple[list[Spring], list[Damper]]:
        springs: list[Spring] = []
        dampers: list[Damper] = []
        kin_names = self.symbols(coords=True)
        consts = self.symbols()
        for section, specs in (("springs", self.doc.springs), ("dampers", self.doc.dampers)):
            for name, spec in specs.items():
                path: KeyPath = (section, name)
                if not self._check_name(path, name, section[:-1]):
                    continue
                if (spec.between is None) == (spec.extension is None):
                    self.error(
                        path,
                        f"{section[:-1]} '{name}' needs exactly one of `between` (two attachment "
                        "points) or `extension` (an expression)",
                        key=True,
                    )
                    continue
                between = self._endpoints((*path, "between"), spec.between, bodies)
                ext = None
                if spec.extension is not None:
                    ext = self.expr((*path, "extension"), spec.extension, kin_names)
                    if ext is None:
                        continue
                elif between is None:
                    continue
                if section == "springs":
                    k = self.expr(
                        (*path, "stiffness"), spec.stiffness, consts, "stiffness" if between else None, "a stiffness"
                    )
                    l0 = (
                        self.expr((*path, "free_length"), spec.free_length, consts, "length")
                        if spec.free_length is not None
                        else sp.Integer(0)
                    )
                    if spec.free_length is not None and ext is not None:
                        self.error(
                            (*path, "free_length"),
                            "`free_length` goes with `between`; with `extension`, "
                            "write the elongation itself (e.g. 'x - L0')",
                            key=True,
                        )
                        continue
                    if k is not None and l0 is not None:
                        springs.append(Spring(name, k, l0, between, ext, self.smap.key_location(path)))
                else:
                    c = self.expr(
                        (*path, "coefficient"),
                        spec.coefficient,
                        consts,
                        "damping" if between else None,
                        "a damping coefficient",
                    )
                    if c is not None:
                        dampers.append(Damper(name, c, between, ext, self.smap.key_location(path)))
        return springs, dampers

    def build_loads(self, bodies: set[str]) -> list[Load]:
        out = []
        names = self.symbols(coords=True, rates=True)
        for name, spec in self.doc.loads.items():
            path: KeyPath = ("loads", name)
            if not self._check_name(path, name, "load"):
                continue
            ok = True
            for role in ("on", "reaction_on"):
                target = getattr(spec, role)
                allowed = bodies | ({GROUND} if role == "reaction_on" else set())
                if target is not None and target not in allowed:
                    close = difflib.get_close_matches(target, sorted(allowed), n=1)
                    self.error(
                        (*path, role),
                        f"load '{name}' refers to unknown body '{target}' (known: {', '.join(sorted(allowed))})",
                        f"did you mean '{close[0]}'?" if close else None,
                    )
                    ok = False
            if spec.force is None and spec.torque is None:
                self.error(path, f"load '{name}' needs a `force` or a `torque`", key=True)
                ok = False
            force = self.vector((*path, "force"), spec.force, names) if spec.force is not None else None
            torque = self.vector((*path, "torque"), spec.torque, names) if spec.torque is not None else None
            at = self.vector((*path, "at"), spec.at, self.symbols(), "length")
            if (
                not ok
                or (spec.force is not None and force is None)
                or (spec.torque is not None and torque is None)
                or at is None
            ):
                continue
            out.append(
                Load(
                    name,
                    spec.on,
                    force,
                    torque,
                    at,
                    spec.frame == "body",
                    spec.reaction_on,
                    self.smap.key_location(path),
                )
            )
        return out

    def build_generalized_forces(self) -> list[tuple[str, sp.Expr]]:
        out = []
        names = self.symbols(coords=True, rates=True)
        for cname, value in self.doc.generalized_forces.items():
            path: KeyPath = ("generalized_forces", cname)
            if cname not in self.coords:
                close = difflib.get_close_matches(cname, list(self.coords), n=1)
                self.error(
                    path,
                    f"'{cname}' is not a declared coordinate (declared: {', '.join(self.coords) or 'none'})",
                    f"did you mean '{close[0]}'?" if close else None,
                    key=True,
                )
                continue
            e = self.expr(path, value, names)
            if e is not None:
                out.append((cname, e))
        return out

    def build_energy(self) -> tuple[sp.Expr | None, sp.Expr | None]:
        spec = self.doc.energy
        if spec is None:
            if self.coords and not self.doc.bodies:
                self.error(
                    ("coordinates",),
                    "the spec has coordinates but no `bodies` and no `energy`; nothing moves",
                    key=True,
                )
            return None, None
        if self.doc.bodies or self.doc.joints:
            self.error(("energy",), "give either `energy` or `bodies`/`joints`, not both", key=True)
            return None, None
        if not self.coords:
            self.error(("energy",), "`energy` needs `coordinates`", key=True)
            return None, None
        t = self.expr(("energy", "kinetic"), spec.kinetic, self.symbols(coords=True, rates=True))
        u = (
            self.expr(("energy", "potential"), spec.potential, self.symbols(coords=True))
            if spec.potential is not None
            else sp.Integer(0)
        )
        return t, u

    def build_ask(self, dynamic: bool) -> frozenset[Ask]:
        if self.doc.ask is not None:
            return frozenset(Ask(a) for a in self.doc.ask)
        if not dynamic:
            return frozenset({Ask.INERTIA})
        everything = set(Ask)
        if not self.doc.bodies:
            everything.discard(Ask.INERTIA)
        return frozenset(everything)


def _mentions(text: str, name: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", text) is not None


__all__ = ["load_system", "load_system_text", "validate_spec"]
