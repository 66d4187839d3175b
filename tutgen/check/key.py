"""The instructor's marking key: which items are asked, and the tolerances and rules of each.

Tolerances belong to the instructor, never to the student: an answers file that sets one is
refused (:mod:`tutgen.check.answers`). The key is a YAML file given as ``tutgen check --key KEY``,
with the fields of a spec's ``marking:`` section (read by the same reader,
:func:`tutgen.spec.builders.marking.read_marking`)::

    ask: [kinetic_energy, mass_matrix, equations_of_motion]   # the items graded (optional)
    tolerance: {rel_tol: 0.005}                               # every number (optional)
    items:                                                    # per item or entry (optional)
      inertia_tensor[1,1]: {rel_tol: 0.01, rounded: true}
      equations_of_motion: {scaling: false}
    significant_figures: 4                                    # decimals as rounded results (optional)

A rule given for a key applies to every entry under it; the most specific rule wins, then the key's
``tolerance``, then the defaults. ``scaling: false`` accepts an equation of motion only as written
or with its terms moved across the ``=``, not multiplied by a constant factor.
"""

from __future__ import annotations

from pathlib import Path

from tutgen.errors import SpecError, SpecErrors
from tutgen.model.marking import KeyRule, Marking
from tutgen.spec.builders.marking import read_marking
from tutgen.spec.loader import load_yaml_file

__all__ = ["KeyRule", "MarkingKey", "read_key"]

#: A marking key is a :class:`~tutgen.model.marking.Marking` (the name the checker has always used).
MarkingKey = Marking


def read_key(path: str | Path) -> MarkingKey:
    """Read a marking key; every problem is raised at once as SpecErrors (file:line:col)."""
    data, smap = load_yaml_file(path)
    errors: list[SpecError] = []
    marking = read_marking(data, smap, (), errors, path=str(path), source="key")
    if errors:
        raise SpecErrors(errors)
    return marking
