"""`tutgen simulate`: integrate the equations of motion, write the trajectory and plot it (docs/simulate.md)."""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors, stdout_write
from tutgen.cli.options import Quiet
from tutgen.cli.stdio import refuse_stdout, refuse_unnamed
from tutgen.limits import DEFAULT_TIMEOUT


class Method(StrEnum):
    auto = "auto"
    DOP853 = "DOP853"
    RK45 = "RK45"
    Radau = "Radau"
    BDF = "BDF"
    LSODA = "LSODA"


def _pairs(items: list[str], option: str) -> dict[str, str]:
    from tutgen.errors import UsageError

    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name.strip() or not value.strip():
            raise UsageError(f"{option} '{item}': expected NAME=VALUE, e.g. {option} theta=30deg")
        out[name.strip()] = value.strip()
    return out


@handle_errors
def simulate(
    spec: Annotated[Path, typer.Argument(metavar="SPEC", help="The spec file (YAML).", show_default=False)],
    output: Annotated[
        str, typer.Option("--output", "-o", metavar="DIR", help="Directory for the trajectory and plots.")
    ] = ".",
    set_: Annotated[
        list[str] | None, typer.Option("--set", metavar="NAME=VALUE", help="A parameter's value (repeatable).")
    ] = None,
    q0: Annotated[
        list[str] | None, typer.Option("--q0", metavar="NAME=VALUE", help="An initial coordinate, e.g. theta=30deg.")
    ] = None,
    qd0: Annotated[
        list[str] | None, typer.Option("--qd0", metavar="NAME=VALUE", help="An initial rate (default 0).")
    ] = None,
    t_end: Annotated[
        float | None, typer.Option("--t-end", metavar="SECONDS", help="End of the interval (default: the spec's).")
    ] = None,
    samples: Annotated[
        int | None,
        typer.Option("--samples", metavar="N", min=2, max=1_000_000, help="Instants written (default: the spec's)."),
    ] = None,
    method: Annotated[
        Method,
        typer.Option(
            "--method",
            metavar="METHOD",
            help=f"Integrator: {', '.join(Method)}; auto: DOP853, or Radau when the start is stiff.",
        ),
    ] = Method.auto,
    rtol: Annotated[
        float, typer.Option("--rtol", metavar="TOL", min=1e-14, max=1e-2, help="Relative tolerance.")
    ] = 1e-10,
    atol: Annotated[float, typer.Option("--atol", metavar="TOL", min=0, max=1, help="Absolute tolerance.")] = 1e-12,
    plots: Annotated[bool, typer.Option("--plots/--no-plots", help="Write the PNG plots.")] = True,
    force: Annotated[bool, typer.Option("--force", help="Overwrite existing output files.")] = False,
    timeout: Annotated[
        float,
        typer.Option("--timeout", metavar="SECONDS", min=0, help="Stop a run that takes longer (0: no limit)."),
    ] = DEFAULT_TIMEOUT,
    quiet: Quiet = False,
) -> None:
    """Integrate the equations of motion of SPEC and write the trajectory (CSV, JSON) and plots (PNG).

    Initial conditions, inputs and the interval come from the spec's `simulate:` section and the
    options. For a system without dissipation or inputs the relative energy drift is reported, and
    the run fails (exit 8) when it exceeds 100 x rtol. Exit 7: the run stopped early (singular mass
    matrix: the trajectory so far is written; the integrator failed; --timeout).
    """
    from tutgen.api import check_output_path
    from tutgen.sim.files import write_simulation
    from tutgen.sim.run import Settings

    refuse_stdout("-o", output, "a simulation writes several files (CSV, JSON, plots)", "a directory")
    refuse_unnamed(spec, "the files of a simulation are named after its spec")
    check_output_path(Path(output))
    settings = Settings(
        values=_pairs(set_ or [], "--set"),
        q0=_pairs(q0 or [], "--q0"),
        qd0=_pairs(qd0 or [], "--qd0"),
        t_end=t_end,
        samples=samples,
        method=method.value,
        rtol=rtol,
        atol=atol,
        timeout=timeout or None,
    )
    summary = write_simulation(spec, Path(output), settings, plots=plots, force=force)
    if not quiet:
        stdout_write(summary)
