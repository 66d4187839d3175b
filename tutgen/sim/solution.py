"""`ask: [simulation]`: the run of a spec's `simulate` section placed in its worked solution.

:func:`attach_simulation` integrates a derivation whose steps include the simulation step
(tutgen/engine/steps.py) and returns it with ``Derivation.simulation`` set: the plots as PNG bytes,
named for the files beside a Markdown, LaTeX or JSON solution, and the numbers the section and the
JSON report (the interval, the integrator, the energy drift). The engine never integrates, and the
renderers never run anything: this is the one place between them, called by tutgen/api.py and the
sheets before rendering.

scipy and matplotlib are imported only here, inside the functions, and only for a derivation that
asks for the step. The plots are the same bytes on every run (tutgen/sim/plots.py: no date, no
software version, fixed size).
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

from tutgen.engine.derivation import Derivation
from tutgen.engine.steps import StepKind
from tutgen.model.simulation import SimulationPlot, SimulationSummary

__all__ = ["attach_simulation", "plot_names", "simulation_summary"]


def plot_names(source: str) -> dict[str, str]:
    """The file names of the plots beside a solution of the spec file ``source``, by kind."""
    # only characters that need no quoting in a Markdown link, a LaTeX \includegraphics or a file system
    stem = re.sub(r"[^A-Za-z0-9_-]", "_", Path(source).stem) or "spec"
    return {"plot": f"{stem}.simulation.png", "snapshots": f"{stem}.snapshots.png"}


def simulation_summary(derivation: Derivation, timeout: float | None = None) -> SimulationSummary:
    """Run the spec's `simulate` section (the command's defaults: DOP853 unless stiff, rtol 1e-10)
    and summarise it. Missing values are the run's located :class:`~tutgen.errors.SpecErrors`;
    ``timeout`` (the solve's) makes the integration stop within the run's deadline."""
    from tutgen.sim.plots import plot_png, snapshots_png
    from tutgen.sim.run import Settings, simulate_system

    system = derivation.system
    result = simulate_system(derivation, Settings(timeout=timeout or None), system.source)
    names = plot_names(system.source)
    plots = [SimulationPlot("plot", names["plot"], plot_png(result))]
    values = {p.symbol: result.values[p.name] for p in system.parameters if p.name in result.values}
    strip = snapshots_png(result, system, values)
    if strip is not None:
        plots.append(SimulationPlot("snapshots", names["snapshots"], strip))
    tr = result.trajectory
    last = len(tr.t) - 1
    total = result.total
    return SimulationSummary(
        plots=tuple(plots),
        t_start=result.t_start,
        t_end=result.t_end,
        t_reached=float(tr.t[last]) if last >= 0 else result.t_start,
        method=tr.method,
        rtol=result.rtol,
        atol=result.atol,
        steps=tr.steps,
        samples=len(tr.t),
        inputs=result.inputs,
        initial=tuple((c, q, qd) for c, q, qd in zip(result.coordinates, result.q0, result.qd0, strict=True)),
        final=tuple(
            (c, float(tr.q[last, i]), float(tr.qd[last, i])) for i, c in enumerate(result.coordinates) if last >= 0
        ),
        energy_initial=float(total[0]) if last >= 0 else 0.0,
        energy_final=float(total[last]) if last >= 0 else 0.0,
        conservative=result.conservative,
        drift=result.drift if result.conservative else None,
        tolerance=result.tolerance,
        check_passed=result.check_passed,
        stopped=tr.stopped,
    )


def attach_simulation(derivation: Derivation, timeout: float | None = None) -> Derivation:
    """``derivation`` with its simulation run, when its steps ask for one; else unchanged."""
    if not derivation.has_step(StepKind.SIMULATION) or derivation.simulation is not None:
        return derivation
    return dataclasses.replace(derivation, simulation=simulation_summary(derivation, timeout))
