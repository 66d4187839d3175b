"""Shared helpers of the answer-checker tests: references from the session cache, marking text."""

from __future__ import annotations

import dataclasses
import tempfile
import textwrap
from functools import cache
from pathlib import Path
from typing import Any

import yaml

from tests.conftest import SPECS, solved
from tutgen.check.compare import Reference, Status, reference_from
from tutgen.check.key import read_key
from tutgen.check.run import FileResult, mark_file

TUTORIAL = SPECS / "tutorial-1"


@cache
def reference(spec: str | Path) -> Reference:
    """The Reference of a spec, derived once per session (through tests/conftest.py's cache)."""
    system, derivation, _ = solved(str(spec))
    return reference_from(system, derivation, str(spec))


def tutorial(pid: int) -> Reference:
    return reference(next(TUTORIAL.glob(f"p{pid:02d}-*.yaml")))


def with_key(ref: Reference, key: str | Path | None) -> Reference:
    """``ref`` with a marking key, given as YAML text (dedented) or as a file."""
    if key is None:
        return ref
    if isinstance(key, Path):
        return dataclasses.replace(ref, key=read_key(key))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "key.yaml"
        path.write_text(textwrap.dedent(key), encoding="utf-8")
        return dataclasses.replace(ref, key=read_key(path))


def mark_text(ref: Reference, text: str, name: str = "answers.yaml", *, key: str | None = None) -> FileResult:
    """Mark answers given as YAML text (dedented), written to a temporary file called ``name``, with
    the marking ``key`` (YAML text) if one is given."""
    ref = with_key(ref, key)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / name
        path.write_text(textwrap.dedent(text), encoding="utf-8")
        result = mark_file(ref, path)
    return result


def mark_data(ref: Reference, data: dict[str, Any], key: dict[str, Any] | None = None) -> FileResult:
    key_text = None if key is None else yaml.safe_dump(key, sort_keys=False)
    return mark_text(ref, yaml.safe_dump(data, sort_keys=False, allow_unicode=True), key=key_text)


def verdicts(result: FileResult) -> dict[str, tuple[Status, str]]:
    """{entry name: (status, feedback)} of every entry of a marked file."""
    assert not result.errors, result.errors
    return {e.name: (e.status, e.feedback) for item in result.items for e in item.entries}


def not_correct(result: FileResult) -> set[str]:
    return {name for name, (status, _) in verdicts(result).items() if status is not Status.CORRECT}


def errors(result: FileResult) -> list[str]:
    """The errors of an invalid answers file, with the temporary directory cut from the paths."""
    folder = str(Path(result.path).parent) + "/"
    return [e.replace(folder, "") for e in result.errors]
