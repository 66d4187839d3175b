"""Quantities with units, exact conversion to SI, and dimensional analysis.

A spec may give a value with a unit: ``15 cm``, ``-9.81 m/s^2``, ``7849 kg/m^3``, ``2 N*m/rad``.
:func:`parse_quantity` turns such text into a :class:`Quantity` whose value is the exact SI
magnitude (``15 cm`` is ``3/20``, ``90 deg`` is ``pi/2``). Like :mod:`tutgen.spec.expr`, the unit
text is read by a small hand-written parser; nothing is evaluated.

Unit expressions::

    unit   := factor (("*" | "/" | <space>) factor)*     # left to right, like arithmetic
    factor := atom (("^" | "**") integer)?               # integer: [+-]digits, or "(" [+-]digits ")"
    atom   := UNIT_NAME | "(" unit ")" | "1"

``/`` divides by the factor right after it only, exactly as in arithmetic: ``kg/m^3`` is kg·m⁻³,
``N*s/m`` is N·s·m⁻¹, but ``a/b*c`` is (a/b)·c, so ``J/kg*s`` would be J·s/kg: write ``a/(b*c)``
(or ``a/b/c``) to divide by a product. ``1`` is allowed as a factor so that ``1/s`` works.
Angles (``rad``, ``deg``, ``rev``) are dimensionless.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, cast

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.functions.elementary.hyperbolic import HyperbolicFunction
from sympy.functions.elementary.trigonometric import InverseTrigonometricFunction, TrigonometricFunction

from tutgen.spec.expr import MAX_DEPTH, MAX_EXPONENT, MAX_LENGTH, ExprError, did_you_mean, number_to_rational

__all__ = [
    "DIMENSIONS",
    "UNITS",
    "Dimension",
    "DimensionMismatch",
    "Quantity",
    "UnitError",
    "dimension_of",
    "parse_quantity",
    "parse_unit",
    "si_unit_latex",
]


class UnitError(ExprError):
    """A unit that cannot be read; ``offset`` is the 0-based index of the problem in the text."""


class DimensionMismatch(ValueError):
    """Two things that must have the same dimension do not (``cannot add kg*m^2 and m``)."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message

    def __str__(self) -> str:
        return self.message


@dataclass(frozen=True)
class Dimension:
    """Exponents of the SI base dimensions mechanics needs: mass (kg), length (m), time (s)."""

    mass: int = 0
    length: int = 0
    time: int = 0

    def __mul__(self, other: Dimension) -> Dimension:
        if not isinstance(other, Dimension):
            return NotImplemented
        return Dimension(self.mass + other.mass, self.length + other.length, self.time + other.time)

    def __truediv__(self, other: Dimension) -> Dimension:
        if not isinstance(other, Dimension):
            return NotImplemented
        return Dimension(self.mass - other.mass, self.length - other.length, self.time - other.time)

    def __pow__(self, exponent: int) -> Dimension:
        if not isinstance(exponent, int) or isinstance(exponent, bool):
            return NotImplemented
        return Dimension(self.mass * exponent, self.length * exponent, self.time * exponent)

    @property
    def is_dimensionless(self) -> bool:
        """Whether every exponent is 0 (a pure number, or an angle)."""
        return self.mass == 0 and self.length == 0 and self.time == 0

    def __str__(self) -> str:
        """The SI base-unit text: ``kg*m/s^2``, ``kg/(m*s^2)``, ``1/s``, ``1`` when dimensionless."""
        top: list[str] = []
        bottom: list[str] = []
        for unit, exponent in (("kg", self.mass), ("m", self.length), ("s", self.time)):
            if exponent:
                side = top if exponent > 0 else bottom
                side.append(unit if abs(exponent) == 1 else f"{unit}^{abs(exponent)}")
        text = "*".join(top) or "1"
        if not bottom:
            return text
        below = bottom[0] if len(bottom) == 1 else "(" + "*".join(bottom) + ")"
        return f"{text}/{below}"


_ONE = Dimension()
_MASS = Dimension(mass=1)
_LENGTH = Dimension(length=1)
_TIME = Dimension(time=1)
_FORCE = Dimension(1, 1, -2)
_ENERGY = Dimension(1, 2, -2)

