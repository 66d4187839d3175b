"""`tutgen figure`: a spec's schematic alone, for slides and exams."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors
from tutgen.cli.options import Quiet
from tutgen.cli.stdio import refuse_stdout


@handle_errors
def figure(
    spec: Annotated[
        Path, typer.Argument(metavar="SPEC", help="The spec file (YAML; '-' for stdin).", show_default=False)
    ],
    output: Annotated[
        Path, typer.Option("--output", "-o", metavar="FILE", help="fig.svg, fig.tex or fig.pdf.", show_default=False)
    ],
    force: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
    body: Annotated[
        str | None,
        typer.Option(
            "--body", metavar="NAME", help="Draw the free-body diagram of this body instead.", show_default=False
        ),
    ] = None,
    quiet: Quiet = False,
) -> None:
    """Draw the schematic of SPEC (or, with --body, one body's free-body diagram) and write it as SVG, a
    LaTeX (TikZ) document or PDF, by -o's suffix."""
    from tutgen.api import plan_outputs, write_outputs
    from tutgen.errors import UsageError
    from tutgen.figure.view import FIGURE_FORMATS, render_figure

    refuse_stdout("-o", output, "the figure's format is chosen by the file's suffix (.svg, .tex, .pdf)")
    fmt = FIGURE_FORMATS.get(output.suffix.lower())
    if fmt is None:
        raise UsageError(f"-o {output}: expected a file ending in .svg, .tex or .pdf")
    targets = plan_outputs([spec], output, "pdf" if fmt == "pdf" else "tex", force=force)
    write_outputs(targets, [render_figure(spec, fmt, body)])
