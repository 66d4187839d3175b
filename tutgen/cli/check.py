"""`tutgen check`: mark answers files against the results of a spec."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors, stdout_write
from tutgen.cli.options import Progress, show_progress
from tutgen.cli.stdio import is_stdio, refuse_second_stdin, refuse_stdout


class Format(StrEnum):
    table = "table"
    json = "json"


@handle_errors
def check(
    spec: Annotated[
        Path,
        typer.Argument(metavar="SPEC", help="The spec the answers are for (YAML; '-' for stdin).", show_default=False),
    ],
    answers: Annotated[
        list[Path],
        typer.Argument(
            metavar="ANSWERS...", help="One or more answers files (YAML; '-' for stdin).", show_default=False
        ),
    ],
    format: Annotated[
        Format,
        typer.Option("--format", "-f", metavar="FORMAT", help=f"Report on stdout: {' or '.join(Format)}."),
    ] = Format.table,
    junit: Annotated[
        Path | None,
        typer.Option("--junit", metavar="FILE", help="Also write a JUnit XML report to FILE.", show_default=False),
    ] = None,
    summary: Annotated[
        Path | None,
        typer.Option(
            "--summary",
            metavar="FILE",
            help="Also write one row per answers file to FILE (.csv or .json).",
            show_default=False,
        ),
    ] = None,
    jobs: Annotated[
        int | None,
        typer.Option(
            "--jobs", "-j", metavar="N", min=1, help="Worker processes (default: one per core).", show_default=False
        ),
    ] = None,
    key: Annotated[
        Path | None,
        typer.Option(
            "--key",
            metavar="FILE",
            help="The instructor's marking key (YAML): asked items, tolerances, scaling.",
            show_default=False,
        ),
    ] = None,
    timeout: Annotated[
        float,
        typer.Option(
            "--timeout",
            metavar="SECONDS",
            min=0,
            help="Seconds per answer; past it: 'could not be checked' (0: no limit).",
        ),
    ] = 5.0,
    file_timeout: Annotated[
        float,
        typer.Option(
            "--file-timeout",
            metavar="SECONDS",
            min=0,
            help="Seconds per answers file; past it the file is stopped (0: none).",
        ),
    ] = 120.0,
    progress: Progress = None,
    quiet: Annotated[
        bool,
        typer.Option(
            "--quiet",
            "-q",
            help="Print errors only: no progress bar, no table (the exit code, --junit, --summary and "
            "--format json still report).",
        ),
    ] = False,
) -> None:
    """Check ANSWERS files against the results tutgen derives for SPEC.

    Answers are compared for equivalence, not text: expanded, factored or trigonometrically
    rewritten expressions are right; equations of motion may be rearranged or scaled. The spec is
    derived once; several answers files are marked in parallel. Reports and JUnit/summary files
    are written only when everything has been marked (existing report files are replaced).

    Tolerances and the items graded are the instructor's (--key), never an answers file's. Every
    file is marked in its own process, bounded by --timeout per answer and --file-timeout per file.

    Exit codes: 0 every answer correct, 1 an answer wrong or missing (or not evaluable, or out of
    time), 2 usage error, 3 invalid spec, key or answers file, 4 spec that tutgen cannot derive,
    70 a bug; with several files, the worst file's.

    One of SPEC, ANSWERS and --key may be '-', read from standard input (errors at <stdin>:line:col).
    """
    from tutgen.check.report import plan_reports, render_report, write_reports
    from tutgen.check.run import check as run_check
    from tutgen.errors import SpecErrors
    from tutgen.spec.loader import load_yaml_file
    from tutgen.spec.stdin import STDIN

    refuse_second_stdin([spec, *answers, key])
    refuse_stdout("--junit", junit, "standard output holds the report")
    refuse_stdout("--summary", summary, "standard output holds the report")
    if any(is_stdio(a) for a in answers):
        try:  # read here, once, not by the marking process that forks for the file
            load_yaml_file(STDIN)
        except SpecErrors:
            pass  # that process reports it, as the file's error
    targets = plan_reports(spec, [*answers, *([key] if key else [])], junit=junit, summary=summary)
    with _progress(show_progress(progress, quiet, len(answers)), len(answers)) as advance:
        run = run_check(
            spec,
            answers,
            jobs=jobs,
            on_done=advance,
            key=key,
            answer_timeout=timeout or None,
            file_timeout=file_timeout or None,
        )
    write_reports(run, targets)
    quiet_table = quiet and format is Format.table
    _print(run.errors, "" if quiet_table else render_report(run, format.value, color=sys.stdout.isatty()))
    raise typer.Exit(run.exit_code)


def _print(errors: list[str], report: str) -> None:
    """Errors of invalid answers files on stderr (file:line:col), the report on stdout; both without
    the control characters and escape sequences a student may have written."""
    from tutgen.safetext import terminal_text

    for error in errors:
        typer.echo(terminal_text(error), err=True)
    stdout_write(report)


@contextmanager
def _progress(show: bool, total: int) -> Iterator[Callable[[], None] | None]:
    """A progress bar on stderr while the files are marked (see :func:`tutgen.cli.options.show_progress`)."""
    if not show:
        yield None
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (TextColumn("marking"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("marking", total=total)
        yield lambda: bar.advance(task)
