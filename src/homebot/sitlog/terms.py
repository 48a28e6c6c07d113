"""SitLog's terms: atoms, numbers, texts, variables, structures and lists; parse, print, unify.

A small hand-written tokenizer and operator-precedence parser rather than a Prolog:
SitLog's functional language needs only terms, a dozen operators and unification
with undo, and every parse error must name its column. Atoms are Python ``str``,
numbers ``int``/``float``, lists ``tuple``, spoken texts ``Text``; ``Var`` is a
logic variable bound in place (``bind`` records it on a ``Trail`` for undo).
"""

from __future__ import annotations

import re
import sys
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from homebot.errors import DialogueError

__all__ = [
    "EMPTY",
    "MAX_TERM_DEPTH",
    "Struct",
    "Term",
    "Text",
    "Trail",
    "Var",
    "copy_term",
    "deref",
    "format_term",
    "is_ground",
    "parse_clauses",
    "parse_term",
    "place_in",
    "resolve",
    "unify",
    "variables_of",
]

#: The atom SitLog uses for "nothing here" (an empty expectation or action).
EMPTY = "empty"

#: The deepest nesting of a term (structures, lists, operators) a file may write. A real
#: dialogue model nests a few levels; the bound keeps the recursive printing, unifying
#: and checking of terms far from Python's stack limit, whatever a file holds.
MAX_TERM_DEPTH = 100


@dataclass(frozen=True, slots=True)
class Text:
    """A spoken or shown text (``"..."`` in the source); printed without quotes."""

    text: str

    def __str__(self) -> str:
        return self.text


@dataclass(frozen=True, slots=True)
class Struct:
    """A compound term ``functor(args...)``; operators (``a:b``, ``x==y``) are structs too."""

    functor: str
    args: tuple[Term, ...]

    @property
    def arity(self) -> int:
        return len(self.args)

    def __str__(self) -> str:
        return format_term(self)


class Var:
    """A logic variable; ``ref`` is what it is bound to (None while unbound)."""

    __slots__ = ("name", "ref")

    def __init__(self, name: str = "_") -> None:
        self.name = name
        self.ref: Term | None = None

    def __repr__(self) -> str:
        return f"Var({self.name}@{id(self):x})"


Term = str | int | float | Text | Struct | Var | tuple["Term", ...]  # tuple: a list of terms


@dataclass
class Trail:
    """Variables bound since a mark, so a failed match can be undone."""

    bound: list[Var] = field(default_factory=list)

    def mark(self) -> int:
        return len(self.bound)

    def undo(self, mark: int) -> None:
        while len(self.bound) > mark:
            self.bound.pop().ref = None


def deref(term: Term) -> Term:
    """Follow variable bindings to a non-variable or an unbound variable."""
    while isinstance(term, Var) and term.ref is not None:
        term = term.ref
    return term


def resolve(term: Term) -> Term:
    """The term with every bound variable replaced by its value (unbound ones stay)."""
    term = deref(term)
    if isinstance(term, Struct):
        return Struct(term.functor, tuple(resolve(arg) for arg in term.args))
    if isinstance(term, tuple):
        return tuple(resolve(item) for item in term)
    return term


def unify(left: Term, right: Term, trail: Trail) -> bool:
    """Unify two terms, binding variables (recorded on ``trail``); False if they clash."""
    left, right = deref(left), deref(right)
    if left is right:
        return True
    if isinstance(left, Var):
        left.ref = right
        trail.bound.append(left)
        return True
    if isinstance(right, Var):
        right.ref = left
        trail.bound.append(right)
        return True
    if isinstance(left, Struct) and isinstance(right, Struct):
        return (left.functor == right.functor and left.arity == right.arity and all(
            unify(a, b, trail) for a, b in zip(left.args, right.args, strict=True)))
    if isinstance(left, tuple) and isinstance(right, tuple):
        return len(left) == len(right) and all(
            unify(a, b, trail) for a, b in zip(left, right, strict=True))
    if type(left) is not type(right) and not (
            isinstance(left, int | float) and isinstance(right, int | float)):
        return False
    return bool(left == right)


def copy_term(term: Term, mapping: dict[Var, Var] | None = None) -> Term:
    """A copy with fresh variables (the same variable maps to the same fresh one)."""
    mapping = {} if mapping is None else mapping
    term = deref(term)
    if isinstance(term, Var):
        if term not in mapping:
            mapping[term] = Var(term.name)
        return mapping[term]
    if isinstance(term, Struct):
        return Struct(term.functor, tuple(copy_term(arg, mapping) for arg in term.args))
    if isinstance(term, tuple):
        return tuple(copy_term(item, mapping) for item in term)
    return term


def variables_of(term: Term) -> Iterator[Var]:
    """The unbound variables of a term, left to right (repeats included)."""
    term = deref(term)
    if isinstance(term, Var):
        yield term
    elif isinstance(term, Struct):
        for arg in term.args:
            yield from variables_of(arg)
    elif isinstance(term, tuple):
        for item in term:
            yield from variables_of(item)


def is_ground(term: Term) -> bool:
    """Whether the term has no unbound variable."""
    return next(variables_of(term), None) is None


