"""`tutgen solve`: specs in, worked solutions out."""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors, stdout_write
from tutgen.cli.options import Quiet
from tutgen.cli.stdio import is_stdio, refuse_second_stdin, refuse_unnamed, write_bytes_to_stdout
from tutgen.limits import DEFAULT_TIMEOUT


class Format(StrEnum):
    md = "md"
    tex = "tex"
    pdf = "pdf"
    json = "json"


class Method(StrEnum):
    both = "both"
    lagrange = "lagrange"
    newton_euler = "newton-euler"


@handle_errors
def solve(
    specs: Annotated[
        list[Path],
        typer.Argument(
            metavar="SPEC...", help="One or more spec files (YAML); '-' reads one from stdin.", show_default=False
        ),
    ],
    format: Annotated[
        Format, typer.Option("--format", "-f", metavar="FORMAT", help="Output format: md, tex, pdf or json.")
    ] = Format.md,
    output: Annotated[
        str | None,
        typer.Option(
            "--output",
            "-o",
            metavar="PATH",
            help="Output file (one spec) or directory (several specs, an existing directory, or a path "
            "ending in '/'); default stdout, and '-' is stdout too (one spec; a PDF only when not a terminal).",
            show_default=False,
        ),
    ] = None,
    force: Annotated[bool, typer.Option("--force", help="Overwrite existing output files.")] = False,
    method: Annotated[
        Method | None,
        typer.Option(
            "--method",
            "-m",
            metavar="METHOD",
            help="The formulations to present: lagrange, newton-euler or both (default: the spec's "
            "`methods:`, Lagrange unless it says otherwise). Lagrange's route always runs, and Newton-Euler "
            "is derived for its agreement check whenever the spec has bodies; its working is printed only "
            "when presented.",
            show_default=False,
        ),
    ] = None,
    timeout: Annotated[
        float,
        typer.Option(
            "--timeout",
            metavar="SECONDS",
            min=0,
            help="Stop a run (reading, deriving and rendering, one budget) that takes longer than this, "
            "saying which stage and step it was at (0: no limit).",
        ),
    ] = DEFAULT_TIMEOUT,
    template_dir: Annotated[
        Path | None,
        typer.Option(
            "--template-dir",
            metavar="DIR",
            help="Your own Jinja templates (solution.md.j2, solution.tex.j2, blocks/…), searched before "
            "the shipped ones and run sandboxed.",
            show_default=False,
        ),
    ] = None,
    expand: Annotated[
        bool,
        typer.Option(
            "--expand",
            help="JSON: also write out the entries of H, C, G, the equations of motion and the Christoffel "
            "symbols of a serial arm too large for them (by default its JSON gives them as results.program, "
            "with results.expanded false). Slow: tens of seconds for a fully symbolic 6-DOF arm.",
        ),
    ] = False,
    quiet: Quiet = False,
) -> None:
    """Derive the worked solution of each SPEC and write it as Markdown, LaTeX, PDF or JSON.

    All specs are read and derived first; nothing is written unless every one succeeds.
    Existing files are overwritten only with --force, and never a spec itself.
    A PDF is written only to a file: --format pdf needs -o.
    SPEC '-' is read from standard input (errors at <stdin>:line:col), and -o - is standard output.
    """
    from tutgen.api import check_output_path, figure_files, plan_outputs, plot_files, solve_and_derive, write_outputs
    from tutgen.errors import UsageError

    refuse_second_stdin(specs)
    to_stdout = output is None or is_stdio(output)
    if output is None and format is Format.pdf:
        raise UsageError("--format pdf writes a file: add -o FILE.pdf (or -o DIR/, or -o - for stdout)")
    if to_stdout and len(specs) > 1:
        raise UsageError("several specs need an output directory: add -o DIR")
    if not to_stdout:
        assert output is not None
        if any(is_stdio(spec) for spec in specs):
            check_output_path(Path(output))
            if len(specs) > 1 or Path(output).is_dir() or output.endswith("/"):
                refuse_unnamed("-", "each file in -o DIR is named after its spec")
        plan_outputs(specs, output, format.value, force=force)  # refuse early, before the slow part
    chosen = method.value if method is not None else None
    texts, derivations = solve_and_derive(specs, format.value, chosen, template_dir, timeout=timeout, expand=expand)
    if to_stdout:  # Markdown's figures are files beside the .md: on stdout the text alone, as always
        text = texts[0]
        if isinstance(text, bytes):
            write_bytes_to_stdout(text, "a PDF")
        else:
            stdout_write(text)
        return
    assert output is not None
    targets = plan_outputs(specs, output, format.value, force=force)
    if format is Format.md:  # the figures beside the .md (tutgen/figure; docs/figures.md)
        figures, contents = figure_files(specs, targets, force=force, derivations=derivations)
        targets, texts = targets + figures, [*texts, *contents]
    elif format in (Format.tex, Format.json):  # the plots of `ask: [simulation]` they name (docs/simulate.md)
        plots, contents = plot_files(specs, targets, derivations, force=force)
        targets, texts = targets + plots, [*texts, *contents]
    write_outputs(targets, texts)
