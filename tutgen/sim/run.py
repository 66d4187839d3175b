"""`tutgen simulate` as a library: settings from the spec and the command line, the run, its files.

:func:`simulate_system` derives and integrates one system and checks its energy; :func:`simulate_spec`
does it for a spec file and returns the files to write (trajectory CSV and JSON, the plots), which
the CLI writes through :func:`tutgen.api.write_outputs` (temporary file and rename): nothing is
written when the settings are bad or the run times out. A run stopped by a singular mass matrix
writes what it has and then reports (exit 7); a run whose energy check fails writes its files and
reports (exit 8).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.errors import (
    DerivationTimeout,
    Location,
    SimulationCheckError,
    SimulationError,
    SpecError,
    SpecErrors,
    UsageError,
)
from tutgen.model.simulation import DEFAULT_INTERVAL, DEFAULT_SAMPLES, Simulation
from tutgen.model.system import System
from tutgen.sim.integrate import Trajectory, integrate

if TYPE_CHECKING:
    from tutgen.sim.model import NumericModel

__all__ = [
    "DRIFT_FACTOR",
    "Settings",
    "SimulationResult",
    "output_names",
    "simulate_spec",
    "simulate_system",
    "simulation_plot",
]

#: The energy check fails when the relative drift exceeds this many times the integrator's rtol.
DRIFT_FACTOR = 100


@dataclass(frozen=True)
class Settings:
    """What the command line adds to or overrides in the spec's `simulate` section (texts as typed)."""

    values: Mapping[str, str] = field(default_factory=dict)  # --set NAME=VALUE
    q0: Mapping[str, str] = field(default_factory=dict)  # --q0 NAME=VALUE
    qd0: Mapping[str, str] = field(default_factory=dict)  # --qd0 NAME=VALUE
    t_end: float | None = None
    samples: int | None = None
    method: str = "auto"
    rtol: float = 1e-10
    atol: float = 1e-12
    timeout: float | None = None


@dataclass(frozen=True)
class SimulationResult:
    """A run: the trajectory, its energies and the energy check."""

    spec_file: str
    coordinates: tuple[str, ...]
    values: dict[str, float]
    inputs: tuple[tuple[str, str], ...]
    t_start: float
    t_end: float
    q0: tuple[float, ...]
    qd0: tuple[float, ...]
    rtol: float
    atol: float
    trajectory: Trajectory
    kinetic: np.ndarray
    potential: np.ndarray
    conservative: bool
    drift: float | None  # max |E - E0| / scale, scale = max(|E0|, max T); None without samples
    # a constrained spec's: its constraints (name, kind) in the multipliers' order, the residuals and the
    # multipliers at the samples (samples x m), the Baumgarte rate, and the coordinates whose initial value
    # (position constraints) or rate (every dependent one) the constraints gave
    constraints: tuple[tuple[str, str], ...] = ()
    residuals: np.ndarray | None = None
    multipliers: np.ndarray | None = None
    stabilisation: float = 0.0
    solved_positions: tuple[str, ...] = ()
    solved_rates: tuple[str, ...] = ()

    @property
    def max_residual(self) -> float | None:
        """max |residual| over the samples and the constraints (None for an unconstrained run)."""
        if self.residuals is None or not self.residuals.size:
            return None
        return float(np.max(np.abs(self.residuals)))

    @property
    def total(self) -> np.ndarray:
        return self.kinetic + self.potential

    @property
    def tolerance(self) -> float:
        return DRIFT_FACTOR * self.rtol

    @property
    def check_passed(self) -> bool | None:
        """True or False for a conservative run, None when energy need not be constant."""
        if not self.conservative or self.drift is None:
            return None
        return bool(self.drift <= self.tolerance)


def _number(text: str, option: str, names: Mapping[str, sp.Expr], values: Mapping[sp.Symbol, sp.Expr]) -> float:
    """A command-line value: a number, a quantity (30deg, 1.5 m) or an expression of parameters with values."""
    from tutgen.spec.expr import ExprError, parse_expression
    from tutgen.spec.units import parse_quantity

    try:
        quantity = parse_quantity(text)
        expr = quantity.value if quantity is not None else parse_expression(text, names)
    except ExprError as exc:
        raise UsageError(f"{option} '{text}': {exc.message}") from None
    expr = sp.sympify(expr).xreplace(dict(values))
    if expr.free_symbols:
        missing = ", ".join(sorted(str(s) for s in expr.free_symbols))
        raise UsageError(f"{option} '{text}': expected a number; {missing} has no value")
    return float(expr)


