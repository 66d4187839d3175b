"""tau = H q_ddot + C q_dot + G of a serial chain by a numeric recursive Newton-Euler pass, in floats and
world axes: the independent computation the serial route's results are checked against
(:func:`tutgen.engine.serial.numeric_checks`), and the tests' reference. It shares nothing with the
symbolic routes but the model."""

from __future__ import annotations

import math
from collections.abc import Sequence

import sympy as sp

from tutgen.engine.inertia import body_inertia
from tutgen.model.system import GROUND, JointKind, System

__all__ = ["numeric_inverse_dynamics"]


def numeric_inverse_dynamics(
    system: System, values: dict[sp.Symbol, float], q: Sequence[float], qd: Sequence[float], qdd: Sequence[float]
) -> list[float]:
    """tau = H q_ddot + C q_dot + G by a numeric recursive Newton-Euler pass (floats, world axes),
    independent of the symbolic route: the agreement check of the fast path.

    Forward: each link's rotation, angular velocity and acceleration, and its origin's acceleration,
    from its parent's. Backward: the force and moment each joint transmits; tau_i is the moment (or
    the force, prismatic) along the joint axis. Gravity enters as an upward acceleration of the base.
    """
    n = len(system.coordinates)
    index = {c.q: i for i, c in enumerate(system.coordinates)}
    by_child = {j.child: j for j in system.joints}

    floats = {s: sp.Float(v) for s, v in values.items()}

    def num(e: sp.Expr) -> float:
        return float(sp.sympify(e).xreplace(floats))  # xreplace: subs with a large dict is slow

    def mat(m: sp.MatrixBase) -> list[list[float]]:
        return [[num(m[i, k]) for k in range(3)] for i in range(3)]

    def mv(a: list[list[float]], v: list[float]) -> list[float]:
        return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]

    def mm(a: list[list[float]], b: list[list[float]]) -> list[list[float]]:
        return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]

    def cross(a: list[float], b: list[float]) -> list[float]:
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def add(*vs: list[float]) -> list[float]:
        return [sum(v[i] for v in vs) for i in range(3)]

    def scale(s: float, v: list[float]) -> list[float]:
        return [s * x for x in v]

    def rot(axis: list[float], angle: float) -> list[list[float]]:
        c, s = math.cos(angle), math.sin(angle)
        x, y, z = axis
        return [
            [c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
            [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
            [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)],
        ]

    g = [num(x) for x in system.gravity] if system.gravity is not None else [0.0, 0.0, 0.0]
    eye = [[1.0 if i == k else 0.0 for k in range(3)] for i in range(3)]
    frame: dict[str, tuple] = {GROUND: (eye, [0.0] * 3, [0.0] * 3, [0.0] * 3, [-x for x in g], [0.0] * 3)}
    # (R world-from-link, origin, omega, alpha, origin acceleration (with -g), origin velocity)

    def place(name: str) -> None:
        if name in frame:
            return
        j = by_child[name]
        place(j.parent)
        r_p, o_p, w_p, al_p, a_p, v_p = frame[j.parent]
        fixed = mm(r_p, mat(j.rotation))
        axis_w = mv(fixed, [num(x) for x in j.axis])
        k = index[j.coordinate.q] if j.coordinate is not None else None
        value = (q[k] if k is not None else 0.0) + num(j.offset)
        rate = qd[k] if k is not None else 0.0
        acc = qdd[k] if k is not None else 0.0
        lever = mv(r_p, [num(x) for x in j.origin_offset])
        o = add(o_p, lever)
        v = add(v_p, cross(w_p, lever))
        a = add(a_p, cross(al_p, lever), cross(w_p, cross(w_p, lever)))
        w, al, r = w_p, al_p, fixed
        if j.kind is JointKind.REVOLUTE:
            r = mm(fixed, rot([num(x) for x in j.axis], value))
            w = add(w_p, scale(rate, axis_w))
            al = add(al_p, scale(acc, axis_w), cross(w_p, scale(rate, axis_w)))
        elif j.kind is JointKind.PRISMATIC:
            s = scale(value, axis_w)
            o = add(o, s)
            v = add(v, cross(w_p, s), scale(rate, axis_w))
            a = add(
                a, cross(al_p, s), cross(w_p, cross(w_p, s)), scale(2 * rate, cross(w_p, axis_w)), scale(acc, axis_w)
            )
        frame[name] = (r, o, w, al, a, v)

    wrench: dict[str, tuple[list[float], list[float]]] = {}  # force and moment about the origin, world
    for body in system.bodies:
        place(body.name)
        r, o, w, al, a, _ = frame[body.name]
        bi = body_inertia(body)
        m = num(bi.mass)
        c = mv(r, [num(x) for x in bi.com]) if m else [0.0] * 3
        a_c = add(a, cross(al, c), cross(w, cross(w, c)))
        i_w = mm(mm(r, mat(bi.inertia_com)), [list(row) for row in zip(*r, strict=True)])
        f = scale(m, a_c)
        moment = add(mv(i_w, al), cross(w, mv(i_w, w)), cross(c, f))
        wrench[body.name] = (f, moment)
    # backward: children first (reverse of a parents-first order)
    order: list[str] = []
    for body in system.bodies:
        chain = []
        name = body.name
        while name != GROUND and name not in order and name not in chain:
            chain.append(name)
            name = by_child[name].parent
        order += reversed(chain)
    tau = [0.0] * n
    for name in reversed(order):
        j = by_child[name]
        f, moment = wrench[name]
        _, o, *_ = frame[name]
        axis_w = mv(mm(frame[j.parent][0], mat(j.rotation)), [num(x) for x in j.axis])
        if j.coordinate is not None:
            k = index[j.coordinate.q]
            tau[k] = sum(axis_w[i] * (moment if j.kind is JointKind.REVOLUTE else f)[i] for i in range(3))
            if j.reflected_inertia is not None:  # the rotor behind a gearbox: n^2 J_m q_ddot
                tau[k] += num(j.reflected_inertia) * qdd[k]
        if j.parent != GROUND:
            pf, pm = wrench[j.parent]
            _, po, *_ = frame[j.parent]
            wrench[j.parent] = (add(pf, f), add(pm, moment, cross(add(o, scale(-1, po)), f)))
    return tau
