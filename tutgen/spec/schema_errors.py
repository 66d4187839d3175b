"""pydantic's errors on a spec's shape, as located messages in the spec's words.

:class:`tutgen.spec.schema.SpecDoc` checks the shape of a spec (which keys, which types); this module
turns what pydantic reports into :class:`tutgen.errors.SpecError` at the ``file:line:col`` of the
offending key or value: an unknown key with the keys allowed there and a "did you mean", a missing
key, a value of the wrong kind with what was expected. Each :class:`Problem` also carries the data
path it is about, so that :mod:`tutgen.spec.validate` can set that part of the spec aside.
"""

from __future__ import annotations

import difflib
from functools import cache
from typing import Any, NamedTuple

from pydantic import ValidationError

from tutgen.errors import Location, SpecError
from tutgen.spec import schema as S
from tutgen.spec.loader import KeyPath, SourceMap
from tutgen.spec.places import where

#: Keys whose value is the name of something declared elsewhere.
_NAME_KEYS = frozenset({"parent", "child", "coordinate", "body", "reaction_body", "joint"})
#: Keys of earlier drafts of the format, and what they are called now.
_RENAMED_KEYS = {"on": "body", "reaction_on": "reaction_body"}

#: pydantic's error types, as what a value should have been.
_TYPE_WORDS = {
    "dict_type": "a mapping",
    "model_type": "a mapping",
    "model_attributes_type": "a mapping",
    "list_type": "a list",
    "string_type": "a text",
    "int_type": "a whole number",
    "float_type": "a number",
    "bool_type": "true or false",
}


@cache
def _schema() -> dict[str, Any]:
    return S.SpecDoc.model_json_schema()


def _resolve(node: dict[str, Any], defs: dict[str, Any], data: Any) -> list[dict[str, Any]]:
    """The object schemas that may describe ``data`` at this schema node."""
    if "$ref" in node:
        return _resolve(defs[node["$ref"].split("/")[-1]], defs, data)
    if "oneOf" in node or "anyOf" in node:
        options = node.get("oneOf", node.get("anyOf", []))
        if "discriminator" in node and isinstance(data, dict):
            ref = node["discriminator"]["mapping"].get(str(data.get("shape")))
            if ref:
                return _resolve({"$ref": ref}, defs, data)
        out: list[dict[str, Any]] = []
        for option in options:
            out += _resolve(option, defs, data)
        return out
    return [node]


def _allowed_keys(path: tuple[Any, ...], data: Any) -> list[str]:
    """Keys allowed at a data path (walking the JSON Schema alongside the data)."""
    root = _schema()
    defs = root.get("$defs", {})
    nodes = [root]
    node_data = data
    for key in path:
        nxt = []
        for node in nodes:
            for obj in _resolve(node, defs, node_data):
                props = obj.get("properties", {})
                if key in props:
                    nxt.append(props[key])
                elif isinstance(obj.get("additionalProperties"), dict):
                    nxt.append(obj["additionalProperties"])
                elif isinstance(obj.get("items"), dict):
                    nxt.append(obj["items"])
        nodes = nxt
        node_data = node_data[key] if isinstance(node_data, (dict, list)) else None
    keys: list[str] = []
    for node in nodes:
        for obj in _resolve(node, defs, node_data):
            keys += [k for k in obj.get("properties", {}) if k not in keys]
    return keys


def _data_path(loc: tuple[Any, ...], data: Any) -> tuple[tuple[Any, ...], Any, bool]:
    """Drop the parts of a pydantic loc that are not in the data (union tags, shorthand wrappers).

    Returns (path, value at path, whether the whole loc was found)."""
    path: list[Any] = []
    node = data
    found = True
    for i, key in enumerate(loc):
        if isinstance(node, dict) and key in node:
            node = node[key]
            path.append(key)
        elif isinstance(node, list) and isinstance(key, int) and 0 <= key < len(node):
            node = node[key]
            path.append(key)
        elif i == len(loc) - 1:
            found = False
        # else: a tag pydantic added (e.g. the 'box' of a discriminated union): skip it
    return tuple(path), node, found


class Problem(NamedTuple):
    """A located error and the data path it is about (to set that part of the spec aside)."""

    path: KeyPath
    error: SpecError


