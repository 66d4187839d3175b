"""Tests for tutgen.spec.loader: safe YAML with a source map and located errors."""

from __future__ import annotations

import itertools
import math
import os
import textwrap
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tutgen.errors import EXIT_INVALID_SPEC, Location, SpecError, SpecErrors
from tutgen.spec import loader
from tutgen.spec.loader import (
    MAX_ALIASES,
    MAX_DEPTH,
    MAX_FILE_BYTES,
    MAX_NODES,
    SourceMap,
    load_yaml_file,
    load_yaml_text,
)

PATH = "spec.yaml"
TAG_NOT_ALLOWED = "is not allowed; a spec holds only plain mappings, lists, strings and numbers"
TOO_DEEP = "the document nests collections more than 64 levels deep (anchors and aliases included); refusing to load it"
TOO_BIG = "the document expands to more than 100000 nodes (anchors and aliases included); refusing to load it"


def load(text: str):
    """Load dedented text as spec.yaml."""
    return load_yaml_text(textwrap.dedent(text), PATH)


def problems(text: str, *, dedent: bool = True) -> list[tuple[int, int, str]]:
    """(line, col, message) of every error that loading ``text`` raises, sorted by position."""
    with pytest.raises(SpecErrors) as info:
        load_yaml_text(textwrap.dedent(text) if dedent else text, PATH)
    for error in info.value.errors:
        assert error.location.path == PATH
    return [(e.location.line, e.location.col, e.message) for e in info.value.errors]


def only_problem(text: str, *, dedent: bool = True) -> tuple[int, int, str]:
    found = problems(text, dedent=dedent)
    assert len(found) == 1, found
    return found[0]


def test_limits_are_the_documented_ones():
    assert (MAX_FILE_BYTES, MAX_NODES, MAX_DEPTH, MAX_ALIASES) == (1_048_576, 100_000, 64, 1_000)


# --- data ---


def test_mapping_order_and_nesting_round_trip():
    data, _ = load(
        """\
        name: cart pole
        bodies:
          cart: {mass: m_c, position: [x, 0, 0]}
          pole:
            mass: m_p
            length: 0.5
        gravity: 9.81
        """
    )
    assert data == {
        "name": "cart pole",
        "bodies": {
            "cart": {"mass": "m_c", "position": ["x", 0, 0]},
            "pole": {"mass": "m_p", "length": 0.5},
        },
        "gravity": 9.81,
    }
    assert list(data) == ["name", "bodies", "gravity"]
    assert list(data["bodies"]["pole"]) == ["mass", "length"]


@pytest.mark.parametrize(
    ("written", "expected"),
    [
        pytest.param("1e-3", 0.001, id="float-exponent-without-dot"),
        pytest.param("-1E+3", -1000.0, id="float-signed-exponent"),
        pytest.param("1.5", 1.5, id="float"),
        pytest.param(".5", 0.5, id="float-leading-dot"),
        pytest.param("1.", 1.0, id="float-trailing-dot"),
        pytest.param("+2.5e2", 250.0, id="float-plus"),
        pytest.param(".inf", math.inf, id="inf"),
        pytest.param("-.Inf", -math.inf, id="minus-inf"),
        pytest.param("+.INF", math.inf, id="plus-inf"),
        pytest.param("12", 12, id="int"),
        pytest.param("-12", -12, id="int-negative"),
        pytest.param("+12", 12, id="int-plus"),
        pytest.param("007", 7, id="int-leading-zeros"),
        pytest.param("0x1F", 31, id="int-hex"),
        pytest.param("0o17", 15, id="int-octal"),
        pytest.param("true", True, id="true"),
        pytest.param("True", True, id="True"),
        pytest.param("TRUE", True, id="TRUE"),
        pytest.param("false", False, id="false"),
        pytest.param("False", False, id="False"),
        pytest.param("FALSE", False, id="FALSE"),
        pytest.param("~", None, id="tilde-null"),
        pytest.param("null", None, id="null"),
        pytest.param("Null", None, id="Null"),
        pytest.param("NULL", None, id="NULL"),
        pytest.param("", None, id="empty-null"),
        pytest.param("yes", "yes", id="yes-is-a-string"),
        pytest.param("no", "no", id="no-is-a-string"),
        pytest.param("on", "on", id="on-is-a-string"),
        pytest.param("off", "off", id="off-is-a-string"),
        pytest.param("tRUE", "tRUE", id="mixed-case-true-is-a-string"),
        pytest.param("nULL", "nULL", id="mixed-case-null-is-a-string"),
        pytest.param("2026-11-23", "2026-11-23", id="date-is-a-string"),
        pytest.param("12:30:00", "12:30:00", id="sexagesimal-is-a-string"),
        pytest.param("15 cm", "15 cm", id="quantity-is-a-string"),
        pytest.param("0b101", "0b101", id="binary-is-a-string"),
        pytest.param("1_000", "1_000", id="underscores-are-a-string"),
        pytest.param("-0x1F", "-0x1F", id="signed-hex-is-a-string"),
        pytest.param("0x", "0x", id="bare-0x-is-a-string"),
        pytest.param("1e", "1e", id="bare-exponent-is-a-string"),
        pytest.param("inf", "inf", id="inf-without-dot-is-a-string"),
        pytest.param("m1 + m2", "m1 + m2", id="expression"),
        pytest.param("'12'", "12", id="single-quoted-number"),
        pytest.param('"true"', "true", id="double-quoted-bool"),
        pytest.param("''", "", id="quoted-empty"),
        pytest.param("'~'", "~", id="quoted-tilde"),
        pytest.param("!!str 12", "12", id="tag-str"),
        pytest.param("! 12", "12", id="non-specific-tag-is-str"),
        pytest.param("!!int '0x1F'", 31, id="tag-int"),
        pytest.param("!!float 1", 1.0, id="tag-float-on-int"),
        pytest.param("!!float 1e-3", 0.001, id="tag-float"),
        pytest.param("!!bool False", False, id="tag-bool"),
        pytest.param("!!null ''", None, id="tag-null"),
        pytest.param("|\n  two\n  lines", "two\nlines\n", id="block-literal"),
        pytest.param(">\n  12", "12\n", id="block-folded-number-is-a-string"),
    ],
)
def test_scalars_follow_the_yaml_1_2_core_schema(written, expected):
    data, _ = load_yaml_text(f"value: {written}\n", PATH)
    value = data["value"]
    assert type(value) is type(expected)
    assert value == expected


