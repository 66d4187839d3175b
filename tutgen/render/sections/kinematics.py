"""The kinematics of each body: the position and velocity of its centre of mass and their square."""

from __future__ import annotations

from typing import Any

from tutgen.render.blocks import SolutionContext, display, section, tex_name


def kinematics(c: SolutionContext) -> dict[str, Any] | None:
    d, tex, num = c.d, c.tex, c.num
    if not d.kinematics or d.kinetic_energy is None:
        return None
    sec = section("Kinematics", "Position and velocity of each centre of mass, in world axes.")
    for k, e in zip(d.kinematics, d.energies, strict=True):
        name = tex_name(k.name)
        sec["blocks"].append(
            display(
                f"\\mathbf r_{{{name}}} = {tex(num(k.com))},\\quad "
                f"\\mathbf v_{{{name}}} = {tex(num(k.velocity))},\\quad " + tex.equation("v^2", num(e.speed_squared))
            )
        )
    return sec