def _split(pairs: Mapping[str, str], option: str, known: list[str], what: str) -> None:
    import difflib

    for name in pairs:
        if name not in known:
            close = difflib.get_close_matches(name, known, n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise UsageError(
                f"{option} {name}=...: unknown {what} '{name}' (known: {', '.join(known) or 'none'}){hint}"
            )


def _needed_parameters(derivation: Derivation, inputs: Mapping[str, sp.Expr]) -> set[sp.Symbol]:
    """The parameters the simulation evaluates: those in H, C, G, Q, U and in the inputs."""
    pieces: list[sp.Basic] = []
    if derivation.program is not None:
        prog = derivation.program
        pieces += [prog.mass_matrix, prog.coriolis_vector, prog.gravity_vector]
        pieces += [e for _, e in prog.definitions]
    else:
        pieces += [derivation.mass_matrix, derivation.coriolis_vector, derivation.gravity_vector]
    pieces += [derivation.generalized_forces, derivation.potential_energy, *inputs.values()]
    if derivation.constraints is not None:
        ck = derivation.constraints.kinematics
        pieces += [ck.jacobian, ck.bias, *ck.functions]
    free: set[sp.Symbol] = set()
    for piece in pieces:
        if piece is not None:
            free |= piece.free_symbols
    return free


def simulate_system(derivation: Derivation, settings: Settings, spec_file: str) -> SimulationResult:
    """Integrate ``derivation`` with the spec's `simulate` section and ``settings``, and check its energy."""
    from tutgen.limits import stage
    from tutgen.sim.model import numeric_model

    system = derivation.system
    sim = system.simulation
    where = sim.origin if sim is not None else system.origin
    params = {p.name: p for p in system.parameters}
    _split(settings.values, "--set", list(params), "parameter")
    coords = [c.name for c in system.coordinates]
    _split(settings.q0, "--q0", coords, "coordinate")
    _split(settings.qd0, "--qd0", coords, "coordinate")
    values: dict[sp.Symbol, sp.Expr] = dict(system.values)
    names = {p.name: p.symbol for p in system.parameters}
    for name, text in settings.values.items():
        values[params[name].symbol] = sp.nsimplify(_number(text, f"--set {name}=", names, values))
    inputs = {k: v for k, v in (sim.inputs if sim is not None else ()) if params[k].symbol not in values}

    # every parameter the model evaluates needs a value or an input: name each one, where declared
    errors = []
    if derivation.constraints is not None and sim is not None:
        # A and b = A_dot q_dot hold for constraints that do not change in time: an input in one would
        # make it move (its time derivatives are missing from b), so the motion would be wrong
        used = set().union(*(sp.sympify(f).free_symbols for f in derivation.constraints.kinematics.functions))
        for name in inputs:
            if params[name].symbol in used:
                errors.append(
                    SpecError(
                        sim.place(f"inputs.{name}"),
                        f"input '{name}' enters the constraints, which would then change in time; the "
                        "simulation takes constraints fixed in time only",
                        f"give {name} a constant value (in `parameters` or --set {name}=VALUE)",
                    )
                )
    needed = _needed_parameters(derivation, inputs)
    for p in system.parameters:
        if p.symbol in needed and p.symbol not in values and p.name not in inputs:
            errors.append(
                SpecError(
                    p.origin,
                    f"parameter '{p.name}' has no value, and the simulation needs one",
                    f"give it a value in `parameters` ({p.name}: 1.5), on the command line (--set {p.name}=1.5), "
                    "or as an input in `simulate.inputs`",
                )
            )
    q0_spec = dict(sim.q0) if sim is not None else {}
    qd0_spec = dict(sim.qd0) if sim is not None else {}
    # a constrained spec: the coordinates the position constraints fix need no initial value (one given is
    # where their solve starts), and the dependent rates follow from the constraints
    guessed: set[str] = set()
    dependent: set[str] = set()
    if derivation.constraints is not None:
        from tutgen.sim.constrained import position_unknowns

        guessed = {coords[j] for j in position_unknowns(derivation)}
        dependent = {coords[j] for j in derivation.constraints.kinematics.dependent}
    given_rates: dict[str, float] = {}
    q0, qd0 = [], []
    for c in system.coordinates:
        if c.name in settings.q0:
            q0.append(_number(settings.q0[c.name], f"--q0 {c.name}=", names, values))
        elif c.name in q0_spec:
            q0.append(float(q0_spec[c.name].xreplace(values)))
        elif c.name in guessed:
            q0.append(0.0)
        else:
            errors.append(
                SpecError(
                    where,
                    f"coordinate '{c.name}' has no initial value",
                    f"add it to `simulate.q0` ({{q0: {{{c.name}: 0}}}}) or give --q0 {c.name}=VALUE",
                )
            )
            continue
        if c.name in settings.qd0:
            qd0.append(_number(settings.qd0[c.name], f"--qd0 {c.name}=", names, values))
        else:
            qd0.append(float(qd0_spec.get(c.name, sp.Integer(0)).xreplace(values)))
        if c.name in dependent and (c.name in settings.qd0 or c.name in qd0_spec):
            given_rates[c.name] = qd0[-1]
    if errors:
        raise SpecErrors(errors)
    unstarted = {c for c in guessed if c not in settings.q0 and c not in q0_spec}  # start: the figure's branch
    t0, t1 = (float(x) for x in ((sim.t_start, sim.t_end) if sim is not None else DEFAULT_INTERVAL))
    if settings.t_end is not None:
        t1 = settings.t_end
        if not t1 > t0:
            raise UsageError(f"--t-end {t1:g}: the simulation starts at t = {t0:g} s; the end must come after it")
    samples = settings.samples or (sim.samples if sim is not None else DEFAULT_SAMPLES)

    float_values = {p.name: float(values[p.symbol]) for p in system.parameters if p.symbol in values}
    stage("building the numeric model")
    alpha = 0.0
    if derivation.constraints is not None:
        from tutgen.sim.constrained import baumgarte_rate

        alpha = baumgarte_rate(t0, t1)
    model = numeric_model(derivation, float_values, inputs, alpha)
    if derivation.constraints is not None:
        q0, qd0 = _consistent(derivation, model, t0, q0, qd0, given_rates, where, sim, float_values, unstarted)
    stage("integration", f"t from {t0:g} to {t1:g} s")
    from tutgen.limits import remaining

    try:
        trajectory = integrate(
            model,
            t0,
            t1,
            np.array(q0),
            np.array(qd0),
            samples,
            settings.method,
            settings.rtol,
            settings.atol,
            seconds=remaining() if settings.timeout else None,
        )
    except DerivationTimeout as exc:
        raise SimulationError(f"the integration did not finish within --timeout ({exc.seconds:g} s)", where) from None
    if trajectory.stop_kind == "timeout":
        raise SimulationError(
            f"the integration did not finish within --timeout {settings.timeout:g} s (it had reached "
            f"t = {trajectory.stop_time:.6g} s of {t1:g} s); raise --timeout, shorten the interval or loosen --rtol",
            where,
        )
    stage("energies")
    kinetic, potential = model.energies(trajectory.t, trajectory.q, trajectory.qd)
    drift = None
    if len(trajectory.t):
        total = kinetic + potential
        scale = max(abs(float(total[0])), float(np.max(kinetic)))
        change = float(np.max(np.abs(total - total[0])))
        drift = float(change / scale if scale > 0 else change)
    return SimulationResult(
        spec_file=spec_file,
        coordinates=tuple(coords),
        values=float_values,
        inputs=tuple((k, str(v)) for k, v in inputs.items()),
        t_start=t0,
        t_end=t1,
        q0=tuple(q0),
        qd0=tuple(qd0),
        rtol=settings.rtol,
        atol=settings.atol,
        trajectory=trajectory,
        kinetic=kinetic,
        potential=potential,
        conservative=model.conservative,
        drift=drift,
        **_constrained_fields(derivation, model, trajectory, guessed, dependent),
    )


def _consistent(
    derivation: Derivation,
    model: NumericModel,
    t0: float,
    q0: list[float],
    qd0: list[float],
    given_rates: Mapping[str, float],
    where: Location,
    sim: Simulation | None,
    values: Mapping[str, float],
    unstarted: set[str],
) -> tuple[list[float], list[float]]:
    """A constrained spec's initial state on its constraints (tutgen/sim/constrained.py); an error at the
    `simulate` section when the position constraints have no root, or a dependent rate given disagrees."""
    from tutgen.sim.constrained import consistent_start

    coords = [c.name for c in derivation.system.coordinates]
    ck = derivation.constraints.kinematics if derivation.constraints is not None else None
    assert ck is not None
    independent = ", ".join(f"{coords[j]} = {q0[j]:.6g}" for j in ck.independent)
    start = consistent_start(derivation, model, t0, np.array(q0), np.array(qd0), values, unstarted)
    if start is None:
        raise SpecErrors(
            [
                SpecError(
                    where,
                    f"the constraints hold at no configuration with {independent}: the position constraints have "
                    "no root from the start given",
                    "choose other initial values of the independent coordinates, or give the dependent ones a "
                    "starting guess in `simulate.q0` (--q0 NAME=VALUE) near the assembly meant",
                )
            ]
        )
    q, qd = start
    errors = []
    for name, value in given_rates.items():
        j = coords.index(name)
        if abs(value - qd[j]) > 1e-9 * (1 + abs(qd[j])):
            place = sim.place(f"qd0.{name}") if sim is not None else where
            errors.append(
                SpecError(
                    place,
                    f"the initial rate of the dependent coordinate '{name}' is {value:.6g}, and the constraints "
                    f"give {qd[j]:.6g} (q_dot_d = B q_dot_i)",
                    f"leave {name} out of `simulate.qd0` (and --qd0): the constraints give it",
                )
            )
    if errors:
        raise SpecErrors(errors)
    return [float(v) for v in q], [float(v) for v in qd]


def _constrained_fields(
    derivation: Derivation, model: NumericModel, trajectory: Trajectory, guessed: set[str], dependent: set[str]
) -> dict[str, object]:
    """The constrained run's fields of :class:`SimulationResult` (none for an unconstrained one)."""
    if derivation.constraints is None:
        return {}
    from tutgen.sim.constrained import residuals_and_multipliers

    residuals, multipliers = residuals_and_multipliers(model, trajectory.t, trajectory.q, trajectory.qd)
    coords = [c.name for c in derivation.system.coordinates]
    return {
        "constraints": model.constraints,
        "residuals": residuals,
        "multipliers": multipliers,
        "stabilisation": model.stabilisation,
        "solved_positions": tuple(c for c in coords if c in guessed),
        "solved_rates": tuple(c for c in coords if c in dependent),
    }


#: The files of a run, by kind: the suffix after the spec's stem.
SUFFIXES = {
    "csv": ".trajectory.csv",
    "json": ".trajectory.json",
    "plot": ".plot.png",
    "snapshots": ".snapshots.png",
}


def output_names(spec: Path) -> dict[str, str]:
    """The file names a run of ``spec`` writes, by kind."""
    return {kind: spec.stem + suffix for kind, suffix in SUFFIXES.items()}


def simulate_spec(
    spec: Path, settings: Settings, *, plots: bool = True
) -> tuple[SimulationResult, dict[str, str | bytes], System]:
    """Load, derive and simulate ``spec`` within ``settings.timeout``; the result and the files' contents
    by kind (``csv``, ``json``, and with ``plots`` the ``plot`` and, for a planar system, ``snapshots``)."""
    from tutgen.engine.pipeline import derive
    from tutgen.limits import deadline
    from tutgen.limits import stage as charge
    from tutgen.sim.output import trajectory_csv, trajectory_json
    from tutgen.spec.validate import load_system

    with deadline(settings.timeout):
        charge("loading the specs", spec.name)
        system = load_system(spec)
        charge("derivation")
        derivation = derive(system, "lagrange")
        result = simulate_system(derivation, settings, spec.name)
        charge("writing the trajectory")
        files: dict[str, str | bytes] = {"csv": trajectory_csv(result), "json": trajectory_json(result)}
        if plots:
            from tutgen.sim.plots import plot_png, snapshots_png

            charge("plotting")
            files["plot"] = plot_png(result)
            values = {
                p.symbol: v for p, v in ((p, result.values.get(p.name)) for p in system.parameters) if v is not None
            }
            strip = snapshots_png(result, system, values)
            if strip is not None:
                files["snapshots"] = strip
    return result, files, system


def outcome_error(result: SimulationResult, written: str) -> SimulationError | None:
    """The error to report after the files are written: a run stopped early, or a failed energy check."""
    tr = result.trajectory
    if tr.stopped is not None:
        state = ", ".join(f"{n} = {v:.6g}" for n, v in zip(result.coordinates, tr.stop_state or (), strict=False))
        return SimulationError(
            f"the simulation stopped: {tr.stopped}, at {state}; the trajectory so far is in {written}"
        )
    if result.check_passed is False:
        return SimulationCheckError(
            f"energy check failed: the total energy of a system without dissipation or inputs drifted by "
            f"{result.drift:.3g} (relative), more than {DRIFT_FACTOR} x rtol = {result.tolerance:.3g}; "
            f"try a tighter --rtol or --method DOP853 (files written to {written})"
        )
    return None


def simulation_plot(derivation: Derivation, settings: Settings, spec_file: str) -> tuple[str, bytes]:
    """The plot of a run as ``(file name, PNG bytes)``, for a worked solution or a sheet to place beside
    its text (the hook for ``ask: [simulation]``; the solution views do not call it yet)."""
    from tutgen.sim.plots import plot_png

    result = simulate_system(derivation, settings, spec_file)
    return Path(spec_file).stem + SUFFIXES["plot"], plot_png(result)
