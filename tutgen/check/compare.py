"""Marking one answers file against one spec's results: equivalence, not string equality.

The results are the ``results`` of tutgen's JSON output (the public contract), parsed back with the
spec grammar's parser; answers are parsed by the same parser with the same names. The modules:

- :mod:`tutgen.check.equivalence`: the decision procedure (exact by expansion or trigonometric
  normal form, else at random states), the size limits, constant factors;
- :mod:`tutgen.check.numeric`: high-precision evaluation at random states;
- :mod:`tutgen.check.feedback`: what differs, in words;
- :mod:`tutgen.check.names`: entry names and what each result field holds;
- :mod:`tutgen.check.key`: the instructor's marking key (asked items, tolerances, scaling);
- this module: walking an answer and its result together, entry by entry, and the verdicts.

Rules (docs/check.md): numbers are equal within the instructor's tolerance; a number with a unit is
converted to SI and its dimension checked where the result's dimension is known. An equation of
motion may be written ``lhs = rhs`` and is accepted up to moving terms across the ``=`` and up to a
constant factor in [1e-6, 1e6] (a number or a product of parameters), reported as "scaled by k". A
Christoffel table in the other convention is accepted with a remark; so are principal axes that
point the other way. Each entry is named as in the reports: ``mass_matrix[1,2]``.
"""

from __future__ import annotations

import re
import weakref
from dataclasses import dataclass, field, replace
from decimal import Decimal
from enum import StrEnum
from typing import Any

import mpmath
import sympy as sp

from tutgen.check.answers import MSG_NO_TOLERANCE, TOLERANCE_KEYS, AnswerItem, AnswerSheet, Segment, Tolerance
from tutgen.check.equivalence import (
    MAX_SCALE,
    MIN_SCALE,
    NUMERIC_HOW,
    Decision,
    constant_factor,
    decide,
    groups,
    is_acceptable_scale,
    reduced,
    too_large,
)
from tutgen.check.feedback import diagnose, number_feedback, round_half_up, significant
from tutgen.check.key import MarkingKey
from tutgen.check.limits import AnswerTimeLimit, answer_deadline
from tutgen.check.names import DIMENSION_OF, TEXT_FIELDS, Path, entry_name, field_of, is_per_coordinate
from tutgen.check.numeric import SEED, TRIALS, value_of_number
from tutgen.errors import SpecError, SpecErrors
from tutgen.render.jsonout import expr_text  # the spec grammar, as the JSON writes it
from tutgen.spec.expr import ExprError, did_you_mean, number_to_rational, parse_expression
from tutgen.spec.loader import KeyPath
from tutgen.spec.units import Dimension, parse_quantity, parse_unit

__all__ = [
    "ASKED_RESULTS",
    "DEFAULT_ANSWER_TIMEOUT",
    "NUMERIC_HOW",
    "SEED",
    "TRIALS",
    "EntryResult",
    "ItemResult",
    "Reference",
    "Status",
    "check_sheet",
    "diagnose",
    "entry_name",
    "equal_how",
    "expr_text",
    "reference_from",
]

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
}
_NUMBER_RE = re.compile(r"\s*[-+]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")
_CHRISTOFFEL_KEY_RE = re.compile(
    r"[A-Za-z]?\[?\s*([0-9]+)\s*,\s*([0-9]+)\s*,\s*([0-9]+)\s*\]?"  # 1,1,2  h[1,1,2]
    r"|[A-Za-z]?([1-9])([1-9])([1-9])"  # 112  h112  c112
)
_OTHER_TABLE = {"christoffel": "christoffel_first_kind", "christoffel_first_kind": "christoffel"}
_TABLE_WORDS = {
    "christoffel": "the tutorial's three-index symbols h_ijk",
    "christoffel_first_kind": "the symmetric Christoffel symbols of the first kind c_ijk",
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
    answer_timeout: float | None = DEFAULT_ANSWER_TIMEOUT  # seconds per entry (None: no limit)


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
        asked=tuple(k for k in doc["results"] if k in {r for a in system.ask for r in ASKED_RESULTS.get(str(a), ())}),
    )