# ---------------------------------------------------------------------------- printing

_PLAIN_ATOM = re.compile(r"[^\W\d_]\w*\Z")  # "josé", "søren"; "José" is a Variable
_SYMBOL_ATOM = re.compile(r"[-+*/\\^<>=~:.?@#&$]+\Z")


def _format_atom(atom: str) -> str:
    if (_PLAIN_ATOM.match(atom) and not atom[0].isupper()) or _SYMBOL_ATOM.match(atom) or (
            atom in ("[]", "!", ";")):
        return atom
    return "'" + atom.replace("\\", "\\\\").replace("'", "\\'") + "'"


def format_term(term: Term, *, operand: bool = False) -> str:
    """Print a term as SitLog's history does: quoted atoms, bare texts, no spaces."""
    term = deref(term)
    if isinstance(term, Var):
        return "_" if term.name.startswith("_") else term.name
    if isinstance(term, Text):
        return term.text
    if isinstance(term, str):
        return _format_atom(term)
    if isinstance(term, bool):
        return "true" if term else "false"
    if isinstance(term, int | float):
        return repr(term)
    if isinstance(term, tuple):
        return "[" + ",".join(format_term(item) for item in term) + "]"
    if term.arity == 2 and term.functor in _INFIX:
        text = (format_term(term.args[0], operand=True) + term.functor
                + format_term(term.args[1], operand=True))
        return f"({text})" if operand else text
    if term.arity == 1 and term.functor == "-" and isinstance(deref(term.args[0]), int | float):
        return f"-({format_term(term.args[0])})"
    return _format_atom(term.functor) + "(" + ",".join(format_term(a) for a in term.args) + ")"


# ---------------------------------------------------------------------------- parsing

# Infix operators: priority and type, as in SWI-Prolog and SitLog's operator table.
_INFIX: Mapping[str, tuple[int, str]] = MappingProxyType({
    "=>": (800, "xfx"), "==>": (800, "xfx"), "=>>": (850, "xfx"),
    "=": (700, "xfx"), "==": (700, "xfx"), "\\==": (700, "xfx"), "\\=": (700, "xfx"),
    "<": (700, "xfx"), ">": (700, "xfx"), "=<": (700, "xfx"), ">=": (700, "xfx"),
    "=:=": (700, "xfx"), "=\\=": (700, "xfx"), "is": (700, "xfx"),
    "+": (500, "yfx"), "-": (500, "yfx"), "*": (400, "yfx"), "/": (400, "yfx"),
    "mod": (400, "yfx"), ":": (200, "xfy"),
})
_TOKEN = re.compile(
    r"""(?P<space>\s+|%[^\n]*)
      | (?P<number>\d+(?:\.\d+)?(?:[eE][+-]?\d+)?)
      | (?P<quoted>'(?:[^'\\]|\\.|'')*')
      | (?P<text>"(?:[^"\\]|\\.)*")
      | (?P<word>[^\W\d]\w*)
      | (?P<symbol>[-+*/\\^<>=~:.?@#&$]+)
      | (?P<punct>[()\[\],|])
    """,
    re.VERBOSE,
)


@dataclass(frozen=True, slots=True)
class _Token:
    kind: str
    text: str
    column: int  # 0-based offset in the source text


def _tokens(source: str, where: str, offset: int) -> list[_Token]:
    result = []
    position = 0
    while position < len(source):
        match = _TOKEN.match(source, position)
        if match is None:
            raise DialogueError(f"{where}, column {offset + position + 1}: unexpected character "
                                f"{source[position]!r}; write atoms, Variables, 'quoted atoms',"
                                " \"texts\", numbers, f(args) or [lists]")
        kind = match.lastgroup or ""
        if kind == "word":  # letters of any script: a capital or "_" first makes a Variable
            text = match.group()
            kind = "var" if text[0] == "_" or text[0].isupper() else "name"
        if kind != "space":
            result.append(_Token(kind, match.group(), position))
        position = match.end()
    result.append(_Token("end", "", len(source)))
    return result


