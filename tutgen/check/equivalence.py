"""The decision procedure: is an answer equal to the result? Exact where sympy can decide, else numeric.

In order (docs/check.md, "The decision procedure"):

1. **Size.** Before anything is expanded, the answer's expansion degree and node count are measured
   on its tree (:func:`degree`, :func:`node_count`). An answer above :data:`DEGREE_FACTOR` times the
   result's degree (at least :data:`DEGREE_FLOOR`) or :data:`NODE_FACTOR` times its node count (at
   least :data:`NODE_FLOOR`) is never expanded: ``((q1 + q2)**64)**64`` would take gigabytes, and
   ``sin(300*q)`` expands to a polynomial of degree 300. It is decided at random states only (step 4).
2. **Expansion.** The difference expands to 0: equal, "exact".
3. **Trigonometric normal form.** The expanded difference reduces to 0 by sin² + cos² = 1 and angle
   sums (:func:`tutgen.engine.tidy.trig_reduce`): equal, "exact".
4. **Random states** (:func:`tutgen.check.numeric.compare_at_states`): both sides evaluated in high
   precision; states where either side is not finite, not real or lost its digits to cancellation are
   discarded. Equal at every usable state: equal, "numeric". Different at one: not equal. Fewer than
   half the states usable: "cannot be evaluated", never equal.

A constant factor (for equations of motion, and for feedback) is accepted only when the answer minus
``k`` times the result is decided 0 by the same procedure, and only for ``|k|`` in
[:data:`MIN_SCALE`, :data:`MAX_SCALE`] at every random state (:func:`is_acceptable_scale`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import mpmath
import sympy as sp

from tutgen.check.numeric import NEEDED_DIGITS, SEED, TRIALS, compare_at_states, evaluate, random_states
from tutgen.engine.tidy import trig_reduce

__all__ = [
    "DEGREE_FACTOR",
    "DEGREE_FLOOR",
    "MAX_SCALE",
    "MIN_SCALE",
    "NODE_FACTOR",
    "NODE_FLOOR",
    "NUMERIC_HOW",
    "Decision",
    "constant_factor",
    "decide",
    "degree",
    "groups",
    "is_acceptable_scale",
    "node_count",
    "reduced",
    "too_large",
]

NUMERIC_HOW = (
    f"numeric: equal at {TRIALS} random states (seed {SEED}, every symbol drawn from [0.3, 2.7], "
    f"at least {NEEDED_DIGITS} digits kept); symbolic simplification did not decide"
)
#: An answer may be this many times the result's expansion degree (but always DEGREE_FLOOR) ...
DEGREE_FACTOR = 4
DEGREE_FLOOR = 16
#: ... and this many times its node count (but always NODE_FLOOR) before it is refused expansion.
NODE_FACTOR = 10
NODE_FLOOR = 400
#: The constant factors an equation of motion may be scaled by, in magnitude.
MIN_SCALE = 1e-6
MAX_SCALE = 1e6
#: Degrees and counts are capped here, so that measuring a hostile tree stays cheap.
_CAP = 10**9

_PERIODIC = (sp.sin, sp.cos, sp.tan, sp.sinh, sp.cosh, sp.tanh, sp.exp)


@lru_cache(maxsize=8192)
def degree(expr: sp.Basic) -> int:
    """An upper bound of the degree ``expand`` and ``trig_reduce`` would produce, read off the tree
    without expanding: a sum has its largest term's degree, a product the sum of its factors', an
    integer power n times its base's; ``sin(3*q1 + q2)`` counts 4, since the angle sums expand to
    powers of that degree."""
    if expr.is_Atom:
        return 1 if expr.is_Symbol else 0
    if expr.is_Add:
        return min(_CAP, max(degree(a) for a in expr.args))
    if expr.is_Mul:
        return min(_CAP, sum(degree(a) for a in expr.args))
    if expr.is_Pow:
        base, exponent = expr.args
        if exponent.is_Integer:
            return min(_CAP, abs(int(exponent)) * degree(base))  # type: ignore[arg-type]
        return min(_CAP, degree(base) + degree(exponent) + 1)
    if isinstance(expr, _PERIODIC) and expr.args:
        multiple = 0
        for term in sp.Add.make_args(expr.args[0]):
            coeff = term.as_coeff_Mul()[0]
            multiple += max(1, int(abs(coeff))) if coeff.is_Rational else 1
        return min(_CAP, max(1, multiple) * max(1, degree(expr.args[0])))
    return min(_CAP, sum(degree(a) for a in expr.args) + 1)


def node_count(expr: sp.Basic, limit: int = _CAP) -> int:
    """The number of nodes of ``expr``'s tree, counted up to ``limit``."""
    n = 0
    for _ in sp.preorder_traversal(expr):
        n += 1
        if n >= limit:
            break
    return n


