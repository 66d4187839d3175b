"""`bodies`: rigid bodies, each a point mass, a lumped mass with inertia, or a set of shaped parts."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp

from tutgen.model.system import Body, Part, Shape
from tutgen.spec import schema as S
from tutgen.spec.builders.context import Context, rotation_matrix
from tutgen.spec.builders.words import article
from tutgen.spec.loader import KeyPath

#: Shapes with a volume, whose mass may be given as a `density`.
_SOLIDS = (Shape.BOX, Shape.CYLINDER, Shape.HOLLOW_CYLINDER, Shape.SPHERE)


def declared_bodies(ctx: Context) -> set[str]:
    """Every body the spec declares: in `bodies` and as links of the `arm`, with errors or not.

    Joints, springs and loads that refer to a body with errors are therefore not reported as well.
    """
    names = {*ctx.doc.bodies, *ctx.dropped_names("bodies")}
    if ctx.doc.arm is not None:
        names |= set(ctx.doc.arm.links)
    names |= set(ctx.dropped_arm_links())
    written = ctx.written(("arm",))
    if "arm" in ctx.dropped_keys and isinstance(written, dict) and isinstance(written.get("links"), dict):
        # the arm was set aside for a shape error: its links still count as declared bodies
        names |= {str(k) for k in written["links"]}
    return names


def build_bodies(ctx: Context) -> list[Body]:
    """The bodies of `bodies`, in spec order (the links of the `arm` are built in :mod:`.arm`)."""
    out = []
    consts = ctx.symbols()
    kin_names = ctx.symbols(coords=True)
    for name, spec in ctx.doc.bodies.items():
        path: KeyPath = ("bodies", name)
        ctx.check_name(path, name, "body")
        ctx.check_name_free(path, name, "body")
        parts: list[Part] = []
        simple = spec.parts is None
        if spec.parts is not None:
            if spec.mass is not None or spec.inertia is not None or spec.com is not None:
                given = ", ".join(f"`{k}`" for k in ("mass", "com", "inertia") if getattr(spec, k) is not None)
                ctx.error(
                    path,
                    f"body '{name}' gives both `parts` and {given}; expected `parts` (each with its own mass) "
                    "or `mass`/`com`/`inertia`, not both",
                    key=True,
                )
                continue
            for pname, pspec in spec.parts.items():
                part = _part(ctx, (*path, "parts", pname), pname, pspec, consts)
                if part is not None:
                    parts.append(part)
        elif spec.mass is not None:
            part = lumped_part(ctx, path, name, spec, consts)
            if part is not None:
                parts.append(part)
        elif spec.inertia is not None or spec.com is not None:
            given = "`com`" if spec.com is not None else "`inertia`"
            ctx.error(path, f"body '{name}' gives {given} but no `mass`; expected a `mass` with it", key=True)
            continue
        position = None
        if spec.position is not None:
            position = ctx.vector((*path, "position"), spec.position, kin_names, "length")
        rotations = ctx.rotations((*path, "orientation"), spec.orientation, kin_names)
        if rotations is None:
            continue
        out.append(Body(name, tuple(parts), position, None, rotations, ctx.smap.key_location(path), simple))
    return out


def lumped_part(
    ctx: Context, path: KeyPath, name: str, spec: S.BodySpec | S.DHLinkSpec, names: Mapping[str, sp.Expr]
) -> Part | None:
    """The one part of a body given by `mass`, `com` and perhaps `inertia` (about the centre of mass):
    a point mass, or a general part; None if a value is bad."""
    mass = ctx.expr((*path, "mass"), spec.mass, names, "mass", "a mass")
    com = ctx.vector((*path, "com"), spec.com, names, "length")
    inertia = inertia_matrix(ctx, (*path, "inertia"), spec.inertia, names)
    if mass is None or com is None or (spec.inertia is not None and inertia is None):
        return None
    shape = Shape.GENERAL if inertia is not None else Shape.POINT
    eye = sp.ImmutableMatrix(sp.eye(3))
    return Part(name, shape, mass, None, (), com, None, eye, inertia, ctx.smap.location(path))


def inertia_matrix(
    ctx: Context, path: KeyPath, spec: S.InertiaSpec | None, names: Mapping[str, sp.Expr]
) -> sp.ImmutableMatrix | None:
    """The symmetric inertia tensor of an `inertia` mapping (xx, yy, zz, xy, xz, yz); None if absent or bad."""
    if spec is None:
        return None
    vals = {
        key: ctx.expr((*path, key), getattr(spec, key), names, "inertia", "an inertia")
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


def _part(ctx: Context, path: KeyPath, name: str, spec: Any, names: Mapping[str, sp.Expr]) -> Part | None:
    """One shaped part of a body: its mass (or density), sizes, place and orientation in the body frame."""
    ctx.check_name(path, name, "part")
    shape = Shape(spec.shape)
    ok = True
    mass = density = None
    if getattr(spec, "mass", None) is not None:
        mass = ctx.expr((*path, "mass"), spec.mass, names, "mass", "a mass")
        ok &= mass is not None
    if getattr(spec, "density", None) is not None:
        density = ctx.expr((*path, "density"), spec.density, names, "density", "a density")
        ok &= density is not None
    solid = shape in _SOLIDS
    has_mass = getattr(spec, "mass", None) is not None
    has_density = getattr(spec, "density", None) is not None
    if has_mass and has_density:
        ctx.error(path, f"part '{name}' gives both `mass` and `density`; expected one of them", key=True)
        ok = False
    elif not has_mass and shape is not Shape.POINT:
        if not solid:
            shape_words = shape.value.replace("_", " ")
            ctx.error(
                path,
                f"part '{name}' is {article(shape_words)} {shape_words}, which has no volume; expected its "
                f"`mass`, found {'`density`' if has_density else 'neither `mass` nor `density`'}",
                key=True,
            )
            ok = False
        elif not has_density:
            ctx.error(
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
            vec = ctx.vector((*path, key), raw, names, "length")
            ok &= vec is not None
            if vec is not None:
                dims.append((key, tuple(vec)))
        else:
            v = ctx.expr((*path, key), raw, names, "length", "a length")
            ok &= v is not None
            dims.append((key, v))
    at = ctx.vector((*path, "at"), spec.at, names, "length")
    ok &= at is not None
    axis = None
    if hasattr(spec, "axis"):
        axis = ctx.axis((*path, "axis"), spec.axis, {})
        ok &= axis is not None
    rotation = sp.ImmutableMatrix(sp.eye(3))
    if getattr(spec, "orientation", None):
        rots = ctx.rotations((*path, "orientation"), spec.orientation, names)
        if rots is None:
            return None
        rotation = rotation_matrix(rots)
    inertia = None
    if shape is Shape.GENERAL:
        inertia = inertia_matrix(ctx, (*path, "inertia"), spec.inertia, names)
        ok &= inertia is not None
    d = dict(dims)
    if shape is Shape.HOLLOW_CYLINDER and ok:
        ro, ri = d["outer_radius"], d["inner_radius"]
        if sp.simplify(ro - ri).is_negative:
            ctx.error(
                (*path, "inner_radius"),
                f"part '{name}': expected inner_radius <= outer_radius, found inner_radius "
                f"'{spec.inner_radius}' > outer_radius '{spec.outer_radius}'",
            )
            ok = False
    if not ok:
        return None
    return Part(name, shape, mass, density, tuple(dims), at, axis, rotation, inertia, ctx.smap.key_location(path))
