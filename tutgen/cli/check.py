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


class Format(StrEnum):
    table = "table"
    json = "json"


@handle_errors
def check(
    spec: Annotated[Path, typer.Argument(help="The spec the answers are for (YAML).", show_default=False)],
    answers: Annotated[list[Path], typer.Argument(help="One or more answers files (YAML).", show_default=False)],
    format: Annotated[Format, typer.Option("--format", "-f", help="Report on stdout: a table or JSON.")] = Format.table,
    junit: Annotated[Path | None, typer.Option("--junit", help="Also write a JUnit XML report to FILE.")] = None,
    summary: Annotated[
        Path | None, typer.Option("--summary", help="Also write one row per answers file to FILE (.csv or .json).")
    ] = None,
    jobs: Annotated[
        int | None, typer.Option("--jobs", "-j", min=1, help="Worker processes (default: one per core).")
    ] = None,
    key: Annotated[
        Path | None,
        typer.Option("--key", help="The instructor's marking key (YAML): asked items, tolerances, scaling."),
    ] = None,
    timeout: Annotated[
        float,
        typer.Option("--timeout", min=0, help="Seconds per answer; past it: 'could not be checked' (0: no limit)."),
    ] = 5.0,
    file_timeout: Annotated[
        float,
        typer.Option("--file-timeout", min=0, help="Seconds per answers file; past it the file is stopped (0: none)."),
    ] = 120.0,
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
    """
    from tutgen.check.report import plan_reports, render_report, write_reports
    from tutgen.check.run import check as run_check

    targets = plan_reports(spec, [*answers, *([key] if key else [])], junit=junit, summary=summary)
    with _progress(len(answers)) as advance:
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
    _print(run.errors, render_report(run, format.value, color=sys.stdout.isatty()))
    raise typer.Exit(run.exit_code)


def _print(errors: list[str], report: str) -> None:
    """Errors of invalid answers files on stderr (file:line:col), the report on stdout; both without
    the control characters and escape sequences a student may have written."""
    from tutgen.safetext import terminal_text

    for error in errors:
        typer.echo(terminal_text(error), err=True)
    stdout_write(report)


@contextmanager
def _progress(total: int) -> Iterator[Callable[[], None] | None]:
    """A progress bar on stderr while several files are marked, only when stderr is a terminal."""
    if total < 2 or not sys.stderr.isatty():
        yield None
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (TextColumn("marking"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as progress:
        task = progress.add_task("marking", total=total)
        yield lambda: progress.advance(task)
