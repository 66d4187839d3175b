"""The numbers of a drawing: a float for every sympy expression of the model (:class:`Numbers`), the
drawing size of a symbolic length (:func:`default_size`), and every body frame at one set of numbers
(:class:`Pose`, with the model's joint conventions, :class:`tutgen.model.system.Joint`)."""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
import sympy as sp

from tutgen.engine.constraints.kinematics import damped_gauss_newton
from tutgen.model.system import GROUND, Body, ConstraintKind, JointKind, System

Vec = np.ndarray

#: While a drawing is made (:func:`reading`), the symbols whose numbers it has read: a drawing is a
#: function of its system's structure and of these numbers only (tutgen.figure.build.draw_system), and
#: of the signs of the symbols read as :class:`Positive`.
_READS: list[set[sp.Basic | Positive]] = []


@dataclass(frozen=True)
class Positive:
    """A read of a symbol's sign alone (:func:`read_positive`): the drawing is the same at every positive
    value of it (a free-body diagram's arrow shows a force's direction, not its size)."""

    symbol: sp.Basic


@contextmanager
def reading() -> Iterator[set[sp.Basic | Positive]]:
    """The symbols every :class:`Numbers` evaluates an expression of, inside the ``with`` (nested
    recordings each get their own set, and the outer one the inner one's too)."""
    read: set[sp.Basic | Positive] = set()
    _READS.append(read)
    try:
        yield read
    finally:
        _READS.pop()
        if _READS:
            _READS[-1].update(read)


def read(symbols: Iterable[sp.Basic]) -> None:
    """Mark ``symbols`` as read by the drawing being made (a number taken from the table directly)."""
    if _READS:
        _READS[-1].update(symbols)


def read_positive(symbols: Iterable[sp.Basic]) -> None:
    """Mark that the drawing being made used only that each of ``symbols`` is positive."""
    if _READS:
        _READS[-1].update(Positive(s) for s in symbols)


def default_size(name: str) -> float:
    """A drawing size for a symbolic length, by the usual letter: links 1, offsets and radii less;
    a trailing number shortens each next link a little (l1 = 1, l2 = 0.85, ...)."""
    base = {"r": 0.22, "R": 0.25, "c": 0.5, "h": 0.6, "b": 0.5, "e": 0.3, "w": 0.4}.get(name[0], 1.0)
    digits = re.search(r"(\d+)$", name)
    k = int(digits.group(1)) if digits else 1
    return base * 0.85 ** max(0, min(k, 9) - 1)


def rotation(axis: Vec, angle: float) -> Vec:
    """The rotation by ``angle`` about ``axis`` (Rodrigues' formula)."""
    a = axis / (np.linalg.norm(axis) or 1.0)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.cos(angle) * np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * np.outer(a, a)


class Numbers:
    """Floats for sympy expressions, from one table of symbol values.

    Values of expressions free of the coordinates are kept in a cache shared by every pose derived
    with :meth:`with_`, since drawing one figure evaluates the same joint offsets for many poses."""

    def __init__(self, table: dict[sp.Symbol, float], moving: frozenset[sp.Symbol] = frozenset()) -> None:
        self.table = {s: sp.Float(v) for s, v in table.items()}
        self.moving = moving
        self.cache: dict[sp.Basic, float] = {}
        self.mcache: dict[int, tuple[object, Vec, set[sp.Basic]]] = {}

    def with_(self, symbol: sp.Symbol, value: float) -> Numbers:
        out = Numbers({}, self.moving)
        out.table = {**self.table, symbol: sp.Float(value)}
        out.cache, out.mcache = self.cache, self.mcache
        return out

    def __call__(self, expr: object) -> float:
        e0 = sp.sympify(expr)
        if e0.is_Number:
            return float(e0)
        if _READS:
            _READS[-1].update(e0.free_symbols)
        hit = self.cache.get(e0)
        if hit is not None:
            return hit
        e = e0.xreplace(self.table)
        rest = e.free_symbols
        if rest:
            e = e.xreplace({s: sp.Float(1) for s in rest})
        try:
            value = float(e)
        except TypeError:
            value = 0.0
        if not (e0.free_symbols & self.moving):
            self.cache[e0] = value
        return value

    def vec(self, m: object) -> Vec:
        return self.mat(m).reshape(-1)

    def mat(self, m: object) -> Vec:
        """A matrix as floats; a constant one is converted once per drawing (keyed by the object,
        which the model keeps alive)."""
        hit = self.mcache.get(id(m))
        if hit is not None and hit[0] is m:
            read(hit[2])
            return hit[1].copy()
        mm = sp.Matrix(m)
        value = np.array([[self(v) for v in row] for row in mm.tolist()], dtype=float)
        free = mm.free_symbols
        if not (free & self.moving):
            self.mcache[id(m)] = (m, value, free)
        return value.copy()


