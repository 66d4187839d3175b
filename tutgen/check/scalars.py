"""Marking one scalar entry: an expression, a number (with its unit and rounding), an equation of motion.

:class:`ScalarMarking` reads an answer with the spec grammar's whitelist parser (an answers file is
data, never code), asks the decision procedure (:func:`tutgen.check.equivalence.decide`) and turns
its outcome into a verdict with feedback. The walk over tables and lists is
:class:`tutgen.check.compare._Marker`'s, which builds on this class.
"""

from __future__ import annotations

import re
import weakref
from dataclasses import dataclass
from decimal import Decimal
from typing import Any

import mpmath
import sympy as sp

from tutgen.check.answers import AnswerSheet, Tolerance
from tutgen.check.decimals import decimal_literals, half_unit, within_rounding
from tutgen.check.equivalence import (
    MAX_SCALE,
    MIN_SCALE,
    Decision,
    constant_factor,
    decide,
    groups,
    is_acceptable_scale,
    reduced,
    too_large,
)
from tutgen.check.feedback import diagnose, number_feedback, round_half_up, significant
from tutgen.check.names import DIMENSION_OF, TEXT_FIELDS, Path, entry_name, field_of
from tutgen.check.notation import ascii_answer
from tutgen.check.numeric import value_of_number
from tutgen.check.verdicts import EntryResult, Reference, Status
from tutgen.errors import SpecError
from tutgen.render.jsonout import expr_text
from tutgen.spec.expr import MAX_LENGTH, ExprError, number_to_rational, parse_expression
from tutgen.spec.loader import KeyPath
from tutgen.spec.units import Dimension, parse_quantity, parse_unit

__all__ = ["NUMBER_RE", "ScalarMarking", "UnknownName", "Unreadable", "answer_limit", "answer_text"]

#: Results measured from a datum: an answer off by a constant is right (a potential energy's zero is a
#: choice; so is, with it, the Lagrangian's).
_DATUM_FIELDS = frozenset({"potential_energy", "lagrangian"})

NUMBER_RE = re.compile(r"\s*[-+]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")

#: Parsed result expressions, per reference (for as long as the reference lives).
_result_cache: weakref.WeakKeyDictionary[Reference, dict[str, sp.Expr]] = weakref.WeakKeyDictionary()


def answer_limit(result: Any) -> int:
    """The longest answer text read for ``result``: twice the text of the result it answers (a large arm's
    Christoffel symbol copied from tutgen's own JSON runs to thousands of characters), and never less than
    the spec grammar's limit, so that the limit stays a bound on what a hostile file makes tutgen read."""
    return max(MAX_LENGTH, 2 * len(str(result)))


class UnknownName(Exception):
    """An answer that uses a name the problem does not have: a wrong answer, with this feedback."""


class Unreadable(Exception):
    """An answer that is not an expression or a quantity (an unclosed parenthesis, an unknown unit):
    that entry is wrong, with the parse error and its place; the rest of the file is still marked."""

    def __init__(self, error: SpecError) -> None:
        super().__init__(str(error))
        self.error = error

    @property
    def feedback(self) -> str:
        e = self.error
        where = f" (at {e.location.line}:{e.location.col})" if e.location.line else ""
        return f"cannot read the answer: {e.message}" + (f" ({e.hint})" if e.hint else "") + where


@dataclass
class _Parsed:
    expr: sp.Expr
    literal: str | None = None  # the number as written, for rounding checks
    unit_factor: sp.Expr = sp.S.One  # SI value of one written unit
    dimension: Dimension | None = None  # of a quantity with a unit


