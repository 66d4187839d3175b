"""Places in a spec: its sections of named entries, how a message names a place, and the parts set aside.

A place is a key path into the loaded data, as the :class:`tutgen.spec.loader.SourceMap` knows it:
``("bodies", "link1", "com", 2)``. A message says it in the reader's words ("'com[3]' of body
'link1'"). A part of the spec whose *shape* is wrong (a named entry, a row of the arm's table, or a
whole top-level key) is reported once and set aside, so that the rest is still checked; its name
still counts as declared.
"""

from __future__ import annotations

from typing import Any

from tutgen.spec.loader import KeyPath

#: Sections that hold named objects, and what one of their entries is called in a message.
NAMED_SECTIONS = {
    "parameters": "parameter",
    "coordinates": "coordinate",
    "bodies": "body",
    "joints": "joint",
    "springs": "spring",
    "dampers": "damper",
    "loads": "load",
    "generalized_forces": "generalized force on",
    "constraints": "constraint",
}
#: Sections every expression or cross-reference depends on: when one of them has the wrong shape as a
#: whole, checking the rest would only report consequences of that one mistake.
FOUNDATIONS = frozenset({"parameters", "coordinates", "bodies"})
#: The rows of the Denavit-Hartenberg table: each one is set aside on its own, like a named entry.
ARM_LINKS: KeyPath = ("arm", "links")


def where(path: KeyPath) -> str:
    """A place in the spec in the reader's words: "body 'link'", "'com[2]' of body 'link'", "'gravity'"."""
    if not path:
        return "the spec"
    owner = None
    rest = tuple(path)
    if tuple(path[:2]) == ARM_LINKS and len(path) >= 3:
        owner = f"arm link '{path[2]}'"
        rest = tuple(path[3:])
    elif path[0] in NAMED_SECTIONS and len(path) >= 2 and isinstance(path[1], str):
        owner = f"{NAMED_SECTIONS[str(path[0])]} '{path[1]}'"
        rest = tuple(path[2:])
        if path[0] == "bodies" and len(rest) >= 2 and rest[0] == "parts":
            owner = f"part '{rest[1]}' of body '{path[1]}'"
            rest = rest[2:]
    if not rest:
        return owner or "the spec"
    text = ""
    for p in rest:
        text += f"[{p + 1}]" if isinstance(p, int) else (f".{p}" if text else str(p))
    return f"'{text}' of {owner}" if owner else f"'{text}'"


def unit_of(path: KeyPath) -> KeyPath:
    """The part of the spec set aside for a shape error at ``path``: a named entry, or a top-level key."""
    if not path:
        return ()
    if tuple(path[:2]) == ARM_LINKS and len(path) >= 3:
        return tuple(path[:3])
    if path[0] in NAMED_SECTIONS and len(path) >= 2:
        return tuple(path[:2])
    return tuple(path[:1])


def prune(data: dict[str, Any], units: set[KeyPath]) -> dict[str, Any]:
    """A copy of ``data`` without ``units`` (top-level keys, or entries of a section)."""
    out = dict(data)
    for unit in units:
        if len(unit) == 1:
            out.pop(unit[0], None)
    for section in {u[0] for u in units if len(u) == 2}:
        entries = {u[1] for u in units if len(u) == 2 and u[0] == section}
        value = out.get(section)
        if isinstance(value, dict):
            out[section] = {k: v for k, v in value.items() if k not in entries}
        elif isinstance(value, list):
            out[section] = [v for i, v in enumerate(value) if i not in entries]
    rows = {u[2] for u in units if len(u) == 3 and tuple(u[:2]) == ARM_LINKS}
    arm = out.get("arm")
    if rows and isinstance(arm, dict) and isinstance(arm.get("links"), dict):
        out["arm"] = {**arm, "links": {k: v for k, v in arm["links"].items() if k not in rows}}
    out.setdefault("title", "")
    return out
