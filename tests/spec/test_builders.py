"""The spec -> model builders as a whole: every top-level key has a builder, and the shared context.

The behaviour of each builder is pinned by ``tests/bad_specs/`` and ``test_validate.py``; these tests
keep the recipe of docs/architecture.md true: a key added to the schema without a builder that reads
it would be silently ignored, and fails here instead.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
import sympy as sp

from tutgen.errors import SpecErrors
from tutgen.spec import schema as S
from tutgen.spec.builders.context import Context
from tutgen.spec.loader import load_yaml_text
from tutgen.spec.validate import load_system_text

BUILDERS = Path(__file__).resolve().parents[2] / "tutgen" / "spec" / "builders"
#: Keys that only the schema reads: the format version is checked for its value there.
SCHEMA_ONLY = {"tutgen"}


def keys_read_by(source: str) -> set[str]:
    """The attributes ``X`` of every ``ctx.doc.X`` in a builder module's source."""
    found = set()
    for node in ast.walk(ast.parse(source)):
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Attribute)
            and node.value.attr == "doc"
            and isinstance(node.value.value, ast.Name)
            and node.value.value.id == "ctx"
        ):
            found.add(node.attr)
    return found


def test_builders_read_every_top_level_key() -> None:
    read = set().union(*(keys_read_by(p.read_text(encoding="utf-8")) for p in sorted(BUILDERS.glob("*.py"))))
    keys = set(S.SpecDoc.model_fields)
    unread = keys - SCHEMA_ONLY - read
    assert not unread, f"top-level spec keys that no builder reads: {sorted(unread)}"
    assert read <= keys, f"builders read keys that the schema does not have: {sorted(read - keys)}"


def test_builders_keys_read_by_finds_attribute_chains() -> None:
    source = "def f(ctx, other):\n    return ctx.doc.bodies, ctx.doc.arm.links, other.doc.loads, ctx.data\n"
    assert keys_read_by(source) == {"bodies", "arm"}


def context_of(text: str) -> Context:
    data, smap = load_yaml_text(text, "<spec>")
    return Context(S.SpecDoc.model_validate(data), data, smap)


@pytest.mark.parametrize(
    ("path", "expected"),
    [
        pytest.param(("parameters",), ["m", "l"], id="section"),
        pytest.param(("parameters", 1), "l", id="list-item"),
        pytest.param(("parameters", 2), None, id="past-the-end"),
        pytest.param(("parameters", "m"), None, id="key-of-a-list"),
        pytest.param(("gravity", "g"), None, id="below-a-list"),
        pytest.param(("title",), "t", id="scalar"),
        pytest.param(("title", 0), None, id="below-a-scalar"),
        pytest.param(("bodies",), None, id="absent"),
    ],
)
def test_context_written_reads_the_data_as_loaded(path: tuple[str | int, ...], expected: object) -> None:
    ctx = context_of("title: t\nparameters: [m, l]\ngravity: [0, -9.81, 0]\n")
    assert ctx.written(path) == expected


def test_context_name_path_points_into_a_list_shorthand() -> None:
    assert context_of("title: t\nparameters: [m, l]\n").name_path("parameters", "l") == ("parameters", 1)
    assert context_of("title: t\nparameters: {m: 1}\n").name_path("parameters", "m") == ("parameters", "m")


def test_context_collects_errors_instead_of_raising() -> None:
    ctx = context_of("title: t\nparameters: [m]\n")
    m = ctx.params["m"] = sp.Symbol("m", positive=True)
    assert ctx.expr(("title",), "m + ", ctx.symbols()) is None
    assert ctx.expr(("title",), "2*m", ctx.symbols()) == 2 * m
    assert ctx.check_name_free(("bodies", "m"), "m", "body") is False
    assert ctx.check_name_free(("bodies", "b"), "b", "body") is True
    assert len(ctx.errors) == 2
    assert "already the name of a parameter; give the body another name" in ctx.errors[1].message


def test_builders_errors_of_several_sections_come_together() -> None:
    spec = """\
title: two sections wrong
parameters: [m]
coordinates: [x]
bodies:
  m: {mass: m}
springs:
  s: {stiffness: k, extension: x}
"""
    with pytest.raises(SpecErrors) as info:
        load_system_text(spec)
    messages = [e.message for e in info.value.errors]
    assert any("'m' is already the name of a parameter" in m for m in messages)
    assert any("unknown name 'k'" in m for m in messages)