#: The named dimensions a spec may declare for a parameter.
DIMENSIONS: Mapping[str, Dimension] = MappingProxyType(
    {
        "dimensionless": _ONE,
        "angle": _ONE,
        "mass": _MASS,
        "length": _LENGTH,
        "time": _TIME,
        "area": Dimension(length=2),
        "volume": Dimension(length=3),
        "density": Dimension(1, -3, 0),
        "velocity": Dimension(0, 1, -1),
        "acceleration": Dimension(0, 1, -2),
        "angular_velocity": Dimension(time=-1),
        "force": _FORCE,
        "torque": _ENERGY,
        "energy": _ENERGY,
        "power": Dimension(1, 2, -3),
        "inertia": Dimension(1, 2, 0),
        "stiffness": Dimension(1, 0, -2),
        "torsional_stiffness": _ENERGY,
        "damping": Dimension(1, 0, -1),
        "torsional_damping": Dimension(1, 2, -1),
        "frequency": Dimension(time=-1),
        "pressure": Dimension(1, -1, -2),
    }
)

_LB = sp.Rational(45359237, 10**8)
_STANDARD_GRAVITY = sp.Rational(980665, 100000)

#: Every unit a quantity may use: name -> (exact factor to SI, dimension).
UNITS: Mapping[str, tuple[sp.Expr, Dimension]] = MappingProxyType(
    {
        # length
        "m": (sp.Integer(1), _LENGTH),
        "cm": (sp.Rational(1, 100), _LENGTH),
        "mm": (sp.Rational(1, 1000), _LENGTH),
        "km": (sp.Integer(1000), _LENGTH),
        "um": (sp.Rational(1, 10**6), _LENGTH),
        "in": (sp.Rational(254, 10000), _LENGTH),
        "ft": (sp.Rational(3048, 10000), _LENGTH),
        # mass
        "kg": (sp.Integer(1), _MASS),
        "g": (sp.Rational(1, 1000), _MASS),
        "mg": (sp.Rational(1, 10**6), _MASS),
        "t": (sp.Integer(1000), _MASS),
        "lb": (_LB, _MASS),
        # time
        "s": (sp.Integer(1), _TIME),
        "ms": (sp.Rational(1, 1000), _TIME),
        "min": (sp.Integer(60), _TIME),
        "h": (sp.Integer(3600), _TIME),
        # angle (dimensionless)
        "rad": (sp.Integer(1), _ONE),
        "deg": (sp.pi / 180, _ONE),
        "rev": (2 * sp.pi, _ONE),
        # force
        "N": (sp.Integer(1), _FORCE),
        "kN": (sp.Integer(1000), _FORCE),
        "mN": (sp.Rational(1, 1000), _FORCE),
        "lbf": (_LB * _STANDARD_GRAVITY, _FORCE),
        # energy, power
        "J": (sp.Integer(1), _ENERGY),
        "kJ": (sp.Integer(1000), _ENERGY),
        "W": (sp.Integer(1), Dimension(1, 2, -3)),
        # pressure
        "Pa": (sp.Integer(1), Dimension(1, -1, -2)),
        "kPa": (sp.Integer(1000), Dimension(1, -1, -2)),
        "MPa": (sp.Integer(10**6), Dimension(1, -1, -2)),
        # frequency
        "Hz": (sp.Integer(1), Dimension(time=-1)),
    }
)

#: Spellings people use for a unit tutgen knows under another name (for hints only).
_ALIASES: Mapping[str, str] = MappingProxyType(
    {
        "sec": "s", "secs": "s", "second": "s", "seconds": "s",
        "meter": "m", "meters": "m", "metre": "m", "metres": "m", "micron": "um", "microns": "um",
        "inch": "in", "inches": "in", "foot": "ft", "feet": "ft",
        "gram": "g", "grams": "g", "lbs": "lb", "tonne": "t", "tonnes": "t",
        "minute": "min", "minutes": "min", "mins": "min", "hr": "h", "hrs": "h", "hour": "h", "hours": "h",
        "degree": "deg", "degrees": "deg", "radian": "rad", "radians": "rad", "rpm": "rev/min",
        "newton": "N", "newtons": "N", "joule": "J", "joules": "J", "watt": "W", "watts": "W",
        "pascal": "Pa", "hertz": "Hz",
    }
)  # fmt: skip


@dataclass(frozen=True)
class Quantity:
    """A number with a unit: its exact SI magnitude, its dimension, and the unit as written."""

    value: sp.Expr
    dimension: Dimension
    unit: str


# ---------------------------------------------------------------------------------------------
# Unit parser
# ---------------------------------------------------------------------------------------------

