"""Load a spec's YAML safely: plain Python data, a source map, and located errors.

PyYAML's reader, scanner and parser do the syntax; the composer here is our own, so that hostile input is
refused while the node graph is built, before anything is expanded:

- nesting deeper than ``MAX_DEPTH`` stops the composer at the collection (or alias) that crosses it, so
  neither PyYAML nor this module ever comes near Python's recursion limit;
- the size of the document *with aliases expanded* is kept as a running total, from per-node sizes
  memoised by node identity, so a "billion laughs" document is measured without expanding it;
- more than ``MAX_ALIASES`` alias uses, and an alias used inside its own anchor, are refused.

No tag is ever constructed. Scalars are resolved here by the YAML 1.2 core schema (``yes``, ``on`` and
``2026-11-23`` stay strings; ``1e-3`` is a float), and every other problem that can be found in one pass
(unknown tags, duplicate keys, bad merge keys, keys that are not scalars) is collected and raised once as
:class:`~tutgen.errors.SpecErrors`.
"""

from __future__ import annotations

import codecs
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any, NamedTuple

import yaml
from yaml.composer import Composer
from yaml.error import Mark, MarkedYAMLError
from yaml.events import (
    AliasEvent,
    MappingEndEvent,
    MappingStartEvent,
    ScalarEvent,
    SequenceEndEvent,
    StreamEndEvent,
)
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode
from yaml.parser import Parser
from yaml.reader import Reader, ReaderError
from yaml.scanner import Scanner

from tutgen.errors import Location, SpecError, SpecErrors
from tutgen.spec.scalars import core_value
from tutgen.spec.stdin import STDIN, STDIN_NAME, read_stdin

__all__ = [
    "MAX_ALIASES",
    "MAX_DEPTH",
    "MAX_FILE_BYTES",
    "MAX_NODES",
    "KeyPath",
    "SourceMap",
    "load_yaml_file",
    "load_yaml_text",
]

#: Largest spec file accepted, in bytes (1 MiB).
MAX_FILE_BYTES: int = 1_048_576
#: Most nodes a document may have once its aliases are expanded (keys, values and items all count).
MAX_NODES: int = 100_000
#: Deepest nesting of collections accepted, aliases expanded (a top-level mapping is depth 1).
MAX_DEPTH: int = 64
#: Most alias uses (``*name``) accepted in one file.
MAX_ALIASES: int = 1_000

#: Where a value sits in the loaded data: mapping keys (str) and list indices (int), from the root.
KeyPath = tuple[str | int, ...]

# --- tags ---

_YAML_TAG = "tag:yaml.org,2002:"
_STR = _YAML_TAG + "str"
_INT = _YAML_TAG + "int"
_FLOAT = _YAML_TAG + "float"
_BOOL = _YAML_TAG + "bool"
_NULL = _YAML_TAG + "null"
_SEQ = _YAML_TAG + "seq"
_MAP = _YAML_TAG + "map"
_ALLOWED_TAGS = frozenset({_STR, _INT, _FLOAT, _BOOL, _NULL, _SEQ, _MAP})
#: The tag our composer gives a scalar written without one: resolved later from its style and text.
_UNTAGGED = "tutgen:untagged"

_TAG_HINT = "remove the tag; the only tags a spec may use are !!str, !!int, !!float, !!bool, !!null, !!seq, !!map"

#: Line breaks as PyYAML's reader counts them ("\r\n" is one break).
_BREAK_RE = re.compile("\r\n|[\r\n\x85\u2028\u2029]")


# --- helpers ---


def _show_tag(tag: str) -> str:
    """A tag as a user would write it: ``tag:yaml.org,2002:set`` is ``!!set``."""
    if tag.startswith(_YAML_TAG):
        return "!!" + tag[len(_YAML_TAG) :]
    return tag


def _short(text: str, limit: int = 40) -> str:
    """A scalar's text for a message: one line, at most ``limit`` characters."""
    text = text.replace("\n", "\\n")
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _describe(node: Node) -> str:
    """What a node is, for a message: "a mapping", "a list", "an empty value", "the value 'x'"."""
    if isinstance(node, MappingNode):
        return "a mapping"
    if isinstance(node, SequenceNode):
        return "a list"
    if node.value == "" and node.style is None:
        return "an empty value"
    return f"the value '{_short(node.value)}'"


