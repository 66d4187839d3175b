"""Marking a steady-motion answer: the steady values, where each exists, what it needs, its stability.

``results.steady_motion.states`` is a list in tutgen's own order, which a student cannot know, so an
answer is not walked against it by position. It is a list of steady motions, each a mapping in the
form of one JSON state::

    steady_motion:
      - at: {theta: "cos(theta) = g/(R*omega**2)"}   # a value, or an equation the value satisfies
        exists_where: "g <= R*omega**2"              # an inequality, a list of them, or "always"
        required: {phi: 0}                           # each held coordinate's generalized force
        inputs: {tau: 0}                             # the drive that gives it
        momenta: {phi: "..."}                        # p_c = dL/dq_dot_c there
        stability: stable                            # stable, unstable, conditional, ...
        stable_where: "g > R*omega**2"               # with conditional

Each answered motion is matched by its ``at`` with the results' motions whose values it gives (an
angle up to a multiple of 2 pi); an equation (``cos(theta) = ...``) matches every motion that satisfies
it, and its other fields must then be right for each. The values are compared at random parameter
values where the motion exists (so that an acos is real there), in high precision over the sympy tree
(:mod:`tutgen.check.numeric`); conditions by their truth at random parameter values, so that
``g/(R*omega^2) <= 1`` is ``g <= R*omega^2`` and ``g <= 2*R*omega^2`` is not. A motion of the results
that no answer matches is missing; an answered one that matches none is wrong, with why. The
expressions are read by the spec grammar's whitelist parser, as every answer is (docs/check.md).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy as sp

from tutgen.check.limits import AnswerTimeLimit, answer_deadline
from tutgen.check.names import Path, entry_name
from tutgen.check.numeric import SEED, evaluate
from tutgen.check.scalars import ScalarMarking, UnknownName, Unreadable, answer_text
from tutgen.check.verdicts import EntryResult, Status
from tutgen.engine.tidy import random_states
from tutgen.errors import SpecError
from tutgen.spec.expr import ExprError, did_you_mean
from tutgen.spec.loader import KeyPath

__all__ = ["STABILITY_WORDS", "STATE_FIELDS", "SteadyMarking"]

#: The fields of one answered steady motion (those of a state of results.steady_motion).
STATE_FIELDS = ("at", "exists_where", "required", "inputs", "momenta", "stability", "stable_where")
#: The words a stability answer may use, and the verdict of the results each one means.
STABILITY_WORDS = {
    "stable": "stable",
    "unstable": "unstable",
    "asymptotically stable": "asymptotically stable",
    "conditional": "conditional",
    "conditionally stable": "conditional",
    "stable under a condition": "conditional",
    "neutral": "neutral",
    "undetermined": "undetermined",
}
#: Words for "no condition" in ``exists_where`` and ``stable_where``.
_ALWAYS = ("always", "none", "true", "everywhere")
#: Random parameter values tried for values (where the motion exists) and for conditions.
_VALUE_STATES, _CONDITION_STATES, _CANDIDATES = 6, 64, 400
#: Relative agreement of two steady values (and of the sides of an equation).
_CLOSE = 1e-12
_RELATION_RE = re.compile(r"<=|>=|≤|≥|<|>")

Walk = Callable[[Any, KeyPath, Any, Path], list[EntryResult]]
_State = dict[sp.Symbol, sp.Expr]


@dataclass(frozen=True)
class _Read:
    """One value of an answered ``at``: as sympy (lhs - rhs for an equation), and as written."""

    expr: sp.Expr
    equation: bool
    value: Any
    keypath: KeyPath
    path: Path


class _Skip(Exception):
    """An answered motion that cannot be marked further (its error or wrong entry is recorded)."""


class SteadyMarking:
    """Marks ``steady_motion`` (one answer item) for a marker, whose ``walk`` marks the tables in it."""

    def __init__(self, marker: ScalarMarking, walk: Walk) -> None:
        self.m = marker
        self.walk = walk
        self.ref = marker.ref
        self.fixed: set[sp.Symbol] = set(self.ref.state)

    # -- the item ---------------------------------------------------------------------------

    def mark(self, answer: Any, keypath: KeyPath, result: dict[str, Any], path: Path) -> list[EntryResult] | None:
        """The entries of the answer, or None when its shape is wrong (the error is recorded)."""
        if isinstance(answer, dict):
            answer = [answer]  # one steady motion
        if not isinstance(answer, list):
            self.m.error(
                keypath,
                "steady_motion is a list of steady motions, each a mapping with `at:` (the values of "
                f"{', '.join(result['others']) or 'the coordinates'}) and the fields " + ", ".join(STATE_FIELDS[1:]),
            )
            return None
        states = list(result["states"])
        angles = self.ref.angles
        held = {self.ref.symbols[f"{n}_dot"] for n in result["rates"]}
        self.fixed = set(self.ref.state) - held  # what a steady value may not hold
        wanted = [n for n in result["others"] if n not in result["free_others"]]
        out: list[EntryResult] = []
        claimed: dict[int, int] = {}  # results state -> the answered motion that matched it first
        for i, motion in enumerate(answer):
            kp, here = (*keypath, i), (*path, i)
            if motion is None:
                continue
            try:
                at = self.fields(motion, kp, result, wanted)
                matched = self.match(at, kp, here, states, angles)
            except _Skip as exc:
                if exc.args:
                    out.append(exc.args[0])
                continue
            again = [k for k in matched if k in claimed]
            if again and len(again) == len(matched):
                first = entry_name((*path, claimed[again[0]]))
                out.append(
                    self.m.wrong(
                        (*here, "at"),
                        (*kp, "at"),
                        motion.get("at"),
                        None,
                        f"the same steady motion as {first}; each is answered once",
                    )
                )
                continue
            for k in matched:
                claimed.setdefault(k, i)
            out += self.mark_fields(motion, kp, here, [states[k] for k in matched], at)
        for k, state in enumerate(states):
            if k not in claimed and state.get("exists") is not False:
                where = _where(state)
                out.append(
                    EntryResult(
                        entry_name(path),
                        Status.MISSING,
                        feedback=f"no answer for the steady motion {where}",
                        location=self.m.where(keypath),
                        expected=where,
                    )
                )
        return out

    def fields(self, motion: Any, kp: KeyPath, result: dict[str, Any], wanted: list[str]) -> dict[str, Any]:
        """The ``at`` of one answered motion, after checking its shape (errors recorded, then _Skip)."""
        if not isinstance(motion, dict):
            self.m.error(
                kp, "a steady motion is a mapping: `at:` (the values) and the fields " + ", ".join(STATE_FIELDS[1:])
            )
            raise _Skip
        bad = False
        for key in motion:
            if key not in STATE_FIELDS:
                close = did_you_mean(str(key), STATE_FIELDS)
                self.m.error(
                    (*kp, key),
                    f"a steady motion has no field '{key}'; its fields are: {', '.join(STATE_FIELDS)}",
                    f"did you mean '{close}'?" if close else None,
                    key=True,
                )
                bad = True
        at = motion.get("at")
        if not isinstance(at, dict) or not at:
            self.m.error(
                kp,
                "a steady motion says where it is: `at: {"
                + ", ".join(f"{n}: ..." for n in wanted or result["others"])
                + "}` (a value, or an equation such as cos(theta) = ...)",
            )
            raise _Skip
        for name in at:
            if name not in result["others"]:
                held = ", ".join(result["rates"])
                why = (
                    f"'{name}' is held at its rate ({held})"
                    if name in result["rates"]
                    else f"'{name}' is no coordinate"
                )
                self.m.error(
                    (*kp, "at", name), f"{why}; `at` gives the values of: {', '.join(result['others'])}", key=True
                )
                bad = True
        missing = [n for n in wanted if n not in at]
        if missing:
            self.m.error((*kp, "at"), f"`at` gives no value of {', '.join(missing)}: a steady motion gives each")
            bad = True
        if "stability" in motion and _word(motion["stability"]) is None:
            self.m.error(
                (*kp, "stability"),
                f"cannot read the stability '{motion['stability']}'; expected one of: {', '.join(STABILITY_WORDS)}",
            )
            bad = True
        if bad:
            raise _Skip
        return at

    # -- matching ------------------------------------------------------------------------------

    def match(
        self, at: dict[str, Any], kp: KeyPath, here: Path, states: list[dict[str, Any]], angles: frozenset[str]
    ) -> list[int]:
        """The results' states this motion's ``at`` gives (raises _Skip with a wrong entry if none)."""
        parsed: dict[str, _Read] = {}
        for name, value in at.items():
            akp = (*kp, "at", name)
            try:
                expr, equation = self.read(value, akp, name)
                parsed[name] = _Read(expr, equation, value, akp, (*here, "at", name))
            except (UnknownName, Unreadable) as exc:
                said = str(exc) if isinstance(exc, UnknownName) else exc.feedback
                raise _Skip(self.m.wrong((*here, "at", name), akp, value, None, said)) from None
        try:
            with answer_deadline(self.ref.answer_timeout):
                found = [k for k, st in enumerate(states) if self.gives(parsed, st, angles)]
        except (AnswerTimeLimit, MemoryError, RecursionError) as exc:
            why = f"time limit: {exc.seconds:g} s per answer" if isinstance(exc, AnswerTimeLimit) else "memory limit"
            raise _Skip(
                EntryResult(
                    entry_name((*here, "at")),
                    Status.TIME_LIMIT,
                    feedback=f"could not be checked ({why})",
                    location=self.m.where((*kp, "at")),
                    given=answer_text(at),
                )
            ) from None
        if not found:
            shown = "; ".join(_where(st) for st in states)
            raise _Skip(
                self.m.wrong(
                    (*here, "at"),
                    (*kp, "at"),
                    at,
                    None,
                    "not a steady motion of this system at these rates (the steady values are: " + shown + ")",
                )
            )
        return found

    def read(self, value: Any, keypath: KeyPath, name: str) -> tuple[sp.Expr, bool]:
        """A value of ``at`` as (expression, is an equation): ``lhs = rhs`` as lhs - rhs."""
        if isinstance(value, bool) or value is None:
            raise Unreadable(_error(self.m, keypath, "expected a value or an equation, found " + str(value).lower()))
        if isinstance(value, str) and "=" in value:
            text = value.replace("==", "=")
            if text.count("=") != 1:
                raise Unreadable(_error(self.m, keypath, "an equation has one '=': write 'lhs = rhs'"))
            lhs_text, rhs_text = text.split("=")
            offset = value.index("=") + (2 if "==" in value else 1)
            lhs = self.m.parseanswer_text(lhs_text, keypath)
            rhs = self.m.parseanswer_text(rhs_text, keypath, offset)
            assert lhs is not None and rhs is not None
            if not (lhs - rhs).has(self.ref.symbols[name]):
                raise Unreadable(_error(self.m, keypath, f"the equation does not hold {name}"))
            return lhs - rhs, True
        parsed = self.m.read(value, keypath, symbolic=True)
        if parsed is None:
            raise Unreadable(_error(self.m, keypath, "cannot read the answer"))
        if parsed.expr.free_symbols & self.fixed:
            raise Unreadable(
                _error(self.m, keypath, "a steady value holds no coordinate, acceleration or rate but a held one")
            )
        return parsed.expr, False

    def gives(self, parsed: dict[str, _Read], state: dict[str, Any], angles: frozenset[str]) -> bool:
        """Whether the answered values are those of ``state``, at random parameter values where it exists
        (a number without symbols: also when it is the result as printed, rounded)."""
        try:
            values = {n: self.m.result_expr(v) for n, v in state["at"].items()}
        except ExprError:
            return False
        coords = {self.ref.symbols[n]: v for n, v in values.items()}
        symbols: set[sp.Symbol] = set()
        for r in parsed.values():
            symbols |= r.expr.free_symbols
        for v in values.values():
            symbols |= v.free_symbols
        symbols -= set(coords)
        conditions = [] if state.get("exists") is False else state.get("exists_where") or []
        points = self.points(symbols, conditions, _VALUE_STATES)
        if not points:
            return False
        for name, r in parsed.items():
            if name not in values:
                continue
            if not r.equation and not symbols:
                if self.m.limited(r.value, r.keypath, state["at"][name], r.path).status is Status.CORRECT:
                    continue  # a decimal as printed (1.058 for 1.0581329...)
            for point in points:
                if r.equation:
                    if not _zero(r.expr.xreplace(coords), point):
                        return False
                elif name in angles:
                    if not (
                        _same(sp.cos(r.expr), sp.cos(values[name]), point)
                        and _same(sp.sin(r.expr), sp.sin(values[name]), point)
                    ):
                        return False
                elif not _same(r.expr, values[name], point):
                    return False
        return True

    def points(self, symbols: set[sp.Symbol], conditions: list[str], count: int) -> list[_State]:
        """Up to ``count`` random parameter values where every condition of the results holds."""
        read = [c for c in (self.result_condition(t) for t in conditions) if c is not None]
        out: list[_State] = []
        for point in random_states(symbols | {s for c in read for s in c.free_symbols}, _CANDIDATES, SEED):
            if all(_truth(c, point) is True for c in read):
                out.append(point)
                if len(out) == count:
                    break
        return out

    # -- the fields ------------------------------------------------------------------------------

    def mark_fields(
        self, motion: dict[str, Any], kp: KeyPath, here: Path, matched: list[dict[str, Any]], at: dict[str, Any]
    ) -> list[EntryResult]:
        """Every field of a matched motion, against each results state it matched."""
        shown = "; ".join(_where(st) for st in matched)
        out = [
            self.m.right(
                (*here, "at"),
                (*kp, "at"),
                at,
                shown,
                f"numeric: the steady motion {shown}, at random parameter values where it exists"
                + (" (an angle up to a multiple of 2 pi)" if set(at) & self.ref.angles else ""),
            )
        ]
        if any(st.get("exists") is False for st in matched):
            out.append(
                self.m.wrong(
                    (*here, "at"), (*kp, "at"), at, shown, "this steady motion does not exist at the given values"
                )
            )
            return out
        for field in STATE_FIELDS[1:]:
            if field not in motion:
                continue
            value, fkp, fpath = motion[field], (*kp, field), (*here, field)
            per_state: list[list[EntryResult]] = []
            for n, st in enumerate(matched):
                known = len(self.m.errors)
                if field in ("exists_where", "stable_where"):
                    found = [self.conditions(value, fkp, st.get(field) or [], fpath)]
                elif field == "stability":
                    found = [self.stability(value, fkp, st, fpath)]
                else:
                    found = self.walk(value, fkp, st.get(field) or {}, fpath)
                if n:
                    del self.m.errors[known:]  # the answer's own errors were found against the first
                per_state.append(found)
            bad = next((f for f in per_state if any(e.status is not Status.CORRECT for e in f)), per_state[0])
            out += bad
        return out

    def stability(self, value: Any, kp: KeyPath, state: dict[str, Any], path: Path) -> EntryResult:
        word = _word(value)
        expected = state.get("stability")
        if word == expected:
            return self.m.right(path, kp, value, expected, "exact: the same verdict")
        reason = state.get("reason")
        if expected == "undetermined":  # tutgen does not decide it: neither right nor wrong
            return self.m.unevaluable(path, kp, value, expected, f"tutgen does not decide this stability ({reason})")
        feedback = f"expected '{expected}'" + (f" ({reason})" if reason else "")
        return self.m.wrong(path, kp, value, expected, feedback)

    # -- conditions ------------------------------------------------------------------------------

    def result_condition(self, text: str) -> sp.Expr | None:
        """A condition of the results as the expression >= 0 where it holds; None when it is no single
        inequality of the grammar (never an error of the answers file)."""
        try:
            return self.condition(text)
        except (ValueError, ExprError):
            return None

    def condition(self, text: str, keypath: KeyPath | None = None) -> sp.Expr:
        """``a <= b`` as the expression that is >= 0 where it holds (b - a); a result's when no keypath."""
        found = _RELATION_RE.findall(text)
        if len(found) != 1:
            if keypath is None:
                raise ValueError(text)
            raise Unreadable(_error(self.m, keypath, "a condition has one of <=, >=, <, >: write 'lhs <= rhs'"))
        op = found[0]
        lhs_text, rhs_text = text.split(op)
        if keypath is None:
            lhs, rhs = self.m.result_expr(lhs_text), self.m.result_expr(rhs_text)
        else:
            lhs = self.m.parseanswer_text(lhs_text, keypath)
            rhs = self.m.parseanswer_text(rhs_text, keypath, text.index(op) + len(op))
            assert lhs is not None and rhs is not None
        return rhs - lhs if op in ("<=", "<", "≤") else lhs - rhs

    def conditions(self, value: Any, kp: KeyPath, result: list[str], path: Path) -> EntryResult:
        """Answered conditions against the results', by their truth at random parameter values."""
        items = value if isinstance(value, list) else [value]
        shown = " and ".join(result) if result else "always"
        try:
            given: list[sp.Expr] = []
            for j, c in enumerate(items):
                ckp = (*kp, j) if isinstance(value, list) else kp
                if (isinstance(c, bool) and c) or (isinstance(c, str) and c.strip().lower() in _ALWAYS):
                    continue
                if not isinstance(c, str):
                    raise Unreadable(_error(self.m, ckp, "a condition is an inequality such as 'g <= R*omega**2'"))
                given.append(self.condition(c, ckp))
        except UnknownName as exc:
            return self.m.wrong(path, kp, value, shown, str(exc))
        except Unreadable as exc:
            return self.m.wrong(path, kp, value, shown, exc.feedback)
        read = [self.result_condition(c) for c in result]
        correct = [c for c in read if c is not None]
        if len(correct) < len(read):
            return self.m.unevaluable(path, kp, value, shown, "tutgen's condition is not an inequality it can compare")
        try:
            with answer_deadline(self.ref.answer_timeout):
                symbols = {s for e in (*given, *correct) for s in e.free_symbols}
                compared = 0
                for point in random_states(symbols, _CONDITION_STATES, SEED):
                    mine = [_truth(e, point) for e in given]
                    theirs = [_truth(e, point) for e in correct]
                    if None in mine or None in theirs:
                        continue  # on a boundary, or not finite there
                    compared += 1
                    if all(mine) != all(theirs):
                        where = ", ".join(f"{s} = {v}" for s, v in sorted(point.items(), key=lambda p: p[0].name))
                        said = "holds" if all(mine) else "does not hold"
                        other = "does not" if all(mine) else "does"
                        return self.m.wrong(
                            path, kp, value, shown, f"expected {shown}; yours {said} at {where}, where that {other}"
                        )
        except (AnswerTimeLimit, MemoryError, RecursionError):
            return EntryResult(
                entry_name(path),
                Status.TIME_LIMIT,
                feedback="could not be checked (time limit)",
                location=self.m.where(kp),
                given=answer_text(value),
            )
        if not compared:
            return self.m.unevaluable(path, kp, value, shown, "not finite or not real at the random parameter values")
        how = f"numeric: the same truth at {compared} random parameter values"
        return self.m.right(path, kp, value, shown, how if symbols else "exact: the same truth")


