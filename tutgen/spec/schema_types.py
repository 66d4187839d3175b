"""The spec schema's scalars: expressions, texts, vectors, names, dimensions, and the base of every model
(tutgen.spec.schema builds the spec's shape from them; split from it to keep each module under 800 lines)."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, WithJsonSchema
from pydantic_core import PydanticCustomError

# ---------------------------------------------------------------------------------------------
# Scalars: expressions, vectors, names
# ---------------------------------------------------------------------------------------------


def describe(value: Any) -> str:
    """A user-facing name for what was found (never a Python repr of a class)."""
    if value is None:
        return "nothing (null)"
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return f"a list of {len(value)} item{'s' if len(value) != 1 else ''}"
    if isinstance(value, str):
        return f"the text '{value}'" if len(value) <= 40 else "a long text"
    return f"the number {value}"


def _expr_scalar(value: Any) -> Any:
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise PydanticCustomError(
            "tutgen_expr", "expected an expression or a number, found {found}", {"found": describe(value)}
        )
    return value


def _vector3(value: Any) -> Any:
    if not isinstance(value, list) or len(value) != 3:
        raise PydanticCustomError(
            "tutgen_vector",
            "expected a vector of 3 components [x, y, z], found {found}",
            {"found": describe(value)},
        )
    return value


#: The range of ``significant_figures``: beyond 15 a double has no more digits to show.
SIGNIFICANT_FIGURES_RANGE = (1, 15)


def significant_figures_value(value: Any) -> Any:
    lo, hi = SIGNIFICANT_FIGURES_RANGE
    if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
        raise PydanticCustomError(
            "tutgen_figures",
            f"expected a whole number from {lo} to {hi}, found {{found}}",
            {"found": describe(value)},
        )
    return value


def _text(value: Any) -> Any:
    if not isinstance(value, str):
        raise PydanticCustomError("tutgen_text", "expected a text, found {found}", {"found": describe(value)})
    return value


EXPR_SCHEMA = {
    "anyOf": [{"type": "string"}, {"type": "number"}],
    "description": "An expression (e.g. 'm1 + m2', 'l*sin(theta)'), a number, or a number with a unit "
    "('15 cm', '7849 kg/m^3').",
}

#: An expression in the spec grammar, a number, or a number with a unit.
Expr = Annotated[Any, BeforeValidator(_expr_scalar), WithJsonSchema(EXPR_SCHEMA)]
#: A text shown to the reader (titles, statements, descriptions). It may hold inline maths between
#: dollars in the expression grammar (``$T = m v^2/2$``; ``\$`` is a dollar sign): validation reads it
#: into a :class:`tutgen.model.text.RichText` (tutgen.spec.richtext).
Text = Annotated[str, BeforeValidator(_text)]
#: Three components [x, y, z], each an expression.
Vector3 = Annotated[
    list[Expr],
    BeforeValidator(_vector3),
    WithJsonSchema({"type": "array", "items": EXPR_SCHEMA, "minItems": 3, "maxItems": 3}),
]
#: A name declared in the spec (a body, a joint, a coordinate, a parameter).
Name = Annotated[str, BeforeValidator(_text)]

AxisName = Literal["x", "y", "z", "-x", "-y", "-z", "+x", "+y", "+z"]


class SpecModel(BaseModel):
    """Base of every part of a spec: unknown keys are errors, so typos are caught."""

    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=False)


# ---------------------------------------------------------------------------------------------
# Parameters and coordinates
# ---------------------------------------------------------------------------------------------

DimensionName = Literal[
    "dimensionless",
    "angle",
    "mass",
    "length",
    "time",
    "area",
    "volume",
    "density",
    "velocity",
    "acceleration",
    "angular_velocity",
    "force",
    "torque",
    "energy",
    "power",
    "inertia",
    "stiffness",
    "torsional_stiffness",
    "damping",
    "torsional_damping",
    "frequency",
    "pressure",
]