def _mark_location(path: str, mark: Mark) -> Location:
    """PyYAML marks are 0-based; a Location is 1-based."""
    return Location(path, mark.line + 1, mark.column + 1)


def _line_col(text: str, index: int) -> tuple[int, int]:
    """1-based line and column of the character at ``index`` of ``text``, counting breaks as PyYAML does."""
    line, start = 1, 0
    for match in _BREAK_RE.finditer(text, 0, index):
        line += 1
        start = match.end()
    return line, index - start + 1


def _multiline_index(text: str, style: str | None, start: int, stop: int, value: str, offset: int) -> int | None:
    """Where in ``text`` the character at ``offset`` of a scalar written over several lines is.

    The scalar's characters other than spaces, tabs and line breaks are found in the text in order,
    with nothing but indentation and line breaks between them (a block scalar's header line is skipped).
    A space of the value is placed just after the character before it. None when the text does not
    read that way (escapes, doubled quotes) or ``offset`` is outside the value.
    """
    if not 0 <= offset <= len(value):
        return None
    i = start
    while i < stop and text[i] in "!&":  # a tag or an anchor starts the node's mark
        while i < stop and text[i] not in " \t":
            i += 1
        while i < stop and text[i] in " \t":
            i += 1
    if style in ("|", ">"):
        breaks = _BREAK_RE.search(text, i, stop)
        if breaks is None:
            return None
        i = breaks.end()
    elif style in ("'", '"'):
        if style == '"' and "\\" in text[i:stop]:
            return None
        i += 1
    position = i
    for index, char in enumerate(value[: offset + 1]):
        if char in " \t\n":
            if index == offset:
                return position
            continue
        found = text.find(char, position, stop)
        if found < 0 or text[position:found].strip(" \t\r\n\x85\u2028\u2029"):
            return None
        if index == offset:
            return found
        position = found + 1
    return position


def _too_big(path: str) -> SpecError:
    return SpecError(
        Location(path),
        f"the file is larger than {MAX_FILE_BYTES} bytes (1 MiB); refusing to load it",
        "a spec is a short text; check that this is the file you meant",
    )


class _Placeholder(ScalarNode):
    """Stands for an alias that could not be resolved (already reported): a null, never reported again."""


class _Refused(Exception):
    """Raised inside the composer for a problem that stops loading at once (limits, several documents)."""

    def __init__(self, error: SpecError) -> None:
        super().__init__(error.message)
        self.error = error


# --- the source map ---


class _Entry(NamedTuple):
    """Where one value of the loaded data was written (1-based positions)."""

    line: int
    col: int
    key_line: int
    key_col: int
    #: column of the scalar's first character when offsets inside it map exactly to columns, else None
    expr_col: int | None
    expr_len: int
    #: a scalar written over several lines (a block ``|``/``>``, or a folded plain or quoted scalar):
    #: its style, where it starts and ends in the text, and its value, so that an offset into the
    #: value can be found in the text (see :meth:`SourceMap.expr_location`); None otherwise
    multiline: tuple[str | None, int, int, str] | None = None


