"""Expressions as text in the spec grammar, fast: the printer of the JSON output and of the checker.

sympy's ``StrPrinter`` dispatches every node through its class hierarchy and, with ``order="lex"``,
re-sorts every sum by its monomials while printing: 337 of the 374 s of the fully symbolic PUMA
560's JSON (issue 17). :func:`grammar_text` prints a short expression as before (lex order, cheap at
that size) and walks a long one once (:func:`fast_text`), printing terms and factors in the order of
the expression's arguments. sympy sorts those when it builds a sum or a product
(``Basic.compare``: by kind, then by name or value, never by hash), so the text is the same on every
run, machine and ``PYTHONHASHSEED``; a result's value is unchanged, only its printed order differs
from the lex order of earlier versions (docs/json-output.md). Repeated subexpressions (a sum that is
a coefficient of several entries) are printed once (a cache keyed by the expression itself, which
sympy compares structurally: ``x + 1.0`` and ``x + 1`` are different keys).

The text reads back to the same expression through :func:`tutgen.spec.expr.parse_expression`
(tests/render/test_grammar.py): ``**`` for powers, ``a/b`` for quotients, ``sqrt(x)``, exact
fractions, ``exp(1)`` for e; a node outside this small set (a float, a derivative, a piecewise
function) is printed by sympy's own printer, kept inside the grammar.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import sympy as sp
from sympy.core.mul import _keep_coeff
from sympy.printing.precedence import PRECEDENCE, PRECEDENCE_FUNCTIONS, PRECEDENCE_VALUES, precedence
from sympy.printing.str import StrPrinter

from tutgen.render.signs import commutative_factors, negative_number
from tutgen.render.size import lower_bound_exceeds

__all__ = ["LEX_BUDGET", "fast_text", "grammar_text"]


class _GrammarPrinter(StrPrinter):
    """sympy's str printer, kept inside the spec grammar (which has no constant E)."""

    def _print_Exp1(self, expr: sp.Basic) -> str:
        return "exp(1)"


_FALLBACK = _GrammarPrinter({"order": "none"})

# precedence of what a printed text is at its top: a sum, a product or quotient, a power, an atom
_SUM, _PRODUCT, _POWER, _ATOM = 1, 2, 3, 4


#: an expression whose size is at most this (the lower bound of tutgen.render.size, about a third of
#: its count_ops) is printed by sympy's lex-ordered printer, as before: cheap at this size, and what a
#: reader of a short result or an answer check's feedback expects (a**2*m, terms by their monomials)
LEX_BUDGET = 60


class _LexPrinter(_GrammarPrinter):
    """The grammar printer in sympy's lex order, its terms ordered by :func:`lex_terms` and its
    parentheses decided by :func:`_precedence` (both sympy's results, faster)."""

    def _as_ordered_terms(self, expr: sp.Basic, order: str | None = None) -> list[sp.Basic]:
        if (order or self.order) == "lex":
            found = lex_terms(expr)
            if found is not None:
                return found
        return list(super()._as_ordered_terms(expr, order=order))

    def parenthesize(self, item: sp.Basic, level: int, strict: bool = False) -> str:
        prec = _precedence(item)
        if prec < level or (not strict and prec <= level):
            return f"({self._print(item)})"
        return str(self._print(item))

    def _print_Mul(self, expr: sp.Basic) -> str:
        """sympy's ``StrPrinter._print_Mul`` for a product as sympy builds it, with :func:`_precedence` and
        each factor's sort key remembered; anything else (an unevaluated product) by sympy's own."""
        args = expr.args
        if args[0] is sp.S.One or any(
            isinstance(a, sp.Number) or (a.is_Pow and all(ai.is_Integer for ai in a.args)) for a in args[1:]
        ):
            return str(super()._print_Mul(expr))
        prec = _precedence(expr)
        c, e = expr.as_coeff_Mul()
        if c < 0:
            expr = _keep_coeff(-c, e)
            sign = "-"
        else:
            sign = ""
        num: list[sp.Basic] = []  # the numerator's items
        den: list[sp.Basic] = []  # the denominator's
        pow_paren = []  # powers with exponent -1 of a base of several factors
        for item in _ordered_factors(expr):
            if item.is_commutative and item.is_Pow and bool(item.exp.as_coeff_Mul()[0] < 0):
                if item.exp is not sp.S.NegativeOne:
                    den.append(_inverted(item))
                else:
                    if len(item.args[0].args) != 1 and isinstance(item.base, (sp.Mul, sp.Pow)):
                        pow_paren.append(item)
                    den.append(item.base)
            elif item.is_Rational and item is not sp.S.Infinity:
                if item.p != 1:
                    num.append(sp.Rational(item.p))
                if item.q != 1:
                    den.append(sp.Rational(item.q))
            else:
                num.append(item)
        num = num or [sp.S.One]
        num_str = [self.parenthesize(x, prec, strict=False) for x in num]
        den_str = [self.parenthesize(x, prec, strict=False) for x in den]
        for item in pow_paren:
            if item.base in den:
                den_str[den.index(item.base)] = f"({den_str[den.index(item.base)]})"
        if not den:
            return sign + "*".join(num_str)
        if len(den) == 1:
            return sign + "*".join(num_str) + "/" + den_str[0]
        return sign + "*".join(num_str) + "/({})".format("*".join(den_str))

    def _print_Add(self, expr: sp.Basic, order: str | None = None) -> str:
        """sympy's ``StrPrinter._print_Add``, with :func:`_precedence`."""
        terms = self._as_ordered_terms(expr, order=order)
        prec = _precedence(expr)
        out: list[str] = []
        for term in terms:
            t = self._print(term)
            if t.startswith("-") and not term.is_Add:
                sign = "-"
                t = t[1:]
            else:
                sign = "+"
            if _precedence(term) < prec or term.is_Add:
                out.extend([sign, f"({t})"])
            else:
                out.extend([sign, t])
        sign = out.pop(0)
        return ("" if sign == "+" else sign) + " ".join(out)


