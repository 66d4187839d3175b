"""Plain YAML scalars resolved by the YAML 1.2 core schema, as a spec reads them.

PyYAML resolves by YAML 1.1, where ``on``, ``yes`` and ``no`` are booleans and ``0777`` is octal; a spec
follows YAML 1.2's core schema instead, so a coordinate named ``on`` stays a string. The loader gives an
untagged plain scalar to :func:`core_value`.

Examples
--------
>>> core_value("yes"), core_value("true"), core_value("0x1F"), core_value("1.5e3"), core_value("~")
('yes', True, 31, 1500.0, None)
"""

from __future__ import annotations

import math
import re
from typing import Any

__all__ = ["core_value"]


_NULL_RE = re.compile(r"null|Null|NULL|~|")
_BOOLS: dict[str, bool] = {
    "true": True, "True": True, "TRUE": True,
    "false": False, "False": False, "FALSE": False,
}  # fmt: skip
_INT_DEC_RE = re.compile(r"[-+]?[0-9]+")
_INT_OCT_RE = re.compile(r"0o[0-7]+")
_INT_HEX_RE = re.compile(r"0x[0-9a-fA-F]+")
_FLOAT_RE = re.compile(r"[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?")
_INF_RE = re.compile(r"[-+]?\.(?:inf|Inf|INF)")
_NAN_RE = re.compile(r"\.(?:nan|NaN|NAN)")


def core_value(text: str) -> Any:
    """Resolve an untagged plain scalar by the YAML 1.2 core schema.

    Raises ``ValueError`` for a decimal integer longer than Python's int-to-str digit limit.
    """
    if _NULL_RE.fullmatch(text):
        return None
    if text in _BOOLS:
        return _BOOLS[text]
    if _INT_DEC_RE.fullmatch(text):
        return int(text, 10)
    if _INT_OCT_RE.fullmatch(text):
        return int(text[2:], 8)
    if _INT_HEX_RE.fullmatch(text):
        return int(text[2:], 16)
    if _FLOAT_RE.fullmatch(text):
        return float(text)
    if _INF_RE.fullmatch(text):
        return -math.inf if text.startswith("-") else math.inf
    if _NAN_RE.fullmatch(text):
        return math.nan
    return text