@dataclass(frozen=True, eq=False)
class SourceMap:
    """Where each value of a loaded spec was written, looked up by its key path.

    Values reached through an alias are located where the anchored node was written, and keys merged in
    with ``<<`` where they were written in the merged mapping.
    """

    path: str
    _entries: Mapping[KeyPath, _Entry] = field(default_factory=dict, repr=False)
    #: the text the spec was loaded from (to find offsets inside scalars written over several lines)
    _text: str = field(default="", repr=False)

    @property
    def text(self) -> str:
        """The text the document was loaded from ("" for a document with nothing to locate)."""
        return self._text

    def _find(self, keypath: KeyPath) -> _Entry | None:
        """The entry at ``keypath``, or at its nearest existing ancestor other than the root."""
        path = tuple(keypath)
        while path:
            entry = self._entries.get(path)
            if entry is not None:
                return entry
            path = path[:-1]
        return None

    def location(self, keypath: KeyPath) -> Location:
        """Where the value at ``keypath`` starts.

        A path that does not exist falls back to its nearest existing ancestor; the root path ``()``
        (and anything with no existing ancestor) is ``Location(path, 1, 1)``.
        """
        entry = self._find(keypath)
        if entry is None:
            return Location(self.path, 1, 1)
        return Location(self.path, entry.line, entry.col)

    def key_location(self, keypath: KeyPath) -> Location:
        """Where the key of the last element of ``keypath`` starts (for a list item: the item itself).

        Falls back like :meth:`location`, to the key of the nearest existing ancestor.
        """
        entry = self._find(keypath)
        if entry is None:
            return Location(self.path, 1, 1)
        return Location(self.path, entry.key_line, entry.key_col)

    def expr_location(self, keypath: KeyPath, offset: int) -> Location:
        """Where the character at 0-based ``offset`` of the string at ``keypath`` was written.

        Exact for a scalar written on one line whose text is its value: a plain scalar, or a quoted one
        without escapes (``\\n``) or doubled quotes (``''``); and for a scalar written over several
        lines (a block ``|`` or ``>``, a plain or quoted scalar folded over lines) whose characters
        other than spaces and line breaks are written as they are. Otherwise (and for an offset outside
        the string) this is :meth:`location` of ``keypath``.
        """
        entry = self._entries.get(tuple(keypath))
        if entry is not None and entry.multiline is not None and self._text:
            found = _multiline_index(self._text, *entry.multiline, offset)
            if found is not None:
                return Location(self.path, *_line_col(self._text, found))
        if entry is None or entry.expr_col is None or not 0 <= offset <= entry.expr_len:
            return self.location(keypath)
        return Location(self.path, entry.line, entry.expr_col + offset)

    def has(self, keypath: KeyPath) -> bool:
        """Whether ``keypath`` exists in the loaded data (``()`` exists unless the data is None)."""
        return tuple(keypath) in self._entries


# --- composing: PyYAML's reader, scanner and parser; our own composer ---


