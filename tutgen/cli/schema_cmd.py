"""`tutgen schema`: the JSON Schemas of the files tutgen reads and writes (tutgen/schemas.py)."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors, stdout_write


class Kind(StrEnum):
    spec = "spec"
    sheet = "sheet"
    solution = "solution"


@handle_errors
def schema(
    kind: Annotated[
        Kind,
        typer.Option(
            "--kind",
            "-k",
            help="Which file: a spec, a sheet, or the JSON of `tutgen solve --format json` (solution).",
        ),
    ] = Kind.spec,
) -> None:
    """Print the JSON Schema (draft 2020-12) of a file tutgen reads or writes, for editors and scripts:
    completion and checking of specs and sheets, validation of the solution JSON. Each has an $id
    urn:tutgen:schema:KIND:VERSION."""
    from tutgen.render.jsonout import dumps
    from tutgen.schemas import SCHEMAS

    stdout_write(dumps(SCHEMAS[kind.value]()))
