"""The derived model as straight-line programs, one per generated function, free of any language.

A :class:`Program` is what every printer of :mod:`tutgen.codegen` reads: the functions to write (H(q),
C(q, q_dot) q_dot, C(q, q_dot), G(q), Q(q, q_dot), the potential energy, inverse and forward dynamics),
each a list of assignments ``x_k = expression`` in evaluation order and the entries of its result in
those names. Common subexpressions are eliminated with ``sympy.cse``; a serial arm's derivation
carries the same dynamics as a short recursive program already (:mod:`tutgen.engine.recursive`), and
H, C q_dot and G are taken from it instead of from the expanded entries.

Names: every symbol the code uses is a name the spec declared (a coordinate ``theta``, its rate
``theta_dot`` and acceleration ``theta_ddot``, a parameter ``m1``), renamed only where it is a
keyword or a name of the target language (:func:`target_names`); temporaries are ``x0, x1, ...``
(another letter if the spec declares such names). No other spec text (title, statement,
descriptions) reaches the code.

Conventions of the generated functions (the same in every language):

- ``inverse_dynamics(q, qd, qdd, p)`` is tau = H q_ddot + C q_dot + G - Q(q, q_dot): the generalized
  force along each coordinate needed beyond the spec's own forces (springs and gravity are in G;
  dampers, loads and the spec's generalized forces, with their parameters from ``p``, in Q);
- ``forward_dynamics(q, qd, tau, p)`` is its inverse, q_ddot = H^-1 (tau + Q - C q_dot - G);
- matrices are row-major; parameters without a value in the spec have no default.

A constrained spec (`constraints:`, loop-closing joints; tutgen/engine/constraints/) keeps H, C, G, Q of
all n coordinates and adds the m constraints (loop-closure equations first, then the spec's, as the
derivation numbers the multipliers lambda_k): ``constraint_residual(q, qd, p)`` (f_k(q) of a position
constraint, a_k(q) . q_dot of a velocity one), ``constraint_jacobian(q, p)`` (A, m x n) and
``constraint_bias(q, qd, p)`` (b = A_dot q_dot, so that A q_ddot + b = 0); ``forward_dynamics`` then
solves the augmented system [[H, -A^T], [A, 0]] [q_ddot; lambda] = [tau + Q - C q_dot - G; -b] (the
constraint forces A^T lambda on the right of H q_ddot + C q_dot + G = Q + tau + A^T lambda) and returns
q_ddot and lambda, n + m entries.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.engine.recursive import needed_definitions

__all__ = [
    "Function",
    "Parameter",
    "Program",
    "build_program",
    "linear_terms",
    "safe_file_name",
    "target_names",
]


@dataclass(frozen=True)
class Parameter:
    """A parameter of the generated code: its name there, its spec name and value (None: none given)."""

    name: str
    spec_name: str
    value: float | None


@dataclass(frozen=True)
class Function:
    """One generated function.

    ``arguments`` are the vector arguments it takes, in order, from ``q``, ``qd``, ``qdd`` and ``tau``
    (the parameters ``p`` always come last); ``uses`` the names it reads from them and from ``p``.
    ``assignments`` are ``(name, expression)`` in evaluation order; ``result`` is the output matrix
    (``shape`` rows x cols) in those names. ``solve`` marks forward dynamics: the result is then
    ``(H, rhs)`` and the function returns H^-1 rhs.
    """

    name: str
    doc: str
    arguments: tuple[str, ...]
    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    result: sp.ImmutableMatrix
    solve: sp.ImmutableMatrix | None = None  # forward dynamics: the right-hand side, result is H

    @property
    def shape(self) -> tuple[int, int]:
        m = self.solve if self.solve is not None else self.result
        return (m.rows, m.cols)

    def free_symbols(self) -> set[sp.Symbol]:
        defined = {s for s, _ in self.assignments}
        used: set[sp.Symbol] = set()
        for _, e in self.assignments:
            used |= e.free_symbols
        used |= self.result.free_symbols
        if self.solve is not None:
            used |= self.solve.free_symbols
        return used - defined


@dataclass(frozen=True)
class Program:
    """Everything a printer needs: names in the target language and the functions to write.

    ``coordinates``, ``rates`` and ``accelerations`` are the names of q_i, q_dot_i and q_ddot_i
    (vector entry i of ``q``, ``qd``, ``qdd``); ``renamed`` lists the spec names changed because
    they are keywords or reserved names of the language (said in the header).
    """

    module: str
    spec_file: str
    language: str
    coordinates: tuple[str, ...]
    rates: tuple[str, ...]
    accelerations: tuple[str, ...]
    forces: tuple[str, ...]  # the entries of forward dynamics' tau
    parameters: tuple[Parameter, ...]
    functions: tuple[Function, ...]
    renamed: tuple[tuple[str, str], ...]
    route: str  # how H, C q_dot and G were obtained (said in the header)
    # a constrained spec's constraints, (name, "position" | "velocity"), in the multipliers' order
    constraints: tuple[tuple[str, str], ...] = ()

    @property
    def n(self) -> int:
        return len(self.coordinates)


#: The vector arguments and the locals of every generated function: spec names equal to one are renamed.
RESERVED_LOCALS = frozenset(
    {"q", "qd", "qdd", "tau", "p", "out", "H", "rhs", "L", "np", "numpy", "math", "i", "j", "shape", "dyn", "t"}
)


def safe_file_name(name: str) -> str:
    """A spec file's name as it may appear in a comment: letters, digits, ``.``, ``-`` and ``_`` only."""
    return re.sub(r"[^A-Za-z0-9._-]", "_", name)[:100] or "spec"