def too_large(given: sp.Expr, correct: sp.Expr) -> str | None:
    """Why ``given`` is too large to expand next to ``correct`` (a sentence for the report), or None."""
    deg, allowed = degree(given), max(DEGREE_FLOOR, DEGREE_FACTOR * degree(correct))
    if deg > allowed:
        return f"not expanded: its degree {deg} is above {allowed} ({DEGREE_FACTOR} times the correct expression's)"
    allowed = max(NODE_FLOOR, NODE_FACTOR * node_count(correct))
    nodes = node_count(given, allowed + 1)
    if nodes > allowed:
        return f"not expanded: it has more than {allowed} operations ({NODE_FACTOR} times the correct expression's)"
    return None


@dataclass(frozen=True)
class Decision:
    """The outcome of the decision procedure: ``equal`` True, False, or None ("cannot be evaluated").

    ``how`` says how an equality was decided ("exact: ...", "numeric: ..."); ``reason`` why the
    states could not decide, or why the answer was not expanded.
    """

    equal: bool | None
    how: str = ""
    reason: str = ""


def decide(given: sp.Expr, correct: sp.Expr, *, rel_tol: float | None = None, abs_tol: float = 0.0) -> Decision:
    """Whether ``given`` equals ``correct``, by the procedure of this module's docstring.

    With ``rel_tol``/``abs_tol`` (the instructor's tolerance) the symbolic steps are skipped and the
    sides must agree within it at every usable random state.
    """
    large = too_large(given, correct)
    if rel_tol is None and large is None:
        e = sp.expand(given - correct)
        if e == 0:
            return Decision(True, "exact: the difference expands to 0")
        if e.has(sp.sin, sp.cos) and trig_reduce(e) == 0:
            return Decision(True, "exact: equal by trigonometric identities")
    found = compare_at_states(given, correct, rel_tol=rel_tol, abs_tol=abs_tol)
    if found.equal is None:
        return Decision(None, reason=found.reason)
    if not found.equal:
        return Decision(False, reason=large or "")
    if rel_tol is not None:
        how = f"numeric: within rel_tol {rel_tol:g} / abs_tol {abs_tol:g} at {TRIALS} random states (seed {SEED})"
        return Decision(True, how)
    return Decision(True, NUMERIC_HOW + (f"; {large}" if large else ""))


@lru_cache(maxsize=8192)
def reduced(expr: sp.Expr) -> sp.Expr:
    """``expr`` in trigonometric normal form (or expanded, if it has no sines or cosines)."""
    return trig_reduce(expr) if expr.has(sp.sin, sp.cos) else sp.expand(expr)


def groups(expr: sp.Expr, state: frozenset[sp.Symbol] | None) -> dict[sp.Expr, sp.Expr]:
    """``expr`` (expanded) as {monomial: coefficient}: by monomials in the state symbols with
    coefficients in the parameters, or (``state`` None) by monomials with numeric coefficients."""
    out: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(expr):
        if state is None:
            coeff, key = term.as_coeff_Mul()
        else:
            coeff, key = term.as_independent(*state, as_Add=False)
        out[key] = out.get(key, sp.S.Zero) + coeff
    return {k: v for k, v in out.items() if sp.expand(v) != 0}


def is_acceptable_scale(k: sp.Expr) -> bool:
    """Whether ``|k|`` lies in [MIN_SCALE, MAX_SCALE] at every random state of its symbols (a factor
    in the parameters, such as ``m2``, is measured at the same states as the answers)."""
    for state in random_states(k.free_symbols):
        v = evaluate(k, state)
        if v is None or v.value == 0:
            return False
        with mpmath.workdps(30):
            size = abs(v.value)
            if not (MIN_SCALE <= size <= MAX_SCALE):
                return False
    return True


def constant_factor(
    given: sp.Expr,
    correct: sp.Expr,
    state: frozenset[sp.Symbol],
    forbidden: frozenset[sp.Symbol],
    *,
    monomial: bool = False,
) -> sp.Expr | None:
    """A non-zero ``k`` free of the state (and of ``forbidden``) with given = k * correct, decided by
    :func:`decide`, or None. With ``monomial``, only a product of powers (2, m2, 1/l) counts, not a
    ratio of sums. The caller bounds ``k`` (:func:`is_acceptable_scale`)."""
    if correct == 0 or given == 0 or too_large(given, correct):
        return None
    grouping = state if (given.free_symbols | correct.free_symbols) & state else None
    g, c = groups(reduced(given), grouping), groups(reduced(correct), grouping)
    tried: set[sp.Expr] = set()
    candidates = [sp.cancel(sp.together(given / correct))]
    candidates += [sp.cancel(g[key] / coeff) for key, coeff in c.items() if key in g]
    for k in candidates:
        if k in tried or k == 0 or k.free_symbols & (state | forbidden):
            continue
        if monomial and any(isinstance(node, sp.Add) for node in sp.preorder_traversal(k)):
            continue
        tried.add(k)
        if k.is_zero is False and decide(given, k * correct).equal:
            return k
        if len(tried) >= 4:
            break
    return None
