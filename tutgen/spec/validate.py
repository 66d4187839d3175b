"""Spec data -> :class:`tutgen.model.System`: shape, names, expressions, units and cross-references.

Every problem is collected with its ``file:line:col`` and reported at once (:class:`SpecErrors`).
Expressions go through the whitelist parser of :mod:`tutgen.spec.expr`; nothing here evaluates
user text as code.
"""

from __future__ import annotations

import dataclasses
import difflib
import keyword
import re
from collections.abc import Mapping
from functools import cache
from pathlib import Path
from typing import Any, NamedTuple

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
from tutgen.spec.expr import FUNCTIONS, ExprError, number_to_rational, parse_expression
from tutgen.spec.figure import validate_figure
from tutgen.spec.loader import KeyPath, SourceMap, load_yaml_file, load_yaml_text
from tutgen.spec.units import DIMENSIONS, Dimension, DimensionMismatch, dimension_of, parse_quantity, parse_unit

RESERVED_NAMES = frozenset({GROUND, "pi", "t", *FUNCTIONS})
MAX_COORDINATES = 12
#: The most values a parameter's ``range`` may allow (variants of a tutorial sheet).
MAX_CHOICES = 10_000


def load_system(path: str | Path) -> System:
    """Read, check and convert one spec file."""
    data, smap = load_yaml_file(path)
    return validate_spec(data, smap)


def load_system_text(text: str, path: str = "<spec>") -> System:
    data, smap = load_yaml_text(text, path)
    return validate_spec(data, smap)


#: Sections that hold named objects, and what one of their entries is called in a message.
NAMED_SECTIONS = {
    "parameters": "parameter",
    "coordinates": "coordinate",
    "bodies": "body",
    "joints": "joint",
    "springs": "spring",
    "dampers": "damper",
    "loads": "load",
    "generalized_forces": "generalized force on",
}
#: Sections every expression or cross-reference depends on: when one of them has the wrong shape as a
#: whole, checking the rest would only report consequences of that one mistake.
_FOUNDATIONS = frozenset({"parameters", "coordinates", "bodies"})
#: Keys whose value is the name of something declared elsewhere.
_NAME_KEYS = frozenset({"parent", "child", "coordinate", "body", "reaction_body", "joint"})
#: The rows of the Denavit-Hartenberg table: each one is set aside on its own, like a named entry.
_ARM_LINKS: KeyPath = ("arm", "links")
#: Keys of earlier drafts of the format, and what they are called now.
_RENAMED_KEYS = {"on": "body", "reaction_on": "reaction_body"}


def validate_spec(data: Any, smap: SourceMap) -> System:
    """Check a loaded spec and build the model; raise SpecErrors listing every problem.

    Shape errors do not stop the other checks: an object (a body, a joint, ...) whose shape is wrong
    is reported, set aside, and still counts as declared, so that the rest of the spec is checked
    without a second report of the same mistake.
    """
    if not isinstance(data, dict):
        found = "an empty file" if data is None else S._describe(data)
        raise SpecErrors(
            [
                SpecError(
                    smap.location(()),
                    f"expected a mapping of spec keys (title, parameters, bodies, ...), found {found}",
                )
            ]
        )
    errors: list[SpecError] = []
    dropped: set[KeyPath] = set()
    work: dict[str, Any] = data
    for _ in range(3):
        try:
            doc = S.SpecDoc.model_validate(work)
            break
        except ValidationError as exc:
            problems = _translate(exc, work, smap)
            errors += [p.error for p in problems]
            units = {_unit(p.path) for p in problems} - {()}
            dropped |= units
            work = _prune(work, units)
    else:  # pragma: no cover - pruning removes every part pydantic complained about
        raise SpecErrors(errors)
    if errors and any(len(u) == 1 and u[0] in _FOUNDATIONS for u in dropped):
        raise SpecErrors(errors)
    builder = _Builder(doc, data, smap, dropped)
    try:
        system = builder.build()
    except SpecErrors as exc:
        raise SpecErrors(errors + exc.errors) from None
    if errors:
        raise SpecErrors(errors)
    return system


def _unit(path: KeyPath) -> KeyPath:
    """The part of the spec set aside for a shape error at ``path``: a named entry, or a top-level key."""
    if not path:
        return ()
    if tuple(path[:2]) == _ARM_LINKS and len(path) >= 3:
        return tuple(path[:3])
    if path[0] in NAMED_SECTIONS and len(path) >= 2:
        return tuple(path[:2])
    return tuple(path[:1])


def _prune(data: dict[str, Any], units: set[KeyPath]) -> dict[str, Any]:
    """A copy of ``data`` without ``units`` (top-level keys, or entries of a section)."""
    out = dict(data)
    for unit in units:
        if len(unit) == 1:
            out.pop(unit[0], None)
    for section in {u[0] for u in units if len(u) == 2}:
        entries = {u[1] for u in units if len(u) == 2 and u[0] == section}
        value = out.get(section)
        if isinstance(value, dict):
            out[section] = {k: v for k, v in value.items() if k not in entries}
        elif isinstance(value, list):
            out[section] = [v for i, v in enumerate(value) if i not in entries]
    rows = {u[2] for u in units if len(u) == 3 and tuple(u[:2]) == _ARM_LINKS}
    arm = out.get("arm")
    if rows and isinstance(arm, dict) and isinstance(arm.get("links"), dict):
        out["arm"] = {**arm, "links": {k: v for k, v in arm["links"].items() if k not in rows}}
    out.setdefault("title", "")
    return out


# ---------------------------------------------------------------------------------------------
# pydantic errors -> located messages
# ---------------------------------------------------------------------------------------------