class _Composer(Reader, Scanner, Parser, Composer):
    """Builds PyYAML's node graph from the parser's events, checking the limits as it goes.

    Never constructs anything: a node keeps the tag it was written with (``_UNTAGGED`` if none).
    Sizes (nodes, aliases expanded) and heights (collection levels) are memoised per node identity when a
    node is finished, so an alias costs a dictionary lookup whatever it stands for.
    """

    def __init__(self, text: str, path: str) -> None:
        Reader.__init__(self, text)
        Scanner.__init__(self)
        Parser.__init__(self)
        Composer.__init__(self)
        self.path = path
        self.errors: list[SpecError] = []
        self._depth = 0  # collections open around the current event
        self._open: set[int] = set()  # ids of the collections being composed
        self._size: dict[int, int] = {}
        self._height: dict[int, int] = {}
        self._total = 0  # nodes so far, aliases expanded
        self._aliases = 0
        self._first_alias: Mark | None = None
        self._document_start: Mark | None = None
        #: where an alias was used, by (id of the collection, slot): a list's index, or 2i / 2i+1 for the
        #: key / value of a mapping's i-th pair
        self.alias_marks: dict[tuple[int, int], Mark] = {}

    def _refuse(self, mark: Mark | None, message: str, hint: str | None = None) -> _Refused:
        location = _mark_location(self.path, mark) if mark is not None else Location(self.path, 1, 1)
        return _Refused(SpecError(location, message, hint))

    def _add_nodes(self, count: int) -> None:
        self._total += count
        if self._total > MAX_NODES:
            raise self._refuse(
                self._first_alias or self._document_start,
                f"the document expands to more than {MAX_NODES} nodes (anchors and aliases included); "
                "refusing to load it",
            )

    def _too_deep(self, mark: Mark) -> _Refused:
        return self._refuse(
            mark,
            f"the document nests collections more than {MAX_DEPTH} levels deep (anchors and aliases "
            "included); refusing to load it",
        )

    def get_single_node(self) -> Node | None:
        """The root node of the only document, or None for an empty stream."""
        self.get_event()  # STREAM-START
        document = None
        if not self.check_event(StreamEndEvent):
            document = self.compose_document()
        if not self.check_event(StreamEndEvent):
            event = self.get_event()
            raise self._refuse(
                event.start_mark,
                "a spec holds one YAML document; found a second document here",
                "remove the '---' or '...' line, or put each spec in a file of its own",
            )
        self.get_event()  # STREAM-END
        return document

    def compose_document(self) -> Node:
        """The root node of the next document."""
        start = self.get_event()  # DOCUMENT-START
        self._document_start = start.start_mark
        node = self.compose_node(None, None)
        self.get_event()  # DOCUMENT-END
        self.anchors = {}
        return node

    def compose_node(self, parent: Node | None, index: Any) -> Node:
        """The next node: an alias resolves to its anchored node (already composed, never copied)."""
        if self.check_event(AliasEvent):
            return self._compose_alias()
        anchor = self.peek_event().anchor
        if self.check_event(ScalarEvent):
            return self.compose_scalar_node(anchor)
        if self.check_event(MappingStartEvent):
            return self.compose_mapping_node(anchor)
        return self.compose_sequence_node(anchor)

    def _compose_child(self, parent: Node, slot: int, index: Any) -> Node:
        """The next node inside ``parent``, remembering where it was written if it is an alias."""
        if self.check_event(AliasEvent):
            self.alias_marks[(id(parent), slot)] = self.peek_event().start_mark
        return self.compose_node(parent, index)

    def _compose_alias(self) -> Node:
        event = self.get_event()
        self._aliases += 1
        if self._first_alias is None:
            self._first_alias = event.start_mark
        if self._aliases > MAX_ALIASES:
            raise self._refuse(
                event.start_mark, f"the document uses more than {MAX_ALIASES} aliases; refusing to load it"
            )
        name = event.anchor
        target = self.anchors.get(name)
        if target is None or id(target) in self._open:
            if target is None:
                message = f"alias '*{name}' refers to no anchor"
                hint = f"define '&{name}' before the first '*{name}'"
            else:
                message = f"alias '*{name}' is used inside its own anchor '&{name}'"
                hint = "a spec cannot contain itself; copy the part you need instead"
            self.errors.append(SpecError(_mark_location(self.path, event.start_mark), message, hint))
            placeholder = _Placeholder(_UNTAGGED, "", event.start_mark, event.end_mark)
            self._finish(placeholder, 1, 0)
            return placeholder
        if self._depth + self._height[id(target)] > MAX_DEPTH:
            raise self._too_deep(event.start_mark)
        self._add_nodes(self._size[id(target)])
        return target

    def _finish(self, node: Node, size: int, height: int) -> None:
        self._size[id(node)] = size
        self._height[id(node)] = height

    def _open_collection(self, node: Node, anchor: str | None) -> None:
        self._depth += 1
        if self._depth > MAX_DEPTH:
            raise self._too_deep(node.start_mark)
        self._add_nodes(1)
        if anchor is not None:
            self.anchors[anchor] = node  # before its children: that is how a recursive alias is caught
        self._open.add(id(node))

    def _close_collection(self, node: Node, children: list[Node]) -> None:
        self._open.discard(id(node))
        self._depth -= 1
        size = 1 + sum(self._size[id(child)] for child in children)
        height = 1 + max((self._height[id(child)] for child in children), default=0)
        self._finish(node, size, height)

    def compose_scalar_node(self, anchor: str | None) -> Node:
        """A scalar node; its tag is the one written (``!`` means str), or ``_UNTAGGED``."""
        event = self.get_event()
        tag = event.tag
        if tag is None:
            tag = _UNTAGGED
        elif tag == "!":
            tag = _STR
        node = ScalarNode(tag, event.value, event.start_mark, event.end_mark, style=event.style)
        self._add_nodes(1)
        self._finish(node, 1, 0)
        if anchor is not None:
            self.anchors[anchor] = node
        return node

    def compose_sequence_node(self, anchor: str | None) -> Node:
        """A sequence node and its items."""
        start = self.get_event()
        tag = _SEQ if start.tag in (None, "!") else start.tag
        node = SequenceNode(tag, [], start.start_mark, None, flow_style=start.flow_style)
        self._open_collection(node, anchor)
        index = 0
        while not self.check_event(SequenceEndEvent):
            node.value.append(self._compose_child(node, index, index))
            index += 1
        node.end_mark = self.get_event().end_mark
        self._close_collection(node, node.value)
        return node

    def compose_mapping_node(self, anchor: str | None) -> Node:
        """A mapping node and its (key, value) pairs, duplicates and all (checked later)."""
        start = self.get_event()
        tag = _MAP if start.tag in (None, "!") else start.tag
        node = MappingNode(tag, [], start.start_mark, None, flow_style=start.flow_style)
        self._open_collection(node, anchor)
        children: list[Node] = []
        while not self.check_event(MappingEndEvent):
            slot = 2 * len(node.value)
            key = self._compose_child(node, slot, None)
            value = self._compose_child(node, slot + 1, key)
            node.value.append((key, value))
            children += (key, value)
        node.end_mark = self.get_event().end_mark
        self._close_collection(node, children)
        return node