def test_nan():
    data, _ = load("a: .nan\nb: .NaN\nc: .NAN\nd: nan\n")
    assert all(isinstance(data[k], float) and math.isnan(data[k]) for k in "abc")
    assert data["d"] == "nan"


def test_keys_are_the_key_text_as_written():
    data, _ = load(
        """\
        1: int
        on: bool-1.1
        true: bool
        ~: null
        "q": quoted
        0x1F: hex
        !!int 7: tagged
        """
    )
    assert list(data) == ["1", "on", "true", "~", "q", "0x1F", "7"]


def test_explicit_collection_tags_are_allowed():
    data, _ = load("a: !!map {x: !!seq [1]}\nb: ! [2]\n")
    assert data == {"a": {"x": [1]}, "b": [2]}


def test_empty_documents_give_none():
    for text in ["", "# only a comment\n", "---\n", "---\n...\n", "\n\n"]:
        data, source_map = load_yaml_text(text, PATH)
        assert data is None
        assert not source_map.has(())
        assert source_map.location(()) == Location(PATH, 1, 1)


def test_scalar_document():
    data, source_map = load("just text\n")
    assert data == "just text"
    assert source_map.has(())


def test_byte_order_mark_is_skipped():
    data, source_map = load_yaml_text("\ufeffa: 1\n", PATH)
    assert data == {"a": 1}
    assert source_map.location(("a",)) == Location(PATH, 1, 4)


def test_alias_shared_subtrees_are_independent_copies():
    data, _ = load(
        """\
        base: &base {mass: 1, axis: [0, 0, 1]}
        one: *base
        two: *base
        """
    )
    assert data["one"] == data["two"] == data["base"]
    data["one"]["axis"].append(9)
    data["two"]["mass"] = 5
    assert data["base"] == {"mass": 1, "axis": [0, 0, 1]}
    assert data["one"]["axis"] is not data["two"]["axis"]


def test_an_anchor_may_be_redefined():
    data, _ = load("a: &x 1\nb: *x\nc: &x 2\nd: *x\n")
    assert data == {"a": 1, "b": 1, "c": 2, "d": 2}


# --- merge keys ---


def test_merge_explicit_keys_win_then_merged_mappings_in_order():
    data, _ = load(
        """\
        a: &a {x: 1, y: 1, z: 1}
        b: &b {y: 2, w: 2}
        m:
          <<: [*a, *b]
          z: 3
        """
    )
    assert data["m"] == {"x": 1, "y": 1, "w": 2, "z": 3}
    assert list(data["m"]) == ["x", "y", "w", "z"]


def test_merge_of_one_mapping_and_nested_merges():
    data, _ = load(
        """\
        base: &base {mass: 1, length: 2}
        arm: &arm
          <<: *base
          length: 3
        link:
          name: link
          <<: *arm
        inline:
          <<: {k: v}
        """
    )
    assert data["arm"] == {"mass": 1, "length": 3}
    assert data["link"] == {"name": "link", "mass": 1, "length": 3}
    assert data["inline"] == {"k": "v"}


def test_quoted_merge_key_is_an_ordinary_key():
    data, _ = load("a: {'<<': 1, \"<<x\": 2}\n")
    assert data == {"a": {"<<": 1, "<<x": 2}}


