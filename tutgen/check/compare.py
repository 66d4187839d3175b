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
from dataclasses import replace
from typing import Any

import sympy as sp

from tutgen.check.answers import MSG_NO_TOLERANCE, TOLERANCE_KEYS, AnswerItem, AnswerSheet, Segment, Tolerance
from tutgen.check.equivalence import NUMERIC_HOW, decide, too_large
from tutgen.check.feedback import diagnose
from tutgen.check.limits import AnswerTimeLimit, answer_deadline
from tutgen.check.matrices import matrix_finding
from tutgen.check.names import Path, entry_name, field_of, is_per_coordinate
from tutgen.check.numeric import SEED, TRIALS
from tutgen.check.scalars import ScalarMarking, UnknownName, Unreadable, answer_limit, answer_text
from tutgen.check.steady import SteadyMarking
from tutgen.check.verdicts import (
    ASKED_RESULTS,
    DEFAULT_ANSWER_TIMEOUT,
    EntryResult,
    ItemResult,
    Reference,
    Status,
    reference_from,
    worst,
)
from tutgen.errors import Location, SpecError, SpecErrors
from tutgen.render.jsonout import expr_text  # the spec grammar, as the JSON writes it
from tutgen.spec.expr import did_you_mean
from tutgen.spec.loader import KeyPath

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
    "key_problems",
    "reference_from",
    "unmarked_items",
    "worst",
]

_CHRISTOFFEL_KEY_RE = re.compile(
    r"[A-Za-z]?\[?\s*([0-9]+)\s*,\s*([0-9]+)\s*,\s*([0-9]+)\s*\]?"  # 1,1,2  h[1,1,2]
    r"|[A-Za-z]?([1-9])([1-9])([1-9])"  # 112  h112  c112
)
_OTHER_TABLE = {"christoffel": "christoffel_first_kind", "christoffel_first_kind": "christoffel"}
_TABLE_WORDS = {
    "christoffel": "the tutorial's three-index symbols h_ijk",
    "christoffel_first_kind": "the symmetric Christoffel symbols of the first kind c_ijk",
}