class _Parser:
    def __init__(self, source: str, where: str, column_offset: int,
                 positions: dict[int, int] | None = None) -> None:
        self.source = source
        self.where = where
        self.offset = column_offset
        self.tokens = _tokens(source, where, column_offset)
        self.index = 0
        self.variables: dict[str, Var] = {}
        self.positions = positions  #: id of each structure and list -> its offset
        self.depth = 0  #: how deeply the term being read nests here

    def error(self, token: _Token, expected: str) -> DialogueError:
        found = f"'{token.text}'" if token.text else "the end"
        if "\n" in self.source:
            return DialogueError(f"{self.place(token)}: expected {expected}, found {found}")
        return DialogueError(f"{self.place(token)}: expected {expected}, found {found} in "
                             f"{_quoted(self.source)}")

    def place(self, token: _Token) -> str:
        if "\n" in self.source:
            return f"{self.where}, {place_in(self.source, token.column)}"
        return f"{self.where}, column {self.offset + token.column + 1}"

    def note(self, term: Term, offset: int) -> Term:
        if self.positions is not None:
            self.positions[id(term)] = offset
        return term

    def peek(self) -> _Token:
        return self.tokens[self.index]

    def take(self) -> _Token:
        token = self.tokens[self.index]
        self.index += 1
        return token

    def expect(self, text: str) -> None:
        token = self.take()
        if token.text != text:
            raise self.error(token, f"'{text}'")

    def parse(self, max_priority: int = 1200) -> Term:
        self.depth += 1
        try:
            return self._operators(max_priority)
        finally:
            self.depth -= 1

    def _deeper(self, token: _Token, levels: int = 0) -> None:
        """Refuse a term nested past ``MAX_TERM_DEPTH`` (``levels`` more than here)."""
        if self.depth + levels > MAX_TERM_DEPTH:
            raise DialogueError(f"{self.place(token)}: the term nests deeper than "
                                f"{MAX_TERM_DEPTH} levels; flatten it (a list instead of "
                                "nested structures, or several situations)")

    def _operators(self, max_priority: int) -> Term:
        self._deeper(self.peek())
        start = self.peek().column
        left = self.primary()
        left_priority = 0
        chained = 0  # a left-associative chain (a-b-c) nests one level per operator
        while True:
            token = self.peek()
            operator = _INFIX.get(token.text) if token.kind in ("symbol", "name") else None
            if operator is None:
                return left
            priority, kind = operator
            left_max = priority if kind == "yfx" else priority - 1
            right_max = priority if kind == "xfy" else priority - 1
            if priority > max_priority or left_priority > left_max:
                return left
            chained += 1
            self._deeper(token, chained)
            self.take()
            right = self.parse(right_max)
            left = self.note(Struct(token.text, (left, right)), start)
            left_priority = priority

    def primary(self) -> Term:
        token = self.take()
        if token.kind == "number":
            if any(c in token.text for c in ".eE"):
                return float(token.text)
            if len(token.text) > sys.get_int_max_str_digits():
                raise DialogueError(f"{self.place(token)}: a number of {len(token.text)} "
                                    "digits, too long to read; write a smaller number")
            return int(token.text)
        if token.kind == "var":
            if token.text == "_":
                return Var("_")
            return self.variables.setdefault(token.text, Var(token.text))
        if token.kind == "text":
            return Text(_unescape(token.text[1:-1]))
        if token.kind in ("name", "quoted", "symbol"):
            name = _unescape(token.text[1:-1]) if token.kind == "quoted" else token.text
            if token.kind == "symbol" and token.text == "-" and self.peek().kind == "number":
                number = self.primary()
                assert isinstance(number, int | float)
                return -number
            if self.peek().text == "(" and self.peek().column == token.column + len(token.text):
                self.take()
                return self.note(Struct(name, self.arguments(")")), token.column)
            return name
        if token.text == "(":
            inner = self.parse()
            self.expect(")")
            return inner
        if token.text == "[":
            if self.peek().text == "]":
                self.take()
                return ()
            return self.note(tuple(self.arguments("]")), token.column)
        raise self.error(token, "a term")

    def arguments(self, closing: str) -> tuple[Term, ...]:
        items = [self.parse(999)]
        while self.peek().text == ",":
            self.take()
            items.append(self.parse(999))
        token = self.take()
        if token.text != closing:
            raise self.error(token, f"',' or '{closing}'")
        return tuple(items)


def _quoted(source: str, most: int = 200) -> str:
    """A term's source quoted in a message, cut in the middle when long."""
    if len(source) <= most:
        return repr(source)
    return f"{source[:most // 2]!r}...{source[-most // 2:]!r}"


def _unescape(text: str) -> str:
    return re.sub(r"\\(.)|''", lambda m: m.group(1) if m.group(1) else "'", text)


def place_in(source: str, offset: int) -> str:
    """``line L, column C`` of an offset in a text."""
    line = source.count("\n", 0, offset) + 1
    column = offset - (source.rfind("\n", 0, offset) + 1) + 1
    return f"line {line}, column {column}"


def parse_clauses(source: str, where: str,
                  positions: dict[int, int] | None = None) -> list[tuple[Term, int]]:
    """Every ``term.`` of a text in Prolog's notation, with the offset where it starts.

    Each clause has its own variables; ``positions`` (if given) receives the offset of
    every structure and list by ``id``.
    """
    parser = _Parser(source, where, 0, positions)
    clauses = []
    while parser.peek().kind != "end":
        start = parser.peek().column
        parser.variables = {}
        term = parser.parse()
        end = parser.take()
        if end.text != ".":
            raise parser.error(end, "'.' at the end of the clause")
        clauses.append((term, start))
    return clauses


def parse_term(source: str, where: str = "<term>",
               variables: dict[str, Var] | None = None, column_offset: int = 0) -> Term:
    """Parse one term. Variables with the same name share one ``Var`` (and ``variables``).

    Raises ``DialogueError`` naming ``where`` and the column of the problem.
    """
    parser = _Parser(source, where, column_offset)
    if variables is not None:
        parser.variables = variables
    term = parser.parse()
    end = parser.peek()
    if end.kind != "end":
        raise parser.error(end, "an operator or the end of the term")
    return term
