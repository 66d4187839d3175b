"""Options that mean the same on every command, declared once so that their names and help agree
(docs/cli.md): ``--quiet``/``-q`` and ``--progress``/``--no-progress``."""

from __future__ import annotations

import sys
from typing import Annotated

import typer

#: ``--quiet``: errors only. The output asked for (a solution or code on standard output, ``-o``'s
#: files, ``check --format json``) is still written; status lines, summaries and progress bars are not.
Quiet = Annotated[
    bool,
    typer.Option(
        "--quiet",
        "-q",
        help="Print errors only: no progress bar, no status or summary lines (the output asked for is still written).",
    ),
]

#: ``--progress``/``--no-progress``: the progress bar on stderr; by default drawn when stderr is a terminal.
Progress = Annotated[
    bool | None,
    typer.Option(
        "--progress/--no-progress",
        help="A progress bar on stderr (default: when stderr is a terminal and there is more than one job).",
        show_default=False,
    ),
]


def show_progress(wanted: bool | None, quiet: bool, total: int) -> bool:
    """Whether to draw a progress bar: never when quiet, as asked with --progress/--no-progress, and
    otherwise for more than one job on a terminal."""
    if quiet:
        return False
    if wanted is not None:
        return wanted
    return total > 1 and sys.stderr.isatty()