class _Marker(ScalarMarking):
    """Marks the items of one sheet against one reference: walks each answer and its result together."""

    def __init__(self, sheet: AnswerSheet, ref: Reference) -> None:
        super().__init__(sheet, ref)
        self._rules: list[tuple[Path, Any]] | None = None

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

    def asked(self) -> list[tuple[Path, Location]] | None:
        """The items the instructor asks for, as (path, location in the key): the key's ``ask``, else None."""
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
            asked = [((k,), Location(self.sheet.path)) for k in self.ref.asked]
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
        if path[:1] == ("steady_motion",):
            entries = self.steady(item, path, result)
        else:
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

    def steady(self, item: AnswerItem, path: Path, result: Any) -> list[EntryResult]:
        """``steady_motion``: its motions matched by value, not by place (:mod:`tutgen.check.steady`)."""
        if len(path) > 1:
            self.error(
                item.keypath,
                f"'{item.key}' names a part of steady_motion by its place in tutgen's list; answer "
                "`steady_motion` as a whole: a list of steady motions, each found by its values (`at:`)",
                key=True,
            )
            raise _Stop
        entries = SteadyMarking(self, self.walk).mark(item.value, item.keypath, result, path)
        if entries is None:
            raise _Stop
        return entries

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
            feedback = "cannot read the answer: expected an expression or a number, found true/false"
            return [self.wrong(path, keypath, answer, result, feedback)]
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
            entry_name(path),
            Status.TIME_LIMIT,
            feedback=feedback,
            location=self.where(keypath),
            given=answer_text(answer),
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
        if sum(e.status is Status.WRONG for e in out) >= 2:
            finding = self.whole_matrix(answer, result)
            if finding is not None:  # one message for the matrix, not one per misplaced entry
                return [self.wrong(path, keypath, answer, result, finding)]
        is_axis = field_of(path) == "principal_axes" and bool(result) and not isinstance(result[0], list)
        if is_axis and len(answer) == n and any(e.status is Status.WRONG for e in out):
            # a principal axis is a direction: accepted pointing the other way
            flipped = [-v if isinstance(v, int | float) and not isinstance(v, bool) else v for v in result]
            again = self.walk_items(answer, keypath, flipped, path)
            if all(e.status is Status.CORRECT for e in again):
                note = f"{entry_name(path)} points the other way; accepted, an axis has no direction"
                return [replace(e, feedback=note) for e in again]
        return out

    def whole_matrix(self, answer: list[Any], result: list[Any]) -> str | None:
        """What is wrong with a matrix answer as a whole (:func:`tutgen.check.matrices.matrix_finding`),
        if it has the result's shape and every entry reads; within the per-answer time limit."""
        shape = [len(row) for row in result if isinstance(row, list)]
        if not shape or len(shape) != len(result) or len(answer) != len(result):
            return None
        if any(not isinstance(row, list) or len(row) != n for row, n in zip(answer, shape, strict=True)):
            return None
        limit = answer_limit(max((str(v) for row in result for v in row), key=len, default=""))
        try:
            with answer_deadline(self.ref.answer_timeout):
                correct = [[self.result_expr(v) for v in row] for row in result]
                given = [
                    [self.read(v, (), bool(c.free_symbols), limit).expr for v, c in zip(row, crow, strict=True)]  # type: ignore[union-attr]
                    for row, crow in zip(answer, correct, strict=True)
                ]
                return matrix_finding(given, correct, self.ref.state, self.ref.forces)
        except (AnswerTimeLimit, MemoryError, RecursionError, UnknownName, Unreadable, AttributeError, TypeError):
            return None  # an entry that does not read, or no time: the entries speak for themselves

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
                    given=answer_text(answer[i]),
                )
            )
        return out

    def list_key(self, key: str, path: Path, n: int) -> int | None:
        if key.isdigit() and 1 <= int(key) <= n:
            return int(key) - 1
        if is_per_coordinate(path) and key in self.ref.coordinates:
            return self.ref.coordinates.index(key)
        return None


class _Stop(Exception):
    """An item whose shape is wrong for its result: the error is recorded, the item is skipped."""


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


def key_problems(ref: Reference) -> list[SpecError]:
    """The marking key's entries that name no result of this spec, located in the key file."""
    marker = _Marker(None, ref)  # type: ignore[arg-type] - resolving keys needs no answers file
    out = []
    named = [(k, segs, loc) for k, segs, loc in ref.key.ask or ()]
    named += [(r.key, r.segments, r.location) for r in ref.key.rules]
    for key, segments, loc in named:
        found = marker.resolve_segments(segments)
        if isinstance(found, str):
            out.append(SpecError(loc, f"the marking's '{key}' names no result of this spec: {found}"))
    return out


def unmarked_items(ref: Reference, path: str, feedback: str) -> tuple[ItemResult, ...]:
    """The asked items of a file that could not be marked to the end, each with ``feedback`` (a time or
    memory limit): the key's ``ask``, else the results the spec's ``ask`` names."""
    if ref.key.ask is not None:
        names = [key for key, _, _ in ref.key.ask]
    else:
        names = list(ref.asked)
    where = f"{path}:1:1"
    return tuple(
        ItemResult(
            n, Status.TIME_LIMIT, (EntryResult(n, Status.TIME_LIMIT, feedback=feedback, location=where),), (), where
        )
        for n in names
    )


def check_sheet(sheet: AnswerSheet, ref: Reference) -> list[ItemResult]:
    """Mark every item of an answers file; raise SpecErrors for problems with the file itself
    (an expression that cannot be read, a key the spec's results do not have, a bad tolerance)."""
    marker = _Marker(sheet, ref)
    items = marker.mark()
    if sheet.errors or marker.errors:
        raise SpecErrors([*sheet.errors, *marker.errors])
    return items