def test_merged_keys_are_located_where_they_were_written():
    _, source_map = load(
        """\
        base: &base
          mass: 1
        link:
          <<: *base
          length: 2
        """
    )
    assert source_map.location(("link", "mass")) == Location(PATH, 2, 9)
    assert source_map.key_location(("link", "mass")) == Location(PATH, 2, 3)
    assert source_map.location(("link", "length")) == Location(PATH, 5, 11)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param("a:\n  <<: 5\n", (2, 7, "the value '5'"), id="scalar"),
        pytest.param("a:\n  <<:\n  b: 1\n", (2, 6, "an empty value"), id="empty"),
        pytest.param("m: &m {x: 1}\na:\n  <<: [*m, 3]\n", (3, 12, "the value '3'"), id="list-with-a-scalar"),
        pytest.param("a:\n  <<: [[1]]\n", (2, 8, "a list"), id="list-of-lists"),
    ],
)
def test_merge_value_that_is_not_a_mapping(text, expected):
    line, col, found = expected
    assert only_problem(text, dedent=False) == (
        line,
        col,
        f"the merge key '<<' takes a mapping or a list of mappings; found {found}",
    )


def test_merge_value_tags_are_checked():
    assert only_problem("a:\n  <<: !!set {x: 1}\n", dedent=False) == (2, 7, f"tag '!!set' {TAG_NOT_ALLOWED}")


def test_two_merge_keys_are_duplicates():
    text = "a: &a {x: 1}\nb: &b {y: 1}\nc:\n  <<: *a\n  <<: *b\n"
    assert only_problem(text, dedent=False) == (5, 3, "duplicate key '<<' (first defined at line 4)")


# --- errors: tags, keys ---


@pytest.mark.parametrize(
    ("value", "shown"),
    [
        pytest.param('!!python/object/apply:os.system ["echo hi"]', "!!python/object/apply:os.system", id="apply"),
        pytest.param("!!python/object:os.system {}", "!!python/object:os.system", id="object"),
        pytest.param("!!python/name:os.system", "!!python/name:os.system", id="name"),
        pytest.param("!foo bar", "!foo", id="local-tag"),
        pytest.param("!!binary aGk=", "!!binary", id="binary"),
        pytest.param("!!timestamp 2026-11-23", "!!timestamp", id="timestamp"),
        pytest.param("!!set {a, b}", "!!set", id="set"),
        pytest.param("!!omap [a: 1]", "!!omap", id="omap"),
        pytest.param("!!merge x", "!!merge", id="merge-tag"),
        pytest.param("!<tag:example.com,2000:x> 1", "tag:example.com,2000:x", id="verbatim"),
    ],
)
def test_tags_outside_the_core_schema_are_refused(value, shown):
    line, col, message = only_problem(f"key: {value}\n")
    assert (line, col) == (1, 6)
    assert message == f"tag '{shown}' {TAG_NOT_ALLOWED}"


def test_python_apply_tag_message_and_hint_exactly():
    with pytest.raises(SpecErrors) as info:
        load_yaml_text('run: !!python/object/apply:os.system ["echo hi"]\n', PATH)
    (error,) = info.value.errors
    assert error == SpecError(
        Location(PATH, 1, 6),
        "tag '!!python/object/apply:os.system' is not allowed; a spec holds only plain mappings, lists, "
        "strings and numbers",
        "remove the tag; the only tags a spec may use are !!str, !!int, !!float, !!bool, !!null, !!seq, !!map",
    )
    assert info.value.exit_code == EXIT_INVALID_SPEC


def test_tag_directive_cannot_smuggle_python_tags():
    text = "%TAG !py! tag:yaml.org,2002:python/\n---\na: !py!name:os.system\n"
    assert only_problem(text, dedent=False) == (3, 4, f"tag '!!python/name:os.system' {TAG_NOT_ALLOWED}")


def test_every_bad_tag_is_reported_including_keys_and_items():
    assert problems(
        """\
        a: !!python/name:os.system
        b:
          - !!binary aGk=
          - !foo {x: !bar 1}
        !baz key: 1
        """
    ) == [
        (1, 4, f"tag '!!python/name:os.system' {TAG_NOT_ALLOWED}"),
        (3, 5, f"tag '!!binary' {TAG_NOT_ALLOWED}"),
        (4, 5, f"tag '!foo' {TAG_NOT_ALLOWED}"),
        (4, 14, f"tag '!bar' {TAG_NOT_ALLOWED}"),
        (5, 1, f"tag '!baz' {TAG_NOT_ALLOWED}"),
    ]


def test_bad_tag_inside_an_alias_is_reported_once():
    assert problems("a: &a [!foo 1]\nb: *a\nc: *a\n") == [(1, 8, f"tag '!foo' {TAG_NOT_ALLOWED}")]


