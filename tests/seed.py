"""The course tutorial's answer key (shared/seed/answers.yaml) and how its problems map to our specs.

Read, never copied: the tests that use it are skipped (and collect nothing) when it is missing.
"""

from __future__ import annotations

from functools import cache
from typing import Any

import yaml

from tests.conftest import SEED

ANSWERS = SEED / "answers.yaml"
SPEC_OF = {
    1: "p01-composite-inertia.yaml",
    2: "p02-pivoted-rod.yaml",
    3: "p03-cart-pendulum.yaml",
    4: "p04-rp-arm.yaml",
    5: "p05-rr-arm.yaml",
    6: "p06-two-prismatic.yaml",
    7: "p07-belt-driven-arm.yaml",
    8: "p08-spatial-rr.yaml",
    9: "p09-pr-manipulator.yaml",
    10: "p10-given-kinetic-energy.yaml",
}
# the answer key's particle names -> the bodies of our specs
BODY_OF = {
    3: {"cart": "cart", "p": "pendulum"},
    4: {"tip": "tip"},
    5: {"m1": "link1", "m2": "link2"},
    6: {"m1": "link1", "m2": "link2"},
    7: {"m1": "link1", "m2": "link2"},
    8: {"m1": "link1", "m2": "link2"},
    9: {"m1": "slider", "m2": "link2"},
}


@cache
def problems() -> dict[int, dict[str, Any]]:
    """The answer key's problems by id ({} when the seed is missing)."""
    if not ANSWERS.exists():
        return {}
    data = yaml.safe_load(ANSWERS.read_text(encoding="utf-8"))
    return {int(p["id"]): p for p in data["problems"]}
