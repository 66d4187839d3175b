"""The derived model as float functions: the generated NumPy code of :mod:`tutgen.codegen`, compiled.

The code compiled here is tutgen's own output (sympy expressions printed by the NumPy printer), in
which every name is a declared spec name that is a Python identifier and not a keyword
(:func:`tutgen.codegen.program.target_names`); the inputs of `simulate.inputs` were read by the
whitelist parser into sympy expressions before they are printed. No user text is ever executed.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np
import sympy as sp

from tutgen.codegen.printers import LANGUAGES
from tutgen.codegen.program import Program, build_program
from tutgen.engine.derivation import Derivation

__all__ = ["NumericModel", "numeric_model"]

TIME = sp.Symbol("t")


@dataclass(frozen=True)
class NumericModel:
    """H, C q_dot, G, Q and U of one derivation as functions of float arrays, with the parameters fixed.

    ``inputs`` evaluates the inputs of the run (parameters given as expressions of t, q, q_dot) and
    returns the parameter object the functions read; ``conservative`` is whether the run has neither
    dissipation nor inputs (its energy must then be constant).
    """

    coordinates: tuple[str, ...]
    mass_matrix: Callable[[np.ndarray, Any], np.ndarray]
    coriolis_vector: Callable[[np.ndarray, np.ndarray, Any], np.ndarray]
    gravity_vector: Callable[[np.ndarray, Any], np.ndarray]
    generalized_forces: Callable[[np.ndarray, np.ndarray, Any], np.ndarray]
    potential_energy: Callable[[np.ndarray, Any], np.ndarray] | None
    parameters: Callable[[float, np.ndarray, np.ndarray], Any]
    conservative: bool

    scalar: Callable[..., tuple[list[list[float]], list[float]]]  # (q, qd, p) -> (H, Q - C q_dot - G), floats

    # a constrained spec's (tutgen/sim/constrained.py): the constraints' kinds ("position" | "velocity")
    # and names in the multipliers' order, their residuals f_k(q) or a_k(q) . q_dot as plain floats, A(q),
    # and the Baumgarte rate alpha (1/s) of the stabilised acceleration constraint
    constraints: tuple[tuple[str, str], ...] = ()
    residual: Callable[..., list[float]] | None = None
    constraint_jacobian: Callable[[np.ndarray, Any], np.ndarray] | None = None
    stabilisation: float = 0.0

    @property
    def matrix_name(self) -> str:
        """What ``accelerations`` returns as its matrix, as a message names it."""
        return "the matrix [[H, -A^T], [A, 0]]" if self.constraints else "the mass matrix H"

    def accelerations(self, t: float, q: np.ndarray, qd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(H, Q - C q_dot - G) at one state, so that q_ddot = H^-1 (Q - C q_dot - G).

        For a constrained spec, (K, r) with K = [[H, -A^T], [A, 0]] and r = [Q - C q_dot - G; -b - 2 alpha
        A q_dot - alpha^2 f], f the position constraints' residuals (Baumgarte's stabilisation: the
        residual e of each constraint obeys e'' + 2 alpha e' + alpha^2 e = 0, or e' + 2 alpha e = 0 for a
        velocity constraint, instead of drifting); K^-1 r = (q_ddot, lambda)."""
        p = self.parameters(t, q, qd)
        h, rhs = self.scalar(q, qd, p)
        h, rhs = np.array(h), np.array(rhs)
        if self.constraints and self.residual is not None and self.stabilisation:
            n = len(q)
            alpha = self.stabilisation
            rates = h[n:, :n] @ qd  # A q_dot: the velocity constraints' residuals, the position ones' rates
            rhs[n:] -= 2 * alpha * rates
            residual = self.residual(q, qd, p)
            for k, (_, kind) in enumerate(self.constraints):
                if kind == "position":
                    rhs[n + k] -= alpha**2 * residual[k]
        return h, rhs

    def energies(self, t: np.ndarray, q: np.ndarray, qd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Kinetic and potential energy along a trajectory (rows of q, qd at the times t)."""
        kinetic = np.empty(len(t))
        potential = np.zeros(len(t))
        for k in range(len(t)):
            p = self.parameters(float(t[k]), q[k], qd[k])
            h = self.mass_matrix(q[k], p)
            kinetic[k] = 0.5 * qd[k] @ h @ qd[k]
            if self.potential_energy is not None:
                potential[k] = float(self.potential_energy(q[k], p))
        return kinetic, potential


def _compile(source: str, name: str) -> dict[str, Any]:
    """Run generated source as a module (dataclasses look their module up in ``sys.modules`` while the
    class is made, so it is registered for the time of the run)."""
    import sys
    import types

    module = types.ModuleType(f"tutgen_generated_{name}")
    sys.modules[module.__name__] = module
    try:
        exec(compile(source, f"<tutgen generated {name}>", "exec"), module.__dict__)
    finally:
        del sys.modules[module.__name__]
    return module.__dict__


def numeric_model(
    derivation: Derivation,
    values: Mapping[str, float],
    inputs: Mapping[str, sp.Expr],
    stabilisation: float = 0.0,
) -> NumericModel:
    """Compile ``derivation``'s dynamics with the parameters ``values`` (spec name -> float) and the
    ``inputs`` (spec name -> expression of t, parameters, coordinates and rates); ``stabilisation`` is a
    constrained spec's Baumgarte rate alpha (:meth:`NumericModel.accelerations`)."""
    _, reserved, printer = LANGUAGES["python"]
    program = build_program(derivation, "python", reserved(), "simulation")
    namespace = _compile(printer(program), "model")
    scalar = _compile(_scalar_source(program), "scalar")["accelerations"]
    residual = None
    if program.constraints:
        residual = _compile(_scalar_source(program, "constraint_residual"), "residual")["constraint_residual"]
    system = derivation.system
    by_spec = {p.spec_name: p.name for p in program.parameters}
    base = {by_spec[k]: float(v) for k, v in values.items() if k in by_spec}
    parameters = _input_function(program, system, base, inputs)
    return NumericModel(
        coordinates=tuple(c.name for c in system.coordinates),
        mass_matrix=namespace["mass_matrix"],
        coriolis_vector=namespace["coriolis_vector"],
        gravity_vector=namespace["gravity_vector"],
        generalized_forces=namespace["generalized_forces"],
        potential_energy=namespace.get("potential_energy"),
        parameters=parameters,
        scalar=scalar,
        conservative=_is_conservative(derivation, values, inputs),
        constraints=program.constraints,
        residual=residual,
        constraint_jacobian=namespace.get("constraint_jacobian"),
        stabilisation=stabilisation,
    )


def _scalar_source(program: Program, name: str = "forward_dynamics") -> str:
    """forward_dynamics' H and right-hand side (tau = 0) as one plain-float function of lists: the
    right-hand side of the integration, called thousands of times, without NumPy's per-call overhead
    (``accelerations(q, qd, p)``); or another function of ``q, qd`` by its ``name``, returning its
    result's entries as a list (``constraint_residual(q, qd, p)``)."""
    from sympy.printing.pycode import PythonCodePrinter

    from tutgen.codegen.program import uses

    printer = PythonCodePrinter({"fully_qualified_modules": True, "standard": "python3"})
    fn = next(f for f in program.functions if f.name == name)
    table = uses(fn, program)
    zero = {sp.Symbol(name): sp.Integer(0) for name in program.forces}
    lines = ["import math", f"def {'accelerations' if fn.solve is not None else name}(q, qd, p):"]
    for a in ("q", "qd"):
        lines += [f"    {name} = {a}[{i}]" for i, name in table.get(a, ())]
    lines += [f"    {name} = p.{name}" for _, name in table["p"]]
    lines += [f"    {s} = {printer.doprint(e.xreplace(zero))}" for s, e in fn.assignments]
    h, rhs = fn.result, fn.solve
    if rhs is None:
        lines.append(f"    return [{', '.join(printer.doprint(e) for e in h)}]")
        return "\n".join(lines) + "\n"
    rows = ", ".join("[" + ", ".join(printer.doprint(h[i, j]) for j in range(h.cols)) + "]" for i in range(h.rows))
    lines.append(f"    return [{rows}], [{', '.join(printer.doprint(e.xreplace(zero)) for e in rhs)}]")
    return "\n".join(lines) + "\n"


def _input_function(
    program: Program, system: Any, base: dict[str, float], inputs: Mapping[str, sp.Expr]
) -> Callable[[float, np.ndarray, np.ndarray], Any]:
    """A function (t, q, qd) -> the parameter object, the inputs evaluated at that instant."""
    fixed = SimpleNamespace(**base)
    if not inputs:
        return lambda t, q, qd: fixed
    from sympy.printing.numpy import NumPyPrinter

    rename: dict[sp.Symbol, sp.Symbol] = {TIME: sp.Symbol("t")}
    for c, name, rate in zip(system.coordinates, program.coordinates, program.rates, strict=True):
        rename[c.q] = sp.Symbol(name)
        rename[c.qd] = sp.Symbol(rate)
    targets = {p.spec_name: p.name for p in program.parameters}
    for prm in system.parameters:
        rename[prm.symbol] = sp.Symbol(targets[prm.name])
    printer = NumPyPrinter({"fully_qualified_modules": True})
    lines = ["import numpy", "def inputs(t, q, qd, p):"]
    for i, (name, rate) in enumerate(zip(program.coordinates, program.rates, strict=True)):
        lines += [f"    {name} = q[{i}]", f"    {rate} = qd[{i}]"]
    lines += [f"    {name} = p.{name}" for name in base]
    values = [f"{targets[k]}={printer.doprint(e.xreplace(rename))}" for k, e in inputs.items()]
    lines.append(f"    return dict({', '.join(values)})")
    function = _compile("\n".join(lines) + "\n", "inputs")["inputs"]

    def parameters(t: float, q: np.ndarray, qd: np.ndarray) -> Any:
        return SimpleNamespace(**base, **{k: float(v) for k, v in function(t, q, qd, fixed).items()})

    return parameters


def _is_conservative(derivation: Derivation, values: Mapping[str, float], inputs: Mapping[str, sp.Expr]) -> bool:
    """Whether the run has no dissipation and no inputs: Q is zero with the run's values, and no input
    enters H, C or G."""
    system = derivation.system
    symbols = {p.name: p.symbol for p in system.parameters}
    subs = {symbols[k]: sp.nsimplify(v) for k, v in values.items() if k in symbols}
    forced = {symbols[k] for k in inputs}
    q_vec = derivation.generalized_forces
    if q_vec is not None:
        for entry in q_vec:
            if sp.expand(entry.xreplace({**subs, **{s: sp.Integer(0) for s in forced}})) != 0:
                return False
            if entry.free_symbols & forced:
                return False
    pieces = [derivation.mass_matrix, derivation.gravity_vector]
    if derivation.program is not None:
        pieces = [derivation.program.mass_matrix, derivation.program.gravity_vector]
    return not any(m is not None and m.free_symbols & forced for m in pieces)