@pytest.mark.parametrize(
    ("value", "message"),
    [
        pytest.param("!!int abc", "'abc' is not an integer (tag '!!int')", id="int"),
        pytest.param("!!int 1.5", "'1.5' is not an integer (tag '!!int')", id="int-float"),
        pytest.param("!!float abc", "'abc' is not a number (tag '!!float')", id="float"),
        pytest.param("!!bool yes", "'yes' is not true or false (tag '!!bool')", id="bool"),
        pytest.param("!!null 0", "'0' is not null (tag '!!null')", id="null"),
        pytest.param("!!seq abc", "tag '!!seq' cannot be used on a scalar", id="seq-on-scalar"),
        pytest.param("!!map abc", "tag '!!map' cannot be used on a scalar", id="map-on-scalar"),
        pytest.param("!!map [1]", "tag '!!map' cannot be used on a list", id="map-on-list"),
        pytest.param("!!seq {a: 1}", "tag '!!seq' cannot be used on a mapping", id="seq-on-mapping"),
        pytest.param("!!str [1]", "tag '!!str' cannot be used on a list", id="str-on-list"),
        pytest.param("!!int {a: 1}", "tag '!!int' cannot be used on a mapping", id="int-on-mapping"),
    ],
)
def test_tag_that_does_not_fit_its_value(value, message):
    assert only_problem(f"key: {value}\n") == (1, 6, message)


def test_integer_with_too_many_digits():
    line, col, message = only_problem("n: " + "9" * 5000 + "\n", dedent=False)
    assert (line, col) == (1, 4)
    assert message.startswith("the integer '999") and message.endswith("' has too many digits")


def test_duplicate_keys_are_all_reported_at_the_second_occurrence():
    assert problems(
        """\
        mass: 1
        length: 2
        mass: 3
        body:
          a: 1
          a: 2
        length: 4
        mass: 5
        """
    ) == [
        (3, 1, "duplicate key 'mass' (first defined at line 1)"),
        (6, 3, "duplicate key 'a' (first defined at line 5)"),
        (7, 1, "duplicate key 'length' (first defined at line 2)"),
        (8, 1, "duplicate key 'mass' (first defined at line 1)"),
    ]


def test_duplicate_key_hint():
    with pytest.raises(SpecErrors) as info:
        load("a: 1\na: 2\n")
    assert info.value.errors[0].hint == "a key may appear once in a mapping; remove or rename one of them"


def test_keys_are_compared_as_written():
    assert problems("{1: a, '1': b}\n") == [(1, 8, "duplicate key '1' (first defined at line 1)")]
    data, _ = load("{1: a, 01: b}\n")
    assert data == {"1": "a", "01": "b"}


def test_duplicate_key_through_an_alias_is_located_at_the_alias():
    text = "k: &k name\nm:\n  name: 1\n  *k : 2\n"
    assert only_problem(text, dedent=False) == (4, 3, "duplicate key 'name' (first defined at line 3)")


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param("? [a, b]\n: 1\n", (1, 3, "a list"), id="list-key"),
        pytest.param("? {a: 1}\n: 1\n", (1, 3, "a mapping"), id="mapping-key"),
        pytest.param("{[a]: 1}\n", (1, 2, "a list"), id="flow-list-key"),
        pytest.param("l: &l [1]\nm:\n  *l : 1\n", (3, 3, "a list"), id="alias-key"),
    ],
)
def test_non_scalar_keys_are_refused(text, expected):
    line, col, found = expected
    message = f"a mapping key must be a name or a number; found {found}"
    assert only_problem(text, dedent=False) == (line, col, message)


# --- errors: aliases and limits ---


def test_undefined_alias():
    assert only_problem("a: *nowhere\n") == (1, 4, "alias '*nowhere' refers to no anchor")


def test_alias_before_its_anchor_is_undefined():
    assert only_problem("a: *x\nb: &x 1\n") == (1, 4, "alias '*x' refers to no anchor")


@pytest.mark.parametrize(
    ("text", "col"),
    [
        pytest.param("a: &a [1, *a]\n", 11, id="list"),
        pytest.param("a: &a {b: *a}\n", 11, id="mapping"),
        pytest.param("a: &a {<<: *a}\n", 12, id="merge"),
        pytest.param("a: &a [[[*a]]]\n", 10, id="nested"),
    ],
)
def test_recursive_alias_is_refused(text, col):
    assert only_problem(text) == (1, col, "alias '*a' is used inside its own anchor '&a'")


def test_unresolved_aliases_as_keys_and_merges_are_reported_once():
    assert problems("a: {*x : 1, *y : 2}\nb: {<<: *z}\nc: {<<: [*w]}\n") == [
        (1, 5, "alias '*x' refers to no anchor"),
        (1, 13, "alias '*y' refers to no anchor"),
        (2, 9, "alias '*z' refers to no anchor"),
        (3, 10, "alias '*w' refers to no anchor"),
    ]