def translate(exc: ValidationError, data: Any, smap: SourceMap) -> list[Problem]:
    """pydantic's errors as located messages in the spec's words, one per mistake.

    The alternatives of a union that all failed at one place become one message ("must be one of:
    x, y, z or a vector ..."); a required key that is missing because it was misspelt is reported
    once, as the misspelt key.
    """
    problems: list[Problem] = []
    suggested: set[tuple[KeyPath, str]] = set()  # (mapping, key) offered as "did you mean"
    missing: list[tuple[KeyPath, str]] = []
    # value problems by place: (what was expected, what was found, hint, location)
    values: dict[KeyPath, list[tuple[str, str, str | None, Location]]] = {}
    literal_only: set[KeyPath] = set()  # places where a choice of names failed
    structured: set[KeyPath] = set()  # places where anything else failed
    for err in exc.errors():
        loc = tuple(err["loc"])
        kind = err["type"]
        path, value, _ = _data_path(loc, data)
        if kind == "extra_forbidden":
            key = str(loc[-1])
            allowed = _allowed_keys(path[:-1], data)
            close = difflib.get_close_matches(key, allowed, n=1)
            if not close and _RENAMED_KEYS.get(key) in allowed:
                close = [_RENAMED_KEYS[key]]
            if close:
                suggested.add((path[:-1], close[0]))
            problems.append(
                Problem(
                    path,
                    SpecError(
                        smap.key_location(path),
                        f"unknown key '{key}' in {where(path[:-1])}; expected one of: " + ", ".join(allowed),
                        f"did you mean '{close[0]}'?" if close else None,
                    ),
                )
            )
        elif kind == "missing":
            missing.append((path, str(loc[-1])))
        elif kind == "union_tag_invalid":
            tag = err["ctx"]["tag"]
            close = difflib.get_close_matches(str(tag), S.SHAPES, n=1)
            problems.append(
                Problem(
                    path,
                    SpecError(
                        smap.location((*path, "shape")),
                        f"unknown shape '{tag}' for {where(path)}; expected one of: " + ", ".join(S.SHAPES),
                        f"did you mean '{close[0]}'?" if close else None,
                    ),
                )
            )
        elif kind == "union_tag_not_found":
            missing.append((path, "shape"))
        elif kind == "tutgen_names" and isinstance(value, list):
            for i, item in enumerate(value):
                if not isinstance(item, str):
                    problems.append(
                        Problem(
                            (*path, i),
                            SpecError(
                                smap.location((*path, i)),
                                f"{where((*path, i))} must be a name; found {S.describe(item)}",
                            ),
                        )
                    )
        else:
            expected, hint = _expected(err, path, value)
            if kind == "literal_error":
                literal_only.add(path)
            else:
                structured.add(path)
            values.setdefault(path, []).append((expected, S.describe(value), hint, smap.location(path)))
    for path, key in missing:
        if (path, key) in suggested:
            continue  # the misspelt key is reported, with this one as its suggestion
        text = f"missing required key '{key}' in {where(path)}"
        if key == "shape":
            text += "; expected one of: " + ", ".join(S.SHAPES)
        problems.append(Problem(path, SpecError(smap.key_location(path) if path else smap.location(()), text)))
    for path, found in values.items():
        if path in literal_only - structured and any(q[: len(path)] == path and q != path for q in values):
            # `axis: [true, 0, 0]` fails as a name and, deeper, as a vector: the vector was meant
            continue
        expected = " or ".join(dict.fromkeys(e for e, _, _, _ in found))
        hint = next((h for _, _, h, _ in found if h), None)
        if path == ("tutgen",):
            message = f"unsupported spec format version: 'tutgen' must be {expected}; found {found[0][1]}"
            hint = hint or f"this version of tutgen reads format {S.SPEC_FORMAT_VERSION}"
        else:
            message = f"{where(path)} must be {expected}; found {found[0][1]}"
        if path == ("arm", "convention"):
            hint = hint or "standard: Spong, Paul (A_i = Rz Tz Tx Rx); modified: Craig (A_i = Rx Tx Rz Tz)"
        problems.append(Problem(path, SpecError(found[0][3], message, hint)))
    return problems


def _expected(err: Any, path: KeyPath, value: Any) -> tuple[str, str | None]:
    """What a value error expected, in words, and a "did you mean" hint if one applies."""
    kind = err["type"]
    if kind == "literal_error":
        expected = err.get("ctx", {}).get("expected", "")
        choices = [c.strip(" '") for c in expected.replace(" or ", ", ").split(",")]
        close = difflib.get_close_matches(str(value), choices, n=1) if isinstance(value, str) else []
        words = choices[0] if len(choices) == 1 else "one of: " + ", ".join(choices)
        return words, (f"did you mean '{close[0]}'?" if close else None)
    if kind == "tutgen_text" and path and path[-1] in _NAME_KEYS:
        return "a name", None
    if kind.startswith("tutgen_"):
        message = str(err["msg"])
        head = message.split(", found ", 1)[0]
        return head.removeprefix("expected "), None
    if kind in ("too_short", "too_long"):
        ctx = err.get("ctx", {})
        if path and path[-1] == "between":
            return "two attachment points [A, B]", None
        if kind == "too_short":  # pragma: no cover - only `between` has a length today
            return f"a list of at least {ctx.get('min_length')} items", None
        return f"a list of at most {ctx.get('max_length')} items", None
    if kind in ("dict_type", "model_type") and path in (("parameters",), ("coordinates",)):
        return "a list of names or a mapping", None
    if kind in ("dict_type", "model_type") and path == ("gravity",):
        return "a vector [x, y, z] or a mapping with `g` and `direction`", None
    if kind == "list_type" and path and path[-1] == "between":
        return "a list of two attachment points [A, B]", None
    if kind == "list_type" and path and path[-1] == "orientation":
        return "a list of rotations", "write e.g. orientation: [{axis: z, angle: theta}]"
    return _TYPE_WORDS.get(kind, str(err["msg"]).removeprefix("Input should be ").rstrip(".")), None
