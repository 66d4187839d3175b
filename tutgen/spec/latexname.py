"""A spec's ``latex:`` display name is a name, not raw TeX: a small whitelist, checked before anything prints it.

The worked solution puts a parameter's or coordinate's ``latex:`` into every formula (LaTeX, PDF and the
Markdown's maths), so it cannot be escaped there. Instead it must be made of

- letters, digits, spaces, ``'`` (a prime) and ``,``;
- ``_`` and ``^``, each followed by its argument (a letter, a digit, a command or a ``{…}`` group) and
  at most one of each per symbol (TeX stops at "Double subscript");
- braces ``{ }``, balanced;
- ``\\_`` (an underscore shown as one), the commands of :data:`SYMBOL_COMMANDS` (Greek letters,
  ``\\ell``, ``\\prime``, ...) and of
  :data:`ARGUMENT_COMMANDS` (accents and alphabets, each followed by its argument: ``\\dot{x}``,
  ``\\mathrm{max}``).

Anything else (``\\def``, ``\\input``, ``\\catcode``, ``\\csname``, ``\\\\``, ``$``, ``#``, ``%``, ``&``,
``~``, ``<img onerror=…>``) is refused with the offset of the first character that is not allowed, so
that validation reports it at its ``file:line:col``. What passes here is valid maths-mode LaTeX for
pdflatex with amsmath, and for KaTeX and MathJax alike.

Examples
--------
>>> check_latex_name(r"\\dot{\\theta}_{m,1}'")
>>> try:
...     check_latex_name(r"m_1\\def\\x{y}")
... except LatexNameError as err:
...     print(err.offset, err)
3 '\\def' is not allowed in a display name
"""

from __future__ import annotations

from tutgen.errors import SpecError
from tutgen.spec.loader import KeyPath, SourceMap
from tutgen.spec.names import GREEK, default_latex

__all__ = [
    "ARGUMENT_COMMANDS",
    "MAX_LENGTH",
    "SYMBOL_COMMANDS",
    "LatexNameError",
    "allowed_summary",
    "check_latex_name",
    "display_name",
]

#: Longest display name accepted, in characters.
MAX_LENGTH = 100
#: Commands that stand for one symbol.
SYMBOL_COMMANDS = frozenset(
    {value[1:] for value in GREEK.values() if value.startswith("\\")} | {"ell", "prime", "partial", "hbar", "ast"}
)
#: Commands that take one argument: accents and alphabets.
ARGUMENT_COMMANDS = frozenset(
    {
        "dot", "ddot", "hat", "bar", "tilde", "vec", "check", "breve", "acute", "grave",
        "widehat", "widetilde", "overline", "underline",
        "mathrm", "mathbf", "mathit", "mathsf", "mathcal", "boldsymbol",
    }
)  # fmt: skip
_PLAIN = frozenset(" ',")