def test_alias_errors_and_other_errors_are_reported_together():
    assert problems("a: &a [*a]\nb: *c\nd: !foo 1\nd: 2\n") == [
        (1, 8, "alias '*a' is used inside its own anchor '&a'"),
        (2, 4, "alias '*c' refers to no anchor"),
        (3, 4, f"tag '!foo' {TAG_NOT_ALLOWED}"),
        (4, 1, "duplicate key 'd' (first defined at line 3)"),
    ]


def billion_laughs(levels: int = 9, width: int = 9) -> str:
    names = [f"l{i}" for i in range(levels + 1)]
    lines = [f"{names[0]}: &{names[0]} [" + ", ".join(["lol"] * width) + "]"]
    for previous, name in itertools.pairwise(names):
        lines.append(f"{name}: &{name} [" + ", ".join([f"*{previous}"] * width) + "]")
    return "\n".join(lines) + "\n"


def test_billion_laughs_is_refused_without_expanding_it():
    assert only_problem(billion_laughs(), dedent=False) == (2, 10, TOO_BIG)


def test_node_limit_counts_aliases():
    # 10 + 10 * 11 ... grows past the limit at l4 (about 11**5 nodes), without ever reaching 1000 aliases
    assert only_problem(billion_laughs(levels=6, width=10), dedent=False) == (2, 10, TOO_BIG)
    data, _ = load_yaml_text(billion_laughs(levels=3, width=10), PATH)
    assert len(data["l3"]) == 10 and data["l3"][9][9][9] == ["lol"] * 10


def test_node_limit_without_aliases_is_located_at_the_document_start(monkeypatch):
    monkeypatch.setattr(loader, "MAX_NODES", 10)
    text = "# comment\nitems: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\n"
    line, col, message = only_problem(text, dedent=False)
    assert (line, col) == (2, 1)
    assert message.startswith("the document expands to more than 10 nodes")


def test_node_limit_is_inclusive(monkeypatch):
    text = "items: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\n"  # the mapping, its key, the list and ten items: 13
    monkeypatch.setattr(loader, "MAX_NODES", 13)
    data, _ = load_yaml_text(text, PATH)
    assert len(data["items"]) == 10
    monkeypatch.setattr(loader, "MAX_NODES", 12)
    assert only_problem(text, dedent=False)[2].startswith("the document expands to more than 12 nodes")


def test_too_many_aliases():
    text = "a: &a 1\nb: [" + ", ".join(["*a"] * (MAX_ALIASES + 1)) + "]\n"
    # the 1001st alias starts after "b: [" and 1000 times "*a, "
    assert only_problem(text, dedent=False) == (
        2,
        5 + 4 * MAX_ALIASES,
        "the document uses more than 1000 aliases; refusing to load it",
    )
    data, _ = load_yaml_text("a: &a 1\nb: [" + ", ".join(["*a"] * MAX_ALIASES) + "]\n", PATH)
    assert len(data["b"]) == MAX_ALIASES


def nested_lists(depth: int) -> str:
    return "[" * depth + "]" * depth + "\n"


def test_depth_limit_is_inclusive():
    data, _ = load_yaml_text(nested_lists(MAX_DEPTH), PATH)
    for _ in range(MAX_DEPTH - 1):
        (data,) = data
    assert data == []


@pytest.mark.parametrize(
    ("text", "where"),
    [
        pytest.param(nested_lists(MAX_DEPTH + 1), (1, 65), id="flow-lists-65"),
        pytest.param(nested_lists(100_000), (1, 65), id="flow-lists-100000"),
        pytest.param("{a: " * 100_000 + "}" * 100_000 + "\n", (1, 257), id="flow-mappings-100000"),
        pytest.param("- " * 100_000 + "x\n", (1, 129), id="block-lists-100000"),
        pytest.param(
            "".join("  " * i + "a:\n" for i in range(70)) + "  " * 70 + "b: 1\n",
            (65, 129),
            id="block-mappings",
        ),
    ],
)
def test_deep_nesting_is_refused_without_recursion(text, where):
    assert only_problem(text, dedent=False) == (*where, TOO_DEEP)


def test_depth_through_aliases_is_refused_at_the_alias():
    text = f"a: &a {nested_lists(40).strip()}\nb: {'[' * 30}*a{']' * 30}\n"
    # the top-level mapping, 30 lists around the alias, and 40 lists in it: 71 levels
    assert only_problem(text, dedent=False) == (2, 34, TOO_DEEP)


