"""`tutgen validate`: read and check spec and sheet files without deriving anything (for editors,
pre-commit hooks and CI; docs/course-ci.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors
from tutgen.cli.options import Quiet
from tutgen.cli.stdio import is_stdio, refuse_second_stdin


def is_sheet_file(path: Path) -> bool:
    """A sheet file has ``tutgen_sheet`` or ``problems`` at its top level (read by the safe loader; a
    file that is not a mapping, or not YAML at all, is left to the spec reader to report)."""
    from tutgen.errors import SpecErrors
    from tutgen.spec.loader import load_yaml_file

    try:
        data = load_yaml_file(path)[0]
    except SpecErrors:  # the spec reader reports it, located
        return False
    return isinstance(data, dict) and ("tutgen_sheet" in data or "problems" in data)


@handle_errors
def validate(
    files: Annotated[
        list[Path],
        typer.Argument(
            metavar="FILE...", help="Spec or sheet files (YAML); '-' reads one from stdin.", show_default=False
        ),
    ],
    quiet: Quiet = False,
) -> None:
    """Check spec and sheet FILES (a sheet with every spec it names) as `tutgen solve` and `tutgen sheet`
    read them, without deriving: every error at its file:line:col, then exit 3 if any file has one.
    Exit codes: 0 every file valid, 2 usage error, 3 an invalid file."""
    from tutgen.errors import SpecError, SpecErrors
    from tutgen.safetext import terminal_text
    from tutgen.sheet.model import load_sheet
    from tutgen.spec.loader import STDIN_NAME
    from tutgen.spec.validate import load_system

    refuse_second_stdin(files)
    errors: list[SpecError] = []
    for path in files:
        try:
            if is_sheet_file(path):
                load_sheet(path)
            else:
                load_system(path)
        except SpecErrors as exc:
            errors += exc.errors
            continue
        if not quiet:
            typer.echo(terminal_text(f"{STDIN_NAME if is_stdio(path) else path}: ok"))
    if errors:
        raise SpecErrors(errors)
