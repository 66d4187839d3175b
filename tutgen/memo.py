"""Results remembered by the identity of the object they were computed from.

The model and the derivation are frozen dataclasses: their ``==`` and ``hash`` walk every field, which
costs a walk of the whole system, and two equal systems are not always the same problem to a caller (a
sheet's question title). What a caller means is "this object again": a drawing for this system, the
free bodies of this derivation. :class:`ByIdentity` keeps the last few, each with its key object
itself, so that an ``id`` is never reused while its entry lives.
"""

from __future__ import annotations

from typing import Generic, TypeVar

__all__ = ["ByIdentity"]

K = TypeVar("K")
V = TypeVar("V")


class ByIdentity(Generic[K, V]):
    """The values of the last ``size`` keys, looked up by the key's identity; the oldest goes first.

    >>> seen: ByIdentity[list[int], int] = ByIdentity(2)
    >>> a, b = [1], [1]
    >>> seen.put(a, 10), seen.get(a), seen.get(b)
    (10, 10, None)
    """

    def __init__(self, size: int) -> None:
        self.size = size
        self._items: dict[int, tuple[K, V]] = {}

    def get(self, key: K) -> V | None:
        hit = self._items.get(id(key))
        return hit[1] if hit is not None and hit[0] is key else None

    def put(self, key: K, value: V) -> V:
        """Remember ``value`` for ``key`` (forgetting the oldest entries past ``size``); returns ``value``."""
        self._items.pop(id(key), None)
        while len(self._items) >= self.size:
            self._items.pop(next(iter(self._items)))
        self._items[id(key)] = (key, value)
        return value