_TYPE_WORDS = {
    "dict_type": "a mapping",
    "model_type": "a mapping",
    "model_attributes_type": "a mapping",
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


def _where(path: KeyPath) -> str:
    """A place in the spec in the reader's words: "body 'link'", "'com[2]' of body 'link'", "'gravity'"."""
    if not path:
        return "the spec"
    owner = None
    rest = tuple(path)
    if tuple(path[:2]) == _ARM_LINKS and len(path) >= 3:
        owner = f"arm link '{path[2]}'"
        rest = tuple(path[3:])
    elif path[0] in NAMED_SECTIONS and len(path) >= 2 and isinstance(path[1], str):
        owner = f"{NAMED_SECTIONS[str(path[0])]} '{path[1]}'"
        rest = tuple(path[2:])
        if path[0] == "bodies" and len(rest) >= 2 and rest[0] == "parts":
            owner = f"part '{rest[1]}' of body '{path[1]}'"
            rest = rest[2:]
    if not rest:
        return owner or "the spec"
    text = ""
    for p in rest:
        text += f"[{p + 1}]" if isinstance(p, int) else (f".{p}" if text else str(p))
    return f"'{text}' of {owner}" if owner else f"'{text}'"


class _Problem(NamedTuple):
    """A located error and the data path it is about (to set that part of the spec aside)."""

    path: KeyPath
    error: SpecError


def _translate(exc: ValidationError, data: Any, smap: SourceMap) -> list[_Problem]:
    """pydantic's errors as located messages in the spec's words, one per mistake.

    The alternatives of a union that all failed at one place become one message ("must be one of:
    x, y, z or a vector ..."); a required key that is missing because it was misspelt is reported
    once, as the misspelt key.
    """
    problems: list[_Problem] = []
    suggested: set[tuple[KeyPath, str]] = set()  # (mapping, key) offered as "did you mean"
    missing: list[tuple[KeyPath, str]] = []
    # value problems by place: (what was expected, what was found, hint, location)
    values: dict[KeyPath, list[tuple[str, str, str | None, Location]]] = {}
    literal_only: set[KeyPath] = set()  # places where a choice of names failed
    structured: set[KeyPath] = set()  # places where anything else failed
    for err in exc.errors():
        loc = tuple(err["loc"])
        kind = err["type"]
        path, value, _ = _data_path(loc, data)
        if kind == "extra_forbidden":
            key = str(loc[-1])
            allowed = _allowed_keys(path[:-1], data)
            close = difflib.get_close_matches(key, allowed, n=1)
            if not close and _RENAMED_KEYS.get(key) in allowed:
                close = [_RENAMED_KEYS[key]]
            if close:
                suggested.add((path[:-1], close[0]))
            problems.append(
                _Problem(
                    path,
                    SpecError(
                        smap.key_location(path),
                        f"unknown key '{key}' in {_where(path[:-1])}; expected one of: " + ", ".join(allowed),
                        f"did you mean '{close[0]}'?" if close else None,
                    ),
                )
            )
        elif kind == "missing":
            missing.append((path, str(loc[-1])))
        elif kind == "union_tag_invalid":
            tag = err["ctx"]["tag"]
            close = difflib.get_close_matches(str(tag), S.SHAPES, n=1)
            problems.append(
                _Problem(
                    path,
                    SpecError(
                        smap.location((*path, "shape")),
                        f"unknown shape '{tag}' for {_where(path)}; expected one of: " + ", ".join(S.SHAPES),
                        f"did you mean '{close[0]}'?" if close else None,
                    ),
                )
            )
        elif kind == "union_tag_not_found":
            missing.append((path, "shape"))
        elif kind == "tutgen_names" and isinstance(value, list):
            for i, item in enumerate(value):
                if not isinstance(item, str):
                    problems.append(
                        _Problem(
                            (*path, i),
                            SpecError(
                                smap.location((*path, i)),
                                f"{_where((*path, i))} must be a name; found {S._describe(item)}",
                            ),
                        )
                    )
        else:
            expected, hint = _expected(err, path, value)
            if kind == "literal_error":
                literal_only.add(path)
            else:
                structured.add(path)
            values.setdefault(path, []).append((expected, S._describe(value), hint, smap.location(path)))
    for path, key in missing:
        if (path, key) in suggested:
            continue  # the misspelt key is reported, with this one as its suggestion
        text = f"missing required key '{key}' in {_where(path)}"
        if key == "shape":
            text += "; expected one of: " + ", ".join(S.SHAPES)
        problems.append(_Problem(path, SpecError(smap.key_location(path) if path else smap.location(()), text)))
    for path, found in values.items():
        if path in literal_only - structured and any(q[: len(path)] == path and q != path for q in values):
            # `axis: [true, 0, 0]` fails as a name and, deeper, as a vector: the vector was meant
            continue
        expected = " or ".join(dict.fromkeys(e for e, _, _, _ in found))
        hint = next((h for _, _, h, _ in found if h), None)
        if path == ("tutgen",):
            message = f"unsupported spec format version: 'tutgen' must be {expected}; found {found[0][1]}"
            hint = hint or f"this version of tutgen reads format {S.SPEC_FORMAT_VERSION}"
        else:
            message = f"{_where(path)} must be {expected}; found {found[0][1]}"
        if path == ("arm", "convention"):
            hint = hint or "standard: Spong, Paul (A_i = Rz Tz Tx Rx); modified: Craig (A_i = Rx Tx Rz Tz)"
        problems.append(_Problem(path, SpecError(found[0][3], message, hint)))
    return problems


def _expected(err: Any, path: KeyPath, value: Any) -> tuple[str, str | None]:
    """What a value error expected, in words, and a "did you mean" hint if one applies."""
    kind = err["type"]
    if kind == "literal_error":
        expected = err.get("ctx", {}).get("expected", "")
        choices = [c.strip(" '") for c in expected.replace(" or ", ", ").split(",")]
        close = difflib.get_close_matches(str(value), choices, n=1) if isinstance(value, str) else []
        words = choices[0] if len(choices) == 1 else "one of: " + ", ".join(choices)
        return words, (f"did you mean '{close[0]}'?" if close else None)
    if kind == "tutgen_text" and path and path[-1] in _NAME_KEYS:
        return "a name", None
    if kind.startswith("tutgen_"):
        message = str(err["msg"])
        head = message.split(", found ", 1)[0]
        return head.removeprefix("expected "), None
    if kind in ("too_short", "too_long"):
        ctx = err.get("ctx", {})
        if path and path[-1] == "between":
            return "two attachment points [A, B]", None
        if kind == "too_short":  # pragma: no cover - only `between` has a length today
            return f"a list of at least {ctx.get('min_length')} items", None
        return f"a list of at most {ctx.get('max_length')} items", None
    if kind in ("dict_type", "model_type") and path in (("parameters",), ("coordinates",)):
        return "a list of names or a mapping", None
    if kind in ("dict_type", "model_type") and path == ("gravity",):
        return "a vector [x, y, z] or a mapping with `g` and `direction`", None
    if kind == "list_type" and path and path[-1] == "between":
        return "a list of two attachment points [A, B]", None
    if kind == "list_type" and path and path[-1] == "orientation":
        return "a list of rotations", "write e.g. orientation: [{axis: z, angle: theta}]"
    return _TYPE_WORDS.get(kind, str(err["msg"]).removeprefix("Input should be ").rstrip(".")), None


# ---------------------------------------------------------------------------------------------
# The builder: names, expressions, units, cross-references
# ---------------------------------------------------------------------------------------------

AXES = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}