_LEX = _LexPrinter({"order": "lex"})


def lex_terms(expr: sp.Basic) -> list[sp.Basic] | None:
    """``expr.as_ordered_terms(order="lex")``, the same list, about twice as fast: sympy's ``as_terms``
    converts every term's number with ``complex()``, through ``evalf``, which was most of a sheet's answer
    keys' time (issue 17); the numbers of a problem's terms repeat, and each is converted once here.
    ``None`` for a sum with an ``Order`` term or a non-commutative factor (sympy's own path then)."""
    from sympy.core.exprtools import decompose_power

    gens: set[sp.Basic] = set()
    terms: list[tuple[sp.Basic, tuple[float, float], dict[sp.Basic, object]]] = []
    for term in sp.Add.make_args(expr):
        if term.is_Order or not term.is_commutative:
            return None
        coeff, rest = term.as_coeff_Mul()
        value = _complex(coeff)
        cpart: dict[sp.Basic, object] = {}
        if rest is not sp.S.One:
            for factor in sp.Mul.make_args(rest):
                if factor.is_number:
                    try:
                        value *= _complex(factor)
                    except (TypeError, ValueError):
                        pass
                    else:
                        continue
                base, exp = decompose_power(factor)
                cpart[base] = exp
                gens.add(base)
        terms.append((term, (value.real, value.imag), cpart))
    index = {g: i for i, g in enumerate(sorted(gens, key=sp.default_sort_key))}

    def key(entry: tuple[sp.Basic, tuple[float, float], dict[sp.Basic, object]]) -> tuple[object, ...]:
        _, (re, im), cpart = entry
        monom = [0] * len(index)
        for base, exp in cpart.items():
            monom[index[base]] = -exp  # type: ignore[operator]
        return tuple(monom), (), ((bool(im), im), (re, im))

    return [term for term, _, _ in sorted(terms, key=key)]


def _ordered_factors(expr: sp.Basic) -> list[sp.Basic]:
    """``expr.as_ordered_factors()`` (a product's commutative factors by their sort keys, then the others),
    each factor's key remembered."""
    if not expr.is_Mul:
        return [expr]
    if expr.is_commutative:  # (set when the product was made) every factor is: no factor asked
        cpart, ncpart = commutative_factors(expr), []
    else:
        cpart, ncpart = expr.args_cnc()
    cpart.sort(key=_sort_key)
    return [*cpart, *ncpart]


@lru_cache(maxsize=1 << 14)
def _sort_key(factor: sp.Basic) -> Any:
    """``factor.sort_key()``, remembered (a problem's factors recur in every variant)."""
    return factor.sort_key(order=None)