class ScalarMarking:
    """Marks scalar entries of one sheet against one reference, collecting answers-file errors."""

    def __init__(self, sheet: AnswerSheet, ref: Reference) -> None:
        self.sheet = sheet
        self.ref = ref
        self.errors: list[SpecError] = []

    # -- reading ------------------------------------------------------------------------------

    def where(self, keypath: KeyPath) -> str:
        return str(self.sheet.location(keypath))

    def error(self, keypath: KeyPath, message: str, hint: str | None = None, *, key: bool = False) -> None:
        loc = self.sheet.source.key_location(keypath) if key else self.sheet.location(keypath)
        self.errors.append(SpecError(loc, message, hint))

    def parseanswer_text(self, text: str, keypath: KeyPath, offset: int = 0, limit: int = MAX_LENGTH) -> sp.Expr | None:
        """An answer's expression; ``limit``: the longest text read (:func:`answer_limit` of its result)."""
        rewritten = ascii_answer(text)  # θ̇₁² as theta1_dot**2, 2 m g as 2*m*g
        try:
            expr = parse_expression(rewritten.text, self.ref.symbols, max_length=limit)
        except ExprError as exc:
            if exc.message.startswith("unknown name"):
                raise UnknownName(exc.message + (f" ({exc.hint})" if exc.hint else "")) from None
            loc = self.sheet.source.expr_location(keypath, offset + rewritten.source_offset(exc.offset))
            raise Unreadable(SpecError(loc, exc.message, exc.hint)) from None
        return expr.xreplace(self.ref.values) if self.ref.values else expr

    def read(self, answer: Any, keypath: KeyPath, symbolic: bool = False, limit: int = MAX_LENGTH) -> _Parsed | None:
        """An answer scalar as sympy. ``symbolic``: the result has symbols, so ``2 m g`` whose words
        are all names of the problem is the product ``2*m*g``, not 2 metres followed by a word; a
        number with a unit otherwise stays a quantity (``2 m`` against a length is 2 metres)."""
        if isinstance(answer, bool):
            raise Unreadable(
                SpecError(self.sheet.location(keypath), "expected an expression or a number, found true/false")
            )
        if isinstance(answer, int | float):
            try:
                value = number_to_rational(answer)
            except ExprError as exc:
                raise Unreadable(SpecError(self.sheet.location(keypath), exc.message)) from None
            literal = self.sheet.raw_number(keypath, answer) or repr(answer)
            return _Parsed(value, literal)
        text = str(answer)
        try:
            quantity = parse_quantity(text)
        except ExprError as exc:  # a number and then no unit: perhaps a product (0.2109 θ̇², 2 m g)
            try:
                expr = self.parseanswer_text(text, keypath, limit=limit)
            except (Unreadable, UnknownName):
                loc = self.sheet.source.expr_location(keypath, exc.offset)
                raise Unreadable(SpecError(loc, exc.message, exc.hint)) from None
            return _Parsed(expr) if expr is not None else None
        if quantity is not None and symbolic:
            try:
                return _Parsed(self.parseanswer_text(text, keypath, limit=limit))  # type: ignore[arg-type]
            except (Unreadable, UnknownName):
                pass  # not an expression in the problem's names: the quantity it reads as
        if quantity is not None:
            match = NUMBER_RE.match(text)
            assert match is not None
            factor, _ = parse_unit(quantity.unit)
            return _Parsed(quantity.value, match.group().strip(), factor, quantity.dimension)
        expr = self.parseanswer_text(text, keypath, limit=limit)
        if expr is None:
            return None
        literal = text.strip() if NUMBER_RE.fullmatch(text) else None
        return _Parsed(expr, literal)

    def result_expr(self, value: Any) -> sp.Expr:
        """A result entry (a JSON number or an expression string) as sympy."""
        if isinstance(value, int | float) and not isinstance(value, bool):
            return number_to_rational(value)
        text = str(value)
        cache = _result_cache.setdefault(self.ref, {})
        if text not in cache:  # tutgen's own text, however long (a large arm's Christoffel symbol): no length limit
            cache[text] = parse_expression(text, self.ref.symbols, max_length=None)
        return cache[text]

    # -- items --------------------------------------------------------------------------------
    def rule(self, path: Path) -> tuple[Tolerance, bool]:
        """The instructor's tolerance and scaling rule for the entry at ``path`` (the marker's)."""
        raise NotImplementedError

    # -- scalars --------------------------------------------------------------------------------

    def wrong(self, path: Path, keypath: KeyPath, answer: Any, result: Any, feedback: str) -> EntryResult:
        return EntryResult(
            entry_name(path),
            Status.WRONG,
            feedback=feedback,
            location=self.where(keypath),
            given=answer_text(answer),
            expected=answer_text(result),
        )

    def right(self, path: Path, keypath: KeyPath, answer: Any, result: Any, how: str, remark: str = "") -> EntryResult:
        return EntryResult(
            entry_name(path),
            Status.CORRECT,
            how=how,
            feedback=remark,
            location=self.where(keypath),
            given=answer_text(answer),
            expected=answer_text(result),
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
        correct = self.result_expr(result)
        try:
            parsed = self.read(answer, keypath, symbolic=bool(correct.free_symbols), limit=answer_limit(result))
        except UnknownName as exc:
            return self.wrong(path, keypath, answer, result, str(exc))
        except Unreadable as exc:
            return self.wrong(path, keypath, answer, result, exc.feedback)
        if parsed is None:
            return self.wrong(path, keypath, answer, result, "cannot read the answer")
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
        if decision.equal is False and self.has_decimals(answer) and not too_large(given, correct):
            if within_rounding(given, correct, self.figures, self.ref.state) is not None:
                return self.right(path, keypath, answer, result, self.as_printed)
        if decision.equal is False and field_name in _DATUM_FIELDS:
            shift = self.datum_shift(given, correct)
            if shift is not None:
                how = f"up to an additive constant: yours minus the correct expression is {expr_text(shift)}"
                remark = f"{entry_name(path)} differs by a constant ({expr_text(shift)}): a different datum"
                return self.right(path, keypath, answer, result, how, remark)
        return self.verdict(decision, given, correct, answer, keypath, result, path)

    @property
    def figures(self) -> int:
        """The significant figures a decimal may be rounded to (0: decimals are exact): the marking's,
        else those the spec's solution prints decimals with."""
        stated = self.ref.key.significant_figures
        return self.ref.figures if stated is None else stated

    @property
    def as_printed(self) -> str:
        return f"as printed: each decimal is the result rounded to {self.figures} significant figures"

    @staticmethod
    def has_decimals(answer: Any) -> bool:
        """Whether an answer holds a decimal literal (``0.2109``, ``1.5e-3``): then its coefficients may
        be the result's as printed (:mod:`tutgen.check.decimals`)."""
        return isinstance(answer, str) and bool(decimal_literals(ascii_answer(answer).text))

    def datum_shift(self, given: sp.Expr, correct: sp.Expr) -> sp.Expr | None:
        """``given - correct`` when it is a non-zero constant (free of the coordinates and rates): a
        potential energy measured from another datum. Decided as every equality is (:func:`decide`)."""
        if too_large(given, correct):
            return None
        shift = reduced(given - correct)
        if shift == 0 or shift.free_symbols & self.ref.state:
            return None
        return shift if decide(given, correct + shift).equal else None

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
            given=answer_text(answer),
            expected=answer_text(result),
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
        literal = parsed.literal or ""
        half = half_unit(literal, self.figures) if self.figures and re.search(r"[.eE]", literal) else None
        if half is not None:
            in_unit = sp.N(self.result_expr(result) / parsed.unit_factor, 30)
            if abs(number_to_rational(literal.lstrip("+")) - sp.Rational(str(in_unit))) <= sp.Rational(str(half)):
                return self.right(path, keypath, answer, result, self.as_printed)
            close_to = in_unit != 0 and abs(given - correct) <= 0.01 * abs(correct)  # a rounding, not a slip
            shown = round_half_up(Decimal(str(in_unit)), self.figures) if close_to else None
            if shown is not None:
                said = number_feedback(given, correct, tol) + f"; to {self.figures} significant figures it is {shown}"
                return self.wrong(path, keypath, answer, result, said)
        return self.wrong(path, keypath, answer, result, number_feedback(given, correct, tol))

    # -- equations of motion ------------------------------------------------------------------------

    def equation(self, answer: Any, keypath: KeyPath, result: Any, path: Path) -> EntryResult:
        """An equation of motion: ``lhs = rhs`` or an expression equal to 0, up to moving terms across the
        ``=`` and a constant factor in [MIN_SCALE, MAX_SCALE] (unless the key turns scaling off)."""
        try:
            given = self.read_equation(answer, keypath, answer_limit(result))
        except UnknownName as exc:
            return self.wrong(path, keypath, answer, result, str(exc))
        except Unreadable as exc:
            return self.wrong(path, keypath, answer, result, exc.feedback)
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
        if self.has_decimals(answer) and not too_large(given, correct):
            if within_rounding(given, correct, self.figures, self.ref.state, factors=(1, -1)) is not None:
                return self.right(path, keypath, answer, result, self.as_printed)
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

    def read_equation(self, answer: Any, keypath: KeyPath, limit: int = MAX_LENGTH) -> sp.Expr | None:
        if isinstance(answer, str) and "=" in answer:
            text = answer.replace("==", "=")
            if text.count("=") != 1:
                loc = self.sheet.source.expr_location(keypath, answer.rfind("="))
                raise Unreadable(SpecError(loc, "an equation has one '=': write 'lhs = rhs'"))
            lhs_text, rhs_text = text.split("=")
            offset = answer.index("=") + (2 if "==" in answer else 1)
            lhs = self.parseanswer_text(lhs_text, keypath, limit=limit)
            rhs = self.parseanswer_text(rhs_text, keypath, offset, limit)
            if lhs is None or rhs is None:
                return None
            return lhs - rhs
        parsed = self.read(answer, keypath, symbolic=True, limit=limit)
        return None if parsed is None else parsed.expr


def answer_text(value: Any) -> str | None:
    """An answer or a result as text for the reports (None for no answer)."""
    return None if value is None else str(value)
