"""The potential energy source by source, each with its datum: where it is zero.

A worked solution states its datum ("the datum for U is at the pivot"), because U is defined only up to a
constant and the reader must know which one was chosen. tutgen's choices are fixed by its formulas:

- gravity: U_b = -m_b g . r_G, zero on the plane through the world origin normal to g (``y = 0`` when g is
  along y); a revolute joint whose axis stays on that plane is named, since a teacher says "at the pivot";
- a spring: U = k (L - L0)^2 / 2, zero at its free length (``x = 0`` for a spring given by an extension);
- a given U (``energy:``): as the problem gives it.

The sentences are plain text in the engine's ASCII notation (tutgen.render.wording typesets them).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from tutgen.engine.derivation import BodyEnergy
from tutgen.engine.kinematics import Kinematics
from tutgen.model.system import JointKind, System

__all__ = ["PotentialSource", "gravity_datum", "potential_sources"]

AXES = "xyz"


@dataclass(frozen=True)
class PotentialSource:
    """One term of U: a body's gravity, a spring, or the U the problem gives, and its datum: the equation
    ``zero_at`` (lhs, rhs) of where it is zero, if one says it, and ``note``, the words that go with it."""

    kind: str  # "gravity", "spring" or "given"
    name: str  # the body's or the spring's name ("" for a given U)
    energy: sp.Expr
    zero_at: tuple[sp.Expr, sp.Expr] | None
    note: str  # "the level of joint 'pivot'", "at its free length", "as the problem gives it"

    @property
    def datum(self) -> str:
        """The datum as one sentence fragment in ASCII: "zero at y = 0, the level of joint 'pivot'"."""
        if self.zero_at is None:
            return self.note
        at = f"zero at {sp.sstr(self.zero_at[0])} = {sp.sstr(self.zero_at[1])}"
        return f"{at}, {self.note}" if self.note else at


def gravity_datum(system: System, kin: Kinematics | None) -> tuple[tuple[sp.Expr, sp.Expr] | None, str]:
    """Where U_b = -m g . r_G is zero: the plane through the origin normal to g, as its equation when g is
    along an axis, with the revolute joints that stay on it (for every q)."""
    g = system.gravity
    nonzero = [k for k in range(3) if g is not None and g[k] != 0]
    if len(nonzero) != 1:
        return None, "zero on the plane through the origin normal to g"
    k = nonzero[0]
    pivots = []
    if kin is not None:
        for joint in system.joints:
            if joint.kind is not JointKind.REVOLUTE:
                continue
            frame = kin.frames.get(joint.child)
            if frame is not None and sp.expand(frame.position[k]) == 0:
                pivots.append(f"'{joint.name}'")
    note = ""
    if len(pivots) == 1:
        note = f"the level of joint {pivots[0]}"
    elif pivots:
        note = f"the level of joints {', '.join(pivots[:-1])} and {pivots[-1]}"
    return (sp.Symbol(AXES[k]), sp.Integer(0)), note


def _spring_datum(system: System, name: str) -> tuple[tuple[sp.Expr, sp.Expr] | None, str]:
    spring = next(s for s in system.springs if s.name == name)
    if spring.extension is not None:
        return (spring.extension, sp.Integer(0)), "its free length"
    if spring.free_length == 0:
        return None, "zero when its ends meet (free length 0)"
    return None, f"zero at its free length {sp.sstr(spring.free_length)}"


def potential_sources(
    system: System,
    bodies: tuple[BodyEnergy, ...],
    springs: tuple[tuple[str, sp.Expr], ...],
    kin: Kinematics | None,
) -> tuple[PotentialSource, ...]:
    """U term by term, in spec order: each body's gravity (bodies without it left out), each spring, or
    the U the problem gives. Their sum is the derivation's U."""
    out: list[PotentialSource] = []
    if system.potential_energy is not None:
        out.append(PotentialSource("given", "", sp.expand(system.potential_energy), None, "as the problem gives it"))
    if system.gravity is not None and any(g != 0 for g in system.gravity):
        at, note = gravity_datum(system, kin)
        out += [PotentialSource("gravity", b.name, b.gravitational, at, note) for b in bodies if b.gravitational != 0]
    for name, energy in springs:
        at, note = _spring_datum(system, name)
        out.append(PotentialSource("spring", name, energy, at, note))
    return tuple(out)
