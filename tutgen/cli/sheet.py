"""`tutgen sheet`: a tutorial sheet (questions and worked solutions), and a variant per student."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import echo_error, handle_errors
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
    sheet: Annotated[Path, typer.Argument(help="The sheet file (YAML).", show_default=False)],
    output: Annotated[
        str | None,
        typer.Option(
            "--output", "-o", metavar="DIR", help="The directory to write into (required).", show_default=False
        ),
    ] = None,
    formats: Annotated[
        list[SheetFormat] | None,
        typer.Option("--format", "-f", help="Output format; repeat for several (default md)."),
    ] = None,
    variants: Annotated[
        int | None,
        typer.Option("--variants", "-n", min=1, max=10_000, help="Build N variants v001..vN.", show_default=False),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="The seed of the variants' values.")] = 0,
    students: Annotated[
        Path | None,
        typer.Option(
            "--students", metavar="ROSTER.csv", help="One variant per student (CSV: id,name).", show_default=False
        ),
    ] = None,
    workers: Annotated[
        int | None,
        typer.Option("--workers", "-j", min=1, help="Worker processes (default: one per core).", show_default=False),
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
    progress: Annotated[
        bool | None,
        typer.Option("--progress/--no-progress", help="A progress bar on stderr (default: when it is a terminal)."),
    ] = None,
    method: Annotated[
        SheetMethod | None,
        typer.Option(
            "--method",
            "-m",
            help="The formulations the worked solutions present, for every problem: Lagrange, Newton-Euler, "
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
) -> None:
    """Build the question sheet and the solution sheet of SHEET, and with --variants or --students a
    variant per student: its concrete specs, question and solution sheets and answer keys.

    Everything is derived and rendered first; nothing is written unless all of it succeeds, and then
    the whole output directory is put in place at once (an existing one is replaced only with --force).
    The same --seed gives the same variants, byte for byte, on any machine and any number of workers.
    """
    from tutgen.limits import deadline
    from tutgen.sheet.run import plan_sheet, run_sheet

    with deadline(timeout):  # one budget: reading the sheet, deriving, building
        plan = plan_sheet(
            sheet,
            output,
            formats=[f.value for f in formats or [SheetFormat.md]],
            variants=variants,
            students=students,
            force=force,
        )
        with _progress(plan.jobs, progress) as advance:
            report = run_sheet(
                plan,
                seed=seed,
                workers=workers,
                scheduler=scheduler,
                timeout=timeout,
                method=method.value if method is not None else None,
                on_done=advance,
            )
    echo_error(report)


@contextmanager
def _progress(total: int, wanted: bool | None) -> Iterator[Callable[[], None] | None]:
    show = wanted if wanted is not None else (total > 1 and sys.stderr.isatty())
    if not show:
        yield None
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (TextColumn("building sheets"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("sheets", total=total)
        yield lambda: bar.advance(task)