def _where(state: dict[str, Any]) -> str:
    """A results state's values as text: ``theta = pi`` (the JSON writes pi as a decimal)."""
    out = []
    for name, v in state["at"].items():
        if isinstance(v, float) and v and abs(v / mpmath.pi - round(v / mpmath.pi)) < 1e-12:
            k = round(v / mpmath.pi)
            v = "pi" if k == 1 else "-pi" if k == -1 else f"{k}*pi"
        out.append(f"{name} = {v}")
    return ", ".join(out)


def _word(value: Any) -> str | None:
    if not isinstance(value, str):
        return None
    text = " ".join(value.strip().lower().rstrip(".").split())
    return STABILITY_WORDS.get(text)


def _error(marker: ScalarMarking, keypath: KeyPath, message: str) -> SpecError:
    return SpecError(marker.sheet.location(keypath), message)


def _value(expr: sp.Expr, point: _State) -> mpmath.mpf | None:
    v = evaluate(expr, point)
    return None if v is None or v.digits < 20 else v.value


def _same(a: sp.Expr, b: sp.Expr, point: _State) -> bool:
    x, y = _value(a, point), _value(b, point)
    if x is None or y is None:
        return False
    return bool(abs(x - y) <= _CLOSE * max(1, abs(x), abs(y)))


def _zero(difference: sp.Expr, point: _State) -> bool:
    """Whether an equation's lhs - rhs is 0 at ``point``, relative to the size of its terms."""
    terms = sp.Add.make_args(difference)
    size = [_value(t, point) for t in terms]
    total = _value(difference, point)
    if total is None or any(s is None for s in size):
        return False
    return bool(abs(total) <= _CLOSE * max([1, *(abs(s) for s in size if s is not None)]))


def _truth(condition: sp.Expr, point: _State) -> bool | None:
    """Whether ``condition >= 0`` at ``point``; None on its boundary (or where it has no value)."""
    v = _value(condition, point)
    if v is None or abs(v) <= 1e-12:
        return None
    return bool(v > 0)