# --- errors: syntax, documents, characters ---


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param("a:\n\tb: 1\n", (2, 1, "found character '\\t' that cannot start any token"), id="tab"),
        pytest.param("a: b: c\n", (1, 5, "mapping values are not allowed here"), id="mapping-in-plain"),
        pytest.param(
            "a: [1, 2\n",
            (
                2,
                1,
                "expected ',' or ']', but got '<stream end>' (while parsing a flow sequence at line 1, column 4)",
            ),
            id="unclosed-list",
        ),
        pytest.param(
            "a:\n  - 1\n - 2\n",
            (
                3,
                2,
                "expected <block end>, but found '<block sequence start>' (while parsing a block mapping "
                "at line 1, column 1)",
            ),
            id="bad-indentation",
        ),
        pytest.param(
            "a: 'open\n",
            (2, 1, "found unexpected end of stream (while scanning a quoted scalar at line 1, column 4)"),
            id="unclosed-quote",
        ),
        pytest.param(
            "a: *\n",
            (
                1,
                5,
                "expected alphabetic or numeric character, but found '\\n' (while scanning an alias at "
                "line 1, column 4)",
            ),
            id="empty-alias",
        ),
    ],
)
def test_syntax_errors(text, expected):
    assert only_problem(text, dedent=False) == expected


def test_tab_syntax_error_has_a_hint():
    with pytest.raises(SpecErrors) as info:
        load_yaml_text("a:\n\tb: 1\n", PATH)
    assert info.value.errors[0].hint == "YAML does not allow tabs for indentation; indent with spaces"


def test_errors_found_before_a_syntax_error_are_kept():
    assert problems("a: *nowhere\nb: [1\n") == [
        (1, 4, "alias '*nowhere' refers to no anchor"),
        (
            3,
            1,
            "expected ',' or ']', but got '<stream end>' (while parsing a flow sequence at line 2, column 4)",
        ),
    ]


@pytest.mark.parametrize(
    ("text", "where"),
    [
        pytest.param("---\na: 1\n---\nb: 2\n", (3, 1), id="two-documents"),
        pytest.param("a: 1\n...\n---\nb: 2\n", (3, 1), id="after-document-end"),
        pytest.param("---\n---\n", (2, 1), id="two-empty-documents"),
    ],
)
def test_more_than_one_document_is_refused(text, where):
    assert only_problem(text, dedent=False) == (
        *where,
        "a spec holds one YAML document; found a second document here",
    )


@pytest.mark.parametrize(
    ("text", "where", "code"),
    [
        pytest.param("a: 1\nb: x\x00y\n", (2, 5), "0000", id="nul"),
        pytest.param("a: \x07\n", (1, 4), "0007", id="bell"),
        pytest.param("a: 1\r\nb: \x1b\r\n", (2, 4), "001b", id="crlf"),
    ],
)
def test_control_characters_are_refused(text, where, code):
    assert only_problem(text, dedent=False) == (
        *where,
        f"unacceptable character #x{code}: special characters are not allowed",
    )


def test_text_over_the_size_limit_is_refused():
    with pytest.raises(SpecErrors) as info:
        load_yaml_text("#" + "é" * (MAX_FILE_BYTES // 2), PATH)
    assert [(e.location, e.message) for e in info.value.errors] == [
        (Location(PATH), "the file is larger than 1048576 bytes (1 MiB); refusing to load it"),
    ]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from([*"ab:-[]{},&*!?|>'\"#\n \t.01<~%", "<<", "&a", "*a", "!!"])).map("".join))
def test_arbitrary_text_loads_or_raises_spec_errors_only(text):
    try:
        load_yaml_text(text, PATH)
    except SpecErrors as errors:
        assert errors.errors
        assert all(e.location.path == PATH for e in errors.errors)


# --- source map ---

SPEC = """\
# a double pendulum
bodies:
  link1:
    mass: m1
    position: [0, -l1, 0]
  link2: {mass: m2, position: [0, "-l2", 'z']}
joints:
  - name: shoulder
    bodies: [base, link1]
  - {name: elbow}
"""


@pytest.fixture(scope="module")
def source_map() -> SourceMap:
    _, result = load_yaml_text(SPEC, PATH)
    return result


@pytest.mark.parametrize(
    ("keypath", "value", "key"),
    [
        pytest.param(("bodies",), (3, 3), (2, 1), id="top-level"),
        pytest.param(("bodies", "link1"), (4, 5), (3, 3), id="block-mapping"),
        pytest.param(("bodies", "link1", "mass"), (4, 11), (4, 5), id="nested-scalar"),
        pytest.param(("bodies", "link1", "position"), (5, 15), (5, 5), id="flow-list"),
        pytest.param(("bodies", "link1", "position", 1), (5, 19), (5, 19), id="list-item"),
        pytest.param(("bodies", "link2", "mass"), (6, 17), (6, 11), id="flow-mapping-value"),
        pytest.param(("bodies", "link2", "position", 1), (6, 35), (6, 35), id="quoted-item"),
        pytest.param(("joints", 0), (8, 5), (8, 5), id="block-list-item"),
        pytest.param(("joints", 0, "bodies", 1), (9, 20), (9, 20), id="item-in-item"),
        pytest.param(("joints", 1, "name"), (10, 12), (10, 6), id="flow-in-block-list"),
    ],
)
def test_source_map_locations(source_map, keypath, value, key):
    assert source_map.has(keypath)
    assert source_map.location(keypath) == Location(PATH, *value)
    assert source_map.key_location(keypath) == Location(PATH, *key)


