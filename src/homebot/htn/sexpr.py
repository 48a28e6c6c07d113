"""An S-expression reader that remembers where every form starts (line and column).

Symbols are kept as written (case-sensitive), or in lower case with ``fold_case``
(JSHOP2 is case-insensitive); numbers become ``int`` or ``float``; ``"strings"``
become ``Text``; ``;`` starts a comment to the end of the line. ``#'name`` (Lisp's
function quote) reads as the symbol ``#'name``. Lists nest at most ``MAX_NESTING``
deep: the reader itself is iterative, but the domain builders walk forms recursively.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from homebot.errors import PlanningError

__all__ = ["MAX_NESTING", "Form", "Text", "plain", "read_forms"]

#: The deepest nesting of parentheses a file may write. JSHOP2's example domains nest
#: about ten deep; this keeps the recursive builders far from Python's stack limit.
MAX_NESTING = 100

_TOKEN = re.compile(r"""\s+|;[^\n]*|(?P<open>\()|(?P<close>\))|(?P<string>"(?:[^"\\]|\\.)*")"""
                    r"""|(?P<bad>["'`,])|(?P<atom>[^\s()";]+)""")


class Text(str):
    """A string literal (in double quotes), told apart from a symbol."""

    __slots__ = ()


@dataclass(frozen=True, slots=True)
class Form:
    """A parenthesised list with the line and column (from 1) of its ``(``."""

    items: tuple[Any, ...]
    line: int
    column: int

    def where(self, source: str) -> str:
        return f"{source}:{self.line}:{self.column}"


def _location(text: str, offset: int) -> tuple[int, int]:
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return line, column


class _Lines:
    """Line and column of offsets met in increasing order, in one pass over the text
    (counting from the start for every form would make a large file quadratic)."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.scanned = 0
        self.line = 1
        self.line_start = 0

    def at(self, offset: int) -> tuple[int, int]:
        newlines = self.text.count("\n", self.scanned, offset)
        if newlines:
            self.line += newlines
            self.line_start = self.text.rfind("\n", self.scanned, offset) + 1
        self.scanned = offset
        return self.line, offset - self.line_start + 1


def _atom(token: str) -> Any:
    try:
        return int(token)
    except ValueError:
        pass
    try:
        if token not in {"+", "-", "."} and any(ch.isdigit() for ch in token):
            return float(token)
    except ValueError:
        pass
    return token


def read_forms(text: str, source: str = "<text>", fold_case: bool = False) -> list[Any]:
    """Every top-level form of ``text``; malformed text raises ``PlanningError`` with its place.

    With ``fold_case`` every symbol is read in lower case (strings stay as written).
    """
    stack: list[tuple[list[Any], tuple[int, int]]] = []
    top: list[Any] = []
    lines = _Lines(text)
    position = 0
    for match in _TOKEN.finditer(text):
        if match.start() != position:  # pragma: no cover - the pattern matches every character
            break
        position = match.end()
        kind = match.lastgroup
        if kind is None:
            continue
        if kind == "open":
            if len(stack) >= MAX_NESTING:
                line, column = _location(text, match.start())
                raise PlanningError(f"{source}:{line}:{column}: parentheses nest deeper than "
                                    f"{MAX_NESTING} levels; flatten the expression")
            stack.append(([], lines.at(match.start())))
        elif kind == "close":
            if not stack:
                line, column = _location(text, match.start())
                raise PlanningError(f"{source}:{line}:{column}: ')' without a matching '('; "
                                    "remove it or add the '(' it closes")
            items, (line, column) = stack.pop()
            form = Form(tuple(items), line, column)
            (stack[-1][0] if stack else top).append(form)
        elif kind == "bad":
            line, column = _location(text, match.start())
            character = match.group()
            hint = ("close the string with '\"'" if character == '"'
                    else f"'{character}' (Lisp quoting) is not supported; write the name plainly")
            raise PlanningError(f"{source}:{line}:{column}: unexpected '{character}'; {hint}")
        else:
            token = match.group()
            value = Text(token[1:-1]) if kind == "string" else _atom(
                token.lower() if fold_case else token)
            (stack[-1][0] if stack else top).append(value)
    if stack:
        line, column = stack[-1][1]
        raise PlanningError(f"{source}:{line}:{column}: this '(' is never closed; add the "
                            "missing ')'")
    return top


def plain(value: Any) -> Any:
    """A form as plain nested lists (what the domain builders take)."""
    if isinstance(value, Form):
        return [plain(item) for item in value.items]
    return value
