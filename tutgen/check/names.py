"""Names of the entries of a result, and what each result field holds (its dimension, text or not).

A path into tutgen's JSON ``results`` is a tuple of keys and 0-based indices; the reports name it the
way an answers file writes it (:func:`entry_name`): ``mass_matrix[1,2]``, ``christoffel[1,1,2]``,
``lagrange_terms[2].dL_dq``.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from tutgen.spec.units import Dimension

__all__ = ["DIMENSION_OF", "PER_COORDINATE", "TEXT_FIELDS", "Path", "entry_name", "field_of", "is_per_coordinate"]

#: Results whose entries are one per coordinate, so a coordinate name may stand for an index.
PER_COORDINATE = frozenset(
    {"equations_of_motion", "lagrange_terms", "generalized_forces", "coriolis_vector", "gravity_vector"}
)
#: Result fields that are names, compared as text.
TEXT_FIELDS = frozenset({"coordinate", "shape", "method", "remarks"})

_M, _L, _T = Dimension(mass=1), Dimension(length=1), Dimension(time=1)
_ONE = Dimension()
_ENERGY = Dimension(1, 2, -2)
_INERTIA = Dimension(1, 2, 0)
#: The dimension of a result field, where it does not depend on the spec.
DIMENSION_OF: Mapping[str, Dimension] = {
    "mass": _M,
    "volume": Dimension(length=3),
    "center_of_mass": _L,
    "centroid": _L,
    "axis_distances": _L,
    "positions": _L,
    "inertia_tensor": _INERTIA,
    "inertia_tensor_com": _INERTIA,
    "inertia_centroid": _INERTIA,
    "principal_moments": _INERTIA,
    "principal_axes": _ONE,
    "velocities": _L / _T,
    "angular_velocities": _ONE / _T,
    "speeds_squared": (_L / _T) ** 2,
    "kinetic_energy": _ENERGY,
    "potential_energy": _ENERGY,
    "lagrangian": _ENERGY,
    "body_kinetic_energies": _ENERGY,
    "force": Dimension(1, 1, -2),  # newton_euler.reaction_forces.<joint>.force
    "moment": _ENERGY,
}

Path = tuple[str | int, ...]


def entry_name(path: Path) -> str:
    """``("mass_matrix", 0, 1)`` is ``mass_matrix[1,2]``; ``("christoffel", "1,1,2")`` is
    ``christoffel[1,1,2]``; ``("lagrange_terms", 1, "dL_dq")`` is ``lagrange_terms[2].dL_dq``."""
    text = ""
    group: list[str] = []
    for part in (*path, None):
        if isinstance(part, int):
            group.append(str(part + 1))
            continue
        if isinstance(part, str) and re.fullmatch(r"[0-9]+(?:,[0-9]+)*", part):
            group.append(part)
            continue
        if group:
            text += "[" + ",".join(group) + "]"
            group = []
        if part is not None:
            text += ("." if text else "") + part
    return text


def field_of(path: Path) -> str | None:
    """The result field a path is in: ``inertia_tensor`` for ``bodies.body.parts.block.inertia_tensor[1,1]``."""
    if not path:
        return None
    if path[0] == "bodies":
        if len(path) >= 3 and path[2] == "parts":
            return str(path[4]) if len(path) >= 5 else None
        return str(path[2]) if len(path) >= 3 else None
    if path[0] == "lagrange_terms" and len(path) >= 3:
        return str(path[2])
    if path[0] == "newton_euler" and len(path) >= 2:
        if path[1] == "reaction_forces":
            return str(path[3]) if len(path) >= 4 else None
        return str(path[1])
    return str(path[0])


def is_per_coordinate(path: Path) -> bool:
    """Whether ``path`` is a list with one entry per coordinate (a coordinate name may index it)."""
    return (len(path) == 1 and path[0] in PER_COORDINATE) or path == ("newton_euler", "equations_of_motion")