def module_name(stem: str) -> str:
    """An identifier for the generated module (and the prefix of C names) from the spec file's stem."""
    name = re.sub(r"[^A-Za-z0-9_]", "_", stem)[:60]
    if not name or not name[0].isalpha():
        name = "m_" + name
    return name


def target_names(names: Iterable[str], reserved: frozenset[str]) -> dict[str, str]:
    """Each spec name as an identifier of the language: unchanged, or with ``_`` appended (repeatedly)
    when it is in ``reserved`` or the renamed form is taken by another name."""
    names = list(names)
    taken = set(names)
    out: dict[str, str] = {}
    for name in names:
        new = name
        while new in reserved or (new != name and new in taken):
            new += "_"
        taken.add(new)
        out[name] = new
    return out


def _temporary_prefix(declared: Iterable[str]) -> str:
    """A letter for the temporaries x0, x1, ... that no declared name uses as ``<letter><digits>``."""
    declared = set(declared)
    for letter in "xwvzy":
        if not any(re.fullmatch(rf"{letter}\d+", d) for d in declared):
            return letter
    return "tmp_x"  # pragma: no cover - a spec that declares x0, w0, v0, z0 and y0


def _float(value: sp.Expr | None) -> float | None:
    if value is None:
        return None
    try:
        return float(value)
    except TypeError:
        return None


