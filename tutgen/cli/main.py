"""The `tutgen` command: one Typer app, one module per command.

Only this package prints to the terminal or sets exit codes. Heavy modules (sympy, pydantic,
jinja2) are imported inside the commands, so `tutgen --help` stays fast.
"""

from __future__ import annotations

import gc
import os
import sys

import typer

from tutgen.cli import check, code, figure, schema_cmd, sheet, simulate, solve, validate
from tutgen.cli.errors import install_signal_handlers, set_debug
from tutgen.cli.help import Command
from tutgen.version import __version__

app = typer.Typer(
    name="tutgen",
    help="Worked solutions for rigid-body and robot dynamics problems, from a short YAML spec.",
    no_args_is_help=True,
    add_completion=True,  # --install-completion, --show-completion (docs/cli.md)
    pretty_exceptions_show_locals=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
    context_settings={"help_option_names": ["-h", "--help"]},  # -h as everywhere else
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"tutgen {__version__}")
        raise typer.Exit()


@app.callback()
def main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version."),
    debug: bool = typer.Option(False, "--debug", help="Show the Python traceback of internal errors."),
) -> None:
    """Worked solutions for rigid-body and robot dynamics problems, from a short YAML spec.

    Exit codes: 0 ok, 1 answers wrong (check), 2 usage error, 3 invalid spec,
    4 valid spec that tutgen cannot derive, 7 simulation stopped early,
    8 simulation failed its energy check, 70 internal error, 130 interrupted, 143 terminated.
    """
    set_debug(debug)
    install_signal_handlers()
    stdin = sys.modules.get("tutgen.spec.stdin")
    if stdin is not None:  # stdin ('-') is read once per command: a new command reads it afresh
        stdin.forget_stdin()


app.command(name="solve", cls=Command)(solve.solve)
app.command(name="schema", cls=Command)(schema_cmd.schema)
app.command(name="check", cls=Command)(check.check)
app.command(name="sheet", cls=Command)(sheet.sheet)
app.command(name="figure", cls=Command)(figure.figure)  # tutgen/cli/figure.py
app.command(name="validate", cls=Command)(validate.validate)  # tutgen/cli/validate.py
app.command(name="simulate", cls=Command)(
    simulate.simulate
)  # tutgen/cli/simulate.py (scipy, matplotlib imported inside)
app.command(name="code", cls=Command)(code.code)  # tutgen/cli/code.py


#: entries of sympy's cache of results (its own default: 1 000), read from ``SYMPY_CACHE_SIZE`` when sympy is
#: first imported: a command that prints thousands of expressions (a sheet's variants) computed again what
#: had fallen out of it. 10 000: about 7 % less CPU for a sheet of 20 variants, 9 MB more memory (issue 17)
SYMPY_CACHE_SIZE = 10_000

#: What the commands set in their environment before they import sympy and numpy, unless the user set it:
#: sympy's cache (above), and one BLAS thread (tutgen's numbers are 3 x 3 to 12 x 12 matrices; OpenBLAS's
#: pool of threads cost about 0.08 s of CPU per command, and a sheet's workers competed with it)
ENVIRONMENT = {"SYMPY_CACHE_SIZE": str(SYMPY_CACHE_SIZE), "OPENBLAS_NUM_THREADS": "1"}


def prepare_environment() -> None:
    """Set :data:`ENVIRONMENT` where the user did not, before sympy or numpy is imported (each reads its
    variable once, then). Results never depend on it, only the time they take."""
    if "sympy" in sys.modules or "numpy" in sys.modules:
        return
    for name, value in ENVIRONMENT.items():
        os.environ.setdefault(name, value)


#: the collector's first threshold (Python's default is 700): sympy and the exact polynomials allocate
#: millions of short-lived objects, almost none in reference cycles, and every 700 allocations the young
#: generation was traversed for nothing (issue 17: 0.1-0.15 s CPU of the symbolic PUMA's 2.7 s)
GC_THRESHOLD = 10_000


def run() -> None:
    """Console-script entry point. sympy is imported inside the commands: its cache is sized first
    (:func:`prepare_environment`).

    The cyclic garbage collector runs less often (:data:`GC_THRESHOLD`), and when the command is done,
    every object left is frozen (``gc.freeze``) so that the interpreter's exit does not traverse them all
    once more (0.15 s after a large arm's derivation); reference counting still frees them, and nothing of
    tutgen's needs a collection to be written out (files are closed when written).
    """
    prepare_environment()
    gc.set_threshold(GC_THRESHOLD, *gc.get_threshold()[1:])
    try:
        app(prog_name="tutgen")
    finally:
        gc.freeze()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(run())
