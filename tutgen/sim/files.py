"""Where a simulation's files go, and writing them: refuse to overwrite before the slow part, write
through temporary files and renames (:func:`tutgen.api.write_outputs`), and report a run that stopped
early or failed its energy check only after its files are written."""

from __future__ import annotations

import os
from pathlib import Path

from tutgen.errors import UsageError
from tutgen.sim.run import Settings, outcome_error, output_names, simulate_spec

__all__ = ["plan_simulation", "write_simulation"]


def plan_simulation(spec: Path, directory: Path, *, plots: bool, force: bool) -> dict[str, Path]:
    """The files of a run of ``spec`` in ``directory``, by kind; a usage error for an existing file
    without ``force``, for the spec itself, or for a ``directory`` that is a file."""
    if directory.exists() and not directory.is_dir():
        raise UsageError(f"-o {directory}: expected a directory for the trajectory and plots, and this is a file")
    names = output_names(spec)
    if not plots:
        names = {k: v for k, v in names.items() if k in ("csv", "json")}
    targets = {kind: directory / name for kind, name in names.items()}
    for target in targets.values():
        if target.exists() and spec.exists() and os.path.samefile(target, spec):
            raise UsageError(f"refusing to overwrite the spec {target}; choose another -o")
        if target.exists() and not force:
            raise UsageError(f"{target} exists; add --force to overwrite it")
    return targets


def write_simulation(spec: Path, directory: Path, settings: Settings, *, plots: bool, force: bool) -> str:
    """Simulate ``spec``, write its files into ``directory`` and return the summary to print; raises the
    run's :class:`~tutgen.errors.SimulationError` after writing when it stopped early or failed its check."""
    from tutgen.api import write_outputs

    targets = plan_simulation(spec, directory, plots=plots, force=force)
    result, files, _ = simulate_spec(spec, settings, plots=plots)
    kinds = [k for k in targets if k in files]
    write_outputs([targets[k] for k in kinds], [files[k] for k in kinds])
    tr = result.trajectory
    lines = [f"wrote {targets[k]}" for k in kinds]
    lines.append(
        f"integrated t = {result.t_start:g} .. {tr.t[-1] if len(tr.t) else result.t_start:g} s with {tr.method} "
        f"({tr.steps} steps, {tr.evaluations} evaluations, rtol {result.rtol:g})"
    )
    if result.solved_positions or result.solved_rates:
        start = ", ".join(
            f"{name} = {result.q0[result.coordinates.index(name)]:.6g}" for name in result.solved_positions
        )
        rates = ", ".join(
            f"{name}_dot = {result.qd0[result.coordinates.index(name)]:.6g}" for name in result.solved_rates
        )
        lines.append(f"from the constraints at the start: {', '.join(x for x in (start, rates) if x)}")
    if result.max_residual is not None:
        lines.append(
            f"largest constraint residual {result.max_residual:.3g} (Baumgarte rate {result.stabilisation:.3g} 1/s)"
        )
    if result.conservative and result.drift is not None:
        verdict = "ok" if result.check_passed else "FAILED"
        lines.append(f"relative energy drift {result.drift:.3g} (tolerance {result.tolerance:.3g}): {verdict}")
    error = outcome_error(result, str(targets["csv"]))
    if error is not None:
        raise error
    return "\n".join(lines) + "\n"
