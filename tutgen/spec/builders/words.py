"""How a message names a dimension: "a mass (kg)", "an angle (a plain number, or deg/rad)"."""

from __future__ import annotations

from tutgen.spec.units import DIMENSIONS, Dimension


def article(words: str) -> str:
    """The indefinite article of ``words``: "an angle", "a length"."""
    return "an" if words[:1] in "aeiou" else "a"


def expected_dimension(name: str) -> str:
    """ "a mass (kg)", "an angle (a plain number, or deg/rad)"."""
    words = name.replace("_", " ")
    dim = DIMENSIONS[name]
    if dim.is_dimensionless:
        unit = "a plain number, or deg/rad" if name == "angle" else "a plain number"
    else:
        unit = str(dim)
    return f"{article(words)} {words} ({unit})"


def found_dimension(dim: Dimension) -> str:
    """ "a length (m)", "a plain number", "a quantity in kg*m"."""
    if dim.is_dimensionless:
        return "a plain number"
    for name, known in DIMENSIONS.items():
        if known == dim:
            words = name.replace("_", " ")
            return f"{article(words)} {words} ({dim})"
    return f"a quantity in {dim}"