class LatexNameError(ValueError):
    """A display name that is not allowed: the message, the 0-based offset of the culprit, a hint."""

    def __init__(self, message: str, offset: int, hint: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.offset = offset
        self.hint = hint if hint is not None else allowed_summary()

    def __str__(self) -> str:
        return self.message


def allowed_summary() -> str:
    """What a display name may be made of, for a hint."""
    accents = ", ".join(f"\\{c}" for c in sorted(ARGUMENT_COMMANDS))
    return (
        "a latex: name may use letters, digits, spaces, _ ^ { } ' , and the commands: the Greek letters "
        f"(\\alpha ... \\omega, \\Gamma ... \\Omega, \\varphi ...), \\ell, \\prime, \\partial, \\hbar, \\ast, \\_, "
        f"and with an argument {accents}"
    )


def _shown(char: str) -> str:
    """A character for a message: printable as itself, anything else by its code point."""
    return f"'{char}'" if char.isprintable() and not char.isspace() else f"the character U+{ord(char):04X}"


class _Checker:
    """One pass over a display name: a tiny TeX reader of groups, symbols and their scripts."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0
        # the '{' not closed yet: its offset, and whether it holds a script's argument (closing it
        # ends the script) rather than a symbol of its own (closing it ends a symbol)
        self.opened: list[tuple[int, bool]] = []
        # per open group (the outermost is the name itself): whether the current symbol already has
        # a subscript / a superscript, and whether a symbol has been seen since the last script
        self.scripts: list[set[str]] = [set()]

    def _peek_argument(self, after: str, where: int) -> None:
        """The next non-space character must start an argument (of a script or a command)."""
        i = self.pos
        while i < len(self.text) and self.text[i] == " ":
            i += 1
        if i >= len(self.text):
            raise LatexNameError(f"'{after}' at the end of the display name has no argument", where,
                                 f"write its argument after it, e.g. '{after}{{1}}'")  # fmt: skip
        char = self.text[i]
        if not (char.isascii() and char.isalnum()) and char not in "{\\":
            raise LatexNameError(f"'{after}' must be followed by its argument (a letter, a digit or {{...}}), "
                                 f"found {_shown(char)}", i, f"e.g. '{after}{{1}}'")  # fmt: skip

    def check(self) -> None:
        text = self.text
        if not text.strip():
            raise LatexNameError("the display name is empty", 0, "omit latex: to typeset the name by tutgen's rule")
        if len(text) > MAX_LENGTH:
            raise LatexNameError(
                f"the display name is too long ({len(text)} characters; the limit is {MAX_LENGTH})", MAX_LENGTH
            )
        while self.pos < len(text):
            start = self.pos
            char = text[start]
            self.pos += 1
            if char == "\\":
                self._command(start)
            elif char.isascii() and char.isalnum():
                self.scripts[-1] = set()  # a new symbol
            elif char == "'":
                if "^" in self.scripts[-1]:
                    raise LatexNameError("a prime after a superscript is a double superscript", start,
                                         "put the prime first: x'^2")  # fmt: skip
                self.scripts[-1].add("'")
            elif char in _PLAIN:
                continue
            elif char in "_^":
                if char in self.scripts[-1]:
                    kind = "subscript" if char == "_" else "superscript"
                    raise LatexNameError(f"double {kind}: this symbol already has one", start,
                                         "put both in one group, e.g. 'I_{xx,1}'")  # fmt: skip
                self.scripts[-1].add(char)
                self._peek_argument(char, start)
                self._argument()
            elif char == "{":
                self.opened.append((start, False))
                self.scripts.append(set())
            elif char == "}":
                if not self.opened:
                    raise LatexNameError("unmatched '}': there is no '{' before it", start)
                _, is_argument = self.opened.pop()
                self.scripts.pop()
                if not is_argument:
                    self.scripts[-1] = set()  # the group is one symbol
            else:
                raise LatexNameError(f"{_shown(char)} is not allowed in a display name", start)
        if self.opened:
            raise LatexNameError("unclosed '{': expected '}', found the end of the display name", self.opened[-1][0])

    def _argument(self) -> None:
        """Consume a script's argument when it is one character (a group or a command is read as usual)."""
        while self.text[self.pos] == " ":
            self.pos += 1
        char = self.text[self.pos]
        if char.isascii() and char.isalnum():
            self.pos += 1
        elif char == "\\":
            start = self.pos
            self.pos += 1
            self._command(start, in_script=True)
        elif char == "{":
            self.opened.append((self.pos, True))
            self.scripts.append(set())
            self.pos += 1

    def _command(self, start: int, in_script: bool = False) -> None:
        text = self.text
        end = self.pos
        while end < len(text) and text[end].isascii() and text[end].isalpha():
            end += 1
        name = text[self.pos : end]
        if not name:
            if text.startswith("_", self.pos):  # \_, an underscore shown as one (tutgen's rule prints a__b so)
                self.pos += 1
                if not in_script:
                    self.scripts[-1] = set()
                return
            shown = "\\" + text[self.pos] if self.pos < len(text) else "\\"
            raise LatexNameError(f"'{shown}' is not allowed in a display name", start)
        self.pos = end
        if name in SYMBOL_COMMANDS:
            if not in_script:
                self.scripts[-1] = set()
            return
        if name in ARGUMENT_COMMANDS:
            if not in_script:
                self.scripts[-1] = set()
            self._peek_argument("\\" + name, start)
            return
        raise LatexNameError(f"'\\{name}' is not allowed in a display name", start)


def check_latex_name(text: str) -> None:
    """Raise :class:`LatexNameError` unless ``text`` is an allowed display name (see the module docstring)."""
    _Checker(text).check()


def display_name(name: str, latex: str | None, smap: SourceMap, path: KeyPath) -> tuple[str, list[SpecError]]:
    """How a parameter or coordinate ``name`` is typeset: its ``latex:`` (at ``path``) if allowed, else
    :func:`tutgen.spec.names.default_latex`; with the error, at the culprit's ``file:line:col``, of a
    ``latex:`` that is not allowed."""
    if latex is None:
        return default_latex(name), []
    try:
        check_latex_name(latex)
    except LatexNameError as exc:
        message = f"the latex of '{name}' is not a display name: {exc.message}"
        return default_latex(name), [SpecError(smap.expr_location(path, exc.offset), message, exc.hint)]
    return latex, []
