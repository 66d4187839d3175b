"""Every error branch of spec validation, pinned by text and position.

Each file in ``tests/bad_specs/`` is one small spec that starts with the errors it must produce::

    # expect: 14:11 joint 'elbow' refers to unknown body 'link3'
    # expect: 21:5 unknown key 'mas' in body 'link2' | hint: did you mean 'mass'?

(``LINE:COL``, then a substring of the message, then optionally ``| hint:`` and a substring of the
hint). The spec must fail with exactly those errors: as many, each at its place, none other.
"""

from __future__ import annotations

import copy
import random
import re
from collections import Counter
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from tests.conftest import all_specs
from tutgen.cli.main import app
from tutgen.errors import EXIT_INVALID_SPEC, SpecError, SpecErrors
from tutgen.spec.loader import load_yaml_file
from tutgen.spec.validate import load_system, load_system_text

BAD_SPECS = Path(__file__).resolve().parent.parent / "bad_specs"
EXPECT_RE = re.compile(r"^# expect: (?P<line>\d+):(?P<col>\d+) (?P<message>.*?)(?: \| hint: (?P<hint>.*))?$")
#: What a message must never show: Python reprs, pydantic's own words, class names of the schema.
NOT_FOR_USERS = re.compile(r"<class|Input should|pydantic|[A-Z][a-z]+Spec\b|function-|literal\[|Traceback")


def bad_specs() -> list[Path]:
    return sorted(BAD_SPECS.glob("*.yaml"))


def expectations(path: Path) -> list[tuple[int, int, str, str | None]]:
    out = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.startswith("# expect:"):
            continue
        match = EXPECT_RE.match(line)
        assert match, f"{path.name}: malformed expectation {line!r}"
        out.append((int(match["line"]), int(match["col"]), match["message"], match["hint"]))
    return out


def errors_of(path: Path) -> list[SpecError]:
    with pytest.raises(SpecErrors) as info:
        load_system(path)
    return info.value.errors


def _matches(error: SpecError, expected: tuple[int, int, str, str | None]) -> bool:
    line, col, message, hint = expected
    return (
        (error.location.line, error.location.col) == (line, col)
        and message in error.message
        and (hint is None or (error.hint is not None and hint in error.hint))
    )


@pytest.mark.parametrize("path", [pytest.param(p, id=p.stem) for p in bad_specs()])
def test_bad_spec_reports_exactly_the_expected_errors(path: Path) -> None:
    expected = expectations(path)
    assert expected, f"{path.name} states no '# expect:' line"
    actual = errors_of(path)
    shown = "\n".join(str(e) for e in actual)
    assert len(actual) == len(expected), f"expected {len(expected)} errors, got {len(actual)}:\n{shown}"
    unmatched = list(actual)
    for exp in expected:
        found = next((e for e in unmatched if _matches(e, exp)), None)
        assert found is not None, f"no error matches {exp}; got:\n{shown}"
        unmatched.remove(found)
    assert not unmatched
    for error in actual:
        assert error.location.path == str(path)
        assert not NOT_FOR_USERS.search(str(error)), str(error)


def test_bad_specs_corpus_reports_several_errors_at_once() -> None:
    counts = Counter(len(expectations(p)) for p in bad_specs())
    assert sum(n for size, n in counts.items() if size >= 2) >= 10
    assert sum(n for size, n in counts.items() if size >= 3) >= 5


@pytest.mark.parametrize(
    "name", ["unknown-keys-nested", "joint-coordinates", "expression-syntax", "yaml-syntax", "empty"]
)
def test_bad_spec_on_the_command_line(name: str) -> None:
    path = BAD_SPECS / f"{name}.yaml"
    result = CliRunner().invoke(app, ["solve", str(path)])
    assert result.exit_code == EXIT_INVALID_SPEC, result.output
    assert result.stdout == ""
    assert "Traceback" not in result.stderr
    located = [line for line in result.stderr.splitlines() if not line.startswith("  hint: ")]
    assert len(located) == len(expectations(path))
    for line, (row, col, message, _) in zip(located, sorted(expectations(path)), strict=True):
        assert line.startswith(f"{path}:{row}:{col}: error: "), line
        assert message in line


def test_valid_specs_validate() -> None:
    for path in all_specs():
        system = load_system(path)
        assert system.title


# --- robustness: whatever the values, only SpecErrors, in the user's words ---

_VALUES = [None, True, 0, -1.5, "", "x", "m", "ground", "2 m", "15 cms", "a +", [], [1], ["a", "b", "c"], {}, {"x": 1}]


def _paths(data: object, prefix: tuple = ()) -> list[tuple]:
    out = [prefix]
    if isinstance(data, dict):
        for key, value in data.items():
            out += _paths(value, (*prefix, key))
    elif isinstance(data, list):
        for i, value in enumerate(data):
            out += _paths(value, (*prefix, i))
    return out


def _mutants(count: int, seed: int = 20261123) -> list[tuple[str, str]]:
    rng = random.Random(seed)
    bases = [(p.stem, load_yaml_file(p)[0]) for p in all_specs()]
    out = []
    for i in range(count):
        name, data = rng.choice(bases)
        data = copy.deepcopy(data)
        for _ in range(rng.randint(1, 3)):
            path = rng.choice([p for p in _paths(data) if p])
            node = data
            for key in path[:-1]:
                node = node[key]
            if isinstance(node, dict) and rng.random() < 0.25:
                del node[path[-1]]
            else:
                node[path[-1]] = copy.deepcopy(rng.choice(_VALUES))
        out.append((f"{name}-{i}", yaml.safe_dump(data, sort_keys=False)))
    return out


def test_mutated_specs_fail_only_with_spec_errors() -> None:
    for name, text in _mutants(150):
        try:
            load_system_text(text, f"{name}.yaml")
        except SpecErrors as exc:
            assert exc.errors
            for error in exc.errors:
                assert not NOT_FOR_USERS.search(str(error)), f"{name}:\n{text}\n{error}"