# --- building plain data ---


class _Builder:
    """Turns a checked node graph into plain data (aliases copied), collecting every problem it sees."""

    def __init__(self, text: str, path: str, alias_marks: Mapping[tuple[int, int], Mark]) -> None:
        self.text = text
        self.path = path
        self.alias_marks = alias_marks
        self.errors: list[SpecError] = []
        self.entries: dict[KeyPath, _Entry] = {}

    def _error(self, where: Node | Mark, message: str, hint: str | None = None) -> None:
        mark = where.start_mark if isinstance(where, Node) else where
        self.errors.append(SpecError(_mark_location(self.path, mark), message, hint))

    def build(self, node: Node, keypath: KeyPath, key_mark: Mark, alias_mark: Mark | None = None) -> Any:
        """The plain value of ``node``, recorded in the source map at ``keypath``.

        ``key_mark`` is where its key (or, in a list, the item) was written; ``alias_mark`` where the
        alias that stands for it was written, if it was reached through one.
        """
        if keypath not in self.entries:
            self.entries[keypath] = self._entry(node, key_mark, alias_mark)
        if isinstance(node, ScalarNode):
            return self._scalar(node)
        if isinstance(node, SequenceNode):
            self._check_collection_tag(node, _SEQ, "a list")
            items: list[Any] = []
            for index, item in enumerate(node.value):
                item_alias = self.alias_marks.get((id(node), index))
                items.append(self.build(item, (*keypath, index), item_alias or item.start_mark, item_alias))
            return items
        self._check_collection_tag(node, _MAP, "a mapping")
        result: dict[str, Any] = {}
        for key, entry_key_mark, value_node, value_alias_mark in self._mapping_entries(node):
            result[key] = self.build(value_node, (*keypath, key), entry_key_mark, value_alias_mark)
        return result

    def _entry(self, node: Node, key_mark: Mark, alias_mark: Mark | None) -> _Entry:
        key_line, key_col = key_mark.line + 1, key_mark.column + 1
        if alias_mark is not None:  # the value is where the alias was written; offsets do not map
            return _Entry(alias_mark.line + 1, alias_mark.column + 1, key_line, key_col, None, 0)
        start = node.start_mark
        multiline = None
        if isinstance(node, ScalarNode):
            expr_col, expr_len = self._expr_column(node), len(node.value)
            if start.line != node.end_mark.line:
                multiline = (node.style, start.index, node.end_mark.index, node.value)
        else:
            expr_col, expr_len = None, 0
        return _Entry(start.line + 1, start.column + 1, key_line, key_col, expr_col, expr_len, multiline)

    def _expr_column(self, node: ScalarNode) -> int | None:
        """1-based column of the scalar's first character, if every character sits where its offset says."""
        start, end = node.start_mark, node.end_mark
        if start.line != end.line:
            return None
        text, i, stop = self.text, start.index, end.index
        while i < stop and text[i] in "!&":  # skip the tag and anchor, which start the node's mark
            while i < stop and text[i] not in " \t":
                i += 1
            while i < stop and text[i] in " \t":
                i += 1
        value = node.value
        if node.style is None:
            first, exact = i, text[i:stop] == value
        elif node.style in ("'", '"'):
            quote = node.style
            first = i + 1
            exact = stop - i >= 2 and text[i] == quote == text[stop - 1] and text[first : stop - 1] == value
        else:
            return None
        return start.column + (first - start.index) + 1 if exact else None

    def _check_collection_tag(self, node: Node, expected: str, what: str) -> None:
        tag = node.tag
        if tag == expected:
            return
        if tag in _ALLOWED_TAGS:
            self._error(node, f"tag '{_show_tag(tag)}' cannot be used on {what}")
        else:
            self._not_allowed(node)

    def _not_allowed(self, node: Node) -> None:
        self._error(
            node,
            f"tag '{_show_tag(node.tag)}' is not allowed; a spec holds only plain mappings, lists, strings and numbers",
            _TAG_HINT,
        )

    def _scalar(self, node: ScalarNode) -> Any:
        tag, text = node.tag, node.value
        if tag == _UNTAGGED:
            if node.style is not None:  # quoted or block: always a string
                return text
            try:
                return core_value(text)
            except ValueError:
                self._error(node, f"the integer '{_short(text)}' has too many digits")
                return text
        if tag == _STR:
            return text
        if tag not in _ALLOWED_TAGS:
            self._not_allowed(node)
            return text
        if tag in (_SEQ, _MAP):
            self._error(node, f"tag '{_show_tag(tag)}' cannot be used on a scalar")
            return text
        try:
            value = core_value(text)
        except ValueError:
            self._error(node, f"the integer '{_short(text)}' has too many digits")
            return text
        if tag == _INT and type(value) is int:
            return value
        if tag == _FLOAT and type(value) in (int, float):
            return float(value)
        if tag == _BOOL and type(value) is bool:
            return value
        if tag == _NULL and value is None:
            return None
        expected = {_INT: "an integer", _FLOAT: "a number", _BOOL: "true or false", _NULL: "null"}[tag]
        self._error(node, f"'{_short(text)}' is not {expected} (tag '{_show_tag(tag)}')")
        return text

    def _mapping_entries(self, node: MappingNode) -> list[tuple[str, Mark, Node, Mark | None]]:
        """(key, where the key was written, value node, where its alias was written) of a mapping.

        Merge keys are resolved: keys written in the mapping win, then each merged mapping in order (the
        first one winning). Merged keys take the place of the ``<<`` entry.
        """
        seen: dict[str, Mark] = {}
        items: list[tuple[str, Mark, Node, Mark | None] | Node] = []  # a bare Node: a merge key's value
        for pair, (key_node, value_node) in enumerate(node.value):
            key_mark = self.alias_marks.get((id(node), 2 * pair)) or key_node.start_mark
            if isinstance(key_node, _Placeholder):
                continue
            if not isinstance(key_node, ScalarNode):
                self._error(key_mark, f"a mapping key must be a name or a number; found {_describe(key_node)}")
                continue
            self._scalar(key_node)  # checks its tag; the key itself is its text as written
            key = key_node.value
            first = seen.get(key)
            if first is not None:
                self._error(
                    key_mark,
                    f"duplicate key '{_short(key)}' (first defined at line {first.line + 1})",
                    "a key may appear once in a mapping; remove or rename one of them",
                )
                continue
            seen[key] = key_mark
            if key == "<<" and key_node.tag == _UNTAGGED and key_node.style is None:
                items.append(value_node)
            else:
                items.append((key, key_mark, value_node, self.alias_marks.get((id(node), 2 * pair + 1))))
        taken = {item[0] for item in items if isinstance(item, tuple)}
        entries: list[tuple[str, Mark, Node, Mark | None]] = []
        for item in items:
            if isinstance(item, tuple):
                entries.append(item)
                continue
            for source in self._merge_sources(item):
                for entry in self._mapping_entries(source):
                    if entry[0] not in taken:
                        taken.add(entry[0])
                        entries.append(entry)
        return entries

    def _merge_sources(self, value: Node) -> list[MappingNode]:
        """The mappings a merge key's value names, in order."""
        if isinstance(value, MappingNode):
            self._check_collection_tag(value, _MAP, "a mapping")
            return [value]
        candidates: list[Node] = [value]
        if isinstance(value, SequenceNode):
            self._check_collection_tag(value, _SEQ, "a list")
            candidates = value.value
        sources: list[MappingNode] = []
        for candidate in candidates:
            if isinstance(candidate, _Placeholder):
                continue
            if isinstance(candidate, MappingNode):
                self._check_collection_tag(candidate, _MAP, "a mapping")
                sources.append(candidate)
            else:
                self._error(
                    candidate,
                    f"the merge key '<<' takes a mapping or a list of mappings; found {_describe(candidate)}",
                    "write '<<: *name' or '<<: [*name1, *name2]' with anchored mappings",
                )
        return sources


