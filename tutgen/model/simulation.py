"""The spec's `simulate:` section as a model value: what `tutgen simulate` integrates (docs/simulate.md)."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from tutgen.errors import Location

#: When the spec gives no `t`: the interval simulated, in seconds.
DEFAULT_INTERVAL = (sp.Integer(0), sp.Integer(10))
#: When the spec gives no `samples`: how many equally spaced instants the trajectory is written at.
DEFAULT_SAMPLES = 1001


@dataclass(frozen=True)
class Simulation:
    """Initial conditions, inputs and the interval of a simulation, as the spec gives them.

    ``q0`` and ``qd0`` map coordinate names to constant values (SI, angles in radians): parameters may
    appear and take their values when the simulation runs. ``inputs`` give parameters that have no
    value an expression of time ``t``, the parameters, the coordinates and their rates (``NAME_dot``).
    ``origin`` is where the section was written; ``places`` where each entry was, by
    ``"q0.theta"``, ``"inputs.tau"``, for the messages of the simulation.
    """

    t_start: sp.Expr
    t_end: sp.Expr
    q0: tuple[tuple[str, sp.Expr], ...]
    qd0: tuple[tuple[str, sp.Expr], ...]
    inputs: tuple[tuple[str, sp.Expr], ...]
    samples: int
    origin: Location
    places: tuple[tuple[str, Location], ...] = ()

    def place(self, key: str) -> Location:
        """Where ``key`` ("q0.theta") was written, or the section itself."""
        return dict(self.places).get(key, self.origin)


@dataclass(frozen=True)
class SimulationPlot:
    """One picture of a run placed in a worked solution: ``kind`` "plot" (q(t), q_dot(t), the
    energy) or "snapshots" (the mechanism's poses), ``name`` the file's name beside the solution."""

    kind: str
    name: str
    png: bytes


@dataclass(frozen=True)
class SimulationSummary:
    """A run of the spec's `simulate` section as a worked solution shows it (``ask: [simulation]``):
    the pictures, and the numbers the text and the JSON report. Built by tutgen/sim/solution.py, read
    by the renderers; floats are SI (angles in radians).

    ``initial`` and ``final`` give each coordinate (name, q, q_dot) at the start and at the last
    sample; ``drift`` is the relative energy drift (None when energy need not be constant, or without
    samples) and ``check_passed`` its verdict against ``tolerance`` (None when not checked);
    ``stopped`` why the run ended before ``t_end`` (a singular H), else None.
    """

    plots: tuple[SimulationPlot, ...]
    t_start: float
    t_end: float
    t_reached: float
    method: str
    rtol: float
    atol: float
    steps: int
    samples: int
    inputs: tuple[tuple[str, str], ...]
    initial: tuple[tuple[str, float, float], ...]
    final: tuple[tuple[str, float, float], ...]
    energy_initial: float
    energy_final: float
    conservative: bool
    drift: float | None
    tolerance: float
    check_passed: bool | None
    stopped: str | None
