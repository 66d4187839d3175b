"""The CLI boundary: user errors become a message on stderr and an exit code; bugs say so.

Every message goes through :func:`tutgen.safetext.terminal_text`: it may quote a title, a name or a
path the user wrote, and an escape sequence in one must not reach the terminal. Ctrl-C and SIGTERM
(raised as :class:`~tutgen.errors.Terminated` by the handler :func:`install_signal_handlers` sets)
end the run with 130 and 143, as a shell reports a program stopped by them, once the cleanup
(``finally`` blocks: LaTeX's process group, worker processes, temporary files) has run.
"""

from __future__ import annotations

import functools
import os
import signal
import sys
from collections.abc import Callable
from typing import ParamSpec, TypeVar

import typer

from tutgen.errors import EXIT_INTERNAL, EXIT_INTERRUPTED, Terminated, TutgenError, UsageError, raise_terminated
from tutgen.safetext import terminal_text

P = ParamSpec("P")
R = TypeVar("R")

_state = {"debug": False}

#: What a shell reports for a program stopped by SIGPIPE (128 + 13).
EXIT_BROKEN_PIPE = 141


def set_debug(on: bool) -> None:
    _state["debug"] = on


def install_signal_handlers() -> None:
    """SIGTERM raises :class:`~tutgen.errors.Terminated` (Python's default would end the process at
    once, with no cleanup), in the main thread, where signal handlers live."""
    try:
        signal.signal(signal.SIGTERM, raise_terminated)
    except ValueError:  # pragma: no cover - not the main thread (an embedding application)
        pass


def echo_error(text: str) -> None:
    """A message on stderr, safe for a terminal."""
    typer.echo(terminal_text(text), err=True)


def handle_errors(func: Callable[P, R]) -> Callable[P, R]:
    """Run a command; print TutgenError text and exit with its code; report anything else as a bug."""

    @functools.wraps(func)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return func(*args, **kwargs)
        except (typer.Exit, typer.Abort):
            raise
        except KeyboardInterrupt as err:
            if _state["debug"]:
                raise
            terminated = isinstance(err, Terminated)
            echo_error("terminated" if terminated else "interrupted")
            raise typer.Exit(Terminated.exit_code if terminated else EXIT_INTERRUPTED) from None
        except TutgenError as err:
            if _state["debug"]:
                raise
            # a spec error names its file and place itself; a usage error needs the word "error"
            plain = isinstance(err, UsageError) and not err.located
            echo_error(f"error: {err}" if plain else str(err))
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
            echo_error("error: the input is nested too deeply to process")
            raise typer.Exit(EXIT_INTERNAL) from None
        except Exception as err:
            if _state["debug"]:
                raise
            echo_error(
                f"internal error: {type(err).__name__}: {err}\n"
                "This is a bug in tutgen. Run the same command with --debug (tutgen --debug solve ...) "
                "for the traceback, and report it with the spec."
            )
            raise typer.Exit(EXIT_INTERNAL) from None

    return wrapper


def stdout_write(text: str) -> None:
    sys.stdout.write(text)
    sys.stdout.flush()