class Pose:
    """Every body frame (origin, rotation world-from-body) at one set of numbers."""

    def __init__(self, system: System, num: Numbers) -> None:
        self.system, self.num = system, num
        self.frames: dict[str, tuple[Vec, Vec]] = {GROUND: (np.zeros(3), np.eye(3))}
        self.joint_at: dict[str, Vec] = {}  # joint -> where it is (world)
        self.axis_of: dict[str, Vec] = {}  # joint -> its world axis
        self.by_child = {j.child: j for j in system.joints}
        for body in system.bodies:
            self.frame(body.name, 0)

    def frame(self, name: str, depth: int) -> tuple[Vec, Vec]:
        if name in self.frames:
            return self.frames[name]
        joint = self.by_child.get(name)
        num = self.num
        if joint is None or depth > 64:
            body = self.system.body(name)
            pos = num.vec(body.position) if body.position is not None else np.zeros(3)
            rot = num.mat(body.rotation) if body.rotation is not None else np.eye(3)
            if body.rotation is None:  # intrinsic rotations, each about the axes turned so far
                for axis, angle in body.rotation_rates:
                    rot = rot @ rotation(num.vec(axis), num(angle))
        else:
            p, r = self.frame(joint.parent, depth + 1)
            base = p + r @ num.vec(joint.origin_offset)
            fixed = num.mat(joint.rotation)
            rb = r @ fixed
            axis_w = rb @ num.vec(joint.axis)
            value = (num(joint.coordinate.q) if joint.coordinate else 0.0) + num(joint.offset)
            pos, rot = base, rb
            if joint.kind is JointKind.REVOLUTE:
                rot = rotation(axis_w, value) @ fixed if joint.absolute else rb @ rotation(num.vec(joint.axis), value)
            elif joint.kind is JointKind.PRISMATIC:
                pos = base + axis_w * value
            self.joint_at[joint.name] = base
            self.axis_of[joint.name] = axis_w / (np.linalg.norm(axis_w) or 1.0)
        self.frames[name] = (pos, rot)
        return pos, rot

    def point(self, body: str, local: Vec) -> Vec:
        p, r = self.frames[body]
        return p + r @ local


def com_local(body: Body, num: Numbers) -> Vec:
    """A body's centre of mass in its own frame (parts without a mass count as 1)."""
    total, acc = 0.0, np.zeros(3)
    for part in body.parts:
        m = num(part.mass) if part.mass is not None else 1.0
        total += m
        acc = acc + m * num.vec(part.at)
    return acc / total if total else np.zeros(3)


#: |gap| (drawing units, lengths near 1) below which a loop is drawn closed, and the step of the
#: finite-difference Jacobian of the gaps
_CLOSED = 1e-10
_STEP = 1e-6


def _gaps(system: System, num: Numbers) -> list[float]:
    """The position constraints at ``num``: each loop-closing joint's gap (three world components), then
    each position constraint of the spec (a velocity constraint does not tie the pose)."""
    out: list[float] = []
    if system.loop_joints:
        pose = Pose(system, num)
        for joint in system.loop_joints:
            out += list(
                pose.point(joint.parent, num.vec(joint.parent_at)) - pose.point(joint.child, num.vec(joint.child_at))
            )
    out += [num(c.expression) for c in system.constraints if c.kind is ConstraintKind.POSITION]
    return out


def _moved(num: Numbers, values: dict[sp.Symbol, float]) -> Numbers:
    for symbol, value in values.items():
        num = num.with_(symbol, value)
    return num


def close_loops(system: System, num: Numbers) -> tuple[Numbers, dict[str, float], bool]:
    """The numbers of a pose that satisfies the position constraints (loop-closing joints, and
    constraints such as rolling's x = R phi), with the independent coordinates kept as drawn.

    The dependent coordinates (those not in ``independent_coordinates``; without that list, the last m,
    m the count of loop-closure equations and constraints, as the engine takes them) that the gaps depend
    on are solved by the engine's damped Gauss-Newton (:func:`~tutgen.engine.constraints.kinematics.
    damped_gauss_newton`) from their default drawing values, so the branch drawn is the one nearest the
    default pose, the same on every run. Returns the numbers, the values solved (by coordinate name), and
    whether the loops close (when they cannot at these sizes, the numbers are returned as they were).
    """
    coords = system.coordinates
    gaps = _gaps(system, num)
    if not gaps:
        return num, {}, True
    # each coordinate's column of the gaps' Jacobian: a gap that is zero with a zero row says nothing
    # (the z of a planar loop); a coordinate with a zero column is not tied (at this pose)
    columns = []
    for c in coords:
        moved = _gaps(system, num.with_(c.q, num(c.q) + _STEP))
        columns.append([(b - a) / _STEP for a, b in zip(gaps, moved, strict=True)])
    rows = [k for k in range(len(gaps)) if abs(gaps[k]) > _CLOSED or any(abs(col[k]) > 1e-9 for col in columns)]
    if system.independent_coordinates:
        dependent = [c for c in coords if c.name not in system.independent_coordinates]
    else:
        m = len([k for k in rows if k < 3 * len(system.loop_joints)]) + len(system.constraints)
        dependent = list(coords[len(coords) - m :]) if m else []
    unknowns = [c for c in dependent if any(abs(columns[coords.index(c)][k]) > 1e-9 for k in rows)]
    if all(abs(gaps[k]) < _CLOSED for k in rows):
        return num, {}, True
    if not unknowns:
        return num, {}, False

    def residual(x: list[object]) -> list[float]:
        values = _gaps(system, _moved(num, {c.q: float(v) for c, v in zip(unknowns, x, strict=True)}))  # type: ignore[arg-type]
        return [values[k] for k in rows]

    def jacobian(x: list[object]) -> list[list[float]]:
        base = [float(v) for v in x]  # type: ignore[arg-type]
        cols = []
        for i in range(len(base)):
            up, down = list(base), list(base)
            up[i] += _STEP
            down[i] -= _STEP
            cols.append([(p - q) / (2 * _STEP) for p, q in zip(residual(up), residual(down), strict=True)])
        return [[col[k] for col in cols] for k in range(len(rows))]

    root = damped_gauss_newton(residual, jacobian, [num(c.q) for c in unknowns], tolerance=_CLOSED, stall=1e-3)
    if root is None:
        return num, {}, False
    solved = {c.q: float(v) for c, v in zip(unknowns, root, strict=True)}
    return _moved(num, solved), {c.name: solved[c.q] for c in unknowns}, True
