"""`tutgen schema`: the JSON Schemas of the files tutgen reads and writes (tutgen/schemas.py)."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

from tutgen.cli.errors import handle_errors, stdout_write
from tutgen.schemas import SCHEMAS

#: The kinds of file, as ``tutgen.schemas.SCHEMAS`` names them (that module imports nothing heavy)
Kind = StrEnum("Kind", {kind: kind for kind in SCHEMAS})
DEFAULT_KIND = Kind("spec")


@handle_errors
def schema(
    kind: Annotated[
        Kind,
        typer.Option(
            "--kind",
            "-k",
            metavar="KIND",
            help="Which file: spec, sheet, answers, key (a marking key), or an output: solution (tutgen solve "
            "--format json), check (tutgen check --format json), summary (--summary FILE.json), simulation "
            "(tutgen simulate's JSON).",
        ),
    ] = DEFAULT_KIND,
) -> None:
    """Print the JSON Schema (draft 2020-12) of a file tutgen reads or writes, for editors and scripts:
    completion and checking of specs, sheets, answers files and marking keys, validation of the JSON
    tutgen writes. Each has an $id urn:tutgen:schema:KIND:VERSION, and each JSON output its "format"
    VERSION. The same schemas are shipped in schemas/KIND.schema.json."""
    from tutgen.render.jsonout import dumps

    stdout_write(dumps(SCHEMAS[kind.value]()))
