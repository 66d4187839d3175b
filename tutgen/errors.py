"""Every error tutgen reports to a user, with where it comes from.

The CLI boundary (``tutgen.cli``) is the only place that catches these: it prints ``str(err)``
to stderr and exits with ``err.exit_code``. Anything else that escapes is a bug.
"""

from __future__ import annotations

from dataclasses import dataclass, field

#: Documented exit codes (README, "Exit codes"). They are a public contract.
EXIT_OK = 0
EXIT_CHECK_FAILED = 1
EXIT_USAGE = 2
EXIT_INVALID_SPEC = 3
EXIT_CANNOT_DERIVE = 4
EXIT_METHODS_DISAGREE = 5
# 6 is tutgen.render.pdf.EXIT_PDF_FAILED
EXIT_SIMULATION_STOPPED = 7
EXIT_SIMULATION_CHECK = 8
EXIT_INTERNAL = 70


@dataclass(frozen=True, order=True)
class Location:
    """A 1-based position in a file (``col`` 0 means "the whole line", line 0 "the whole file")."""

    path: str
    line: int = 0
    col: int = 0

    def __str__(self) -> str:
        if self.line <= 0:
            return self.path
        if self.col <= 0:
            return f"{self.path}:{self.line}"
        return f"{self.path}:{self.line}:{self.col}"


class TutgenError(Exception):
    """Base class of every error meant for the user."""

    exit_code: int = EXIT_INTERNAL


@dataclass(frozen=True)
class SpecError(TutgenError, ValueError):
    """One problem in a spec, at one place: what was expected and what was found."""

    location: Location
    message: str
    hint: str | None = None
    exit_code: int = field(default=EXIT_INVALID_SPEC, compare=False)

    def __str__(self) -> str:
        text = f"{self.location}: error: {self.message}"
        if self.hint:
            text += f"\n  hint: {self.hint}"
        return text


class SpecErrors(TutgenError, ValueError):
    """Every problem found in one or more specs, sorted by position; raised once."""

    exit_code = EXIT_INVALID_SPEC

    def __init__(self, errors: list[SpecError]) -> None:
        unique = sorted(set(errors), key=lambda e: (e.location, e.message))
        self.errors: list[SpecError] = unique
        super().__init__("\n".join(str(e) for e in unique))

    def __str__(self) -> str:
        return "\n".join(str(e) for e in self.errors)


class LocatedError(TutgenError):
    """An error with a message and, where one is known, the place it is about (``file:line:col: error: …``)."""

    def __init__(self, message: str, location: Location | None = None) -> None:
        self.location = location
        self.message = message
        super().__init__(message)

    def __str__(self) -> str:
        where = f"{self.location}: " if self.location else ""
        return f"{where}error: {self.message}"


class DerivationError(LocatedError):
    """A valid spec that tutgen cannot derive (or a derivation that failed its own checks)."""

    exit_code = EXIT_CANNOT_DERIVE


class AgreementError(DerivationError):
    """Newton-Euler and Lagrange gave different equations of motion for a valid spec.

    The two routes are the same physics, so a difference is a tutgen bug; it is reported, never hidden.
    ``coordinate`` names the equation that differs.
    """

    exit_code = EXIT_METHODS_DISAGREE

    def __init__(self, message: str, location: Location | None = None, coordinate: str | None = None) -> None:
        self.coordinate = coordinate
        super().__init__(message, location)


class UsageError(TutgenError):
    """A command-line mistake that Click itself cannot see (e.g. -o would overwrite a spec)."""

    exit_code = EXIT_USAGE
    #: whether the text starts with its own ``file:line: error:`` (else the CLI puts "error: " in front)
    located = False


class TemplateError(UsageError):
    """An error in a user's template (``--template-dir``): its syntax, an undefined variable, something
    the sandbox refuses, a template that includes itself forever; located at the template's line."""

    located = True

    def __init__(self, location: Location, message: str) -> None:
        self.location = location
        self.message = message
        super().__init__(f"{location}: error: {message}")


class DerivationTimeout(DerivationError):
    """A run went past its time limit (``--timeout``); ``stage`` is the part of the run it was in
    ("derivation", "rendering", "LaTeX compile", …) and ``step`` where in it."""

    def __init__(self, seconds: float, step: str, stage: str = "derivation") -> None:
        self.seconds = seconds
        self.step = step
        self.stage = stage
        shown = f"{seconds:g}"
        if stage == "derivation":
            text = f"the derivation did not finish within {shown} s (it was at: {step})"
        else:
            # the budget is shared by the whole run: say so, the derivation may have used most of it
            text = (
                f"the run did not finish within {shown} s (--timeout covers load, derive and render; "
                f"it was at: {stage}, {step})"
            )
        super().__init__(f"{text}; simplify the spec or raise --timeout")

    def __reduce__(self) -> tuple[object, ...]:
        """Pickled with its own arguments (a sheet's worker sends it to the parent), and its location."""
        return type(self), (self.seconds, self.step, self.stage), self.__dict__


class SimulationError(LocatedError):
    """`tutgen simulate` could not integrate to the end: a singular mass matrix at a state along the way
    (the trajectory so far is written), the integrator failed, or ``--timeout`` ran out."""

    exit_code = EXIT_SIMULATION_STOPPED


class SimulationCheckError(SimulationError):
    """A simulation ran to the end but failed its own check: the energy of a system without dissipation
    or inputs drifted by more than 100 times the integrator's tolerance (the outputs are written)."""

    exit_code = EXIT_SIMULATION_CHECK


#: What a shell reports for a program stopped by SIGINT (128 + 2) and by SIGTERM (128 + 15).
EXIT_INTERRUPTED = 130
EXIT_TERMINATED = 143


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised as an exception (``tutgen.cli`` installs the handler) so that cleanup runs: a
    LaTeX compile's process group is killed, worker processes are stopped, temporary files removed.
    A :class:`KeyboardInterrupt`, so code that stops on Ctrl-C stops on it too."""

    exit_code = EXIT_TERMINATED


def raise_terminated(signum: int, frame: object) -> None:
    """A SIGTERM handler: raise :class:`Terminated`."""
    raise Terminated()
