"""The CLI boundary: user errors become a message on stderr and an exit code; bugs say so."""

from __future__ import annotations

import functools
import os
import sys
from collections.abc import Callable
from typing import ParamSpec, TypeVar

import typer

from tutgen.errors import EXIT_INTERNAL, TutgenError, UsageError

P = ParamSpec("P")
R = TypeVar("R")

_state = {"debug": False}

#: What a shell reports for a program stopped by SIGPIPE (128 + 13).
EXIT_BROKEN_PIPE = 141


def set_debug(on: bool) -> None:
    _state["debug"] = on


def handle_errors(func: Callable[P, R]) -> Callable[P, R]:
    """Run a command; print TutgenError text and exit with its code; report anything else as a bug."""

    @functools.wraps(func)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return func(*args, **kwargs)
        except (typer.Exit, typer.Abort, KeyboardInterrupt):
            raise
        except TutgenError as err:
            if _state["debug"]:
                raise
            # a spec error names its file and place itself; a usage error needs the word "error"
            typer.echo(f"error: {err}" if isinstance(err, UsageError) else str(err), err=True)
            raise typer.Exit(err.exit_code) from None
        except BrokenPipeError:
            # the reader went away (`tutgen solve spec.yaml | head`): not an error of ours; stop quietly,
            # and keep Python from complaining again when it flushes stdout at exit
            try:
                os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            except (OSError, ValueError):  # pragma: no cover - stdout is not a real file
                pass
            raise typer.Exit(EXIT_BROKEN_PIPE) from None
        except RecursionError:
            if _state["debug"]:
                raise
            typer.echo("error: the input is nested too deeply to process", err=True)
            raise typer.Exit(EXIT_INTERNAL) from None
        except Exception as err:
            if _state["debug"]:
                raise
            typer.echo(
                f"internal error: {type(err).__name__}: {err}\n"
                "This is a bug in tutgen. Run the same command with --debug (tutgen --debug solve ...) "
                "for the traceback, and report it with the spec.",
                err=True,
            )
            raise typer.Exit(EXIT_INTERNAL) from None

    return wrapper


def stdout_write(text: str) -> None:
    sys.stdout.write(text)
    sys.stdout.flush()
