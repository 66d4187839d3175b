"""`tutgen code`: the derived model as Python/NumPy, C, MATLAB or Julia functions (docs/code.md)."""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors, stdout_write
from tutgen.cli.options import Quiet
from tutgen.cli.stdio import is_stdio, refuse_unnamed
from tutgen.limits import DEFAULT_TIMEOUT


class Language(StrEnum):
    python = "python"
    c = "c"
    matlab = "matlab"
    julia = "julia"


@handle_errors
def code(
    spec: Annotated[
        Path, typer.Argument(metavar="SPEC", help="The spec file (YAML; '-' for stdin).", show_default=False)
    ],
    lang: Annotated[
        Language, typer.Option("--lang", "-l", metavar="LANGUAGE", help=f"Target language: {', '.join(Language)}.")
    ] = Language.python,
    output: Annotated[
        str | None,
        typer.Option(
            "--output",
            "-o",
            metavar="PATH",
            help="Output file, or a directory (existing, or ending in '/'); default stdout ('-' too).",
            show_default=False,
        ),
    ] = None,
    force: Annotated[bool, typer.Option("--force", help="Overwrite an existing output file.")] = False,
    linear: Annotated[
        bool, typer.Option("--linear", help="Also the linear model about an equilibrium: K(q) and D(q).")
    ] = False,
    timeout: Annotated[
        float, typer.Option("--timeout", metavar="SECONDS", min=0, help="Stop a run that takes longer (0: no limit).")
    ] = DEFAULT_TIMEOUT,
    quiet: Quiet = False,
) -> None:
    """Write H(q), C q_dot, C, G(q), Q, U, inverse and forward dynamics of SPEC as functions in --lang.

    Common subexpressions are shared; parameters with a value in the spec are defaults. Only
    declared names reach the code (a keyword of the language is renamed, as the header says).
    """
    from tutgen.api import check_output_path, write_outputs
    from tutgen.codegen.run import code_for_spec, plan_code_output

    if output is not None and is_stdio(output):
        output = None
    if output is not None and is_stdio(spec):
        check_output_path(Path(output))
        if Path(output).is_dir() or output.endswith("/"):
            refuse_unnamed(spec, "-o DIR names the file after the spec")
    target = plan_code_output(spec, output, lang.value, force=force) if output is not None else None
    text = code_for_spec(spec, lang.value, timeout=timeout or None, linear=linear)
    if target is None:
        stdout_write(text)
        return
    write_outputs([target], [text])