def _inverted(item: sp.Basic) -> sp.Basic:
    """sympy's ``apow`` of ``StrPrinter._print_Mul``: a power with its exponent's sign changed."""
    b, e = item.as_base_exp()
    eargs = list(sp.Mul.make_args(e))
    if eargs[0] is sp.S.NegativeOne:
        eargs = eargs[1:]
    else:
        eargs[0] = -eargs[0]
    e = sp.Mul._from_args(eargs)
    if isinstance(item, sp.Pow):
        return item.func(b, e, evaluate=False)
    return item.func(e, evaluate=False)


#: how sympy's ``precedence`` finds the precedence of an object of each class: by walking the class's MRO
#: for a name in its tables, every time; the walk's outcome depends on the class alone
_PRECEDENCE_OF: dict[type, tuple[str, Any]] = {}


def _precedence(item: sp.Basic) -> int:
    """``sympy.printing.precedence.precedence(item)``, the same number: the walk of the class's MRO done
    once per class, and a product's sign read off its number (sympy compares the product with its
    negative, building it) when that number is finite (a product's number is never zero)."""
    how = _PRECEDENCE_OF.get(type(item))
    if how is None:
        how = _PRECEDENCE_OF[type(item)] = _precedence_rule(type(item))
    kind, rule = how
    if kind == "value":
        return int(rule)
    if kind == "mul" and not any(hasattr(a, "precedence") and isinstance(a, sp.Function) for a in item.args):
        first = item.args[0]
        if not first.is_Number:
            return PRECEDENCE["Mul"]
        if isinstance(first, sp.Rational):  # finite: its sign is its numerator's (no assumptions asked of
            return PRECEDENCE["Add"] if first.p < 0 else PRECEDENCE["Mul"]  # a number just made: costly)
        if first.is_finite:
            return PRECEDENCE["Add"] if first.is_extended_negative else PRECEDENCE["Mul"]
    return int(precedence(item))


def _precedence_rule(cls: type) -> tuple[str, Any]:
    if hasattr(cls, "precedence"):
        return "sympy", None
    for base in cls.mro():
        name = base.__name__
        if name in PRECEDENCE_FUNCTIONS:
            return ("mul", None) if name == "Mul" else ("sympy", None)
        if name in PRECEDENCE_VALUES:
            return "value", PRECEDENCE_VALUES[name]
    return "value", PRECEDENCE["Atom"]


@lru_cache(maxsize=1 << 14)
def _complex(number: sp.Basic) -> complex:
    """``complex(number)``, remembered (sympy compares numbers structurally: equal keys, equal values)."""
    return complex(number)


def grammar_text(expr: sp.Basic) -> str:
    """An expression in the spec grammar: a short one in sympy's lex order, a long one in the order of
    its arguments (see the module's docstring).

    >>> x, y = sp.symbols("x y")
    >>> grammar_text(-x**2 / (2 * y) + sp.sqrt(x) - sp.Rational(1, 3))
    'sqrt(x) - x**2/(2*y) - 1/3'
    >>> long = sp.Add(*(sp.Symbol(f"m{i}") * x ** (i % 3) for i in range(70)))
    >>> grammar_text(long)[:30]
    'm0 + m12 + m15 + m18 + m21 + m'
    """
    if not lower_bound_exceeds([expr], LEX_BUDGET):
        return _lex_text(expr)
    return _text(expr)[0]


@lru_cache(maxsize=1 << 13)
def _lex_text(expr: sp.Basic) -> str:
    """A short expression in sympy's lex order, remembered: sorting its terms is most of a sheet's answer
    keys' time, and the results of a problem's variants repeat (a velocity holds the lengths alone)."""
    return str(_LEX.doprint(expr))


def fast_text(expr: sp.Basic) -> str:
    """An expression in the spec grammar, always in the order of its arguments (one walk of the tree).

    >>> x, y = sp.symbols("x y")
    >>> fast_text(-x**2 / (2 * y) + sp.sqrt(x) - sp.Rational(1, 3))
    '-1/3 + sqrt(x) - x**2/(2*y)'
    """
    return _text(expr)[0]


def _wrapped(expr: sp.Basic, above: int) -> str:
    """The text of ``expr``, in parentheses when it binds less tightly than ``above``."""
    text, level = _text(expr)
    return f"({text})" if level < above else text


