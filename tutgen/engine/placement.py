"""Where a joint puts its child link: one placement for the engines of serial chains, whatever their scalars.

The convention (as :meth:`tutgen.engine.kinematics.Kinematics` places frames in world axes): the child
frame is the parent's, moved to ``origin_offset`` (parent axes), turned by the fixed ``rotation`` F,
then moved by the joint itself about or along ``axis`` (axes after F):

- revolute:  ^pR_c = F Rot(a, q + offset),  the lever p = origin_offset;
- prismatic: ^pR_c = F,  p = origin_offset + F a (q + offset);
- fixed (or a joint without a coordinate): ^pR_c = F,  p = origin_offset.

with Rot(a, t) = a a^T + cos t (E - a a^T) + sin t [a]x (Rodrigues, a a unit vector). The joint's
motion per unit rate, in the child's axes, is (angular, linear) = (a, 0) for a revolute joint and
(0, a) for a prismatic one.

:mod:`tutgen.engine.serial` computes with exact trigonometric polynomials and
:mod:`tutgen.engine.recursive` with sympy expressions recorded as a straight-line program, so the
placement is written once against :class:`Scalars`, the few operations both provide. A new joint kind
is placed here (and admitted by :func:`tutgen.engine.serial.is_serial_chain`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Generic, Protocol, TypeVar

import sympy as sp

from tutgen.model.system import Joint, JointKind

__all__ = ["Placement", "Scalars", "place_joint"]

S = TypeVar("S")


class Scalars(Protocol[S]):
    """The arithmetic of one engine's scalars."""

    zero: S
    one: S

    def const(self, value: sp.Expr) -> S:
        """A constant of the spec (a length, an entry of F, a coordinate that slides) as a scalar."""
        ...

    def add(self, *terms: S) -> S: ...

    def mul(self, *factors: S) -> S: ...

    def neg(self, a: S) -> S: ...

    def sub(self, a: S, b: S) -> S: ...

    def name(self, a: S) -> S:
        """An intermediate result worth keeping (a program line); the identity for exact scalars."""
        ...

    def turn(self, joint: Joint) -> tuple[S, S]:
        """cos and sin of a revolute joint's angle q + offset."""
        ...


@dataclass(frozen=True)
class Placement(Generic[S]):
    """A child link's frame relative to its parent's, and the motion its joint adds."""

    rotation: list[list[S]]  # ^pR_c: child components -> parent components
    transpose: list[list[S]]  # ^cR_p: parent components -> child components (the same objects)
    lever: list[S]  # the child origin from the parent origin, parent axes
    axis: list[S]  # the joint axis, child axes
    # (angular, linear) velocity of the child per unit rate of the joint's coordinate, child axes;
    # None for a joint that does not move
    motion: tuple[list[S], list[S]] | None


def place_joint(ring: Scalars[S], joint: Joint) -> Placement[S]:
    """The placement of ``joint``'s child (see the module docstring), in ``ring``'s scalars.

    The entries of ^pR_c are named row by row, then (prismatic) the slide q + offset and the lever:
    a program that records names (:mod:`tutgen.engine.recursive`) lists them in that order.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> rail = load_system_text('''
    ... {tutgen: 1, title: slider, parameters: [m, d], coordinates: [s], bodies: {cart: {mass: m}},
    ...  joints: {rail: {type: prismatic, parent: ground, child: cart, axis: y, origin: [d, 0, 0], coordinate: s}}}
    ... ''').joints[0]
    >>> class Plain:  # plain sympy, nothing named
    ...     zero, one, const = sp.S.Zero, sp.S.One, staticmethod(sp.sympify)
    ...     add, mul = staticmethod(lambda *t: sp.Add(*t)), staticmethod(lambda *f: sp.Mul(*f))
    ...     neg, sub = staticmethod(lambda a: -a), staticmethod(lambda a, b: a - b)
    ...     name = staticmethod(lambda a: a)
    >>> at = place_joint(Plain(), rail)
    >>> at.lever, at.motion
    ([d, s, 0], ([0, 0, 0], [0, 1, 0]))
    """
    f = sp.Matrix(joint.rotation)
    fixed = [[ring.const(f[i, m]) for m in range(3)] for i in range(3)]
    axis = [ring.const(x) for x in joint.axis]
    lever = [ring.const(x) for x in joint.origin_offset]
    moving = joint.coordinate is not None
    if joint.kind is JointKind.REVOLUTE and moving:
        c, s = ring.turn(joint)
        a = axis
        skew = [[ring.zero, ring.neg(a[2]), a[1]], [a[2], ring.zero, ring.neg(a[0])], [ring.neg(a[1]), a[0], ring.zero]]
        turned = [
            [
                ring.add(
                    ring.mul(a[i], a[j]),
                    ring.mul(c, ring.sub(ring.one if i == j else ring.zero, ring.mul(a[i], a[j]))),
                    ring.mul(s, skew[i][j]),
                )
                for j in range(3)
            ]
            for i in range(3)
        ]
        rotation = [
            [ring.name(ring.add(*(ring.mul(fixed[i][m], turned[m][j]) for m in range(3)))) for j in range(3)]
            for i in range(3)
        ]
    else:
        rotation = [[ring.name(fixed[i][j]) for j in range(3)] for i in range(3)]
        if joint.kind is JointKind.PRISMATIC and moving:
            assert joint.coordinate is not None
            slide = ring.name(ring.add(ring.const(joint.coordinate.q), ring.const(joint.offset)))
            # F a in sympy, where products of constants such as sqrt(2)/2 * sqrt(2) come out exact
            direction = [ring.const(d) for d in f * sp.Matrix(joint.axis)]
            lever = [ring.name(ring.add(lv, ring.mul(d, slide))) for lv, d in zip(lever, direction, strict=True)]
    zero3 = [ring.zero, ring.zero, ring.zero]
    motion = None
    if moving and joint.kind is JointKind.REVOLUTE:
        motion = (axis, zero3)
    elif moving and joint.kind is JointKind.PRISMATIC:
        motion = (zero3, axis)
    transpose = [[rotation[j][i] for j in range(3)] for i in range(3)]
    return Placement(rotation, transpose, lever, axis, motion)