class _Builder:
    def __init__(
        self, doc: S.SpecDoc, data: dict[str, Any], smap: SourceMap, dropped: set[KeyPath] | None = None
    ) -> None:
        self.doc = doc
        self.data = data
        self.smap = smap
        self.errors: list[SpecError] = []
        self.params: dict[str, sp.Symbol] = {}
        self.coords: dict[str, Coordinate] = {}
        self.dims: dict[sp.Symbol, Dimension | None] = {}
        # parts of the spec set aside for shape errors (already reported): their names still count
        # as declared, so that nothing else is reported because of them
        self.dropped: set[KeyPath] = set(dropped or ())
        self.dropped_keys = {str(u[0]) for u in self.dropped if len(u) == 1}
        self.body_names: set[str] = set()
        self.placed: dict[str, str] = {}  # body -> the joint that places it

    def dropped_names(self, section: str) -> list[str]:
        """Names of the entries of ``section`` set aside for shape errors."""
        return sorted(str(u[1]) for u in self.dropped if len(u) == 2 and u[0] == section and isinstance(u[1], str))

    # -- helpers -------------------------------------------------------------------------
    def error(self, path: KeyPath, message: str, hint: str | None = None, key: bool = False) -> None:
        loc = self.smap.key_location(path) if key else self.smap.location(path)
        self.errors.append(SpecError(loc, message, hint))

    def name_path(self, section: str, name: str) -> KeyPath:
        """Where a declared name was written: its key, or its item in a list shorthand ``[m1, m2]``."""
        written = self.data.get(section)
        if isinstance(written, list) and name in written:
            return (section, written.index(name))
        return (section, name)

    def check_listed_twice(self, section: str) -> None:
        """A list shorthand ``[m, l, m]`` would silently merge the two ``m``: report the second one."""
        written = self.data.get(section)
        if not isinstance(written, list):
            return
        first: dict[str, int] = {}
        for i, name in enumerate(written):
            if not isinstance(name, str):
                continue
            if name in first:
                where = self.smap.location((section, first[name]))
                self.error(
                    (section, i),
                    f"{NAMED_SECTIONS[section]} '{name}' is listed twice in '{section}' "
                    f"(first at line {where.line}, column {where.col})",
                    "a name may appear once; remove one of them",
                    key=True,
                )
            else:
                first[name] = i

    def _check_name(self, path: KeyPath, name: str, what: str) -> bool:
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
        """Parse one expression (or quantity) at ``path``; record an error and return None if bad.

        ``what`` names the value in a message when its dimension alone does not ("gravity").
        """
        expected = ""
        if dimension is not None:
            expected = _expected_dimension(dimension)
            if what and what.split(" ", 1)[-1] != dimension.replace("_", " "):
                expected += f" for {what}"
        if isinstance(value, str):
            try:
                quantity = parse_quantity(value)
            except ExprError as exc:
                self.errors.append(SpecError(self.smap.expr_location(path, exc.offset), exc.message, exc.hint))
                return None
            if quantity is not None:
                if dimension is not None and quantity.dimension != DIMENSIONS[dimension]:
                    found_words = _found_dimension(quantity.dimension)
                    self.error(path, f"expected {expected}, found '{value}', which is {found_words}")
                    return None
                return quantity.value
        try:
            result = parse_expression(value, names)
        except ExprError as exc:
            hint = self._name_hint(exc, names) or exc.hint
            self.errors.append(SpecError(self.smap.expr_location(path, exc.offset), exc.message, hint))
            return None
        if dimension is not None:
            try:
                found = dimension_of(result, self.dims)
            except DimensionMismatch as exc:
                self.error(path, f"the units in '{value}' do not agree: {exc.args[0] if exc.args else exc}")
                return None
            if found is not None and found != DIMENSIONS[dimension] and not result.is_number:
                self.error(path, f"expected {expected}, found '{value}', which is {_found_dimension(found)}")
                return None
        return result

    def _name_hint(self, exc: ExprError, names: Mapping[str, sp.Expr]) -> str | None:
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
            self.error(path, f"{_where(path)} must be a direction; found the zero vector")
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
        used: dict[str, str] = {}  # coordinate -> the joint it drives (arm rows and joints alike)
        arm_bodies, arm_joints = self.build_arm(used)
        bodies = arm_bodies + bodies  # the arm first: bodies in `bodies` may hang from its links
        joints = arm_joints + self.build_joints(self.body_names, arm_joints, used)
        springs, dampers = self.build_elements(self.body_names)
        loads = self.build_loads(self.body_names)
        gforces = self.build_generalized_forces()
        kinetic, potential = self.build_energy()
        self.check_explicit_placement()
        figure = validate_figure(doc.figure, self.smap, self.coords, self.params, self.errors)  # spec/figure.py
        if self.errors:
            raise SpecErrors(self.errors)
        ask = self.build_ask(bool(self.coords))
        # each coordinate's dimension is known only now (a joint may have given it)
        coords = {n: dataclasses.replace(c, si_dimension=self.dims.get(c.q)) for n, c in self.coords.items()}
        joints = [
            dataclasses.replace(j, coordinate=coords[j.coordinate.name]) if j.coordinate is not None else j
            for j in joints
        ]
        return System(
            title=doc.title.strip(),
            statement=doc.statement.strip() if doc.statement else None,
            source=self.smap.path,
            parameters=tuple(self.parameters),
            coordinates=tuple(coords.values()),
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
            figure=figure,
        )

    def build_parameters(self) -> None:
        self.parameters: list[Parameter] = []
        self.check_listed_twice("parameters")
        # parameters that appear in forces are plain real numbers; the rest (masses, lengths,
        # stiffnesses, g) are positive, which lets sqrt(l**2) become l
        force_text = " ".join(str(v) for v in self.doc.generalized_forces.values())
        for load in self.doc.loads.values():
            force_text += " " + " ".join(str(v) for v in (load.force or []) + (load.torque or []))
        for name in self.dropped_names("parameters"):
            if name.isidentifier() and name not in FUNCTIONS and name != "pi":
                self.params[name] = sp.Symbol(name, real=True)
                self.dims[self.params[name]] = None
        for name, spec in self.doc.parameters.items():
            path = self.name_path("parameters", name)
            if not self._check_name(path, name, "parameter"):
                continue
            is_force = _mentions(force_text, name)
            symbol = sp.Symbol(name, real=True) if is_force else sp.Symbol(name, positive=True)
            value: sp.Expr | None = None
            unit: str | None = None
            dim: Dimension | None = DIMENSIONS[spec.dimension] if spec.dimension else None
            # declared before its value is checked: a bad value is one error, not one per use
            self.params[name] = symbol
            self.dims[symbol] = dim
            if spec.value is not None:
                vpath = (*path, "value") if self.smap.has((*path, "value")) else path
                if isinstance(spec.value, str):
                    try:
                        quantity = parse_quantity(spec.value)
                    except ExprError as exc:
                        self.errors.append(SpecError(self.smap.expr_location(vpath, exc.offset), exc.message, exc.hint))
                        continue
                    if quantity is not None:
                        if spec.dimension is not None and dim is not None and quantity.dimension != dim:
                            self.error(
                                vpath,
                                f"parameter '{name}' is declared as {_expected_dimension(spec.dimension)}, "
                                f"but its value '{spec.value}' is {_found_dimension(quantity.dimension)}",
                            )
                            continue
                        value, unit, dim = quantity.value, quantity.unit, quantity.dimension
                        self.dims[symbol] = dim
                if value is None:
                    value = self.expr(vpath, spec.value, {})
                    if value is None:
                        continue
            choices: tuple[sp.Expr, ...] | None = None
            if spec.range is not None or spec.choices is not None or spec.step is not None:
                allowed = self.parameter_choices(path, name, spec, dim)
                if allowed is None:
                    continue
                choices, range_unit, dim = allowed
                unit = range_unit or unit
                self.dims[symbol] = dim
                if value is None:
                    value = choices[(len(choices) - 1) // 2] if spec.range is not None else choices[0]
                elif value not in choices:
                    self.error((*path, "value"), f"the value of parameter '{name}' is not one of its allowed values")
                    continue
            if value is not None and symbol.is_positive and not all(v.is_positive for v in (choices or (value,))):
                # a zero or negative value: the symbol must not be assumed positive, or
                # sqrt(a**2) would become a before the value is put in
                dims = self.dims.pop(symbol)
                symbol = sp.Symbol(name, real=True)
                self.params[name] = symbol
                self.dims[symbol] = dims
            latex = spec.latex if spec.latex is not None else sp.latex(symbol)
            where = self.smap.key_location(path)
            self.parameters.append(
                Parameter(name, symbol, value, latex, spec.description, unit, where, self.dims.get(symbol), choices)
            )

    def parameter_choices(
        self, path: KeyPath, name: str, spec: S.ParameterSpec, declared: Dimension | None
    ) -> tuple[tuple[sp.Expr, ...], str | None, Dimension | None] | None:
        """The allowed values (exact, SI) of a parameter with a ``range`` or ``choices`` (variants of a
        tutorial sheet), its unit as written and its dimension; None after reporting an error."""
        if spec.range is not None and spec.choices is not None:
            self.error((*path, "choices"), f"parameter '{name}' has both a range and choices; give one of them")
            return None
        if spec.step is not None and spec.range is None:
            self.error((*path, "step"), f"parameter '{name}' has a step but no range", "write range: [lo, hi]")
            return None
        factor: sp.Expr = sp.Integer(1)
        dim = declared
        if spec.unit is not None:
            upath = (*path, "unit")
            try:
                factor, udim = parse_unit(spec.unit)
            except ExprError as exc:
                self.errors.append(SpecError(self.smap.expr_location(upath, exc.offset), exc.message, exc.hint))
                return None
            if declared is not None and udim != declared and spec.dimension is not None:
                self.error(
                    upath,
                    f"parameter '{name}' is declared as {_expected_dimension(spec.dimension)}, "
                    f"but its unit '{spec.unit}' is {_found_dimension(udim)}",
                )
                return None
            dim = udim
        key = "range" if spec.range is not None else "choices"
        try:
            if spec.range is not None:
                lo, hi = (number_to_rational(v) for v in spec.range)
                if hi < lo:
                    self.error((*path, key), f"the range of parameter '{name}' goes down: write [lo, hi] with lo <= hi")
                    return None
                step = number_to_rational(spec.step) if spec.step is not None else (hi - lo) / 10
                if hi == lo:
                    step = sp.Integer(1)
                if step <= 0:
                    self.error((*path, "step"), f"the step of parameter '{name}' must be positive")
                    return None
                count = int(sp.floor((hi - lo) / step)) + 1
                if count > MAX_CHOICES:
                    self.error(
                        (*path, "step"),
                        f"the range of parameter '{name}' has {count} values; the limit is {MAX_CHOICES}",
                        "use a larger step",
                    )
                    return None
                numbers = [lo + k * step for k in range(count)]
            else:
                assert spec.choices is not None
                numbers = [number_to_rational(v) for v in spec.choices]
                for i, n in enumerate(numbers):
                    if n in numbers[:i]:
                        self.error((*path, key, i), f"choice {spec.choices[i]} of parameter '{name}' is listed twice")
                        return None
        except ExprError as exc:
            self.error((*path, key), f"parameter '{name}': {exc.message}")
            return None
        return tuple(n * factor for n in numbers), spec.unit, dim

    def build_coordinates(self) -> None:
        self.check_listed_twice("coordinates")
        names = [*self.doc.coordinates, *self.dropped_names("coordinates")]
        if len(names) > MAX_COORDINATES:
            extra = names[MAX_COORDINATES]
            self.error(
                self.name_path("coordinates", extra),
                f"expected at most {MAX_COORDINATES} coordinates, found {len(names)} "
                f"('{extra}' is number {MAX_COORDINATES + 1})",
                "tutgen derives symbolic equations; split the problem, or fix some coordinates",
                key=True,
            )
        for name in self.dropped_names("coordinates"):
            if name.isidentifier() and name not in FUNCTIONS and name != "pi":
                self.coords[name] = self._coordinate(name, None, None, None)
        for name, spec in self.doc.coordinates.items():
            path = self.name_path("coordinates", name)
            if not self._check_name(path, name, "coordinate"):
                continue
            if name in self.params:
                # declared anyway (as a coordinate), so that its uses are not reported too
                self.error(path, f"'{name}' is declared both as a parameter and as a coordinate", key=True)
            self.coords[name] = self._coordinate(name, spec.latex, spec.description, spec.dimension)
            if spec.dimension == "length":
                self.dims[self.coords[name].q] = DIMENSIONS["length"]
            elif spec.dimension == "angle":
                self.dims[self.coords[name].q] = DIMENSIONS["angle"]

    def _coordinate(self, name: str, latex: str | None, description: str | None, dimension: str | None) -> Coordinate:
        q = sp.Symbol(name, real=True)
        qd = sp.Symbol(f"{name}_dot", real=True)
        qdd = sp.Symbol(f"{name}_ddot", real=True)
        return Coordinate(
            name,
            q,
            qd,
            qdd,
            latex if latex is not None else sp.latex(q),
            description,
            dimension,
            self.smap.key_location(self.name_path("coordinates", name)),
        )

    def build_gravity(self) -> sp.ImmutableMatrix | None:
        spec = self.doc.gravity
        if spec is None:
            return None
        path: KeyPath = ("gravity",)
        names = self.symbols()
        if spec.vector is not None:
            if spec.g is not None or spec.direction is not None:
                extra = "g" if spec.g is not None else "direction"
                self.error(
                    (*path, extra),
                    f"gravity gives both `vector` and `{extra}`; expected a vector, or `g` with `direction`",
                    key=True,
                )
                return None
            vpath = path if isinstance(self.data.get("gravity"), list) else (*path, "vector")
            return self.vector(vpath, spec.vector, names, "acceleration")
        if spec.g is None or spec.direction is None:
            found = (
                "`g` without `direction`"
                if spec.g is not None
                else "`direction` without `g`"
                if spec.direction is not None
                else "neither"
            )
            self.error(
                path,
                f"gravity needs a `vector`, or `g` and `direction` (e.g. {{g: g, direction: -y}}); found {found}",
                key=True,
            )
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
        # every declared body counts as known, even one with errors, so that joints, springs and
        # loads that refer to it are not reported as well
        self.body_names = {*self.doc.bodies, *self.dropped_names("bodies")}
        if self.doc.arm is not None:
            self.body_names |= set(self.doc.arm.links)
        self.body_names |= {str(u[2]) for u in self.dropped if len(u) == 3 and tuple(u[:2]) == _ARM_LINKS}
        written = self.data.get("arm")
        if "arm" in self.dropped_keys and isinstance(written, dict) and isinstance(written.get("links"), dict):
            # the arm was set aside for a shape error: its links still count as declared bodies
            self.body_names |= {str(k) for k in written["links"]}
        for name, spec in self.doc.bodies.items():
            path: KeyPath = ("bodies", name)
            self._check_name(path, name, "body")
            if name in self.params or name in self.coords:
                self.error(
                    path,
                    f"'{name}' is already the name of a {'parameter' if name in self.params else 'coordinate'}"
                    "; give the body another name",
                    key=True,
                )
            parts: list[Part] = []
            simple = spec.parts is None
            if spec.parts is not None:
                if spec.mass is not None or spec.inertia is not None or spec.com is not None:
                    given = ", ".join(f"`{k}`" for k in ("mass", "com", "inertia") if getattr(spec, k) is not None)
                    self.error(
                        path,
                        f"body '{name}' gives both `parts` and {given}; expected `parts` (each with its own mass) "
                        "or `mass`/`com`/`inertia`, not both",
                        key=True,
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
                given = "`com`" if spec.com is not None else "`inertia`"
                self.error(path, f"body '{name}' gives {given} but no `mass`; expected a `mass` with it", key=True)
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
        vals = {
            key: self.expr((*path, key), getattr(spec, key), names, "inertia", "an inertia")
            for key in ("xx", "yy", "zz", "xy", "xz", "yz")
        }
        if any(v is None for v in vals.values()):
            return None
        return sp.ImmutableMatrix(
            [
                [vals["xx"], vals["xy"], vals["xz"]],
                [vals["xy"], vals["yy"], vals["yz"]],
                [vals["xz"], vals["yz"], vals["zz"]],
            ]
        )

    def build_part(self, path: KeyPath, name: str, spec: Any, names: Mapping[str, sp.Expr]) -> Part | None:
        self._check_name(path, name, "part")
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
        has_mass = getattr(spec, "mass", None) is not None
        has_density = getattr(spec, "density", None) is not None
        if has_mass and has_density:
            self.error(path, f"part '{name}' gives both `mass` and `density`; expected one of them", key=True)
            ok = False
        elif not has_mass and shape is not Shape.POINT:
            if not solid:
                shape_words = shape.value.replace("_", " ")
                self.error(
                    path,
                    f"part '{name}' is {_article(shape_words)} {shape_words}, which has no volume; expected its "
                    f"`mass`, found {'`density`' if has_density else 'neither `mass` nor `density`'}",
                    key=True,
                )
                ok = False
            elif not has_density:
                self.error(
                    path,
                    f"part '{name}' needs a `mass` or a `density`; found neither",
                    key=True,
                )
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
            if sp.simplify(ro - ri).is_negative:
                self.error(
                    (*path, "inner_radius"),
                    f"part '{name}': expected inner_radius <= outer_radius, found inner_radius "
                    f"'{spec.inner_radius}' > outer_radius '{spec.outer_radius}'",
                )
                ok = False
        if not ok:
            return None
        return Part(name, shape, mass, density, tuple(dims), at, axis, rotation, inertia, self.smap.key_location(path))

    # -- joints ----------------------------------------------------------------------------
    def build_joints(
        self, bodies: set[str], arm: list[Joint] | None = None, used: dict[str, str] | None = None
    ) -> list[Joint]:
        """The joints of `joints`; ``arm`` are those of the DH table (already built), ``used`` the
        coordinates they drive."""
        out: list[Joint] = []
        # body -> the joint that places it
        children: dict[str, str] = {j.child: j.name for j in arm or []}
        # (joint, parent, child) of every well-formed link
        links: list[tuple[str, str, str]] = [(j.name, j.parent, j.child) for j in arm or []]
        used = {} if used is None else used
        arm_joints = {j.name for j in arm or []}
        consts = self.symbols()
        known = sorted(bodies | {GROUND})
        for name, spec in self.doc.joints.items():
            path: KeyPath = ("joints", name)
            self._check_name(path, name, "joint")
            ok = True
            if name in arm_joints:
                self.error(
                    path,
                    f"joint '{name}' is also the name of a joint of the arm; give one of them another name",
                    "an arm row's joint is called joint<i> unless its `joint` key names it",
                    key=True,
                )
                ok = False
            if spec.child == GROUND:
                self.error(
                    (*path, "child"),
                    f"joint '{name}' has the ground as its child; expected the body that the joint moves "
                    f"(known: {', '.join(sorted(bodies)) or 'none'})",
                )
                ok = False
            for role in ("parent", "child"):
                target = getattr(spec, role)
                if target in bodies or (target == GROUND and (role == "parent" or not ok)):
                    continue
                close = difflib.get_close_matches(target, known, n=1)
                self.error(
                    (*path, role),
                    f"joint '{name}' refers to unknown body '{target}' (known: {', '.join(known)})",
                    f"did you mean '{close[0]}'?" if close else None,
                )
                ok = False
            if ok and spec.parent == spec.child:
                self.error(
                    (*path, "child"),
                    f"joint '{name}' connects body '{spec.child}' to itself; expected a child other than its parent",
                )
                ok = False
            elif ok and spec.child in children:
                self.error(
                    (*path, "child"),
                    f"body '{spec.child}' is already placed by joint '{children[spec.child]}'; "
                    "expected one joint from each body to its parent",
                )
                ok = False
            elif ok:
                children[spec.child] = name
                links.append((name, spec.parent, spec.child))
            kind = JointKind(spec.type)
            coord = None
            if kind is JointKind.FIXED:
                if spec.coordinate is not None:
                    self.error(
                        (*path, "coordinate"),
                        f"joint '{name}' is fixed, so it has no coordinate; found coordinate '{spec.coordinate}'",
                        "remove `coordinate`, or make the joint revolute or prismatic",
                    )
                    ok = False
            elif spec.coordinate is None:
                self.error(
                    path,
                    f"joint '{name}' is {kind.value} and needs a `coordinate` "
                    f"(declared: {', '.join(self.coords) or 'none'}); found none",
                    key=True,
                )
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
                        f"coordinate '{spec.coordinate}' already drives joint '{used[spec.coordinate]}'; "
                        "expected one joint per coordinate",
                    )
                    ok = False
                used[spec.coordinate] = name
                expected = "angle" if kind is JointKind.REVOLUTE else "length"
                if coord.dimension is not None and coord.dimension != expected:
                    self.error(
                        (*path, "coordinate"),
                        f"joint '{name}' is {kind.value}, so its coordinate must be {_article(expected)} {expected}; "
                        f"found '{coord.name}', declared as {_article(coord.dimension)} {coord.dimension}",
                    )
                    ok = False
                self.dims.setdefault(coord.q, DIMENSIONS[expected])
            if spec.angle == "absolute" and kind is not JointKind.REVOLUTE:
                self.error(
                    (*path, "angle"),
                    f"joint '{name}' is {kind.value}; only a revolute joint can measure an absolute angle",
                    "remove `angle: absolute`",
                )
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
            motor = self.motor((*path, "motor"), spec.motor, kind, f"joint '{name}'")
            if not ok or axis is None or origin is None or offset is None or rots is None or motor is None:
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
                    rotor_inertia=motor[0],
                    gear_ratio=motor[1],
                )
            )
        self.placed = dict(children)
        self.check_loops(links)
        return out

    def motor(
        self, path: KeyPath, spec: S.MotorSpec | None, kind: JointKind, owner: str
    ) -> tuple[sp.Expr | None, sp.Expr | None] | None:
        """(rotor inertia, gear ratio) of a joint's motor, (None, None) without one; None if bad."""
        if spec is None:
            return None, None
        if kind is JointKind.FIXED:
            self.error(path, f"{owner} is fixed, so it has no motor; found `motor`", "remove `motor`", key=True)
            return None
        consts = self.symbols()
        inertia = self.expr((*path, "rotor_inertia"), spec.rotor_inertia, consts, "inertia", "a rotor inertia")
        ratio: sp.Expr | None = sp.Integer(1)
        if spec.gear_ratio is not None:
            # revolute: rotor turns per joint turn (a plain number); prismatic: rotor radians per metre
            dim = "dimensionless" if kind is JointKind.REVOLUTE else None
            ratio = self.expr((*path, "gear_ratio"), spec.gear_ratio, consts, dim, "a gear ratio")
        values = {p.symbol: p.value for p in self.parameters if p.value is not None}
        if inertia is not None and inertia.subs(values).is_negative:
            self.error(
                (*path, "rotor_inertia"),
                f"the rotor inertia of {owner} must not be negative; found '{spec.rotor_inertia}'",
            )
            inertia = None
        if ratio is not None and spec.gear_ratio is not None and ratio.subs(values).is_nonpositive:
            self.error(
                (*path, "gear_ratio"),
                f"the gear ratio of {owner} must be positive (rotor speed / joint speed); found '{spec.gear_ratio}'",
                "a motor turning the other way has the same reflected inertia n^2 J_m: give |n|",
            )
            ratio = None
        if inertia is None or ratio is None:
            return None
        return inertia, (ratio if spec.gear_ratio is not None else None)

    # -- the arm: a Denavit-Hartenberg table, desugared into bodies and joints ----------------
    def build_arm(self, used: dict[str, str]) -> tuple[list[Body], list[Joint]]:
        """One body and one joint per row of `arm.links`, placed exactly as the DH matrices place them.

        modified (Craig), A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i): the row's joint has
        origin (a_{i-1}, 0, 0) + Rx(alpha_{i-1}) (0, 0, d_i), the fixed rotation Rx(alpha_{i-1}) and axis
        z (a prismatic row: origin (a_{i-1}, 0, 0), rotation Rx(alpha_{i-1}) Rz(theta_i), sliding along z),
        and the body frame is DH frame i.

        standard (Spong, Paul), A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i): a joint cannot put fixed
        transforms after its motion, so the body frame of link i is the frame after Rz(theta_i) Tz(d_i)
        (on joint axis i, where Craig puts frame i), and DH frame i = body frame Tx(a_i) Rx(alpha_i). The
        link's centre of mass and inertia, given in DH frame i, are moved into the body frame exactly:
        c' = (a_i, 0, 0) + Rx(alpha_i) c and J' = Rx(alpha_i) J Rx(alpha_i)^T; the next row's joint then
        starts from (a_i, 0, 0) turned by Rx(alpha_i), as a modified row would.
        """
        spec = self.doc.arm
        if spec is None:
            return [], []
        if not spec.links and not any(len(u) == 3 and tuple(u[:2]) == _ARM_LINKS for u in self.dropped):
            self.error(("arm", "links"), "the arm has no links; expected one row per link, from the base outward")
            return [], []
        from tutgen.engine.kinematics import rotation_about

        x_axis = sp.ImmutableMatrix([1, 0, 0])
        z_axis = sp.ImmutableMatrix([0, 0, 1])

        def rot(axis: sp.ImmutableMatrix, angle: sp.Expr) -> sp.Matrix:
            return sp.eye(3) if angle == 0 else rotation_about(axis, angle)

        consts = self.symbols()
        kin_names = self.symbols(coords=True)
        by_q = {c.q: c for c in self.coords.values()}
        standard = spec.convention == "standard"
        other_joints = set(self.doc.joints)
        bodies: list[Body] = []
        joints: list[Joint] = []
        names: dict[str, str] = {}  # joint name -> its row
        parent = GROUND
        before = (sp.Integer(0), sp.Integer(0))  # standard: the previous row's (a, alpha); frame 0 is the world
        for i, (name, row) in enumerate(spec.links.items(), start=1):
            path: KeyPath = (*_ARM_LINKS, name)
            where = f"arm link '{name}'"
            self._check_name(path, name, "link")
            ok = True
            if name in self.params or name in self.coords:
                self.error(
                    path,
                    f"'{name}' is already the name of a {'parameter' if name in self.params else 'coordinate'}"
                    "; give the link another name",
                    key=True,
                )
                ok = False
            if name in self.doc.bodies:
                self.error(
                    path,
                    f"'{name}' is both a link of the arm and a body in `bodies`; give one of them another name",
                    key=True,
                )
                ok = False
            joint_name = row.joint if row.joint is not None else f"joint{i}"
            jpath: KeyPath = (*path, "joint") if row.joint is not None else path
            if row.joint is not None:
                self._check_name(jpath, joint_name, "joint")
            if joint_name in names or joint_name in other_joints:
                first = f"the joint of arm link '{names[joint_name]}'" if joint_name in names else "a joint in `joints`"
                self.error(
                    jpath,
                    f"the joint of {where} is called '{joint_name}', which is already {first}; expected a new name",
                    "name it with the row's `joint` key",
                    key=row.joint is None,
                )
                ok = False
            names.setdefault(joint_name, name)
            theta = self.expr((*path, "theta"), row.theta, kin_names, "angle")
            d = self.expr((*path, "d"), row.d, kin_names, "length")
            a = self.expr((*path, "a"), row.a, consts, "length")
            alpha = self.expr((*path, "alpha"), row.alpha, consts, "angle")
            kind, coord, offset = self._dh_variable(path, where, row, theta, d, by_q, used, joint_name)
            ok &= kind is not None
            body = self._dh_body(path, name, row, consts)
            motor = self.motor((*path, "motor"), row.motor, kind or JointKind.REVOLUTE, where)
            here_a, here_alpha = before if standard else (a, alpha)
            if standard:
                before = (a, alpha)
            if not ok or None in (theta, d, a, alpha, here_a, here_alpha, body, motor, offset):
                parent = name
                continue
            assert kind is not None and body is not None and motor is not None and coord is not None
            rx = rot(x_axis, here_alpha)
            if kind is JointKind.REVOLUTE:
                origin = sp.Matrix([here_a, 0, 0]) + rx * sp.Matrix([0, 0, d])
                rotation = rx
            else:
                origin = sp.Matrix([here_a, 0, 0])
                rotation = rx * rot(z_axis, theta)
            if standard:  # the link's data, given in DH frame i, into the body frame (see the docstring)
                body = self._dh_moved(body, a, rot(x_axis, alpha))
            bodies.append(body)
            joints.append(
                Joint(
                    joint_name,
                    kind,
                    parent,
                    name,
                    coord,
                    z_axis,
                    sp.ImmutableMatrix(origin.applyfunc(sp.expand)),
                    sp.ImmutableMatrix(sp.Matrix(rotation).applyfunc(sp.expand)),
                    offset,
                    False,
                    self.smap.key_location(path),
                    rotor_inertia=motor[0],
                    gear_ratio=motor[1],
                )
            )
            parent = name
        return bodies, joints

    def _dh_variable(
        self,
        path: KeyPath,
        where: str,
        row: S.DHLinkSpec,
        theta: sp.Expr | None,
        d: sp.Expr | None,
        by_q: dict[sp.Expr, Coordinate],
        used: dict[str, str],
        joint_name: str,
    ) -> tuple[JointKind | None, Coordinate | None, sp.Expr | None]:
        """The joint variable of a DH row: which of theta and d holds a coordinate, and the constant beside it."""
        if theta is None or d is None:
            return None, None, None
        found = {key: sorted(e.free_symbols & by_q.keys(), key=str) for key, e in (("theta", theta), ("d", d))}
        declared = ", ".join(self.coords) or "none"
        if found["theta"] and found["d"]:
            self.error(
                (*path, "d"),
                f"{where} uses a coordinate in both `theta` ('{row.theta}') and `d` ('{row.d}'); expected one "
                "joint variable: in `theta` (a revolute joint) or in `d` (a prismatic joint), the other a constant",
            )
            return None, None, None
        if not found["theta"] and not found["d"]:
            self.error(
                path,
                f"{where} has no joint variable: neither `theta` nor `d` uses a coordinate (declared: {declared}); "
                "expected a coordinate in `theta` (revolute) or in `d` (prismatic)",
                "e.g. theta: q1; a link that does not move goes in `bodies`, with a fixed joint",
                key=True,
            )
            return None, None, None
        key = "theta" if found["theta"] else "d"
        kind = JointKind.REVOLUTE if key == "theta" else JointKind.PRISMATIC
        value, written = (theta, row.theta) if key == "theta" else (d, row.d)
        if row.type is not None and row.type != kind.value:
            self.error(
                (*path, "type"),
                f"{where} is declared {row.type}, but its coordinate is in `{key}`, which makes it {kind.value}; "
                f"expected the coordinate in `{'theta' if row.type == 'revolute' else 'd'}`",
            )
            return None, None, None
        q = found[key][0]
        offset = sp.expand(value - q)
        if len(found[key]) > 1 or offset.free_symbols & by_q.keys():
            self.error(
                (*path, key),
                f"expected `{key}` of {where} to be one coordinate plus a constant (e.g. 'q2 + pi/2'), "
                f"found '{written}'",
            )
            return None, None, None
        coord = by_q[q]
        if coord.name in used:
            self.error(
                (*path, key),
                f"coordinate '{coord.name}' already drives joint '{used[coord.name]}'; "
                "expected one joint per coordinate",
            )
            return None, None, None
        used[coord.name] = joint_name
        expected = "angle" if kind is JointKind.REVOLUTE else "length"
        if coord.dimension is not None and coord.dimension != expected:
            self.error(
                (*path, key),
                f"{where} is {kind.value}, so its coordinate must be {_article(expected)} {expected}; "
                f"found '{coord.name}', declared as {_article(coord.dimension)} {coord.dimension}",
            )
            return None, None, None
        self.dims.setdefault(coord.q, DIMENSIONS[expected])
        return kind, coord, offset

    def _dh_body(self, path: KeyPath, name: str, row: S.DHLinkSpec, consts: Mapping[str, sp.Expr]) -> Body | None:
        """The link as a body given by mass, centre of mass and inertia (in DH frame i), or massless."""
        parts: list[Part] = []
        if row.mass is not None:
            mass = self.expr((*path, "mass"), row.mass, consts, "mass", "a mass")
            com = self.vector((*path, "com"), row.com, consts, "length")
            inertia = self.inertia_matrix((*path, "inertia"), row.inertia, consts)
            if mass is None or com is None or (row.inertia is not None and inertia is None):
                return None
            shape = Shape.GENERAL if inertia is not None else Shape.POINT
            eye = sp.ImmutableMatrix(sp.eye(3))
            parts.append(Part(name, shape, mass, None, (), com, None, eye, inertia, self.smap.location(path)))
        elif row.inertia is not None or row.com is not None:
            given = "`com`" if row.com is not None else "`inertia`"
            self.error(path, f"arm link '{name}' gives {given} but no `mass`; expected a `mass` with it", key=True)
            return None
        return Body(name, tuple(parts), None, None, (), self.smap.key_location(path), True)

    @staticmethod
    def _dh_moved(body: Body, a: sp.Expr, rx: sp.Matrix) -> Body:
        """A standard-convention link's data from DH frame i into its body frame: c' = (a, 0, 0) + Rx c,
        J' = Rx J Rx^T (DH frame i is the body frame moved by a along x and turned by Rx)."""
        parts = []
        for p in body.parts:
            at = (sp.Matrix([a, 0, 0]) + rx * sp.Matrix(p.at)).applyfunc(sp.expand)
            inertia = None if p.inertia is None else (rx * sp.Matrix(p.inertia) * rx.T).applyfunc(sp.expand)
            parts.append(
                dataclasses.replace(
                    p,
                    at=sp.ImmutableMatrix(at),
                    inertia=None if inertia is None else sp.ImmutableMatrix(inertia),
                )
            )
        return dataclasses.replace(body, parts=tuple(parts))

    def check_loops(self, links: list[tuple[str, str, str]]) -> None:
        """Every chain of parents must end at the ground: report each loop once, at its first joint."""
        parent_of = {child: (parent, joint) for joint, parent, child in links}
        order = {joint: i for i, (joint, _, _) in enumerate(links)}
        reported: set[frozenset[str]] = set()
        for start in parent_of:
            chain = [start]
            node = start
            while node in parent_of:
                node = parent_of[node][0]
                if node in chain:
                    loop = chain[chain.index(node) :]
                    if frozenset(loop) not in reported:
                        reported.add(frozenset(loop))
                        joints = sorted((parent_of[b][1] for b in loop), key=order.__getitem__)
                        # start the printed chain at the child of the first joint, for a stable message
                        i = next(k for k, b in enumerate(loop) if parent_of[b][1] == joints[0])
                        loop = loop[i:] + loop[:i]
                        self.error(
                            ("joints", joints[0]),
                            f"the joints {', '.join(joints)} form a loop (each body's parent, in turn: "
                            + " -> ".join([*loop, loop[0]])
                            + "); expected a tree in which every body leads back to ground",
                            key=True,
                        )
                    break
                chain.append(node)

    def check_explicit_placement(self) -> None:
        for name, spec in self.doc.bodies.items():
            if name in self.placed and (spec.position is not None or spec.orientation):
                key = "position" if spec.position is not None else "orientation"
                self.error(
                    ("bodies", name, key),
                    f"body '{name}' is placed by joint '{self.placed[name]}', so it cannot also have "
                    f"a `position` or `orientation`; found `{key}`",
                    "remove it, or remove the joint",
                    key=True,
                )

    # -- springs, dampers, loads, forces, energy --------------------------------------------
    def _endpoints(
        self, path: KeyPath, between: list[S.EndpointSpec] | None, bodies: set[str]
    ) -> tuple[Endpoint, Endpoint] | None:
        if between is None:
            return None
        out = []
        known = sorted(bodies | {GROUND})
        for i, ep in enumerate(between):
            at = self.vector((*path, i, "at"), ep.at, self.symbols(), "length")
            if ep.body not in known:
                close = difflib.get_close_matches(ep.body, known, n=1)
                epath = (*path, i, "body") if isinstance(self.smap_get((*path, i)), dict) else (*path, i)
                self.error(
                    epath,
                    f"{_where(path[:2])} refers to unknown body '{ep.body}' (known: {', '.join(known)})",
                    f"did you mean '{close[0]}'?" if close else None,
                )
                continue
            if at is not None:
                out.append(Endpoint(ep.body, at))
        if len(out) != 2:
            return None
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
            what = section[:-1]
            for name, spec in specs.items():
                path: KeyPath = (section, name)
                self._check_name(path, name, what)
                ok = True
                if spec.between is not None and spec.extension is not None:
                    self.error(
                        (*path, "extension"),
                        f"{what} '{name}' gives both `between` and `extension`; expected one of them",
                        key=True,
                    )
                    ok = False
                elif spec.between is None and spec.extension is None:
                    self.error(
                        path,
                        f"{what} '{name}' needs `between` (two attachment points) or `extension` "
                        "(an expression of the coordinates); found neither",
                        key=True,
                    )
                    ok = False
                between = self._endpoints((*path, "between"), spec.between, bodies)
                ok &= spec.between is None or between is not None
                ext = None
                if spec.extension is not None:
                    ext = self.expr((*path, "extension"), spec.extension, kin_names)
                    ok &= ext is not None
                # with `between`, the elongation is a length and the units of k and c follow
                physical = between is not None
                if section == "springs":
                    k = self.expr(
                        (*path, "stiffness"), spec.stiffness, consts, "stiffness" if physical else None, "a stiffness"
                    )
                    l0 = (
                        self.expr((*path, "free_length"), spec.free_length, consts, "length")
                        if spec.free_length is not None
                        else sp.Integer(0)
                    )
                    if spec.free_length is not None and spec.extension is not None and spec.between is None:
                        self.error(
                            (*path, "free_length"),
                            f"spring '{name}' gives `free_length` with `extension`; `free_length` goes with "
                            "`between`: with `extension`, write the elongation itself (e.g. 'x - L0')",
                            key=True,
                        )
                        ok = False
                    if ok and k is not None and l0 is not None:
                        springs.append(Spring(name, k, l0, between, ext, self.smap.key_location(path)))
                else:
                    c = self.expr(
                        (*path, "coefficient"),
                        spec.coefficient,
                        consts,
                        "damping" if physical else None,
                        "a damping coefficient",
                    )
                    if ok and c is not None:
                        dampers.append(Damper(name, c, between, ext, self.smap.key_location(path)))
        return springs, dampers

    def build_loads(self, bodies: set[str]) -> list[Load]:
        out = []
        names = self.symbols(coords=True, rates=True)
        for name, spec in self.doc.loads.items():
            path: KeyPath = ("loads", name)
            self._check_name(path, name, "load")
            ok = True
            for role in ("body", "reaction_body"):
                target = getattr(spec, role)
                allowed = bodies | ({GROUND} if role == "reaction_body" else set())
                if target is not None and target not in allowed:
                    close = difflib.get_close_matches(target, sorted(allowed), n=1)
                    self.error(
                        (*path, role),
                        f"load '{name}' refers to unknown body '{target}' "
                        f"(known: {', '.join(sorted(allowed)) or 'none'})",
                        f"did you mean '{close[0]}'?" if close else None,
                    )
                    ok = False
            if spec.force is None and spec.torque is None:
                self.error(path, f"load '{name}' needs a `force` or a `torque` (or both); found neither", key=True)
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
                    spec.body,
                    force,
                    torque,
                    at,
                    spec.frame == "body",
                    spec.reaction_body,
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
                    f"generalized force on '{cname}': '{cname}' is not a declared coordinate "
                    f"(declared: {', '.join(self.coords) or 'none'})",
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
        # keys set aside for shape errors (or unknown ones, perhaps a misspelt `bodies`) may be what
        # is missing here: guess nothing about them
        unsure = bool(self.dropped_keys - {"tutgen", "title", "statement", "gravity", "ask"})
        has_bodies = bool(self.doc.bodies or self.doc.joints or self.body_names or self.doc.arm)
        has_bodies |= bool(self.dropped_names("joints"))
        if spec is None:
            if self.coords and not has_bodies and not unsure:
                self.error(
                    ("coordinates",),
                    "the spec has `coordinates` but no `bodies` and no `energy`; expected one of them, "
                    "to say what moves",
                    key=True,
                )
            return None, None
        if has_bodies:
            given = "`bodies`" if self.doc.bodies or self.body_names else "`joints`"
            given = "`arm`" if self.doc.arm is not None else given
            self.error(
                ("energy",),
                f"the spec gives both `energy` and {given}; expected the energy, or the bodies, not both",
                key=True,
            )
            return None, None
        if not self.coords:
            if not unsure:
                self.error(
                    ("energy",),
                    "`energy` needs `coordinates` (the q_i that T and U depend on); found none",
                    key=True,
                )
            return None, None
        t = self.expr(("energy", "kinetic"), spec.kinetic, self.symbols(coords=True, rates=True))
        if t is not None:
            t = self._check_quadratic(t)
        if self.doc.gravity is not None:
            self.error(
                ("gravity",),
                "`gravity` has no effect when the energies are given; expected its potential energy in "
                "`energy.potential` (e.g. m*g*h), found a `gravity` section",
                key=True,
            )
        u = (
            self.expr(("energy", "potential"), spec.potential, self.symbols(coords=True))
            if spec.potential is not None
            else sp.Integer(0)
        )
        return t, u

    def _check_quadratic(self, t: sp.Expr) -> sp.Expr | None:
        """T must be a quadratic form in the velocities: T = q_dot^T H(q) q_dot / 2."""
        rates = [c.qd for c in self.coords.values()]
        expanded = sp.expand(t)
        bad = []
        for term in sp.Add.make_args(expanded):
            powers = term.as_powers_dict()
            degree = sum(powers.get(r, 0) for r in rates)
            if degree != 2 or any(not sp.sympify(powers.get(r, 0)).is_Integer for r in rates):
                bad.append(term)
        if bad:
            shown = ", ".join(sp.sstr(b) for b in bad[:3]) + (", ..." if len(bad) > 3 else "")
            self.error(
                ("energy", "kinetic"),
                "expected the kinetic energy as a quadratic form in the velocities, T = q_dot^T H(q) q_dot / 2 "
                f"(every term of degree 2 in the NAME_dot), found the term{'s' if len(bad) > 1 else ''} {shown}",
            )
            return None
        return t

    def build_ask(self, dynamic: bool) -> frozenset[Ask]:
        if self.doc.ask is not None:
            return frozenset(Ask(a) for a in self.doc.ask)
        if not dynamic:
            return frozenset({Ask.INERTIA})
        everything = set(Ask)
        if not self.doc.bodies:
            everything.discard(Ask.INERTIA)
        return frozenset(everything)


def _article(words: str) -> str:
    return "an" if words[:1] in "aeiou" else "a"


def _expected_dimension(name: str) -> str:
    """ "a mass (kg)", "an angle (a plain number, or deg/rad)"."""
    words = name.replace("_", " ")
    dim = DIMENSIONS[name]
    if dim.is_dimensionless:
        unit = "a plain number, or deg/rad" if name == "angle" else "a plain number"
    else:
        unit = str(dim)
    return f"{_article(words)} {words} ({unit})"


def _found_dimension(dim: Dimension) -> str:
    """ "a length (m)", "a plain number", "a quantity in kg*m"."""
    if dim.is_dimensionless:
        return "a plain number"
    for name, known in DIMENSIONS.items():
        if known == dim:
            words = name.replace("_", " ")
            return f"{_article(words)} {words} ({dim})"
    return f"a quantity in {dim}"


def _mentions(text: str, name: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", text) is not None


__all__ = ["load_system", "load_system_text", "validate_spec"]