# ---------------------------------------------------------------------------------------------
# Marking one answers file
# ---------------------------------------------------------------------------------------------


#: Parsed result expressions, per reference (for as long as the reference lives).
_result_cache: weakref.WeakKeyDictionary[Reference, dict[str, sp.Expr]] = weakref.WeakKeyDictionary()


class _UnknownName(Exception):
    """An answer that uses a name the problem does not have: a wrong answer, with this feedback."""


@dataclass
class _Parsed:
    expr: sp.Expr
    literal: str | None = None  # the number as written, for rounding checks
    unit_factor: sp.Expr = sp.S.One  # SI value of one written unit
    dimension: Dimension | None = None  # of a quantity with a unit


class _Marker:
    """Marks the items of one sheet against one reference, collecting answers-file errors."""

    def __init__(self, sheet: AnswerSheet, ref: Reference) -> None:
        self.sheet = sheet
        self.ref = ref
        self.errors: list[SpecError] = []
        self._rules: list[tuple[Path, Any]] | None = None

    # -- reading ------------------------------------------------------------------------------

    def where(self, keypath: KeyPath) -> str:
        return str(self.sheet.location(keypath))

    def error(self, keypath: KeyPath, message: str, hint: str | None = None, *, key: bool = False) -> None:
        loc = self.sheet.source.key_location(keypath) if key else self.sheet.location(keypath)
        self.errors.append(SpecError(loc, message, hint))

    def parse_text(self, text: str, keypath: KeyPath, offset: int = 0) -> sp.Expr | None:
        try:
            expr = parse_expression(text, self.ref.symbols)
        except ExprError as exc:
            if exc.message.startswith("unknown name"):
                raise _UnknownName(exc.message + (f" ({exc.hint})" if exc.hint else "")) from None
            loc = self.sheet.source.expr_location(keypath, offset + exc.offset)
            self.errors.append(SpecError(loc, exc.message, exc.hint))
            return None
        return expr.xreplace(self.ref.values) if self.ref.values else expr

    def read(self, answer: Any, keypath: KeyPath) -> _Parsed | None:
        """An answer scalar as sympy (None after recording an answers-file error)."""
        if isinstance(answer, bool):
            self.error(keypath, "expected an expression or a number, found true/false")
            return None
        if isinstance(answer, int | float):
            try:
                value = number_to_rational(answer)
            except ExprError as exc:
                self.error(keypath, exc.message)
                return None
            literal = self.sheet.raw_number(keypath, answer) or repr(answer)
            return _Parsed(value, literal)
        text = str(answer)
        try:
            quantity = parse_quantity(text)
        except ExprError as exc:
            self.errors.append(SpecError(self.sheet.source.expr_location(keypath, exc.offset), exc.message, exc.hint))
            return None
        if quantity is not None:
            match = _NUMBER_RE.match(text)
            assert match is not None
            factor, _ = parse_unit(quantity.unit)
            return _Parsed(quantity.value, match.group().strip(), factor, quantity.dimension)
        expr = self.parse_text(text, keypath)
        if expr is None:
            return None
        literal = text.strip() if _NUMBER_RE.fullmatch(text) else None
        return _Parsed(expr, literal)

    def result_expr(self, value: Any) -> sp.Expr:
        """A result entry (a JSON number or an expression string) as sympy."""
        if isinstance(value, int | float) and not isinstance(value, bool):
            return number_to_rational(value)
        text = str(value)
        cache = _result_cache.setdefault(self.ref, {})
        if text not in cache:
            cache[text] = parse_expression(text, self.ref.symbols)
        return cache[text]

    # -- items --------------------------------------------------------------------------------

    def mark(self) -> list[ItemResult]:
        marked: list[tuple[Path, ItemResult]] = []
        seen: dict[Path, str] = {}
        for item in self.sheet.items:
            resolved = self.resolve(item)
            if resolved is None:
                continue
            path, result = resolved
            clash = next((p for p in seen if _overlaps(p, path)), None)
            if clash is not None:
                self.error(
                    item.keypath,
                    f"'{item.key}' answers {entry_name(path)} again (already answered by '{seen[clash]}'); "
                    "each entry may be answered once",
                    key=True,
                )
                continue
            seen[path] = item.key
            try:
                marked.append((path, self.mark_item(item, path, result)))
            except _Stop:
                continue
        return self.graded(marked)

    def asked(self) -> list[tuple[Path, str]] | None:
        """The items the instructor asks for, as (path, location): the key's ``ask``, else None."""
        if self.ref.key.ask is None:
            return None
        out = []
        for _, segments, loc in self.ref.key.ask:
            found = self.resolve_segments(segments)
            if not isinstance(found, str):
                out.append((found[0], loc))
        return out

    def graded(self, marked: list[tuple[Path, ItemResult]]) -> list[ItemResult]:
        """The items that count: one per asked item (missing where nothing answers it), in the order
        asked. Without a key's ``ask`` the answered items count, and a file that answers nothing is
        missing every result the spec's ``ask`` names."""
        asked = self.asked()
        if asked is None:
            if marked or self.sheet.items:
                return [item for _, item in marked]
            asked = [((k,), "") for k in self.ref.asked]
        out = []
        for path, _ in asked:
            name = entry_name(path)
            inside = [item for p, item in marked if p[: len(path)] == path]
            around = [item for p, item in marked if len(p) < len(path) and path[: len(p)] == p]
            entries = [e for item in inside for e in item.entries]
            entries += [e for item in around for e in item.entries if _is_under(e.name, name)]
            if not entries:
                where = f"{self.sheet.path}:1:1"
                missing = EntryResult(name, Status.MISSING, feedback="no answer", location=where)
                out.append(ItemResult(name, Status.MISSING, (missing,), location=where))
                continue
            remarks = tuple(r for item in (*inside, *around) for r in item.remarks)
            location = (inside or around)[0].location
            out.append(ItemResult(name, worst([e.status for e in entries]), tuple(entries), remarks, location))
        return out

    def resolve(self, item: AnswerItem) -> tuple[Path, Any] | None:
        """The results path and value an item's key names (None after recording an error)."""
        found = self.resolve_segments(item.segments)
        if isinstance(found, str):
            hint = None
            if found.startswith("this spec has no result"):
                hint = "this spec's results are: " + ", ".join(self.ref.results)
            self.error(item.keypath, f"cannot read the key '{item.key}': {found}", hint, key=True)
            return None
        return found

    def resolve_segments(self, segments: tuple[Segment, ...]) -> tuple[Path, Any] | str:
        """The results path and value a key's segments name, or why they name none."""
        node: Any = self.ref.results
        path: list[str | int] = []
        for seg in segments:
            step = self.step(node, tuple(path), seg)
            if isinstance(step, str):
                return step
            for part in step:
                node = node[part]
                path.append(part)
        return tuple(path), node

    def rule(self, path: Path) -> tuple[Tolerance, bool]:
        """The instructor's tolerance and scaling rule for the entry at ``path``: of the most specific
        key rule above it (tolerance fields left open fall back to less specific rules)."""
        cache = self._rules
        if cache is None:
            cache = []
            for r in self.ref.key.rules:
                found = self.resolve_segments(r.segments)
                if not isinstance(found, str):
                    cache.append((found[0], r))
            cache.sort(key=lambda pr: -len(pr[0]))
            self._rules = cache
        tol, scaling = Tolerance(), None
        for p, r in cache:
            if path[: len(p)] == p:
                tol = tol.over(r.tolerance)
                scaling = r.scaling if scaling is None else scaling
        return tol, scaling is not False

    def step(self, node: Any, path: Path, seg: Segment) -> tuple[str | int, ...] | str:
        """The path parts one key segment takes from ``node``, or why it cannot."""
        where = entry_name(path) if path else "the results"
        if isinstance(seg, str):
            if isinstance(node, dict):
                if seg in node:
                    return (seg,)
                if not path:
                    return f"this spec has no result '{seg}' (its spec does not ask for it)"
                close = did_you_mean(seg, [str(k) for k in node])
                return f"{where} has no entry '{seg}'" + (f"; did you mean '{close}'?" if close else "")
            if isinstance(node, list) and is_per_coordinate(path):
                if seg in self.ref.coordinates:
                    return (self.ref.coordinates.index(seg),)
                return f"'{seg}' is not a coordinate (coordinates: {', '.join(self.ref.coordinates)})"
            return f"{where} has no entry '{seg}'"
        if isinstance(node, dict):
            key = ",".join(str(i) for i in seg)
            if key in node:
                return (key,)
            return f"{where} has no entry [{key}]"
        parts: list[int] = []
        for index in seg:
            if not isinstance(node, list):
                return f"{entry_name((*path, *parts))} is a single value; it has no entry [{index}]"
            if index > len(node):
                return f"{entry_name((*path, *parts))} has {len(node)} entries; there is no entry [{index}]"
            parts.append(index - 1)
            node = node[index - 1]
        return tuple(parts)

    def mark_item(self, item: AnswerItem, path: Path, result: Any) -> ItemResult:
        remarks: list[str] = []
        entries = self.walk(item.value, item.keypath, result, path)
        table = path[0] if path and path[0] in _OTHER_TABLE else None
        if table and any(e.status is Status.WRONG for e in entries):
            other = (_OTHER_TABLE[table], *path[1:])
            other_result = self.lookup(other)
            if other_result is not None:
                # the same answer against the other table: accepted when no entry is wrong there
                known = len(self.errors)  # the answers file's errors were found on the first walk
                again = self.walk(item.value, item.keypath, other_result, other)
                del self.errors[known:]
                if not any(a.status is Status.WRONG for a in again):
                    entries = [
                        replace(e, how=a.how, status=Status.CORRECT, feedback="", expected=a.expected)
                        if e.status is Status.WRONG and a.status is Status.CORRECT
                        else e
                        for e, a in zip(entries, again, strict=True)
                    ]
                    remarks.append(
                        f"these are {_TABLE_WORDS[other[0]]} (the result '{other[0]}'), not "
                        f"{_TABLE_WORDS[table]}; accepted, since both give the same Coriolis vector"
                    )
        for e in entries:
            if e.status is Status.CORRECT and e.feedback and e.feedback not in remarks:
                remarks.append(e.feedback)
        if not entries:  # `mass_matrix: {}`, a list of empty mappings: nothing answered
            entries = [
                EntryResult(entry_name(path), Status.MISSING, feedback="no answer", location=self.where(item.keypath))
            ]
        status = worst([e.status for e in entries])
        return ItemResult(entry_name(path), status, tuple(entries), tuple(remarks), str(item.location))

    def lookup(self, path: Path) -> Any:
        node: Any = self.ref.results
        for part in path:
            try:
                node = node[part]
            except (KeyError, IndexError, TypeError):
                return None
        return node

    # -- walking an answer and a result together ---------------------------------------------------

    def walk(self, answer: Any, keypath: KeyPath, result: Any, path: Path) -> list[EntryResult]:
        if isinstance(answer, dict) and "value" in answer and all(k == "value" or k in TOLERANCE_KEYS for k in answer):
            for k in answer:
                if k != "value":  # tolerances are the instructor's: refused in an answers file
                    self.error((*keypath, k), MSG_NO_TOLERANCE.format(key=k), key=True)
            answer, keypath = answer["value"], (*keypath, "value")
        if isinstance(answer, bool) and not isinstance(result, bool):
            self.error(keypath, "expected an expression or a number, found true/false")
            return []
        if answer is None or (isinstance(answer, str) and not answer.strip()):
            return [EntryResult(entry_name(path), Status.MISSING, feedback="no answer", location=self.where(keypath))]
        if isinstance(result, dict):
            return self.walk_table(answer, keypath, result, path)
        if isinstance(result, list):
            return self.walk_list(answer, keypath, result, path)
        if isinstance(answer, list | dict):
            kind = "a list" if isinstance(answer, list) else "a mapping"
            return [self.wrong(path, keypath, answer, result, f"expected a single value, found {kind}")]
        return [self.limited(answer, keypath, result, path)]

    def limited(self, answer: Any, keypath: KeyPath, result: Any, path: Path) -> EntryResult:
        """:meth:`scalar` under the per-answer time limit; an answer that runs out of time or memory is
        "could not be checked", and marking goes on."""
        seconds = self.ref.answer_timeout
        try:
            with answer_deadline(seconds):
                return self.scalar(answer, keypath, result, path)
        except AnswerTimeLimit as exc:
            feedback = f"could not be checked (time limit: {exc.seconds:g} s per answer)"
        except MemoryError:
            feedback = "could not be checked (memory limit)"
        except RecursionError:
            feedback = "could not be checked (nested too deeply)"
        return EntryResult(
            entry_name(path), Status.TIME_LIMIT, feedback=feedback, location=self.where(keypath), given=_text(answer)
        )

    def walk_table(self, answer: Any, keypath: KeyPath, result: dict[str, Any], path: Path) -> list[EntryResult]:
        if not isinstance(answer, dict):
            keys = ", ".join(list(result)[:6]) + (", ..." if len(result) > 6 else "")
            self.error(keypath, f"{entry_name(path)} is a table: expected a mapping of its entries ({keys})")
            raise _Stop
        out: list[EntryResult] = []
        taken: dict[str, Any] = {}
        for key, value in answer.items():
            name = self.table_key(str(key), result)
            if name is not None and name in taken:
                self.error(
                    (*keypath, key),
                    f"'{key}' answers {entry_name((*path, name))} again (already answered as '{taken[name]}')",
                    key=True,
                )
                continue
            if name is not None:
                taken[name] = key
            if name is None:
                close = did_you_mean(str(key), [str(k) for k in result])
                self.error(
                    (*keypath, key),
                    f"{entry_name(path)} has no entry '{key}'; its entries are: " + ", ".join(map(str, result)),
                    f"did you mean '{close}'?" if close else None,
                    key=True,
                )
                continue
            out += self.walk(value, (*keypath, key), result[name], (*path, name))
        return out

    @staticmethod
    def table_key(key: str, result: dict[str, Any]) -> str | None:
        """The entry of ``result`` a table key names: as written, or a Christoffel index in any of the
        forms ``1,1,2``, ``112``, ``h112``, ``c112``, ``[1,1,2]``."""
        if key in result:
            return key
        match = _CHRISTOFFEL_KEY_RE.fullmatch(key.strip())
        if match:
            indices = [g for g in match.groups() if g is not None]
            name = ",".join(str(int(i)) for i in indices)
            if name in result:
                return name
        return None

    def walk_list(self, answer: Any, keypath: KeyPath, result: list[Any], path: Path) -> list[EntryResult]:
        n = len(result)
        if isinstance(answer, dict):
            pairs: list[tuple[int, Any, KeyPath]] = []
            for key, value in answer.items():
                index = self.list_key(str(key), path, n)
                if index is None:
                    choices = [str(i) for i in range(1, n + 1)]
                    if is_per_coordinate(path):
                        choices = list(self.ref.coordinates)
                    self.error(
                        (*keypath, key),
                        f"{entry_name(path)} has no entry '{key}'; expected one of: {', '.join(choices)}",
                        key=True,
                    )
                    continue
                if any(index == i for i, _, _ in pairs):
                    self.error((*keypath, key), f"'{key}' answers {entry_name((*path, index))} again", key=True)
                    continue
                pairs.append((index, value, (*keypath, key)))
            out: list[EntryResult] = []
            for index, value, kp in sorted(pairs, key=lambda p: p[0]):
                out += self.walk(value, kp, result[index], (*path, index))
            return out
        if not isinstance(answer, list):
            rows = "a matrix" if result and isinstance(result[0], list) else f"a list of {n} entries"
            return [self.wrong(path, keypath, answer, result, f"expected {rows}, found a single value")]
        out = self.walk_items(answer, keypath, result, path)
        is_axis = field_of(path) == "principal_axes" and bool(result) and not isinstance(result[0], list)
        if is_axis and len(answer) == n and any(e.status is Status.WRONG for e in out):
            # a principal axis is a direction: accepted pointing the other way
            flipped = [-v if isinstance(v, int | float) and not isinstance(v, bool) else v for v in result]
            again = self.walk_items(answer, keypath, flipped, path)
            if all(e.status is Status.CORRECT for e in again):
                note = f"{entry_name(path)} points the other way; accepted, an axis has no direction"
                return [replace(e, feedback=note) for e in again]
        return out

    def walk_items(self, answer: list[Any], keypath: KeyPath, result: list[Any], path: Path) -> list[EntryResult]:
        """A list answer against a list result, entry by entry; short lists miss entries, long ones
        have extra (wrong) ones."""
        n = len(result)
        out: list[EntryResult] = []
        for i, value in enumerate(answer[:n]):
            out += self.walk(value, (*keypath, i), result[i], (*path, i))
        for i in range(len(answer), n):
            out.append(
                EntryResult(entry_name((*path, i)), Status.MISSING, feedback="no answer", location=self.where(keypath))
            )
        for i in range(n, len(answer)):
            out.append(
                EntryResult(
                    entry_name((*path, i)),
                    Status.WRONG,
                    feedback=f"extra entry: {entry_name(path)} has only {n} entries",
                    location=self.where((*keypath, i)),
                    given=_text(answer[i]),
                )
            )
        return out

    def list_key(self, key: str, path: Path, n: int) -> int | None:
        if key.isdigit() and 1 <= int(key) <= n:
            return int(key) - 1
        if is_per_coordinate(path) and key in self.ref.coordinates:
            return self.ref.coordinates.index(key)
        return None

    # -- scalars --------------------------------------------------------------------------------

    def wrong(self, path: Path, keypath: KeyPath, answer: Any, result: Any, feedback: str) -> EntryResult:
        return EntryResult(
            entry_name(path),
            Status.WRONG,
            feedback=feedback,
            location=self.where(keypath),
            given=_text(answer),
            expected=_text(result),
        )

    def right(self, path: Path, keypath: KeyPath, answer: Any, result: Any, how: str, remark: str = "") -> EntryResult:
        return EntryResult(
            entry_name(path),
            Status.CORRECT,
            how=how,
            feedback=remark,
            location=self.where(keypath),
            given=_text(answer),
            expected=_text(result),
        )

    def scalar(self, answer: Any, keypath: KeyPath, result: Any, path: Path) -> EntryResult:
        field_name = field_of(path)
        if field_name in TEXT_FIELDS:
            if str(answer).strip() == str(result):
                return self.right(path, keypath, answer, result, "exact: the same text")
            return self.wrong(path, keypath, answer, result, f"expected '{result}'")
        if isinstance(result, bool):
            if answer is result:
                return self.right(path, keypath, answer, result, "exact: the same truth value")
            return self.wrong(path, keypath, answer, result, f"expected {str(result).lower()}")
        if field_name == "equations_of_motion":
            return self.equation(answer, keypath, result, path)
        try:
            parsed = self.read(answer, keypath)
        except _UnknownName as exc:
            return self.wrong(path, keypath, answer, result, str(exc))
        if parsed is None:
            return self.wrong(path, keypath, answer, result, "cannot read the answer")
        correct = self.result_expr(result)
        expected_dim = DIMENSION_OF.get(field_name or "")
        if parsed.dimension is not None and expected_dim is not None and parsed.dimension != expected_dim:
            return self.wrong(
                path, keypath, answer, result, f"wrong units: yours are {parsed.dimension}, expected {expected_dim}"
            )
        given = parsed.expr
        tol, _ = self.rule(path)
        if not given.free_symbols and not correct.free_symbols:
            return self.number(parsed, answer, keypath, result, path, tol.over(self.ref.key.tolerance))
        if tol.is_set and not tol.rounded:  # the instructor's tolerance for this expression
            decision = decide(given, correct, rel_tol=tol.rel, abs_tol=tol.abs)
        else:
            decision = decide(given, correct)
        return self.verdict(decision, given, correct, answer, keypath, result, path)

    def verdict(
        self,
        decision: Decision,
        given: sp.Expr,
        correct: sp.Expr,
        answer: Any,
        keypath: KeyPath,
        result: Any,
        path: Path,
    ) -> EntryResult:
        """The entry's verdict from the decision procedure's: right, cannot be evaluated, or wrong with
        what differs."""
        if decision.equal:
            return self.right(path, keypath, answer, result, decision.how)
        if decision.equal is None:
            return self.unevaluable(path, keypath, answer, result, decision.reason)
        return self.wrong(path, keypath, answer, result, diagnose(given, correct, self.ref.state))

    def unevaluable(self, path: Path, keypath: KeyPath, answer: Any, result: Any, reason: str) -> EntryResult:
        return EntryResult(
            entry_name(path),
            Status.CANNOT_EVALUATE,
            feedback="cannot be evaluated" + (f": {reason}" if reason else ""),
            location=self.where(keypath),
            given=_text(answer),
            expected=_text(result),
        )

    def number(
        self, parsed: _Parsed, answer: Any, keypath: KeyPath, result: Any, path: Path, tol: Tolerance
    ) -> EntryResult:
        given_value = value_of_number(parsed.expr)
        if given_value is None:  # sqrt(-1), acos(2), (-8)**(1/3), 1/0
            return self.unevaluable(path, keypath, answer, result, "it has no finite real value")
        given, correct = float(given_value), float(sp.N(self.result_expr(result), 20))
        if tol.rounded and parsed.literal is not None:
            shown = significant(parsed.literal)
            if shown is None:  # a zero: right only if the result is (to abs_tol)
                if abs(correct) <= tol.abs:
                    return self.right(path, keypath, answer, result, f"within abs_tol {tol.abs:g}")
                return self.wrong(path, keypath, answer, result, "the correct value is not 0")
            value, figures = shown
            in_unit = Decimal(repr(float(sp.N(self.result_expr(result) / parsed.unit_factor, 20))))
            if in_unit == 0:
                return self.wrong(path, keypath, answer, result, f"the correct value is 0 (yours is {given:.4g})")
            target = round_half_up(in_unit, figures)
            if value == target:
                return self.right(path, keypath, answer, result, f"correctly rounded to {figures} significant figures")
            if abs(value - in_unit) <= Decimal(1).scaleb(in_unit.adjusted() - figures + 1):
                shown_target = format(target, f".{figures - 1}e") if "e" in parsed.literal.lower() else str(target)
                return self.wrong(
                    path,
                    keypath,
                    answer,
                    result,
                    f"not correctly rounded: to {figures} significant figures it is {shown_target}",
                )
            return self.wrong(path, keypath, answer, result, number_feedback(given, correct, tol))
        with mpmath.workdps(30):
            close = abs(given_value - mpmath.mpf(correct)) <= max(tol.abs, tol.rel * abs(correct))
        if close:
            limit = f"rel_tol {tol.rel:g}" if tol.rel * abs(correct) >= tol.abs else f"abs_tol {tol.abs:g}"
            return self.right(path, keypath, answer, result, f"within {limit}")
        return self.wrong(path, keypath, answer, result, number_feedback(given, correct, tol))

    # -- equations of motion ------------------------------------------------------------------------

    def equation(self, answer: Any, keypath: KeyPath, result: Any, path: Path) -> EntryResult:
        """An equation of motion: ``lhs = rhs`` or an expression equal to 0, up to moving terms across the
        ``=`` and a constant factor in [MIN_SCALE, MAX_SCALE] (unless the key turns scaling off)."""
        try:
            given = self.read_equation(answer, keypath)
        except _UnknownName as exc:
            return self.wrong(path, keypath, answer, result, str(exc))
        if given is None:
            return self.wrong(path, keypath, answer, result, "cannot read the answer")
        correct = self.result_expr(result)
        decision = decide(given, correct)
        if decision.equal:
            return self.right(path, keypath, answer, result, decision.how)
        if decision.equal is None:
            return self.unevaluable(path, keypath, answer, result, decision.reason)
        k = constant_factor(given, correct, self.ref.state, self.ref.forces)
        if k is not None:
            name = entry_name(path)
            if k == -1:
                remark = f"{name}: the terms are on the other side of '='"
                return self.right(
                    path, keypath, answer, result, "exact: equal with every term moved across '='", remark
                )
            _, scaling = self.rule(path)
            if not scaling:
                feedback = f"scaled by {expr_text(k)}: this equation is marked without scaling; write it as derived"
                return self.wrong(path, keypath, answer, result, feedback)
            if not is_acceptable_scale(k):
                feedback = f"scaled by {expr_text(k)}: a factor outside [{MIN_SCALE:g}, {MAX_SCALE:g}] is not accepted"
                return self.wrong(path, keypath, answer, result, feedback)
            remark = f"{name}: scaled by the constant factor {expr_text(k)}"
            how = f"scaled by {expr_text(k)}: equal up to this constant factor"
            return self.right(path, keypath, answer, result, how, remark)
        return self.wrong(path, keypath, answer, result, diagnose(self.scaled(given, correct), correct, self.ref.state))

    def scaled(self, given: sp.Expr, correct: sp.Expr) -> sp.Expr:
        """``given`` divided by the constant factor under which most of its terms agree with ``correct``
        (so that one wrong term in a scaled equation is reported as one wrong term)."""
        if too_large(given, correct):
            return given
        state = self.ref.state
        g, c = groups(reduced(given), state), groups(reduced(correct), state)
        best, agreeing = sp.S.One, -1
        for key in c:
            if key not in g:
                continue
            k = sp.cancel(g[key] / c[key])
            if k == 0 or k.free_symbols & (state | self.ref.forces) or k.is_zero is not False:
                continue
            count = sum(1 for kk in c if kk in g and sp.expand(g[kk] - k * c[kk]) == 0)
            if count > agreeing or (count == agreeing and k == 1):
                best, agreeing = k, count
        return given if best == 1 else sp.expand(given / best)

    def read_equation(self, answer: Any, keypath: KeyPath) -> sp.Expr | None:
        if isinstance(answer, str) and "=" in answer:
            text = answer.replace("==", "=")
            if text.count("=") != 1:
                self.errors.append(
                    SpecError(
                        self.sheet.source.expr_location(keypath, answer.rfind("=")),
                        "an equation has one '=': write 'lhs = rhs'",
                    )
                )
                return None
            lhs_text, rhs_text = text.split("=")
            offset = answer.index("=") + (2 if "==" in answer else 1)
            lhs = self.parse_text(lhs_text, keypath)
            rhs = self.parse_text(rhs_text, keypath, offset)
            if lhs is None or rhs is None:
                return None
            return lhs - rhs
        parsed = self.read(answer, keypath)
        return None if parsed is None else parsed.expr