_NUMBER_RE = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NAME_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_INTEGER_RE = re.compile(r"[0-9]+")
_NAME_WITH_DIGITS_RE = re.compile(r"([A-Za-z]+)([0-9]+)")
_WHITESPACE = frozenset(" \t\r\n\f\v")
_OPERATORS = ("**", "*", "/", "^", "(", ")", "+", "-")
_NUMBER_IN_UNIT = "a unit cannot contain a number; write powers with '^', e.g. 'm^2'"
_CHAR_HINTS = {
    ".": "multiply units with '*' or a space, e.g. 'N*m' or 'N m'; unit powers are whole numbers",
    "·": "multiply units with '*' or a space, e.g. 'N*m' or 'N m'",
    "µ": "write micro as 'u', e.g. 'um'",
    "μ": "write micro as 'u', e.g. 'um'",
    "²": "write powers with '^', e.g. 'm^2'",
    "³": "write powers with '^', e.g. 'm^3'",
}


@dataclass(frozen=True, slots=True)
class _Token:
    kind: str  # "name", "integer", "op" or "end"
    text: str
    offset: int

    def describe(self) -> str:
        return "the end of the unit" if self.kind == "end" else f"'{self.text}'"

    def is_op(self, *ops: str) -> bool:
        return self.kind == "op" and self.text in ops


class _UnitParser:
    """Parses ``text[start:]`` as a unit expression; offsets are indices into ``text``."""

    def __init__(self, text: str, start: int) -> None:
        self.text = text
        self.pos = start
        self.prev: _Token | None = None
        self.tok = self._scan()

    def _scan(self) -> _Token:
        text = self.text
        pos = self.pos
        while pos < len(text) and text[pos] in _WHITESPACE:
            pos += 1
        if pos >= len(text):
            self.pos = len(text)
            return _Token("end", "", len(text))
        for kind, pattern in (("name", _NAME_RE), ("integer", _INTEGER_RE)):
            match = pattern.match(text, pos)
            if match:
                self.pos = match.end()
                return _Token(kind, match.group(), pos)
        for op in _OPERATORS:
            if text.startswith(op, pos):
                self.pos = pos + len(op)
                return _Token("op", op, pos)
        char = text[pos]
        raise UnitError(f"unexpected character {char!r} in a unit", pos, _CHAR_HINTS.get(char))

    def _advance(self) -> _Token:
        tok = self.tok
        self.prev = tok
        self.tok = self._scan()
        return tok

    def parse(self) -> tuple[sp.Expr, Dimension]:
        if self.tok.kind == "end":
            raise UnitError("empty unit", self.tok.offset)
        factor, dimension = self._product(0)
        if self.tok.kind != "end":
            if self.tok.is_op(")"):
                raise UnitError("unmatched ')' in the unit: there is no '(' before it", self.tok.offset)
            raise self._unexpected("'*', '/', '^' or the end of the unit")
        return factor, dimension

    def _unexpected(self, expected: str) -> UnitError:
        after = "" if self.prev is None else f" after {self.prev.describe()}"
        hint = None
        if self.tok.is_op("+", "-"):
            hint = "a quantity is one number followed by a unit, e.g. '15 cm' or '9.81 m/s^2'"
        elif self.tok.kind == "integer":
            hint = _NUMBER_IN_UNIT
        return UnitError(f"expected {expected}{after}, found {self.tok.describe()}", self.tok.offset, hint)

    def _starts_factor(self) -> bool:
        return self.tok.kind == "name" or self.tok.is_op("(") or (self.tok.kind == "integer" and self.tok.text == "1")

    def _product(self, depth: int) -> tuple[sp.Expr, Dimension]:
        factor, dimension = self._power(depth)
        while True:
            if self.tok.is_op("*", "/"):
                op = self._advance().text
            elif self._starts_factor():
                op = "*"  # a space (or nothing, before '(') multiplies
            else:
                return factor, dimension
            right, right_dimension = self._power(depth)
            if op == "*":
                factor, dimension = factor * right, dimension * right_dimension
            else:
                factor, dimension = factor / right, dimension / right_dimension

    def _power(self, depth: int) -> tuple[sp.Expr, Dimension]:
        factor, dimension = self._atom(depth)
        if not self.tok.is_op("^", "**"):
            return factor, dimension
        self._advance()
        exponent = self._exponent()
        return sp.Pow(factor, exponent), dimension**exponent

    def _exponent(self) -> int:
        parenthesised = self.tok.is_op("(")
        if parenthesised:
            self._advance()
        first = self.tok
        sign = 1
        if self.tok.is_op("+", "-"):
            sign = -1 if self._advance().text == "-" else 1
        if self.tok.kind != "integer":
            hint = "unit powers are whole numbers, e.g. 'm^2' or 's^-2'"
            raise UnitError(
                f"expected a whole-number power after {self.prev.describe() if self.prev else '^'}, "
                f"found {self.tok.describe()}",
                self.tok.offset,
                hint,
            )
        digits = self.tok.text.lstrip("0") or "0"
        if len(digits) > 3 or int(digits) > MAX_EXPONENT:
            raise UnitError(f"the power of a unit is too large (the limit is ±{MAX_EXPONENT})", first.offset)
        self._advance()
        if parenthesised:
            if not self.tok.is_op(")"):
                raise self._unexpected("')'")
            self._advance()
        return sign * int(digits)

    def _atom(self, depth: int) -> tuple[sp.Expr, Dimension]:
        tok = self.tok
        if tok.kind == "name":
            if tok.text not in UNITS:
                raise _unknown_unit(tok.text, tok.offset)
            self._advance()
            return UNITS[tok.text]
        if tok.kind == "integer" and tok.text == "1":
            self._advance()
            return sp.Integer(1), _ONE
        if tok.is_op("("):
            if depth >= MAX_DEPTH:
                raise UnitError(f"the unit is nested too deeply (more than {MAX_DEPTH} parentheses)", tok.offset)
            self._advance()
            inner = self._product(depth + 1)
            if self.tok.kind == "end":
                raise UnitError("unclosed '(' in the unit: expected ')', found the end of the unit", tok.offset)
            if not self.tok.is_op(")"):
                raise self._unexpected("'*', '/', '^' or ')'")
            self._advance()
            return inner
        after = "" if self.prev is None else f" after {self.prev.describe()}"
        hint = None
        if tok.kind == "integer":
            hint = _NUMBER_IN_UNIT
        raise UnitError(f"expected a unit{after}, found {tok.describe()}", tok.offset, hint)


