"""The verdicts of `tutgen check` and what answers are compared with (a :class:`Reference`).

An entry (one scalar of an answer) is correct, wrong, missing, "cannot be evaluated" or "could not
be checked (time limit)"; an item (one answer, or one item the instructor asks for) has the worst of
its entries' verdicts (:func:`worst`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

import sympy as sp

from tutgen.check.key import MarkingKey
from tutgen.render.printer import SIGNIFICANT_FIGURES

__all__ = [
    "ASKED_RESULTS",
    "DEFAULT_ANSWER_TIMEOUT",
    "PRINTED_FIGURES",
    "EntryResult",
    "ItemResult",
    "Reference",
    "Status",
    "derived_ask",
    "reference_from",
    "worst",
]

#: The significant figures of the decimals in a worked solution when the spec does not say.
PRINTED_FIGURES = SIGNIFICANT_FIGURES
#: Seconds one answer (one entry) may take to mark (``tutgen check --timeout``).
DEFAULT_ANSWER_TIMEOUT = 5.0
#: What a spec's ``ask`` asks for, as result keys: the items a file with no answer is missing.
ASKED_RESULTS = {
    "inertia": ("inertia_tensor",),
    "kinetic_energy": ("kinetic_energy",),
    "potential_energy": ("potential_energy",),
    "lagrangian": ("lagrangian",),
    "lagrange_equations": ("lagrange_terms",),
    "equations_of_motion": ("equations_of_motion",),
    "matrix_form": ("mass_matrix", "coriolis_vector", "gravity_vector"),
    "christoffel": ("christoffel",),
    "steady_motion": ("steady_motion",),
}


class Status(StrEnum):
    """The verdict on an entry or an item. An item has the worst of its entries', in this order:
    wrong, time_limit, cannot_evaluate, missing, correct."""

    CORRECT = "correct"
    WRONG = "wrong"
    MISSING = "missing"
    CANNOT_EVALUATE = "cannot_evaluate"  # not finite, not real or lost to cancellation at most states
    TIME_LIMIT = "time_limit"  # could not be checked within the time (or memory) limit


#: Worst first: the status an item takes from its entries.
_SEVERITY = (Status.WRONG, Status.TIME_LIMIT, Status.CANNOT_EVALUATE, Status.MISSING)


def worst(statuses: list[Status]) -> Status:
    """The worst of ``statuses`` (correct when there are none to worry about)."""
    for status in _SEVERITY:
        if status in statuses:
            return status
    return Status.CORRECT


@dataclass(frozen=True)
class EntryResult:
    """The verdict on one entry (a scalar) of an answer."""

    name: str  # as in the reports: mass_matrix[1,2]
    status: Status
    how: str = ""  # how a correct entry was decided ("exact: ...", "numeric: ...", "within rel_tol ...")
    feedback: str = ""  # what differs (wrong), what is missing, or a remark
    location: str = ""  # file:line:col of the answer
    given: str | None = None  # the answer as written
    expected: str | None = None  # the result, as in tutgen's JSON


@dataclass(frozen=True)
class ItemResult:
    """The verdict on one answer of the file (a top-level key): the worst of its entries."""

    name: str
    status: Status
    entries: tuple[EntryResult, ...]
    remarks: tuple[str, ...] = ()
    location: str = ""

    @property
    def problems(self) -> tuple[EntryResult, ...]:
        """The entries that are wrong or missing."""
        return tuple(e for e in self.entries if e.status is not Status.CORRECT)


@dataclass(frozen=True, eq=False)
class Reference:
    """What answers are compared with: one spec's results and the names its expressions use.

    Plain data and sympy symbols only, so it can be sent to worker processes. Compared by identity,
    so that each process parses a reference's result expressions once (:func:`_result_cache`).
    """

    spec: str
    title: str
    results: dict[str, Any]
    symbols: dict[str, sp.Symbol]
    values: dict[sp.Symbol, sp.Expr]
    coordinates: tuple[str, ...]
    state: frozenset[sp.Symbol]  # every q, q_dot, q_ddot
    forces: frozenset[sp.Symbol] = field(default_factory=frozenset)  # symbols of the generalized forces
    asked: tuple[str, ...] = ()  # result keys the spec asks for (its ``ask``), those it has
    key: MarkingKey = field(default_factory=MarkingKey)  # the instructor's marking key
    figures: int = PRINTED_FIGURES  # the significant figures the spec's solution prints decimals with
    answer_timeout: float | None = DEFAULT_ANSWER_TIMEOUT  # seconds per entry (None: no limit)
    angles: frozenset[str] = frozenset()  # the coordinates that are angles (a steady value up to 2 pi)


def reference_from(system: Any, derivation: Any, spec: str) -> Reference:
    """The :class:`Reference` of a derived spec (a System and its Derivation)."""
    from tutgen.render.jsonout import derivation_to_json

    doc = derivation_to_json(derivation)
    symbols: dict[str, sp.Symbol] = {p.name: p.symbol for p in system.parameters}
    state: set[sp.Symbol] = set()
    for c in system.coordinates:
        symbols[c.name], symbols[f"{c.name}_dot"], symbols[f"{c.name}_ddot"] = c.q, c.qd, c.qdd
        state |= {c.q, c.qd, c.qdd}
    forces: set[sp.Symbol] = set()
    if derivation.generalized_forces is not None:
        forces = set(derivation.generalized_forces.free_symbols) - state
    return Reference(
        spec=spec,
        title=system.title,
        results=doc["results"],
        symbols=symbols,
        values=dict(system.values),
        coordinates=tuple(c.name for c in system.coordinates),
        state=frozenset(state),
        forces=frozenset(forces),
        asked=derived_ask(system, doc["results"]),
        figures=getattr(system, "significant_figures", None) or PRINTED_FIGURES,
        angles=frozenset(c.name for c in system.coordinates if c.dimension == "angle"),
    )


def derived_ask(system: Any, results: dict[str, Any]) -> tuple[str, ...]:
    """The items marked when no marking states them, from the spec's ``ask`` (docs/check.md): each
    asked step's results (:data:`ASKED_RESULTS`) that this spec has, in the order of the results,
    without what the problem gives (a kinetic or potential energy stated in ``energy:``) and without
    a gravity vector that is zero (nothing to answer)."""
    wanted = {r for a in system.ask for r in ASKED_RESULTS.get(str(a), ())}
    if getattr(system, "kinetic_energy", None) is not None:
        wanted.discard("kinetic_energy")
    if getattr(system, "potential_energy", None) is not None:
        wanted.discard("potential_energy")
    if all(str(g).strip() == "0" for g in results.get("gravity_vector") or ()):
        wanted.discard("gravity_vector")
    return tuple(k for k in results if k in wanted)


# ---------------------------------------------------------------------------------------------
# Marking one answers file
# ---------------------------------------------------------------------------------------------
