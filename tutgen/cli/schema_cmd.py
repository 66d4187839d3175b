"""`tutgen schema`: the JSON Schema of the spec format."""

from __future__ import annotations

from tutgen.cli.errors import handle_errors, stdout_write


@handle_errors
def schema() -> None:
    """Print the JSON Schema of the spec format (for editors: completion and checking)."""
    from tutgen.render.jsonout import dumps
    from tutgen.spec.schema import json_schema

    stdout_write(dumps(json_schema()))