# --- errors from PyYAML ---


def _syntax_error(path: str, err: MarkedYAMLError) -> SpecError:
    mark = err.problem_mark or err.context_mark
    location = _mark_location(path, mark) if mark is not None else Location(path)
    message = err.problem or err.context or "invalid YAML"
    context_mark = err.context_mark
    if (
        err.problem
        and err.context
        and context_mark is not None
        and mark is not None
        and (context_mark.line, context_mark.column) != (mark.line, mark.column)
    ):
        message += f" ({err.context} at line {context_mark.line + 1}, column {context_mark.column + 1})"
    hint = None
    if "'\\t'" in message:
        hint = "YAML does not allow tabs for indentation; indent with spaces"
    return SpecError(location, message, hint)


def _reader_error(path: str, text: str, err: ReaderError) -> SpecError:
    character = err.character
    code = character if isinstance(character, int) else ord(character[:1] or "\0")
    line, col = _line_col(text, err.position)
    return SpecError(
        Location(path, line, col),
        f"unacceptable character #x{code:04x}: {err.reason}",
        "remove the control character",
    )


def _decode_error(path: str, data: bytes, err: UnicodeDecodeError) -> SpecError:
    line = data.count(b"\n", 0, err.start) + 1
    line_start = data.rfind(b"\n", 0, err.start) + 1
    col = len(data[line_start : err.start].decode("utf-8", errors="replace")) + 1
    return SpecError(
        Location(path, line, col),
        f"the file is not valid UTF-8 (byte 0x{data[err.start]:02x}: {err.reason})",
        "save the spec as UTF-8",
    )