@pytest.mark.parametrize(
    ("keypath", "value", "key"),
    [
        pytest.param(("bodies", "link3", "mass"), (3, 3), (2, 1), id="missing-key"),
        pytest.param(("bodies", "link1", "inertia"), (4, 5), (3, 3), id="missing-leaf"),
        pytest.param(("joints", 7), (8, 3), (7, 1), id="missing-index"),
        pytest.param(("joints", 0, "name", "deeper"), (8, 11), (8, 5), id="below-a-scalar"),
        pytest.param(("nothing",), (1, 1), (1, 1), id="missing-top-level"),
        pytest.param((), (1, 1), (1, 1), id="root"),
    ],
)
def test_source_map_falls_back_to_the_nearest_ancestor(source_map, keypath, value, key):
    assert source_map.location(keypath) == Location(PATH, *value)
    assert source_map.key_location(keypath) == Location(PATH, *key)


def test_source_map_has(source_map):
    assert source_map.has(())
    assert source_map.has(["joints", 1, "name"])
    assert not source_map.has(("joints", 2))
    assert not source_map.has(("joints", "0"))
    assert source_map.path == PATH


def test_source_map_of_an_alias_points_at_the_alias():
    _, source_map = load(
        """\
        base: &base
          mass: m
        link: *base
        list: [*base]
        """
    )
    assert source_map.location(("link",)) == Location(PATH, 3, 7)
    assert source_map.key_location(("link",)) == Location(PATH, 3, 1)
    assert source_map.location(("link", "mass")) == Location(PATH, 2, 9)
    assert source_map.location(("list", 0)) == Location(PATH, 4, 8)
    assert source_map.expr_location(("link", "mass"), 0) == Location(PATH, 2, 9)


def test_empty_source_map():
    source_map = SourceMap("x.yaml")
    assert source_map.location(("a", 1)) == Location("x.yaml", 1, 1)
    assert not source_map.has(())


@pytest.mark.parametrize(
    ("line", "keypath", "offset", "expected"),
    [
        pytest.param("mass: m1 + *", ("mass",), 5, (1, 12), id="plain"),
        pytest.param("mass: m1 + *", ("mass",), 0, (1, 7), id="plain-first"),
        pytest.param("mass: m1 + *", ("mass",), 6, (1, 13), id="plain-end"),
        pytest.param("mass: 'm1 + *'", ("mass",), 5, (1, 13), id="single-quoted"),
        pytest.param('mass: "m1 + *"', ("mass",), 5, (1, 13), id="double-quoted"),
        pytest.param("mass: !!str m1 + *", ("mass",), 5, (1, 18), id="tagged-plain"),
        pytest.param("mass: &m 'm1 + *'", ("mass",), 5, (1, 16), id="anchored-quoted"),
        pytest.param("l: [a, 'b + c']", ("l", 1), 4, (1, 13), id="list-item"),
        pytest.param("mass: m1 + *", ("mass",), 7, (1, 7), id="offset-past-end"),
        pytest.param("mass: m1 + *", ("mass",), -1, (1, 7), id="negative-offset"),
        pytest.param('mass: "m1\\t+ *"', ("mass",), 5, (1, 7), id="escape-falls-back"),
        pytest.param("mass: 'it''s + *'", ("mass",), 5, (1, 7), id="doubled-quote-falls-back"),
        pytest.param("mass: m1\n  + *", ("mass",), 5, (2, 5), id="multi-line-plain"),
        pytest.param("mass: |\n  m1 + *", ("mass",), 5, (2, 8), id="block-literal"),
        pytest.param("mass: >-  # note\n  m1\n  + *", ("mass",), 5, (3, 5), id="block-folded-comment"),
        pytest.param("mass: 'm1\n  + *'", ("mass",), 3, (2, 3), id="multi-line-quoted"),
        pytest.param("mass: !!str &a |\n  m1 + *", ("mass",), 5, (2, 8), id="block-tag-anchor"),
        pytest.param("mass: |\n  m1 + *", ("mass",), 2, (2, 5), id="block-space-after-char"),
        pytest.param('mass: "m1\\t\n  + *"', ("mass",), 5, (1, 7), id="multi-line-escape-falls-back"),
        pytest.param("mass: 'it''s\n  + *'", ("mass",), 6, (1, 7), id="multi-line-doubled-quote-falls-back"),
        pytest.param("mass: |\n  m1 + *", ("mass",), 99, (1, 7), id="multi-line-offset-past-end"),
        pytest.param("mass: [m1]", ("mass",), 0, (1, 7), id="non-scalar-falls-back"),
        pytest.param("mass: m1 + *", ("other",), 0, (1, 1), id="missing-falls-back"),
        pytest.param("a: &x m1 + *\nb: *x", ("b",), 5, (2, 4), id="alias-falls-back"),
    ],
)
def test_expr_location(line, keypath, offset, expected):
    _, source_map = load_yaml_text(line + "\n", PATH)
    assert source_map.expr_location(keypath, offset) == Location(PATH, *expected)