def build_program(
    derivation: Derivation,
    language: str,
    reserved: frozenset[str],
    spec_file: str,
    linear: bool = False,
) -> Program:
    """The functions of ``derivation`` with names for ``language`` (``reserved``: its keywords and the
    names the printer uses), ready to print; with ``linear`` also the linear model's K(q) and D(q)
    (:func:`linear_terms`)."""
    system = derivation.system
    if derivation.mass_matrix is None:
        from tutgen.errors import DerivationError

        raise DerivationError("the spec has no coordinates: there are no dynamics to generate code for", system.origin)
    coords = system.coordinates
    spec_names = [c.name for c in coords]
    spec_names += [f"{c.name}_dot" for c in coords] + [f"{c.name}_ddot" for c in coords]
    spec_names += [p.name for p in system.parameters]
    names = target_names(spec_names, reserved | RESERVED_LOCALS)
    renamed = tuple((a, b) for a, b in names.items() if a != b)
    n = len(coords)

    rename: dict[sp.Symbol, sp.Symbol] = {}
    for c in coords:
        rename[c.q] = sp.Symbol(names[c.name])
        rename[c.qd] = sp.Symbol(names[f"{c.name}_dot"])
        rename[c.qdd] = sp.Symbol(names[f"{c.name}_ddot"])
    for p in system.parameters:
        rename[p.symbol] = sp.Symbol(names[p.name])
    letter = _temporary_prefix(names.values())
    parameters = tuple(Parameter(names[p.name], p.name, _float(p.value)) for p in system.parameters)

    def renamed_matrix(m: sp.MatrixBase) -> sp.ImmutableMatrix:
        return sp.ImmutableMatrix(m.xreplace(rename))

    # the entries of forward dynamics' tau argument, as locals named after their coordinates
    taken = set(names.values())
    tau_names = []
    for c in coords:
        local = f"tau_{names[c.name]}"
        while local in taken or local in reserved:
            local += "_"
        taken.add(local)
        tau_names.append(local)
    tau = sp.ImmutableMatrix([sp.Symbol(t) for t in tau_names])
    hm = derivation.mass_matrix
    q_vec = derivation.generalized_forces if derivation.generalized_forces is not None else sp.zeros(n, 1)
    g_vec = derivation.gravity_vector if derivation.gravity_vector is not None else sp.zeros(n, 1)
    c_vec = derivation.coriolis_vector if derivation.coriolis_vector is not None else sp.zeros(n, 1)
    qdd = sp.ImmutableMatrix([c.qdd for c in coords])
    prog = derivation.program
    route = "sympy.cse of the derived entries"
    defs: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()
    c_mat = derivation.coriolis_matrix
    c_mat_doc = "C(q, q_dot) with C q_dot the Coriolis vector, from the Christoffel symbols of H (n x n)."
    if prog is not None:
        # the recursive program gives H, C q_dot and G of the links and gravity; the springs' part of G
        # (which the serial route adds to its expanded G) is dU_springs/dq
        route = "the derivation's recursive program (Newton-Euler for C q_dot and G, composite bodies for H)"
        defs = prog.definitions
        u_springs = sp.Add(*[e for _, e in derivation.spring_energies])
        springs = sp.ImmutableMatrix([sp.diff(u_springs, c.q) for c in coords])
        hm, c_vec, g_vec = prog.mass_matrix, prog.coriolis_vector, prog.gravity_vector + springs
        # C from the program's H differentiated forward (tutgen/codegen/coriolis.py), not expanded
        from tutgen.codegen.coriolis import program_coriolis_matrix

        more, c_mat = program_coriolis_matrix(prog)
        defs = (*defs, *more)
        c_mat_doc = (
            "C(q, q_dot) with C q_dot the Coriolis vector, from the Christoffel symbols of the first kind "
            "of the program's H, differentiated forward (n x n)."
        )

    results: list[tuple[str, str, tuple[str, ...], sp.MatrixBase, sp.MatrixBase | None]] = [
        ("mass_matrix", "H(q), the mass matrix (n x n).", ("q",), hm, None),
        ("coriolis_vector", "C(q, q_dot) q_dot, the Coriolis and centrifugal terms (n).", ("q", "qd"), c_vec, None),
    ]
    if c_mat is not None:
        results.append(("coriolis_matrix", c_mat_doc, ("q", "qd"), c_mat, None))
    results += [
        ("gravity_vector", "G(q) = dU/dq, gravity and springs (n).", ("q",), g_vec, None),
        (
            "generalized_forces",
            "Q(q, q_dot), dampers, loads and given generalized forces (n).",
            ("q", "qd"),
            q_vec,
            None,
        ),
    ]
    if derivation.potential_energy is not None:
        results.append(
            (
                "potential_energy",
                "U(q), the potential energy of gravity and springs (1 x 1).",
                ("q",),
                sp.ImmutableMatrix([[derivation.potential_energy]]),
                None,
            )
        )
    constraints: tuple[tuple[str, str], ...] = ()
    forward_matrix, forward_rhs = hm, tau + q_vec - c_vec - g_vec
    forward_doc = "q_ddot = H^-1 (tau + Q - C q_dot - G) (n); tau as in inverse_dynamics."
    if derivation.constraints is not None:
        ck = derivation.constraints.kinematics
        constraints = tuple((c.name, c.kind.value) for c in ck.constraints)
        m = len(constraints)
        a = ck.jacobian
        results += [
            (
                "constraint_residual",
                "The constraints' residuals (m): f_k(q) of a position constraint, a_k(q) . q_dot of a velocity one.",
                ("q", "qd"),
                sp.ImmutableMatrix(list(ck.functions)),
                None,
            ),
            ("constraint_jacobian", "A(q), the constraint Jacobian (m x n): A q_dot = 0.", ("q",), a, None),
            ("constraint_bias", "b = A_dot q_dot (m), so that A q_ddot + b = 0.", ("q", "qd"), ck.bias, None),
        ]
        # [[H, -A^T], [A, 0]] [q_ddot; lambda] = [tau + Q - C q_dot - G; -b]
        forward_matrix = sp.ImmutableMatrix(sp.BlockMatrix([[hm, -a.T], [a, sp.zeros(m, m)]]).as_explicit())
        forward_rhs = sp.ImmutableMatrix([*forward_rhs, *(-ck.bias)])
        forward_doc = (
            "q_ddot and lambda (n + m): [[H, -A^T], [A, 0]] [q_ddot; lambda] = [tau + Q - C q_dot - G; -b], "
            "the constrained motion and its multipliers; tau as in inverse_dynamics."
        )
    results += [
        (
            "inverse_dynamics",
            "tau = H q_ddot + C q_dot + G - Q: the generalized forces that give q_ddot (n).",
            ("q", "qd", "qdd"),
            hm * qdd + c_vec + g_vec - q_vec,
            None,
        ),
        ("forward_dynamics", forward_doc, ("q", "qd", "tau"), forward_matrix, forward_rhs),
    ]
    if linear and derivation.constraints is not None:
        from tutgen.errors import DerivationError

        # K and D of all the coordinates would ignore the constraints: a wrong linear model, not a partial one
        raise DerivationError(
            "`tutgen code --linear` does not handle `constraints` or loop-closing joints yet: K and D would be "
            "those of the unconstrained coordinates; generate the code without --linear",
            derivation.constraints.kinematics.constraints[0].origin,
        )
    if linear:
        stiffness, damping = linear_terms(derivation)
        results += [
            (
                "linear_stiffness",
                "K(q*) = d(G - Q)/dq at q_dot = 0: about an equilibrium q*, "
                "H dq_ddot + D dq_dot + K dq = dtau (n x n).",
                ("q",),
                stiffness,
                None,
            ),
            (
                "linear_damping",
                "D(q*) = -dQ/dq_dot at q_dot = 0, the linear model's damping (n x n).",
                ("q",),
                damping,
                None,
            ),
        ]
    functions = []
    for name, doc, args, result, solve in results:
        functions.append(
            _function(
                name,
                doc,
                args,
                renamed_matrix(result),
                renamed_matrix(solve) if solve is not None else None,
                tuple((rename.setdefault(s, s), e.xreplace(rename)) for s, e in defs),
                letter,
            )
        )
    return Program(
        module=module_name(spec_file.rsplit(".", 1)[0]),
        spec_file=safe_file_name(spec_file),
        language=language,
        coordinates=tuple(names[c.name] for c in coords),
        rates=tuple(names[f"{c.name}_dot"] for c in coords),
        accelerations=tuple(names[f"{c.name}_ddot"] for c in coords),
        forces=tuple(tau_names),
        parameters=parameters,
        functions=tuple(functions),
        renamed=renamed,
        route=route,
        constraints=constraints,
    )