class _Stop(Exception):
    """An item whose shape is wrong for its result: the error is recorded, the item is skipped."""


def _text(value: Any) -> str | None:
    """An answer or a result as text for the reports (None for no answer)."""
    return None if value is None else str(value)


def _overlaps(a: Path, b: Path) -> bool:
    """Whether two answered paths name a common entry (one is the other, or inside it)."""
    n = min(len(a), len(b))
    return a[:n] == b[:n]


def _is_under(name: str, item: str) -> bool:
    """Whether the entry called ``name`` is ``item`` or inside it (``mass_matrix[1,2]`` in ``mass_matrix``)."""
    return name == item or name.startswith((item + "[", item + "."))


def equal_how(difference: sp.Expr) -> str | None:
    """How ``difference`` was shown to be 0 (exactly, else at random states), or None if it was not.

    Numerically a difference is compared as two sides (its positive terms against its negative ones),
    since "zero to 15 digits" means nothing without the size of what cancelled."""
    terms = sp.Add.make_args(difference if too_large(difference, sp.S.One) else sp.expand(difference))
    positive = sp.Add(*(t for t in terms if t.could_extract_minus_sign() is False))
    negative = sp.Add(*(t for t in terms if t.could_extract_minus_sign() is not False))
    decision = decide(positive, -negative)
    return decision.how if decision.equal else None


def check_sheet(sheet: AnswerSheet, ref: Reference) -> list[ItemResult]:
    """Mark every item of an answers file; raise SpecErrors for problems with the file itself
    (an expression that cannot be read, a key the spec's results do not have, a bad tolerance)."""
    marker = _Marker(sheet, ref)
    items = marker.mark()
    if sheet.errors or marker.errors:
        raise SpecErrors([*sheet.errors, *marker.errors])
    return items