def _unknown_unit(name: str, offset: int) -> UnitError:
    """The error for a unit name tutgen does not know, with the most useful hint."""
    suggestion = _ALIASES.get(name) or _ALIASES.get(name.lower())
    if suggestion is None and name.endswith("s") and name[:-1] in UNITS:
        suggestion = name[:-1]  # a plural: "cms", "kgs", "degs"
    match = _NAME_WITH_DIGITS_RE.fullmatch(name)
    if suggestion is None and match and match.group(1) in UNITS:
        hint = f"write powers with '^', e.g. '{match.group(1)}^{match.group(2)}'"
    else:
        suggestion = suggestion or did_you_mean(name, UNITS)
        hint = f"did you mean '{suggestion}'?" if suggestion else "known units: " + ", ".join(UNITS)
    return UnitError(f"unknown unit '{name if len(name) <= 40 else name[:37] + '...'}'", offset, hint)


def parse_unit(text: str) -> tuple[sp.Expr, Dimension]:
    """The exact SI factor and the dimension of a unit expression (``kg/m^3``, ``N m``, ``1/s``).

    Offsets of a :class:`UnitError` are indices into ``text``. ``str(dimension)`` of any
    :class:`Dimension` parses back to that dimension with factor 1.
    """
    if len(text) > MAX_LENGTH:
        raise UnitError(f"the unit is too long ({len(text)} characters; the limit is {MAX_LENGTH})", MAX_LENGTH)
    return _UnitParser(text, 0).parse()


def parse_quantity(text: str) -> Quantity | None:
    """A number literal followed by a unit (``15 cm``, ``-9.81 m/s^2``, ``1e-3 kg``), or None.

    Returns None when ``text`` is not of that shape: a bare number (``0.05``), an expression
    (``m1 + 2``, ``2*l``), or text longer than ``MAX_LENGTH`` (the caller then parses it as an
    expression). Once a number is directly followed by a letter the text is taken to be a
    quantity, and a bad unit raises :class:`UnitError` with the offset (into ``text``) of the
    problem and a hint (``15 cms``: "unknown unit 'cms'", "did you mean 'cm'?").
    """
    if not isinstance(text, str) or len(text) > MAX_LENGTH:
        return None
    start = len(text) - len(text.lstrip())
    match = _NUMBER_RE.match(text, start)
    if not match:
        return None
    unit_start = match.end()
    while unit_start < len(text) and text[unit_start] in _WHITESPACE:
        unit_start += 1
    if unit_start >= len(text) or not text[unit_start].isalpha():
        return None
    try:
        number = number_to_rational(match.group())
    except ExprError as err:
        raise UnitError(err.message, start + err.offset, err.hint) from None
    factor, dimension = _UnitParser(text, unit_start).parse()
    unit = " ".join(text[unit_start:].split())
    return Quantity(value=sp.Mul(number, factor), dimension=dimension, unit=unit)