def linear_terms(derivation: Derivation) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix]:
    """K = d(G - Q)/dq and D = -dQ/dq_dot, both at q_dot = 0: linearised about an equilibrium (q*, 0)
    (G - Q = tau* there, q_ddot* = 0), H q_ddot + C q_dot + G - Q = tau becomes
    H(q*) dq_ddot + D(q*) dq_dot + K(q*) dq = dtau; C q_dot is quadratic in q_dot and drops out.
    G is the derivation's (expanded on the serial route), so K has the derivation's own form."""
    system = derivation.system
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    n = len(q)
    g_vec = derivation.gravity_vector if derivation.gravity_vector is not None else sp.zeros(n, 1)
    q_vec = derivation.generalized_forces if derivation.generalized_forces is not None else sp.zeros(n, 1)
    rest = {s: sp.Integer(0) for s in qd}
    stiffness = sp.ImmutableMatrix(n, n, lambda i, j: sp.diff(g_vec[i] - q_vec[i], q[j]).xreplace(rest))
    damping = sp.ImmutableMatrix(n, n, lambda i, j: -sp.diff(q_vec[i], qd[j]).xreplace(rest))
    return stiffness, damping


def _function(
    name: str,
    doc: str,
    arguments: tuple[str, ...],
    result: sp.ImmutableMatrix,
    solve: sp.ImmutableMatrix | None,
    definitions: Sequence[tuple[sp.Symbol, sp.Expr]],
    letter: str,
) -> Function:
    """One function: the program's definitions it needs (renamed x_k in order of use), then ``sympy.cse``
    of what is left."""
    outputs = [result] + ([solve] if solve is not None else [])
    assignments: list[tuple[sp.Symbol, sp.Expr]] = []
    if definitions:
        needed = list(needed_definitions(definitions, outputs))
        fresh = {s: sp.Symbol(f"{letter}{k}") for k, (s, _) in enumerate(needed)}
        assignments = [(fresh[s], e.xreplace(fresh)) for s, e in needed]
        outputs = [m.xreplace(fresh) for m in outputs]
        start = len(assignments)
    else:
        start = 0
    flat = [e for m in outputs for e in m]
    symbols = (sp.Symbol(f"{letter}{k}") for k in range(start, 10**9))
    replacements, reduced = sp.cse(flat, symbols=symbols, order="none")
    assignments += replacements
    it = iter(reduced)
    rebuilt = [sp.ImmutableMatrix(m.rows, m.cols, [next(it) for _ in range(m.rows * m.cols)]) for m in outputs]
    return Function(
        name=name,
        doc=doc,
        arguments=arguments,
        assignments=tuple(assignments),
        result=rebuilt[0],
        solve=rebuilt[1] if solve is not None else None,
    )


def uses(function: Function, program: Program) -> Mapping[str, list[tuple[int, str]]]:
    """Which entries of each vector argument (and which parameters) ``function`` reads, in order:
    ``{"q": [(0, "theta"), ...], "p": [(-1, "m1"), ...]}``."""
    free = {s.name for s in function.free_symbols()}
    table: dict[str, list[tuple[int, str]]] = {}
    vectors = {"q": program.coordinates, "qd": program.rates, "qdd": program.accelerations, "tau": program.forces}
    for arg in function.arguments:
        if arg in vectors:
            table[arg] = [(i, name) for i, name in enumerate(vectors[arg]) if name in free]
    table["p"] = [(-1, prm.name) for prm in program.parameters if prm.name in free]
    return table
