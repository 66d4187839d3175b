"""`python -m tutgen`."""

from tutgen.cli.main import run

run()
