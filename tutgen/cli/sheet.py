"""`tutgen sheet`: a tutorial sheet (questions and worked solutions), and a variant per student."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import echo_error, handle_errors
from tutgen.cli.options import Progress, Quiet, show_progress
from tutgen.cli.stdio import refuse_stdout
from tutgen.limits import DEFAULT_TIMEOUT


class SheetMethod(StrEnum):
    lagrange = "lagrange"
    both = "both"
    newton_euler = "newton-euler"


class SheetFormat(StrEnum):
    md = "md"
    tex = "tex"
    pdf = "pdf"
    moodle = "moodle"  # Moodle XML of every variant (docs/lms.md)
    qti = "qti"  # an IMS QTI 2.1 package (docs/lms.md)


@handle_errors
def sheet(
    sheet: Annotated[Path, typer.Argument(metavar="SHEET", help="The sheet file (YAML).", show_default=False)],
    output: Annotated[
        str | None,
        typer.Option(
            "--output", "-o", metavar="DIR", help="The directory to write into (required).", show_default=False
        ),
    ] = None,
    formats: Annotated[
        list[SheetFormat] | None,
        typer.Option(
            "--format",
            "-f",
            metavar="FORMAT",
            help=f"Output format: {', '.join(SheetFormat)}; repeat for several (default md).",
            show_default=False,
        ),
    ] = None,
    variants: Annotated[
        int | None,
        typer.Option(
            "--variants", "-n", metavar="N", min=1, max=10_000, help="Build N variants v001..vN.", show_default=False
        ),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", metavar="SEED", help="The seed of the variants' values.")] = 0,
    students: Annotated[
        Path | None,
        typer.Option(
            "--students", metavar="ROSTER.csv", help="One variant per student (CSV: id,name).", show_default=False
        ),
    ] = None,
    workers: Annotated[
        int | None,
        typer.Option(
            "--workers", "-j", metavar="N", min=1, help="Worker processes (default: one per core).", show_default=False
        ),
    ] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(
            "--scheduler",
            metavar="ADDRESS",
            help="Build on a Dask distributed scheduler (needs tutgen[dask]).",
            show_default=False,
        ),
    ] = None,
    progress: Progress = None,
    method: Annotated[
        SheetMethod | None,
        typer.Option(
            "--method",
            "-m",
            metavar="METHOD",
            help="The formulations the worked solutions present, for every problem: lagrange, newton-euler "
            "or both (default: each problem spec's `methods:`, Lagrange unless it says otherwise).",
            show_default=False,
        ),
    ] = None,
    force: Annotated[bool, typer.Option("--force", help="Overwrite existing output files.")] = False,
    timeout: Annotated[
        float,
        typer.Option(
            "--timeout",
            metavar="SECONDS",
            min=0,
            help="Stop the run (reading, deriving and building the sheets) after this long (0: no limit).",
        ),
    ] = DEFAULT_TIMEOUT,
    quiet: Quiet = False,
) -> None:
    """Build the question sheet and the solution sheet of SHEET, and with --variants or --students a
    variant per student: its concrete specs, question and solution sheets and answer keys.

    Everything is derived and rendered first; nothing is written unless all of it succeeds, and then
    the whole output directory is put in place at once (an existing one is replaced only with --force).
    The same --seed gives the same variants, byte for byte, on any machine and any number of workers.
    """
    from tutgen.limits import deadline
    from tutgen.sheet.run import plan_sheet, run_sheet

    refuse_stdout("-o", output, "a sheet is a directory of files", "a directory")
    with deadline(timeout):  # one budget: reading the sheet, deriving, building
        plan = plan_sheet(
            sheet,
            output,
            formats=[f.value for f in formats or [SheetFormat.md]],
            variants=variants,
            students=students,
            force=force,
        )
        with _progress(plan.jobs, show_progress(progress, quiet, plan.jobs)) as advance:
            report = run_sheet(
                plan,
                seed=seed,
                workers=workers,
                scheduler=scheduler,
                timeout=timeout,
                method=method.value if method is not None else None,
                on_done=advance,
            )
    if not quiet:
        echo_error(report)


@contextmanager
def _progress(total: int, show: bool) -> Iterator[Callable[[], None] | None]:
    """A progress bar on stderr while the variants are built (:func:`tutgen.cli.options.show_progress`)."""
    if not show:
        yield None
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (TextColumn("building sheets"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("sheets", total=total)
        yield lambda: bar.advance(task)
