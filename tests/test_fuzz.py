"""Fuzzing the whole pipeline: mutated tutorial specs are solved, or refused with a located error.

Hypothesis takes the ten tutorial specs' YAML data and drops keys, renames keys, swaps values between
fields, replaces values with random strings, numbers and lists, and truncates the text. Each mutant goes
through ``load_system_text`` and ``derive`` (under a deadline, so a slow mutant cannot hang the run).
The only acceptable outcomes are a derivation, :class:`SpecErrors` whose every error is located in the
mutant, or a :class:`DerivationError` (located, or a clean timeout). ``max_examples`` comes from the
Hypothesis profile (tests/conftest.py); ``HYPOTHESIS_PROFILE=long`` runs more.
"""

from __future__ import annotations

import copy
import re
from typing import Any

import yaml
from hypothesis import given
from hypothesis import strategies as st

from tests.conftest import SPECS
from tutgen.engine.pipeline import derive_with_deadline
from tutgen.errors import DerivationError, DerivationTimeout, SpecErrors
from tutgen.spec.loader import load_yaml_file
from tutgen.spec.validate import load_system_text

TUTORIAL = sorted((SPECS / "tutorial-1").glob("*.yaml"))
BASES = {p.stem: load_yaml_file(p)[0] for p in TUTORIAL}
NAME = "fuzz.yaml"
#: Seconds one mutant may take to derive.
DEADLINE = 10
NOT_FOR_USERS = re.compile(r"<class|Input should|pydantic|[A-Z][a-z]+Spec\b|function-|literal\[|Traceback")
KEYS = (
    "mass com parts type parent child axis coordinate origin offset value stiffness extension force torque "
    "kinetic potential gravity ground x theta"
).split()

SCALARS = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=20),
    st.sampled_from(["m", "2 m", "l1*sin(theta)", "x_dot", "ground", "z", "-y", "0", "1e300", "a +", "15 cms"]),
)
VALUES = st.one_of(SCALARS, st.lists(SCALARS, max_size=4), st.dictionaries(st.sampled_from(KEYS), SCALARS, max_size=3))

#: How many mutants the last run tried, by outcome (printed by the long run).
tried: dict[str, int] = {"solved": 0, "spec_error": 0, "derivation_error": 0, "timeout": 0}


def _paths(data: Any, prefix: tuple = ()) -> list[tuple]:
    out = [prefix] if prefix else []
    if isinstance(data, dict):
        for key, value in data.items():
            out += _paths(value, (*prefix, key))
    elif isinstance(data, list):
        for i, value in enumerate(data):
            out += _paths(value, (*prefix, i))
    return out


def _parent(tree: Any, path: tuple) -> Any:
    for key in path[:-1]:
        tree = tree[key]
    return tree


@st.composite
def mutants(draw: st.DrawFn) -> str:
    tree = copy.deepcopy(BASES[draw(st.sampled_from(sorted(BASES)))])
    for _ in range(draw(st.integers(1, 4))):
        paths = _paths(tree)
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        parent = _parent(tree, path)
        op = draw(st.sampled_from(["drop", "rename", "swap", "replace", "replace"]))
        if op == "drop":
            del parent[path[-1]]
        elif op == "rename" and isinstance(parent, dict):
            new = draw(st.one_of(st.sampled_from(KEYS), st.text(min_size=1, max_size=12)))
            parent[new] = parent.pop(path[-1])
        elif op == "swap":
            other = draw(st.sampled_from(paths))
            other_parent = _parent(tree, other)
            try:
                a, b = parent[path[-1]], other_parent[other[-1]]
            except (KeyError, IndexError, TypeError):  # the other path went away with this one
                continue
            parent[path[-1]], other_parent[other[-1]] = copy.deepcopy(b), copy.deepcopy(a)
        else:
            parent[path[-1]] = draw(VALUES)
    text = yaml.safe_dump(tree, sort_keys=False, allow_unicode=True)
    if draw(st.integers(0, 4)) == 0:
        text = text[: draw(st.integers(0, len(text)))]
    return text


def check_mutant(text: str) -> str:
    """Solve one mutant; return its outcome, or fail the test for anything but the acceptable ones."""
    try:
        system = load_system_text(text, NAME)
    except SpecErrors as exc:
        assert exc.errors, text
        for error in exc.errors:
            assert error.location.path == NAME, f"{text}\n{error}"
            assert not NOT_FOR_USERS.search(str(error)), f"{text}\n{error}"
        return "spec_error"
    try:
        derive_with_deadline(system, "both", DEADLINE)
    except DerivationTimeout:
        return "timeout"
    except DerivationError as exc:
        assert exc.location is not None, f"{text}\n{exc}"
        return "derivation_error"
    return "solved"


@given(mutants())
def test_fuzz_mutated_tutorial_specs_solve_or_fail_located(text: str) -> None:
    outcome = check_mutant(text)
    tried[outcome] += 1


def test_fuzz_report_counts() -> None:
    """Runs after the fuzz test in file order; ``-s`` shows how many mutants it tried."""
    print(f"\nfuzz: {sum(tried.values())} mutants tried: {tried}")