# ---------------------------------------------------------------------------------------------
# Dimensional analysis
# ---------------------------------------------------------------------------------------------

_DIMENSIONLESS_FUNCTIONS = (
    TrigonometricFunction,
    InverseTrigonometricFunction,
    HyperbolicFunction,
    sp.exp,
    sp.log,
)


def _function_name(expr: sp.Basic) -> str:
    return str(expr.func.__name__)


def _power_dimension(base: Dimension | None, exponent: sp.Expr, exponent_dim: Dimension | None) -> Dimension | None:
    if exponent_dim is not None and not exponent_dim.is_dimensionless:
        raise DimensionMismatch(f"the exponent of a power must be dimensionless, found {exponent_dim}")
    if base is None:
        return None
    if base.is_dimensionless:
        return _ONE
    if isinstance(exponent, sp.Float):
        exponent = sp.Rational(exponent)
    if isinstance(exponent, sp.Integer):
        return base ** int(exponent)
    if isinstance(exponent, sp.Rational):
        p, q = int(exponent.p), int(exponent.q)
        scaled = (base.mass * p, base.length * p, base.time * p)
        if all(e % q == 0 for e in scaled):
            return Dimension(*(e // q for e in scaled))
        raise DimensionMismatch(
            f"cannot raise {base} to the power {exponent}: the result has no whole-number dimension"
        )
    raise DimensionMismatch(
        f"cannot raise {base} to the power {exponent}: a quantity with a dimension needs a number exponent"
    )


def _agree(dims: list[Dimension | None], verb: str) -> Dimension | None:
    """The common dimension of ``dims``; raises if two known ones differ; None if any is unknown."""
    known = [d for d in dims if d is not None]
    for other in known[1:]:
        if other != known[0]:
            raise DimensionMismatch(f"cannot {verb} {known[0]} and {other}")
    return known[0] if known and len(known) == len(dims) else None


def dimension_of(expr: sp.Expr, dims: Mapping[sp.Symbol, Dimension | None]) -> Dimension | None:
    """The dimension of ``expr`` given the dimensions of its symbols, or None when unknown.

    Numbers (anything without free symbols) are dimensionless; a symbol's dimension is
    ``dims.get(symbol)`` (missing or None: unknown). Terms of a sum (and the two sides of an
    ``Eq``) must agree, products multiply, powers need a rational exponent that leaves whole
    exponents (``sqrt(m^2)`` is ``m``), and the arguments of sin, cos, tan, their inverses, the
    hyperbolic functions, exp and log must be dimensionless (their result is dimensionless even
    when the argument is unknown). ``atan2(y, x)`` needs agreeing arguments and is dimensionless;
    ``Abs`` keeps the dimension, ``sign`` drops it. A derivative divides by the dimension of each
    variable; an applied undefined function such as ``q(t)`` is looked up in ``dims`` like a
    symbol. Anything else with free symbols is unknown (None).

    Every part is checked, even when the result is unknown: a mismatch anywhere raises
    :class:`DimensionMismatch`.
    """
    if isinstance(expr, sp.Symbol):
        return dims.get(expr)
    if isinstance(expr, AppliedUndef):
        return cast(Mapping[Any, Dimension | None], dims).get(expr)
    if isinstance(expr, sp.Derivative):
        result = dimension_of(expr.expr, dims)
        for variable, count in expr.variable_count:
            variable_dim = dimension_of(variable, dims)
            if result is None or variable_dim is None:
                result = None
            else:
                result = result / variable_dim ** int(count)
        return result
    if not expr.free_symbols:
        return _ONE
    if isinstance(expr, sp.Add):
        return _agree([dimension_of(arg, dims) for arg in expr.args], "add")
    if isinstance(expr, sp.Equality):
        return _agree([dimension_of(expr.lhs, dims), dimension_of(expr.rhs, dims)], "equate")
    if isinstance(expr, sp.Mul):
        product: Dimension | None = _ONE
        for arg in expr.args:
            arg_dim = dimension_of(arg, dims)
            product = None if product is None or arg_dim is None else product * arg_dim
        return product
    if isinstance(expr, sp.Pow):
        base, exponent = expr.args
        return _power_dimension(dimension_of(base, dims), exponent, dimension_of(exponent, dims))
    if isinstance(expr, sp.atan2):
        y_dim, x_dim = (dimension_of(arg, dims) for arg in expr.args)
        if y_dim is not None and x_dim is not None and y_dim != x_dim:
            raise DimensionMismatch(f"the arguments of atan2 must have the same dimension, found {y_dim} and {x_dim}")
        return _ONE
    if isinstance(expr, _DIMENSIONLESS_FUNCTIONS):
        for arg in expr.args:
            arg_dim = dimension_of(arg, dims)
            if arg_dim is not None and not arg_dim.is_dimensionless:
                raise DimensionMismatch(
                    f"the argument of {_function_name(expr)} must be dimensionless, found {arg_dim}"
                )
        return _ONE
    if isinstance(expr, sp.Abs):
        return dimension_of(expr.args[0], dims)
    if isinstance(expr, sp.sign):
        dimension_of(expr.args[0], dims)
        return _ONE
    return None


# ---------------------------------------------------------------------------------------------
# Numbers as written (for the worked solution's "Given" and the concrete specs of sheet variants)
# ---------------------------------------------------------------------------------------------


def in_unit(value: sp.Expr, unit: str | None) -> sp.Expr:
    """An exact SI ``value`` in the unit it was written in (``3/20`` m with unit ``cm`` -> 15)."""
    if not unit:
        return value
    factor, _ = parse_unit(unit)
    return sp.simplify(value / factor) if not (value / factor).is_Rational else value / factor


def decimal_text(x: sp.Expr) -> str:
    """An exact rational as a decimal literal when it terminates (``7/2`` -> ``3.5``), else ``p/q``."""
    r = sp.Rational(x)
    if r.q == 1:
        return str(r.p)
    q, twos, fives = r.q, 0, 0
    while q % 2 == 0:
        q, twos = q // 2, twos + 1
    while q % 5 == 0:
        q, fives = q // 5, fives + 1
    if q != 1:
        return f"{r.p}/{r.q}"
    digits = max(twos, fives)
    scaled = abs(r.p) * (10**digits // r.q)
    whole, frac = divmod(scaled, 10**digits)
    text = f"{whole}.{frac:0{digits}d}".rstrip("0").rstrip(".")
    return ("-" if r.p < 0 else "") + text


# ---------------------------------------------------------------------------------------------
# SI units of results (for the worked solution: J_xx = 9.59 x 10^-3 kg m^2, T = 2.925 theta_dot^2 J)
# ---------------------------------------------------------------------------------------------

#: the named SI units a result is printed with, by dimension; an energy is printed in J, and a
#: generalized force of an angle (a torque, the same dimension) in N m: see :func:`si_unit_latex`
_NAMED_UNITS: Mapping[Dimension, str] = MappingProxyType(
    {
        _MASS: "kg",
        _LENGTH: "m",
        _TIME: "s",
        _FORCE: "N",
        _ENERGY: "J",
        Dimension(1, 2, -3): "W",
        Dimension(1, -1, -2): "Pa",
    }
)


def si_unit_latex(dimension: Dimension, torque: bool = False) -> str:
    """The SI unit of a dimension as the body of ``\\mathrm{…}``: a named unit where there is one
    (``N``, ``J``, ``kg``; ``N\\,m`` for an energy that is a torque), else the base units with their
    powers, ``kg\\,m^{2}``, ``m^{3}``, ``kg\\,m\\,s^{-1}``; ``""`` for a dimensionless quantity.

    Examples
    ========
    >>> si_unit_latex(DIMENSIONS["inertia"]), si_unit_latex(DIMENSIONS["energy"])
    ('kg\\\\,m^{2}', 'J')
    >>> si_unit_latex(DIMENSIONS["torque"], torque=True), si_unit_latex(DIMENSIONS["angle"])
    ('N\\\\,m', '')
    """
    if dimension.is_dimensionless:
        return ""
    if dimension == _ENERGY and torque:
        return "N\\,m"
    if dimension in _NAMED_UNITS:
        return _NAMED_UNITS[dimension]
    parts = []
    for unit, exponent in (("kg", dimension.mass), ("m", dimension.length), ("s", dimension.time)):
        if exponent:
            parts.append(unit if exponent == 1 else f"{unit}^{{{exponent}}}")
    return "\\,".join(parts)
