"""``xreplace`` that remembers every subtree it rebuilt.

A sheet's unit puts one variant's values into some hundreds of results (H, C, G, T, V, the equations,
their steps) that share most of their subtrees: ``m_2 a_1 a_2 \\cos q_2`` is in H, in T, in L and in
each of Lagrange's terms. sympy's ``xreplace`` rebuilds a shared subtree every time it meets it (and sympy
then asks each rebuilt product its assumptions afresh); :func:`replaced` rebuilds it once per memo.
"""

from __future__ import annotations

from typing import Any

import sympy as sp

__all__ = ["DECIMALS", "replaced"]


def replaced(expr: Any, rule: Any, trees: dict[Any, tuple[Any, bool]]) -> tuple[Any, bool]:
    """sympy's ``Basic._xreplace(rule)`` (the result, and whether anything was replaced), node for node,
    with each subtree's result remembered in ``trees`` (one memo per ``rule``): a subtree met again, in
    this expression or in a later one, is not rebuilt. The same objects as ``expr.xreplace(rule)``: an
    unchanged subtree is itself, a changed one ``func(*args)`` of the same arguments. ``rule``: what
    ``in`` and ``[]`` work on (a dict, or :data:`DECIMALS`)."""
    try:
        return trees[expr]
    except KeyError:
        pass
    if expr in rule:
        out = rule[expr], True
    else:
        args = []
        changed = False
        for a in expr.args:
            if getattr(a, "_xreplace", None) is not None:  # sympy's own test of an argument
                new, hit = replaced(a, rule, trees)
                args.append(new)
                changed |= hit
            else:
                args.append(a)
        out = (expr.func(*args), True) if changed else (expr, False)
    trees[expr] = out
    return out


class _Decimals:
    """The rule of :func:`tutgen.render.blocks.all_decimals` for every expression at once: a rational
    that is not an integer, as a 15-digit decimal (what ``{r: Float(r, 15) for r in
    expr.atoms(Rational) if r.q != 1}`` maps it to)."""

    def __contains__(self, node: object) -> bool:
        return isinstance(node, sp.Rational) and node.q != 1

    def __getitem__(self, node: sp.Rational) -> sp.Float:
        return sp.Float(node, 15)


DECIMALS = _Decimals()