@lru_cache(maxsize=1 << 16)
def _text(expr: sp.Basic) -> tuple[str, int]:
    """(text, precedence of its top) of one expression."""
    if expr.is_Symbol:
        return expr.name, _ATOM
    if expr.is_Integer:
        return str(expr), (_ATOM if expr >= 0 else _SUM)
    if expr.is_Rational:
        return f"{expr.p}/{expr.q}", (_PRODUCT if expr.p > 0 else _SUM)
    if expr.is_Add:
        return _add(expr), _SUM
    if expr.is_Mul:
        return _mul(expr)
    if expr.is_Pow:
        return _pow(expr)
    if expr.is_Function and type(expr).__name__ in _FUNCTIONS:
        return f"{type(expr).__name__}({', '.join(_text(a)[0] for a in expr.args)})", _ATOM
    text = _FALLBACK.doprint(expr)
    return text, (_ATOM if expr.is_Atom and not text.startswith("-") else _SUM)


# the functions of the spec grammar (tutgen.spec.expr.FUNCTIONS) by the name of their sympy class
_FUNCTIONS = frozenset(
    {"sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "exp", "log", "atan2", "Abs"}
)


def _negative(term: sp.Basic) -> bool:
    """A term printed with a minus sign: a negative number, or a product with a negative coefficient."""
    first = term if term.is_Number else term.args[0] if term.is_Mul else None
    if first is None or not first.is_Number:
        return False
    if isinstance(first, (sp.Rational, sp.Float)):  # finite: negative_number is its is_negative
        return negative_number(first)
    return bool(first.is_negative)


def _add(expr: sp.Basic) -> str:
    out: list[str] = []
    for i, term in enumerate(expr.args):
        if _negative(term):
            body = _positive_text(term)
            out.append(f"-{body}" if i == 0 else f" - {body}")
        else:
            text = _text(term)[0]  # a term of a sum needs no parentheses
            out.append(text if i == 0 else f" + {text}")
    return "".join(out)


def _positive_text(term: sp.Basic) -> str:
    """The text of -term for a negative number or a product with a negative coefficient, as a term of
    a sum (a product binds tighter than the sign in front of it)."""
    if term.is_Number:
        return _text(-term)[0]
    coeff = -term.args[0]
    return _product(coeff, term.args[1:])[0]


def _mul(expr: sp.Basic) -> tuple[str, int]:
    args = expr.args
    if args[0].is_Number:
        coeff, factors = args[0], args[1:]
    else:
        coeff, factors = sp.Integer(1), args
    if coeff.is_negative:
        text, _ = _product(-coeff, factors)
        return f"-{text}", _SUM
    return _product(coeff, factors)


def _product(coeff: sp.Basic, factors: tuple[sp.Basic, ...]) -> tuple[str, int]:
    """coeff * factors, for a positive number coeff: numerator / denominator, as StrPrinter writes it."""
    num: list[str] = []
    den: list[str] = []
    if coeff.is_Rational:
        if coeff.p != 1:
            num.append(str(coeff.p))
        if coeff.q != 1:
            den.append(str(coeff.q))
    elif coeff != 1:
        num.append(_wrapped(coeff, _PRODUCT + 1))
    for f in factors:
        if f.is_Pow and f.exp.is_Rational and f.exp.is_negative:
            inverse = f.base if f.exp == -1 else sp.Pow(f.base, -f.exp, evaluate=False)
            den.append(_wrapped(inverse, _PRODUCT + 1))
        else:
            num.append(_wrapped(f, _PRODUCT + 1))
    top = "*".join(num) if num else "1"
    if not den:
        return top, _PRODUCT
    bottom = den[0] if len(den) == 1 else "(" + "*".join(den) + ")"
    return f"{top}/{bottom}", _PRODUCT


def _pow(expr: sp.Basic) -> tuple[str, int]:
    base, exp = expr.args
    if base is sp.E:
        return f"exp({_text(exp)[0]})", _ATOM
    if exp is sp.S.Half:
        return f"sqrt({_text(base)[0]})", _ATOM
    if exp.is_Rational and exp.is_negative:
        return _product(sp.Integer(1), (expr,))
    base_text = _wrapped(base, _POWER + 1)
    if base.is_Number and (base.is_negative or not base.is_Integer):
        base_text = f"({_text(base)[0]})"
    exp_text = _text(exp)[0] if (exp.is_Integer and exp >= 0) or exp.is_Symbol else f"({_text(exp)[0]})"
    return f"{base_text}**{exp_text}", _POWER