def test_expr_location_in_a_nested_spec(source_map):
    assert source_map.expr_location(("bodies", "link1", "position", 1), 1) == Location(PATH, 5, 20)
    assert source_map.expr_location(("bodies", "link2", "position", 1), 1) == Location(PATH, 6, 37)


# --- files ---


def test_load_file(tmp_path: Path):
    spec = tmp_path / "spec.yaml"
    spec.write_text(SPEC, encoding="utf-8")
    data, source_map = load_yaml_file(spec)
    assert data["bodies"]["link1"]["mass"] == "m1"
    assert source_map.path == str(spec)
    assert source_map.location(("bodies", "link1", "mass")) == Location(str(spec), 4, 11)
    assert load_yaml_file(str(spec))[0] == data


def test_load_file_with_bom_and_crlf(tmp_path: Path):
    spec = tmp_path / "bom.yaml"
    spec.write_bytes(b"\xef\xbb\xbfa: 1\r\nb: x\r\n")
    data, source_map = load_yaml_file(spec)
    assert data == {"a": 1, "b": "x"}
    assert source_map.location(("a",)) == Location(str(spec), 1, 4)
    assert source_map.location(("b",)) == Location(str(spec), 2, 4)


def test_errors_in_a_file_carry_its_path(tmp_path: Path):
    spec = tmp_path / "dup.yaml"
    spec.write_text("a: 1\na: 2\n", encoding="utf-8")
    with pytest.raises(SpecErrors) as info:
        load_yaml_file(spec)
    assert [e.location for e in info.value.errors] == [Location(str(spec), 2, 1)]


def file_error(path: Path) -> SpecError:
    with pytest.raises(SpecErrors) as info:
        load_yaml_file(path)
    (error,) = info.value.errors
    return error


def test_file_over_the_size_limit_is_refused(tmp_path: Path):
    spec = tmp_path / "big.yaml"
    spec.write_bytes(b"#" * (MAX_FILE_BYTES + 1))
    error = file_error(spec)
    assert error.location == Location(str(spec))
    assert error.message == "the file is larger than 1048576 bytes (1 MiB); refusing to load it"


def test_file_size_is_checked_before_reading(tmp_path: Path, monkeypatch):
    spec = tmp_path / "big.yaml"
    spec.write_bytes(b"#" * (MAX_FILE_BYTES + 1))
    read_sizes: list[int] = []
    real_open = open

    class Spy:
        def __init__(self, handle):
            self.handle = handle

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.handle.close()

        def fileno(self):
            return self.handle.fileno()

        def read(self, size=-1):
            read_sizes.append(size)
            return self.handle.read(size)

    monkeypatch.setattr("builtins.open", lambda *args, **kwargs: Spy(real_open(*args, **kwargs)))
    assert file_error(spec).message.startswith("the file is larger than")
    assert read_sizes == []


def test_missing_file(tmp_path: Path):
    spec = tmp_path / "nope.yaml"
    assert file_error(spec) == SpecError(Location(str(spec)), "cannot read file: No such file or directory")


def test_directory(tmp_path: Path):
    assert file_error(tmp_path) == SpecError(Location(str(tmp_path)), "cannot read file: Is a directory")


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0, reason="root can read anything")
def test_unreadable_file(tmp_path: Path):
    spec = tmp_path / "secret.yaml"
    spec.write_text("a: 1\n", encoding="utf-8")
    spec.chmod(0)
    assert file_error(spec) == SpecError(Location(str(spec)), "cannot read file: Permission denied")


@pytest.mark.parametrize(
    ("content", "where", "message"),
    [
        pytest.param(b"a: 1\nb: caf\xe9\n", (2, 7), "byte 0xe9: invalid continuation byte", id="latin-1"),
        pytest.param(b"a: \xff\n", (1, 4), "byte 0xff: invalid start byte", id="invalid-start"),
        pytest.param("a: 1\nb: é\n".encode() + b"\x80", (3, 1), "byte 0x80: invalid start byte", id="after-text"),
        pytest.param("é: 1\nbé: é\xe9".encode()[:-1], (2, 6), "byte 0xc3: unexpected end of data", id="truncated"),
        pytest.param(b"\xef\xbb\xbfa: \xff", (1, 4), "byte 0xff: invalid start byte", id="after-bom"),
        pytest.param("a: 1\n".encode("utf-16"), (1, 1), "byte 0xff: invalid start byte", id="utf-16"),
    ],
)
def test_invalid_utf8(tmp_path: Path, content, where, message):
    spec = tmp_path / "bad.yaml"
    spec.write_bytes(content)
    error = file_error(spec)
    assert error.location == Location(str(spec), *where)
    assert error.message == f"the file is not valid UTF-8 ({message})"
    assert error.hint == "save the spec as UTF-8"
