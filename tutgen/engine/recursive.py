"""H(q), C(q, q_dot) q_dot and G(q) of serial arms as a straight-line program (recursive Newton-Euler).

:func:`tutgen.engine.serial.serial_dynamics` writes every entry out in expanded, canonical form:
compact for planar chains, but the Coriolis vector of a fully symbolic 6-DOF arm then has about
140k operations and takes seconds to build. A simulation or a code generator does not need the
expanded form; it needs the same numbers from a short program. So here the dynamics are computed
the way they are evaluated numerically, with sympy symbols in place of floats:

- every intermediate quantity that is more than a symbol, a number or a negated/scaled symbol
  becomes a new symbol ``x0, x1, ...`` whose definition is recorded, in evaluation order; sin and
  cos of the joint angles come first. Products by 0 and 1 are skipped, so the exact zeros and ones
  of fixed rotations such as Rx(90 deg) cost nothing, and equal subexpressions get one symbol;
- C(q, q_dot) q_dot and G are recursive Newton-Euler passes in link axes (Luh-Walker-Paul, with the
  link inertia about its frame origin as in Featherstone's spatial form): one with q_ddot = 0 and
  no gravity, one with q_dot = q_ddot = 0 and gravity as an upward acceleration of the base;
- H comes from the composite-rigid-body algorithm (O(n^2) scalar work), plus the reflected rotor
  inertia n^2 J_m on H_ii, as in serial_dynamics. (n passes with a unit q_ddot each, q_dot = 0, give
  the same H at twice the time and twice the operations on the 6-DOF arm.)

Definitions that no output uses are dropped at the end; the others keep their names, so the listing
may skip some x_k. Nothing is expanded or simplified, so the cost is linear in the number of program
lines. What it costs (2 shared cores, sympy 1.14): the fully symbolic PUMA-like 6R arm of issue 8 in
0.04-0.07 s for H, C q_dot and G together (first call in a fresh process 0.07 s), with 1326 operations
in all (H 524 with its definitions, C q_dot 752, G 190), against 5 s and 45k operations for H alone
for KanesMethod in the same run, and 2.7 s (H 37k, C q_dot 141k) for serial_dynamics; a planar
10-link chain 35 ms.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from itertools import count

import sympy as sp

from tutgen.engine.inertia import centroidal_inertia, part_mass
from tutgen.engine.placement import place_joint
from tutgen.engine.serial import is_serial_chain
from tutgen.errors import DerivationError
from tutgen.model.system import GROUND, Body, Joint, JointKind, System

__all__ = ["NestedDynamics", "count_ops", "expand", "nested_dynamics", "numeric_function"]

Vec = list[sp.Expr]
Rows = list[list[float]]
Mat = list[list[sp.Expr]]
ZERO = sp.S.Zero
ONE = sp.S.One


# ---------------------------------------------------------------------------------------------
# The result
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class NestedDynamics:
    """H q_ddot + C(q, q_dot) q_dot + G(q) as a straight-line program.

    ``definitions`` are ``(x_k, expression)`` pairs in evaluation order: each expression uses only
    coordinates, rates, parameters and earlier x's. The three matrices are written in those symbols;
    :func:`expand` substitutes them back (small arms only: the expanded form is what this avoids).
    """

    coordinates: tuple[sp.Symbol, ...]
    rates: tuple[sp.Symbol, ...]
    definitions: tuple[tuple[sp.Symbol, sp.Expr], ...]
    mass_matrix: sp.ImmutableMatrix
    coriolis_vector: sp.ImmutableMatrix
    gravity_vector: sp.ImmutableMatrix
    timings: tuple[tuple[str, float], ...] = field(compare=False)

    def needed(self, *matrices: sp.MatrixBase) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
        """The definitions the given matrices use, directly or through other definitions, in order."""
        return needed_definitions(self.definitions, matrices)

    def substituted(self) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
        """H, C q_dot and G in coordinates, rates and parameters (back-substitution, no expansion)."""
        return expand(self)


def needed_definitions(
    definitions: Sequence[tuple[sp.Symbol, sp.Expr]], matrices: Sequence[sp.MatrixBase]
) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
    index = {s: i for i, (s, _) in enumerate(definitions)}
    todo = [s for m in matrices for e in m for s in e.free_symbols if s in index]
    used: set[sp.Symbol] = set()
    while todo:
        s = todo.pop()
        if s in used:
            continue
        used.add(s)
        todo += [t for t in definitions[index[s]][1].free_symbols if t in index and t not in used]
    return tuple(d for d in definitions if d[0] in used)


def expand(dyn: NestedDynamics) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
    """H, C q_dot and G in coordinates, rates and parameters: each definition, in order, is substituted
    into the later ones and the outputs (``xreplace``, no expansion).

    The result is correct but unsimplified and grows quickly with the arm; it is for checks on small
    arms. Numbers at a state come cheaper from :func:`numeric_function`.
    """
    values: dict[sp.Symbol, sp.Expr] = {}
    for s, e in dyn.definitions:
        values[s] = e.xreplace(values)
    return (
        dyn.mass_matrix.xreplace(values),
        dyn.coriolis_vector.xreplace(values),
        dyn.gravity_vector.xreplace(values),
    )


def count_ops(dyn: NestedDynamics, *matrices: sp.MatrixBase) -> int:
    """Operations (``sympy.count_ops``) of the given matrices (default: H, C q_dot and G) plus those
    of every definition they need: the size of the program that evaluates them."""
    if not matrices:
        matrices = (dyn.mass_matrix, dyn.coriolis_vector, dyn.gravity_vector)
    defs = dyn.needed(*matrices)
    return int(sum(sp.count_ops(e) for _, e in defs) + sum(sp.count_ops(e) for m in matrices for e in m))


def numeric_function(dyn: NestedDynamics, arguments: Sequence[sp.Symbol]) -> Callable[..., tuple[Rows, Rows, Rows]]:
    """A Python function of ``arguments`` (floats, in that order) returning (H, C q_dot, G) as nested
    lists of floats: the straight-line program printed as Python code, one line per definition.

    Every free symbol of the program that is not a definition must be among ``arguments``.
    """
    from sympy.printing.pycode import PythonCodePrinter

    printer = PythonCodePrinter({"fully_qualified_modules": True, "standard": "python3"})
    names = {s: f"a{i}" for i, s in enumerate(arguments)}
    names |= {s: f"d{i}" for i, (s, _) in enumerate(dyn.definitions)}
    rename = {s: sp.Symbol(v) for s, v in names.items()}
    lines = [f"def _program({', '.join(f'a{i}' for i in range(len(arguments)))}):"]
    for s, e in dyn.definitions:
        lines.append(f"    {names[s]} = {printer.doprint(e.xreplace(rename))}")

    def matrix(m: sp.MatrixBase) -> str:
        rows = [
            f"[{', '.join(printer.doprint(m[i, j].xreplace(rename)) for j in range(m.cols))}]" for i in range(m.rows)
        ]
        return f"[{', '.join(rows)}]"

    lines.append(f"    return {matrix(dyn.mass_matrix)}, {matrix(dyn.coriolis_vector)}, {matrix(dyn.gravity_vector)}")
    namespace: dict[str, object] = {}
    exec(compile("\n".join(lines), "<tutgen.engine.recursive program>", "exec"), {"math": math}, namespace)
    return namespace["_program"]  # type: ignore[return-value]


# ---------------------------------------------------------------------------------------------
# The program under construction
# ---------------------------------------------------------------------------------------------


def _is_tiny(e: sp.Expr) -> bool:
    """A symbol, a number, or a number times a symbol (-x3, 2*x5): not worth a name of its own."""
    if e.is_Atom:
        return True
    return bool(e.is_Mul and len(e.args) == 2 and e.args[0].is_Number and e.args[1].is_Atom)


def _is_zero(e: sp.Expr) -> bool:
    return e is ZERO or (e.is_Number and e == 0)


def _is_one(e: sp.Expr) -> bool:
    return e is ONE or (e.is_Number and e == 1)


def _prod(*factors: sp.Expr) -> sp.Expr:
    """sp.Mul of a few factors, 0 if any is 0, without the ones."""
    kept = []
    for f in factors:
        if _is_zero(f):
            return ZERO
        if not _is_one(f):
            kept.append(f)
    if not kept:
        return ONE
    return kept[0] if len(kept) == 1 else sp.Mul(*kept)


def _sum(*terms: sp.Expr) -> sp.Expr:
    kept = [t for t in terms if not _is_zero(t)]
    if not kept:
        return ZERO
    return kept[0] if len(kept) == 1 else sp.Add(*kept)


class _Program:
    """Definitions in evaluation order; equal expressions share one symbol."""

    def __init__(self, taken: set[str]) -> None:
        self.definitions: list[tuple[sp.Symbol, sp.Expr]] = []
        self._known: dict[sp.Expr, sp.Symbol] = {}
        self._names: Iterator[sp.Symbol] = (sp.Symbol(f"x{i}") for i in count() if f"x{i}" not in taken)

    def name(self, e: sp.Expr, force: bool = False) -> sp.Expr:
        if not force and _is_tiny(e):
            return e
        s = self._known.get(e)
        if s is None:
            s = next(self._names)
            self._known[e] = s
            self.definitions.append((s, e))
        return s

    # vectors are lists of three named scalars
    def dot(self, a: Vec, b: Vec) -> sp.Expr:
        return self.name(_sum(*(_prod(x, y) for x, y in zip(a, b, strict=True))))

    def cross(self, a: Vec, b: Vec) -> Vec:
        return [
            self.name(_sum(_prod(a[1], b[2]), -_prod(a[2], b[1]))),
            self.name(_sum(_prod(a[2], b[0]), -_prod(a[0], b[2]))),
            self.name(_sum(_prod(a[0], b[1]), -_prod(a[1], b[0]))),
        ]

    def add(self, *vs: Vec) -> Vec:
        return [self.name(_sum(*(v[i] for v in vs))) for i in range(3)]

    def scale(self, s: sp.Expr, v: Vec) -> Vec:
        return [self.name(_prod(s, x)) for x in v]

    def apply(self, m: Mat, v: Vec) -> Vec:
        return [self.name(_sum(*(_prod(m[i][k], v[k]) for k in range(3)))) for i in range(3)]


def _is_zero_vec(v: Vec) -> bool:
    return all(_is_zero(x) for x in v)


# ---------------------------------------------------------------------------------------------
# The chain: links parents first, their rotations, levers and inertias at the frame origin
# ---------------------------------------------------------------------------------------------


@dataclass
class _Link:
    name: str
    joint: Joint
    parent: int  # index into the link list, -1 for the ground
    k: int | None  # coordinate index of a moving joint
    axis: Vec  # joint axis in the link's own axes
    rt: Mat  # ^cR_p: parent components -> link components
    r: Mat  # ^pR_c
    lever: Vec  # the link origin from the parent's, parent axes
    mass: sp.Expr
    first_moment: Vec  # m c about the link origin, link axes
    inertia: Mat  # about the link origin, link axes (symmetric: the same objects mirrored)


def _origin_inertia(prog: _Program, body: Body) -> tuple[sp.Expr, Vec, Mat]:
    """The body's mass m, first moment h = m c and inertia about its frame origin (body axes), summed
    part by part: the centre of mass, a quotient for a body of several parts, never appears. The
    parallel-axis shift J_O = J_G + m (|c|^2 E - c c^T) is written into the program, not expanded."""
    mass: list[sp.Expr] = []
    moment: list[Vec] = []
    inertia: list[Mat] = []
    for part in body.parts:
        m, _ = part_mass(part)
        j_c = centroidal_inertia(part, m)
        c = [sp.sympify(x) for x in part.at]
        h = [prog.name(_prod(m, x)) for x in c]
        sq = _sum(*(_prod(hx, x) for hx, x in zip(h, c, strict=True)))  # m |c|^2
        mass.append(m)
        moment.append(h)
        inertia.append(
            [[_sum(j_c[a, b], sq if a == b else ZERO, -_prod(h[a], c[b])) for b in range(3)] for a in range(3)]
        )
    total = prog.name(_sum(*mass))
    first = [prog.name(_sum(*(h[i] for h in moment))) for i in range(3)]
    upper = {(a, b): prog.name(_sum(*(j[a][b] for j in inertia))) for a in range(3) for b in range(a, 3)}
    return total, first, [[upper[(min(a, b), max(a, b))] for b in range(3)] for a in range(3)]


class _Named:
    """:class:`~tutgen.engine.placement.Scalars` over sympy expressions, each intermediate a program line."""

    zero = ZERO
    one = ONE

    def __init__(self, prog: _Program, trig: dict[int, tuple[sp.Expr, sp.Expr]], index: dict[sp.Symbol, int]) -> None:
        self.prog = prog
        self.trig = trig
        self.index = index

    def const(self, value: sp.Expr) -> sp.Expr:
        return sp.sympify(value)

    def add(self, *terms: sp.Expr) -> sp.Expr:
        return _sum(*terms)

    def mul(self, *factors: sp.Expr) -> sp.Expr:
        return _prod(*factors)

    def neg(self, a: sp.Expr) -> sp.Expr:
        return -a

    def sub(self, a: sp.Expr, b: sp.Expr) -> sp.Expr:
        return a - b

    def name(self, a: sp.Expr) -> sp.Expr:
        return self.prog.name(a)

    def turn(self, joint: Joint) -> tuple[sp.Expr, sp.Expr]:
        assert joint.coordinate is not None
        return self.trig[self.index[joint.coordinate.q]]


def _chain(system: System, prog: _Program, index: dict[sp.Symbol, int]) -> list[_Link]:
    """The links parents first, each placed by :func:`~tutgen.engine.placement.place_joint` (its
    conventions: ^pR_c = F Rot(a, q + offset), the lever in parent axes)."""
    by_child = {j.child: j for j in system.joints}
    # sin and cos of the joint angles are the first definitions (coordinate order)
    trig: dict[int, tuple[sp.Expr, sp.Expr]] = {}
    for k, c in enumerate(system.coordinates):
        joint = next(j for j in system.joints if j.coordinate is not None and j.coordinate.q == c.q)
        if joint.kind is JointKind.REVOLUTE:
            angle = c.q + joint.offset
            trig[k] = (prog.name(sp.cos(angle), force=True), prog.name(sp.sin(angle), force=True))
    links: list[_Link] = []
    where: dict[str, int] = {GROUND: -1}

    scalars = _Named(prog, trig, index)

    def place(name: str) -> int:
        if name in where:
            return where[name]
        joint = by_child[name]
        parent = place(joint.parent)
        k = index[joint.coordinate.q] if joint.coordinate is not None else None
        at = place_joint(scalars, joint)
        axis, r, rt, lever = at.axis, at.rotation, at.transpose, at.lever
        mass, first_moment, inertia = _origin_inertia(prog, system.body(name))
        links.append(_Link(name, joint, parent, k, axis, rt, r, lever, mass, first_moment, inertia))
        where[name] = len(links) - 1
        return where[name]

    for body in system.bodies:
        place(body.name)
    return links


# ---------------------------------------------------------------------------------------------
# Recursive Newton-Euler and the composite-rigid-body algorithm
# ---------------------------------------------------------------------------------------------


def _joint_motion(prog: _Program, link: _Link, w: Vec, rate: sp.Expr, accel: sp.Expr) -> tuple[Vec, Vec, Vec]:
    """What the joint's own motion adds to the link's angular velocity, angular acceleration and origin
    acceleration (link axes), given w = the parent's angular velocity in link axes.

    Revolute: omega += z q_dot and omega_dot += w x z q_dot + z q_ddot (the joint axis turns with the
    parent). Prismatic: a += 2 w x z q_dot (Coriolis: sliding in a turning frame) + z q_ddot.
    """
    zero3 = [ZERO, ZERO, ZERO]
    zq = [prog.name(_prod(rate, x)) for x in link.axis]
    zqdd = [prog.name(_prod(accel, x)) for x in link.axis]
    if link.joint.kind is JointKind.REVOLUTE:
        return zq, prog.add(prog.cross(w, zq), zqdd), zero3
    return zero3, zero3, prog.add(prog.scale(sp.Integer(2), prog.cross(w, zq)), zqdd)


def _rnea(
    prog: _Program, links: list[_Link], n: int, qd: Sequence[sp.Expr], qdd: Sequence[sp.Expr], gravity: Vec
) -> list[sp.Expr]:
    """tau of one inverse-dynamics pass, everything in link axes (the rotor term excluded).

    Forward, parents first: omega, omega_dot and the acceleration a of the link's frame origin
    (the base accelerates upward at -g, which adds gravity to every link). Backward, children first:
    the force f and moment n (about the link origin) that the joint transmits to the link,
        f = m a + omega_dot x h + omega x (omega x h) + sum over children R f_c,
        n = I omega_dot + omega x (I omega) + h x a + sum over children (R n_c + p_c x R f_c),
    with h = m c and I about the link origin; tau = z . n (revolute) or z . f (prismatic), z the joint axis.
    """
    zero3 = [ZERO, ZERO, ZERO]
    w: list[Vec] = []
    dw: list[Vec] = []
    acc: list[Vec] = []
    base_acc = [-x for x in gravity]
    for link in links:
        pw = w[link.parent] if link.parent >= 0 else zero3
        pdw = dw[link.parent] if link.parent >= 0 else zero3
        pa = acc[link.parent] if link.parent >= 0 else base_acc
        # acceleration of this link's origin, parent axes: a_p + dw_p x p + w_p x (w_p x p)
        a = pa
        if not _is_zero_vec(pdw):
            a = prog.add(a, prog.cross(pdw, link.lever))
        if not _is_zero_vec(pw):
            a = prog.add(a, prog.cross(pw, prog.cross(pw, link.lever)))
        a = prog.apply(link.rt, a)
        wi = prog.apply(link.rt, pw)
        dwi = prog.apply(link.rt, pdw)
        if link.k is not None:
            dw_joint, ddw_joint, a_joint = _joint_motion(prog, link, wi, qd[link.k], qdd[link.k])
            dwi = prog.add(dwi, ddw_joint)
            a = prog.add(a, a_joint)
            wi = prog.add(wi, dw_joint)
        w.append(wi)
        dw.append(dwi)
        acc.append(a)

    f: list[Vec] = []
    mom: list[Vec] = []
    for i, link in enumerate(links):
        h, inertia = link.first_moment, link.inertia
        fi = prog.scale(link.mass, acc[i])
        ni = prog.cross(h, acc[i])
        if not _is_zero_vec(dw[i]):
            fi = prog.add(fi, prog.cross(dw[i], h))
            ni = prog.add(ni, prog.apply(inertia, dw[i]))
        if not _is_zero_vec(w[i]):
            fi = prog.add(fi, prog.cross(w[i], prog.cross(w[i], h)))
            ni = prog.add(ni, prog.cross(w[i], prog.apply(inertia, w[i])))
        f.append(fi)
        mom.append(ni)
    tau = [ZERO] * n
    for i in range(len(links) - 1, -1, -1):
        link = links[i]
        if link.k is not None:
            load = mom[i] if link.joint.kind is JointKind.REVOLUTE else f[i]
            tau[link.k] = prog.dot(link.axis, load)
        if link.parent >= 0:
            fp = prog.apply(link.r, f[i])
            np_ = prog.add(prog.apply(link.r, mom[i]), prog.cross(link.lever, fp))
            f[link.parent] = prog.add(f[link.parent], fp)
            mom[link.parent] = prog.add(mom[link.parent], np_)
    return tau


def _crba(prog: _Program, links: list[_Link], n: int) -> list[list[sp.Expr]]:
    """H by the composite-rigid-body algorithm.

    Each link's composite inertia (m, h, I about its origin, its axes) is the link's own plus its
    children's, moved to the parent frame: h' = R h + m p, I' = R I R^T + (m |p|^2 + 2 p.h') E - ...
    (the parallel-axis shift written with h so the centre of mass, a quotient, never appears).
    H_kk = s_k . F with F = I_c s_k the spatial force of a unit joint rate; F is then carried to each
    ancestor (f' = R f, n' = R n + p x f') and H_jk = s_j . F there.
    """
    m = [link.mass for link in links]
    h = [list(link.first_moment) for link in links]
    inertia = [[list(row) for row in link.inertia] for link in links]
    for i in range(len(links) - 1, -1, -1):
        link = links[i]
        p = link.parent
        if p < 0 or (_is_zero(m[i]) and _is_zero_vec(h[i]) and all(_is_zero_vec(r) for r in inertia[i])):
            continue
        r, lv = link.r, link.lever
        hr = prog.apply(r, h[i])
        ri = [prog.apply(r, [inertia[i][a][b] for a in range(3)]) for b in range(3)]  # columns of R I
        # R I R^T, upper triangle: (R I R^T)_ab = sum_c (R I)_ac R_bc
        shift_diag = _sum(
            _prod(m[i], _sum(*(_prod(x, x) for x in lv))),
            _prod(sp.Integer(2), _sum(*(_prod(x, y) for x, y in zip(lv, hr, strict=True)))),
        )
        new = [[ZERO] * 3 for _ in range(3)]
        for a in range(3):
            for b in range(a, 3):
                rir = _sum(*(_prod(ri[c][a], r[b][c]) for c in range(3)))
                shift = _sum(
                    shift_diag if a == b else ZERO,
                    -_prod(m[i], lv[a], lv[b]),
                    -_prod(hr[a], lv[b]),
                    -_prod(lv[a], hr[b]),
                )
                new[a][b] = prog.name(_sum(inertia[p][a][b], rir, shift))
                new[b][a] = new[a][b]
        inertia[p] = new
        h[p] = prog.add(h[p], hr, prog.scale(m[i], lv))
        m[p] = prog.name(_sum(m[p], m[i]))

    hm = [[ZERO] * n for _ in range(n)]
    for i, link in enumerate(links):
        if link.k is None:
            continue
        z = link.axis
        if link.joint.kind is JointKind.REVOLUTE:  # s = (z, 0): f = z x h, n = I z
            fv = prog.cross(z, h[i])
            nv = prog.apply(inertia[i], z)
        else:  # s = (0, z): f = m z, n = h x z
            fv = prog.scale(m[i], z)
            nv = prog.cross(h[i], z)
        k = link.k
        diag = prog.dot(z, nv if link.joint.kind is JointKind.REVOLUTE else fv)
        if link.joint.reflected_inertia is not None:  # the rotor behind a gearbox: n^2 J_m
            diag = prog.name(_sum(diag, sp.sympify(link.joint.reflected_inertia)))
        hm[k][k] = diag
        j = i
        while links[j].parent >= 0:
            cur = links[j]
            fv = prog.apply(cur.r, fv)
            nv = prog.add(prog.apply(cur.r, nv), prog.cross(cur.lever, fv))
            j = cur.parent
            anc = links[j]
            if anc.k is not None:
                entry = prog.dot(anc.axis, nv if anc.joint.kind is JointKind.REVOLUTE else fv)
                hm[anc.k][k] = hm[k][anc.k] = entry
    return hm


# ---------------------------------------------------------------------------------------------
# Entry point
# ---------------------------------------------------------------------------------------------


def nested_dynamics(system: System) -> NestedDynamics:
    """H, C(q, q_dot) q_dot and G of a serial chain (see :func:`~tutgen.engine.serial.is_serial_chain`)
    as a straight-line program: the same dynamics as :func:`~tutgen.engine.serial.serial_dynamics`,
    in nested rather than expanded form.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> arm = load_system_text('''
    ... tutgen: 1
    ... title: two links
    ... parameters: [m1, m2, l1, l2, g]
    ... coordinates: [t1, t2]
    ... gravity: [0, -g, 0]
    ... bodies: {a: {mass: m1, com: [l1, 0, 0]}, b: {mass: m2, com: [l2, 0, 0]}}
    ... joints:
    ...   j1: {type: revolute, parent: ground, child: a, coordinate: t1}
    ...   j2: {type: revolute, parent: a, child: b, origin: [l1, 0, 0], coordinate: t2}
    ... ''')
    >>> dyn = nested_dynamics(arm)
    >>> dyn.definitions[:4]
    ((x0, cos(t1)), (x1, sin(t1)), (x2, cos(t2)), (x3, sin(t2)))
    >>> sp.expand(expand(dyn)[0][0, 1])
    l1*l2*m2*cos(t2) + l2**2*m2
    """
    if not is_serial_chain(system):
        raise DerivationError(
            "nested_dynamics needs a serial chain (revolute, prismatic and fixed joints from the ground)",
            system.origin,
        )
    start = time.perf_counter()
    coords = tuple(c.q for c in system.coordinates)
    rates = tuple(c.qd for c in system.coordinates)
    n = len(coords)
    index = {q: i for i, q in enumerate(coords)}
    taken = {str(s) for p in system.parameters for s in (p.symbol,)}
    taken |= {str(s) for c in system.coordinates for s in (c.q, c.qd, c.qdd)}
    prog = _Program(taken)
    links = _chain(system, prog, index)
    t_chain = time.perf_counter()
    hm = _crba(prog, links, n)
    t_h = time.perf_counter()
    zeros = [ZERO] * n
    cq = _rnea(prog, links, n, rates, zeros, [ZERO, ZERO, ZERO])
    t_c = time.perf_counter()
    gravity = [sp.sympify(x) for x in system.gravity] if system.gravity is not None else [ZERO, ZERO, ZERO]
    gv = _rnea(prog, links, n, zeros, zeros, gravity) if not _is_zero_vec(gravity) else zeros
    t_g = time.perf_counter()
    mass_matrix = sp.ImmutableMatrix(n, n, [hm[i][j] for i in range(n) for j in range(n)])
    coriolis_vector = sp.ImmutableMatrix(n, 1, cq)
    gravity_vector = sp.ImmutableMatrix(n, 1, gv)
    # drop what no output uses (the composite inertia above the last revolute joint, constants of
    # massless links): the names keep their numbers, so the listing may skip some x_k
    definitions = needed_definitions(prog.definitions, (mass_matrix, coriolis_vector, gravity_vector))
    t_prune = time.perf_counter()
    result = NestedDynamics(
        coordinates=coords,
        rates=rates,
        definitions=definitions,
        mass_matrix=mass_matrix,
        coriolis_vector=coriolis_vector,
        gravity_vector=gravity_vector,
        timings=(
            ("chain", t_chain - start),
            ("mass_matrix", t_h - t_chain),
            ("coriolis", t_c - t_h),
            ("gravity", t_g - t_c),
            ("prune", t_prune - t_g),
            ("total", time.perf_counter() - start),
        ),
    )
    return result
