"""What the instructor marks: the items graded, the tolerance of numbers, the rules per item.

One value serves every place a marking can be stated: a spec's ``marking:`` section, a sheet's (copied
into each variant's ``marking-<problem>.yaml``) and a marking key file (``tutgen check --key``). They
are read by :func:`tutgen.spec.builders.marking.read_marking`; :mod:`tutgen.check` marks by them
(docs/check.md, "The marking key").

Result keys are paths into the ``results`` of tutgen's JSON (``mass_matrix``, ``mass_matrix[1,2]``,
``lagrange_terms[2].dL_dq``), kept as the text written and its parsed :data:`Segment` steps.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from tutgen.errors import Location

__all__ = ["DEFAULT_ABS_TOL", "DEFAULT_REL_TOL", "KeyRule", "Marking", "Segment", "Tolerance"]

#: Default relative tolerance of a numeric answer (tutgen's numbers are exact or 12+ digits).
DEFAULT_REL_TOL = 1e-9
#: Default absolute tolerance of a numeric answer (what "zero" means for a number).
DEFAULT_ABS_TOL = 1e-12

#: One step of a key path: a name (a result key, a body, a coordinate) or a group of 1-based indices.
Segment = str | tuple[int, ...]


@dataclass(frozen=True)
class Tolerance:
    """How close a numeric answer must be. A field left None takes the file's, then the default.

    A number ``a`` is right when ``|a - r| <= max(abs_tol, rel_tol * |r|)`` for the result ``r``.
    With ``rounded`` a number written as a literal must instead be ``r`` rounded half-up to the
    significant figures the literal shows (``3.46e-3`` for 3.4676e-3 is wrong: it rounds to 3.47e-3).
    """

    rel_tol: float | None = None
    abs_tol: float | None = None
    rounded: bool | None = None

    def over(self, base: Tolerance) -> Tolerance:
        """This tolerance, with the fields it leaves open taken from ``base``."""
        return Tolerance(
            self.rel_tol if self.rel_tol is not None else base.rel_tol,
            self.abs_tol if self.abs_tol is not None else base.abs_tol,
            self.rounded if self.rounded is not None else base.rounded,
        )

    @property
    def is_set(self) -> bool:
        return self.rel_tol is not None or self.abs_tol is not None or self.rounded is not None

    @property
    def rel(self) -> float:
        return DEFAULT_REL_TOL if self.rel_tol is None else self.rel_tol

    @property
    def abs(self) -> float:
        return DEFAULT_ABS_TOL if self.abs_tol is None else self.abs_tol


@dataclass(frozen=True)
class KeyRule:
    """The rule of one item or entry: a tolerance and whether equations may be scaled."""

    key: str
    segments: tuple[Segment, ...]
    tolerance: Tolerance = field(default_factory=Tolerance)
    scaling: bool | None = None
    location: Location = field(default_factory=lambda: Location("<key>"))


@dataclass(frozen=True)
class Marking:
    """A marking: the items graded (``ask``), the default tolerance, the rules per item, and the
    significant figures from which a written decimal counts as the result rounded.

    ``ask`` None grades the items a file answers (a library caller's choice; ``tutgen check`` always
    has an ask: the key's, the spec's ``marking:``, or the one derived from the spec's ``ask``).
    ``source`` says where the marking was stated: ``key`` (a key file), ``spec`` (a spec's or sheet's
    ``marking:``), ``derived`` (from the spec's ``ask``: no marking was stated), ``answered`` (none).
    ``significant_figures`` None takes the spec's (how its solution prints decimals); 0 turns off.
    """

    path: str | None = None
    ask: tuple[tuple[str, tuple[Segment, ...], Location], ...] | None = None  # (key, segments, location)
    tolerance: Tolerance = field(default_factory=Tolerance)
    rules: tuple[KeyRule, ...] = field(default_factory=tuple)
    significant_figures: int | None = None
    source: str = "key"

    @property
    def is_stated(self) -> bool:
        """Whether an instructor stated this marking (a key or a ``marking:`` section)."""
        return self.source in ("key", "spec")
