"""Text from a user (a student's name, a roster field, a spec's title) made safe for where it is written.

Each function takes any string and returns one that the target cannot misread:

- :func:`terminal_text` for a terminal: no escape sequences (ANSI CSI/OSC/…), no control characters
  other than newline and tab, so a name cannot move the cursor, recolour the screen or set a title;
- :func:`xml_text` for XML 1.0 (JUnit reports): only the characters XML 1.0 allows;
- :func:`csv_cell` for a CSV cell a spreadsheet opens: a cell that begins with ``= + - @``, a tab or a
  carriage return is read as a formula by Excel, LibreOffice and Google Sheets ("CSV injection"), so it
  is prefixed with an apostrophe, as OWASP recommends; control characters are removed as for a terminal.

Escaping of markup (``&``, ``<``, LaTeX specials) is the writer's job (``xml.etree``, ``latex_escape``);
these functions only remove what no escaping can make harmless.

Examples
--------
>>> terminal_text("Ada\\x1b[2J\\x1b]0;pwned\\x07 Lovelace")
'Ada Lovelace'
>>> csv_cell("=HYPERLINK(\\"http://x\\")")
'\\'=HYPERLINK("http://x")'
>>> csv_cell("-3.5")
'-3.5'
>>> xml_text("a\\x00b\\x0bc")
'abc'
"""

from __future__ import annotations

import re

__all__ = ["csv_cell", "terminal_text", "xml_text"]

# ECMA-48 escape sequences: CSI (ESC [ … final byte), OSC/DCS/SOS/PM/APC strings (ESC ] … BEL or ST),
# and two-character escapes (ESC + one byte); also their 8-bit C1 forms (U+009B CSI, U+009D OSC, …).
_ESCAPE_SEQUENCE = re.compile(
    r"(?:\x1b\[|\x9b)[0-?]*[ -/]*[@-~]"  # CSI … final
    r"|(?:\x1b[\]PX^_]|[\x90\x98\x9d\x9e\x9f]).*?(?:\x07|\x1b\\|\x9c|$)"  # OSC, DCS, SOS, PM, APC strings
    r"|\x1b[ -~]?",  # any other escape, or a lone ESC at the end
    re.DOTALL,
)
# C0 controls except tab and newline, DEL, C1 controls; also the bidirectional overrides, which can
# make a name read backwards on screen (the "Trojan source" characters)
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")
# what XML 1.0 forbids: C0 controls except tab, newline, carriage return; surrogates; U+FFFE, U+FFFF
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")
# the first characters that make a spreadsheet evaluate a cell
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


def terminal_text(text: str) -> str:
    """`text` without escape sequences and without control characters other than newline and tab."""
    return _CONTROL.sub("", _ESCAPE_SEQUENCE.sub("", text))


def xml_text(text: str) -> str:
    """`text` with every character that XML 1.0 does not allow removed (markup is escaped by the writer)."""
    return _NOT_XML.sub("", text)


def csv_cell(text: str) -> str:
    """`text` for a CSV cell: control characters removed, and a leading apostrophe where a spreadsheet
    would otherwise read the cell as a formula. A plain number (``-3.5``, ``+1e3``) is left as it is, so
    marks and values stay numbers."""
    clean = _CONTROL.sub("", _ESCAPE_SEQUENCE.sub("", text.replace("\t", " ")))
    # as written (a tab or a carriage return first), and once cleaned (a control character or an escape
    # sequence, which the cleaning removes, before the "=")
    if (text.startswith(_FORMULA_START) or clean.startswith(_FORMULA_START)) and not _NUMBER.fullmatch(clean):
        return "'" + clean
    return clean
