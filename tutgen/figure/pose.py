"""The numbers of a drawing: a float for every sympy expression of the model (:class:`Numbers`), the
drawing size of a symbolic length (:func:`default_size`), and every body frame at one set of numbers
(:class:`Pose`, with the model's joint conventions, :class:`tutgen.model.system.Joint`)."""

from __future__ import annotations

import re

import numpy as np
import sympy as sp

from tutgen.model.system import GROUND, Body, JointKind, System

Vec = np.ndarray


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
        self.mcache: dict[int, tuple[object, Vec]] = {}

    def with_(self, symbol: sp.Symbol, value: float) -> Numbers:
        out = Numbers({}, self.moving)
        out.table = {**self.table, symbol: sp.Float(value)}
        out.cache, out.mcache = self.cache, self.mcache
        return out

    def __call__(self, expr: object) -> float:
        e0 = sp.sympify(expr)
        if e0.is_Number:
            return float(e0)
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
            return hit[1].copy()
        mm = sp.Matrix(m)
        value = np.array([[self(v) for v in row] for row in mm.tolist()], dtype=float)
        if not (mm.free_symbols & self.moving):
            self.mcache[id(m)] = (m, value)
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
