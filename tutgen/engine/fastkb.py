"""A faster copy of sympy's assumption tables (issue 17), installed when :mod:`tutgen.engine` is imported.

Every sympy object starts with its class's table of default assumptions. The first time one of its
``is_*`` properties is asked, the table is copied so that the object can record what it learns
(``sympy.core.assumptions.make_property``). ``StdFactKB.copy`` builds the copy by deducing every fact
of the table again from scratch (``deduce_all_facts``), although the table is already closed under
deduction (the deduction is idempotent: "that would be a bug otherwise", a sympy maintainer in
diofant/diofant#1133). On a tutorial sheet, every variant makes new numbers,
products and powers, and these copies were 4 % of the rendering's CPU time.

:func:`install` replaces the method with a copy of the dictionary itself, the same entries and the same
generator, after checking on a probe of sympy's classes that the two copies agree, and only when the
method is still sympy's own. ``TUTGEN_SYMPY_KB=sympy`` leaves sympy as it is. The results never depend
on it (tests/engine/test_fastkb.py checks the tables, and a sheet with and without it byte for byte).
"""

from __future__ import annotations

import os
from typing import Any

#: sympy's own ``StdFactKB.copy``, once :func:`install` has replaced it (to put it back: :func:`uninstall`)
_ORIGINAL: Any = None


def _dict_copy(self: Any) -> Any:
    """``StdFactKB.copy`` without re-deducing: a table closed under deduction, entry for entry."""
    new = dict.__new__(type(self))
    dict.update(new, self)
    new.rules = self.rules
    new._generator = self._generator.copy()
    return new


def _probes() -> list[Any]:
    """Tables of default assumptions of the kinds of objects a derivation makes, and of symbols with
    assumptions (a parameter is positive, a coordinate real)."""
    import sympy as sp

    x = sp.Symbol("x")
    return [
        sp.Float(1.5).default_assumptions,
        sp.Rational(1, 3).default_assumptions,
        sp.Integer(2).default_assumptions,
        (x * sp.Symbol("y")).default_assumptions,
        (x + 1).default_assumptions,
        (x**2).default_assumptions,
        sp.sin(x).default_assumptions,
        sp.Symbol("m", positive=True)._assumptions,
        sp.Symbol("q", real=True)._assumptions,
    ]


def _same(a: Any, b: Any) -> bool:
    return type(a) is type(b) and dict(a) == dict(b) and a.rules is b.rules and a.generator == b.generator


def install() -> bool:
    """Use :func:`_dict_copy` for sympy's assumption tables; whether it is in use."""
    global _ORIGINAL
    if _ORIGINAL is not None:
        return True
    if os.environ.get("TUTGEN_SYMPY_KB") == "sympy":
        return False
    from sympy.core.assumptions import StdFactKB

    original = StdFactKB.__dict__.get("copy")
    if original is None or getattr(original, "__module__", "") != "sympy.core.assumptions":
        return False  # not the method this module knows
    try:
        if not all(_same(original(kb), _dict_copy(kb)) for kb in _probes()):
            return False
    except Exception:  # a sympy whose tables look otherwise: leave it as it is
        return False
    _ORIGINAL = original
    StdFactKB.copy = _dict_copy  # type: ignore[method-assign]
    return True


def uninstall() -> None:
    """Put sympy's own ``StdFactKB.copy`` back (tests that compare the two)."""
    global _ORIGINAL
    if _ORIGINAL is None:
        return
    from sympy.core.assumptions import StdFactKB

    StdFactKB.copy = _ORIGINAL  # type: ignore[method-assign]
    _ORIGINAL = None
