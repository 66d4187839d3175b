"""A simulated trajectory as CSV and JSON text (the columns and keys are documented in docs/simulate.md).

Numbers are written with ``repr`` (the shortest text that reads back as the same double), so a run
gives the same bytes every time on the same platform and libraries. Spec text appears only as
declared names (coordinates, parameters), and in CSV headers a name is one that cannot start a
spreadsheet formula (identifiers only).
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

import numpy as np

from tutgen.version import __version__

if TYPE_CHECKING:
    from tutgen.sim.run import SimulationResult

__all__ = ["FORMAT_VERSION", "trajectory_csv", "trajectory_json"]

#: The version of the JSON document's layout (additive changes keep it).
FORMAT_VERSION = 1


def _number(x: float) -> str:
    return repr(float(x))


def trajectory_csv(result: SimulationResult) -> str:
    """One row per sample: t, each coordinate, each rate (NAME_dot), then T, U and E = T + U; for a
    constrained spec then each constraint's residual (residual_NAME) and each multiplier (lambda_k)."""
    names = result.coordinates
    header = ["t", *names, *(f"{n}_dot" for n in names), "kinetic_energy", "potential_energy", "total_energy"]
    header += [f"residual_{name}" for name, _ in result.constraints]
    header += [f"lambda_{k + 1}" for k in range(len(result.constraints))]
    rows = [",".join(header)]
    tr = result.trajectory
    for k in range(len(tr.t)):
        values = [tr.t[k], *tr.q[k], *tr.qd[k], result.kinetic[k], result.potential[k], result.total[k]]
        if result.residuals is not None and result.multipliers is not None:
            values += [*result.residuals[k], *result.multipliers[k]]
        rows.append(",".join(_number(v) for v in values))
    return "\n".join(rows) + "\n"


def _list(values: np.ndarray) -> list[float]:
    return [float(v) for v in values]


def trajectory_json(result: SimulationResult) -> str:
    """The run's settings, the samples by name, the energies and the energy check, as one document."""
    tr = result.trajectory
    doc: dict[str, Any] = {
        "tutgen": __version__,
        "format": FORMAT_VERSION,
        "spec": result.spec_file,
        "coordinates": list(result.coordinates),
        "parameters": {k: float(v) for k, v in result.values.items()},
        "inputs": dict(result.inputs),
        "integrator": {
            "method": tr.method,
            "rtol": result.rtol,
            "atol": result.atol,
            "steps": tr.steps,
            "evaluations": tr.evaluations,
        },
        "interval": [result.t_start, result.t_end],
        "initial": {
            "q": {n: float(v) for n, v in zip(result.coordinates, result.q0, strict=True)},
            "qd": {n: float(v) for n, v in zip(result.coordinates, result.qd0, strict=True)},
        },
        "t": _list(tr.t),
        "q": {n: _list(tr.q[:, i]) for i, n in enumerate(result.coordinates)},
        "qd": {n: _list(tr.qd[:, i]) for i, n in enumerate(result.coordinates)},
        "energy": {
            "kinetic": _list(result.kinetic),
            "potential": _list(result.potential),
            "total": _list(result.total),
        },
        "energy_check": {
            "conservative": result.conservative,
            "relative_drift": result.drift,
            "tolerance": result.tolerance if result.conservative else None,
            "passed": result.check_passed,
        },
        "stopped": None
        if tr.stopped is None
        else {
            "reason": tr.stop_kind,
            "message": tr.stopped,
            "t": tr.stop_time,
            "q": list(tr.stop_state) if tr.stop_state is not None else None,
        },
    }
    if result.constraints and result.residuals is not None and result.multipliers is not None:
        doc["constraints"] = {
            "method": "baumgarte",
            "stabilisation": result.stabilisation,
            "solved_positions": list(result.solved_positions),
            "solved_rates": list(result.solved_rates),
            "max_residual": result.max_residual,
            "items": [
                {
                    "name": name,
                    "kind": kind,
                    "multiplier": f"lambda_{k + 1}",
                    "residual": _list(result.residuals[:, k]),
                    "lambda": _list(result.multipliers[:, k]),
                }
                for k, (name, kind) in enumerate(result.constraints)
            ],
        }
    return json.dumps(doc, indent=1, allow_nan=False, default=_number) + "\n"