# --- public API ---


def load_yaml_text(text: str, path: str) -> tuple[Any, SourceMap]:
    """Load one YAML document from ``text`` as plain data, with its source map.

    ``path`` only names the text in locations. The data is made of ``dict`` (keys are ``str``, the key's
    text as written, in the order written), ``list``, ``str``, ``int``, ``float``, ``bool`` and ``None``;
    subtrees shared through aliases are independent copies. An empty document gives ``None``.

    Raises :class:`~tutgen.errors.SpecErrors` listing every problem found (never a PyYAML exception).
    """
    path = str(path)
    if text.startswith("\ufeff"):
        text = text[1:]
    if len(text) > MAX_FILE_BYTES or len(text.encode("utf-8", "surrogatepass")) > MAX_FILE_BYTES:
        raise SpecErrors([_too_big(path)])
    try:
        composer = _Composer(text, path)
    except ReaderError as err:
        raise SpecErrors([_reader_error(path, text, err)]) from None
    try:
        root = composer.get_single_node()
    except _Refused as refused:
        raise SpecErrors([*composer.errors, refused.error]) from None
    except MarkedYAMLError as err:
        raise SpecErrors([*composer.errors, _syntax_error(path, err)]) from None
    except ReaderError as err:
        raise SpecErrors([*composer.errors, _reader_error(path, text, err)]) from None
    except yaml.YAMLError as err:  # PyYAML has no other kind today; never let one escape
        raise SpecErrors([*composer.errors, SpecError(Location(path), str(err))]) from None
    if root is None:  # no document at all
        return None, SourceMap(path)
    builder = _Builder(text, path, composer.alias_marks)
    data = builder.build(root, (), root.start_mark)
    errors = composer.errors + builder.errors
    if errors:
        raise SpecErrors(errors)
    if data is None:  # "---" alone, or "~": nothing to locate either
        return None, SourceMap(path)
    return data, SourceMap(path, MappingProxyType(builder.entries), text)


def load_yaml_file(path: str | Path) -> tuple[Any, SourceMap]:
    """Load the YAML spec file at ``path``; see :func:`load_yaml_text`.

    The file must be UTF-8 (a byte-order mark is fine) and at most ``MAX_FILE_BYTES`` long; the size is
    checked before the file is read in full. Locations name the file as ``str(path)``; the path ``-``
    (:data:`tutgen.spec.stdin.STDIN`) is standard input, read once (:func:`tutgen.spec.stdin.read_stdin`)
    and located as ``<stdin>``.

    Raises :class:`~tutgen.errors.SpecErrors`, also when the file cannot be read.
    """
    if str(path) == STDIN:
        return _load_bytes(read_stdin(MAX_FILE_BYTES + 1), STDIN_NAME)
    name = str(path)
    try:
        with open(path, "rb") as handle:
            if os.fstat(handle.fileno()).st_size > MAX_FILE_BYTES:
                raise SpecErrors([_too_big(name)])
            data = handle.read(MAX_FILE_BYTES + 1)
    except OSError as err:
        reason = err.strerror or str(err)
        raise SpecErrors([SpecError(Location(name), f"cannot read file: {reason}")]) from None
    return _load_bytes(data, name)


def _load_bytes(data: bytes, name: str) -> tuple[Any, SourceMap]:
    if len(data) > MAX_FILE_BYTES:
        raise SpecErrors([_too_big(name)])
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8) :]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise SpecErrors([_decode_error(name, data, err)]) from None
    return load_yaml_text(text, name)
