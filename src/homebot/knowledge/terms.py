"""Tokens and statements of the paper's Prolog-like KB syntax, with line and column.

A small hand-written tokenizer and recursive-descent parser rather than a parser
library: the grammar is a handful of productions (atoms, numbers, lists, ``f(...)``,
the non-associative operators ``=>`` (800, xfx) and ``=>>`` (850, xfx) of SitLog's
KB service), every error must name the line, the column and what was expected, and
the 10 000-individual benchmark KB must load in well under half a second, which a
single ``re.findall`` pass over the text plus a parser over plain strings achieves
(positions are recovered only when an error is reported).
"""

from __future__ import annotations

import math
import re
import sys
import unicodedata
from typing import NamedTuple

from homebot.errors import KnowledgeError
from homebot.knowledge.model import ANY, Literal, Preference, Statement, Value

__all__ = [
    "Compound",
    "TermParser",
    "format_atom",
    "format_entry",
    "format_literal",
    "format_statement",
    "format_value",
    "parse_statement",
    "statement_from_term",
]

_TOKEN = re.compile(
    r"""%[^\n]*                       # line comment
      | /\*.*?\*/                     # block comment
      | '(?:[^'\\\n]|\\.|'')*'        # quoted atom
      | =>>|=>                        # the two operators
      | -?\d+(?:\.\d+)?(?:[eE][+-]?\d+)?   # number
      | [^\W\d]\w*                    # atom, or variable (capital or _ first; rejected)
      | [\[\](),.|-]                  # punctuation and the bare '-'
      | \S                            # anything else (rejected)
    """,
    re.VERBOSE | re.DOTALL,
)
# Letters of any script: an atom starts with a letter that is not a capital ("josé",
# "søren"), a variable with a capital or "_" ("José" must be quoted: 'José').
_PLAIN_ATOM = re.compile(r"[^\W\d_]\w*\Z")
_NUMBER_START = frozenset("-0123456789")
_END = ""  # sentinel token after the last one


class Compound(NamedTuple):
    """A parsed ``functor(args...)`` term; ``=>`` and ``=>>`` are compounds too."""

    functor: str
    args: tuple[object, ...]


Term = object  # str (atom) | int | float | list (Prolog list) | Compound


class TermParser:
    """Recursive descent over the token strings of one text."""

    __slots__ = ("index", "source", "text", "tokens")

    def __init__(self, text: str, source: str = "<text>") -> None:
        if not text.isascii():  # "josé" typed with a combining accent is one word too
            text = unicodedata.normalize("NFC", text)
        self.text = text
        self.source = source
        tokens = _TOKEN.findall(text)
        if "%" in text or "/*" in text:
            tokens = [t for t in tokens if not _is_comment(t)]
        tokens.append(_END)
        self.tokens: list[str] = tokens
        self.index = 0

    # -- errors ------------------------------------------------------------------

    def position(self, index: int) -> tuple[int, int]:
        """Line and column (both from 1) of token ``index``."""
        count = 0
        offset = len(self.text)
        for match in _TOKEN.finditer(self.text):
            if _is_comment(match.group()):
                continue
            if count == index:
                offset = match.start()
                break
            count += 1
        line = self.text.count("\n", 0, offset) + 1
        column = offset - (self.text.rfind("\n", 0, offset) + 1) + 1
        return line, column

    def error(
        self, expected: str, index: int | None = None, found: str | None = None
    ) -> KnowledgeError:
        """A ``KnowledgeError`` naming the place, what was expected and what was found."""
        at = self.index if index is None else index
        line, column = self.position(at)
        if found is None:
            found = describe_token(self.tokens[at])
        return KnowledgeError(
            f"{self.source}, line {line}, column {column}: expected {expected}, found {found}"
        )

    def expect(self, token: str, expected: str | None = None) -> None:
        """Consume ``token`` or raise an error saying it was expected."""
        if self.tokens[self.index] != token:
            raise self.error(expected or f"'{token}'")
        self.index += 1

    def at_end(self) -> bool:
        """Whether every token has been consumed."""
        return self.tokens[self.index] == _END

    # -- terms ---------------------------------------------------------------------

    def expression(self) -> Term:
        """``operand ['=>>' operand]``; ``=>>`` does not associate."""
        left = self.operand()
        if self.tokens[self.index] == "=>>":
            self.index += 1
            right = self.operand()
            if self.tokens[self.index] == "=>>":
                raise self.error("',' or a closing bracket ('=>>' cannot be chained)")
            return Compound("=>>", (left, right))
        return left

    def operand(self) -> Term:
        """``primary ['=>' primary]``; ``=>`` does not associate."""
        left = self.primary()
        if self.tokens[self.index] == "=>":
            self.index += 1
            right = self.primary()
            if self.tokens[self.index] == "=>":
                raise self.error(
                    "',', '=>>' or a closing bracket ('=>' cannot be chained; "
                    "a conditional default is written Antecedent=>>Consequent)"
                )
            return Compound("=>", (left, right))
        return left

    def primary(self) -> Term:
        """An atom, a number, a list, ``f(args)`` or a parenthesised expression."""
        tokens = self.tokens
        token = tokens[self.index]
        first = token[:1]
        if "a" <= first <= "z" or (first > "\x7f" and first.isalpha() and not first.isupper()):
            self.index += 1
            if tokens[self.index] == "(":
                self.index += 1
                args = [self.expression()]
                while tokens[self.index] == ",":
                    self.index += 1
                    args.append(self.expression())
                self.expect(")", "',' or ')'")
                return Compound(token, tuple(args))
            return token
        if first == "'" and len(token) > 1 and token.endswith("'"):
            self.index += 1
            return unquote(token)
        if first == "-" and token == "-":
            self.index += 1
            return ANY
        if first in _NUMBER_START and token != "-":
            if "." in token or "e" in token or "E" in token:
                self.index += 1
                return float(token)
            if len(token.lstrip("-")) > sys.get_int_max_str_digits():
                raise self.error("a number short enough to read",
                                 found=f"a number of {len(token)} digits")
            self.index += 1
            return int(token)
        if token == "[":
            self.index += 1
            items: list[Term] = []
            if tokens[self.index] == "]":
                self.index += 1
                return items
            items.append(self.expression())
            while tokens[self.index] == ",":
                self.index += 1
                items.append(self.expression())
            self.expect("]", "',' or ']'")
            return items
        if token == "(":
            self.index += 1
            inner = self.expression()
            self.expect(")", "')'")
            return inner
        if first == "_" or first.isupper():
            raise self.error(
                "an atom, a number or a list",
                found=f"the variable {token} (atoms start with a lower-case letter; "
                f"quote it as '{token}')",
            )
        raise self.error("an atom, a number or a list")


def _is_comment(token: str) -> bool:
    return token.startswith("%") or token.startswith("/*")


def describe_token(token: str) -> str:
    """How a token is named in an error message."""
    if token == _END:
        return "the end of the text"
    if token.startswith("'") and (len(token) == 1 or not token.endswith("'")):
        return "an unterminated quoted atom"
    return f"'{token}'"


def unquote(token: str) -> str:
    """The atom a quoted-atom token stands for."""
    body = token[1:-1]
    if "\\" not in body and "''" not in body:
        return body
    out: list[str] = []
    i = 0
    while i < len(body):
        char = body[i]
        if char == "\\" and i + 1 < len(body):
            nxt = body[i + 1]
            out.append({"n": "\n", "t": "\t"}.get(nxt, nxt))
            i += 2
        elif char == "'" and body[i + 1 : i + 2] == "'":
            out.append("'")
            i += 2
        else:
            out.append(char)
            i += 1
    return "".join(out)


# -- terms to statements --------------------------------------------------------------


class TermShapeError(Exception):
    """A well-formed term that is not a statement; carries what was expected."""


def statement_from_term(term: Term, weight: int) -> Statement:
    """The literal (weight 0) or conditional default (weight > 0) a term states."""
    if isinstance(term, Compound) and term.functor == "=>>":
        if weight == 0:
            raise TermShapeError(
                "a weight of 1 or more after a conditional default (=>>); "
                "weight 0 is only for plain properties and relations"
            )
        antecedent, consequent = term.args
        antecedents = _antecedents(antecedent)
        result = _literal(consequent, "the consequent of '=>>'", allow_any=True)
        if result.captures and not any(a.captures for a in antecedents):
            raise TermShapeError(
                "an antecedent that captures a value (p=>'-') when the consequent is "
                f"{format_literal(result)}"
            )
        return Preference(antecedents, result, weight)
    literal = _literal(term, "a property or relation (p, p=>v, not(p), not(p=>v))")
    if weight == 0:
        return literal
    return Preference((), literal, weight)


def _antecedents(term: Term) -> tuple[Literal, ...]:
    if term == ANY:
        return ()
    if isinstance(term, list):
        if not term:
            raise TermShapeError("at least one antecedent in the list (write '-' for always)")
        return tuple(_literal(item, "an antecedent literal", allow_any=True) for item in term)
    return (_literal(term, "an antecedent ('-', a literal or a list of literals)", allow_any=True),)


def _literal(term: Term, expected: str, *, allow_any: bool = False) -> Literal:
    negated = False
    if isinstance(term, Compound) and term.functor == "not" and len(term.args) == 1:
        negated = True
        term = term.args[0]
    if isinstance(term, str) and term != ANY:
        return Literal(term, None, negated)
    if isinstance(term, Compound) and term.functor == "=>":
        name, value = term.args
        if not isinstance(name, str) or name == ANY:
            raise TermShapeError(f"{expected}, with an atom before '=>'")
        if value == ANY and not allow_any:
            raise TermShapeError(
                f"{expected}; '-' (any value) belongs in conditional defaults only"
            )
        return Literal(name, _value(value, expected), negated)
    raise TermShapeError(expected)


def _value(term: Term, expected: str) -> Value:
    if isinstance(term, str):
        return term
    if isinstance(term, bool):
        raise TermShapeError(f"{expected}, with an atom, a number or a list as value")
    if isinstance(term, int):
        return term
    if isinstance(term, float):
        if not math.isfinite(term):
            raise TermShapeError(f"{expected}, with a finite number as value")
        return term
    if isinstance(term, list):
        return tuple(_value(item, expected) for item in term)
    raise TermShapeError(f"{expected}, with an atom, a number or a list as value")


def parse_statement(text: str, weight: int = 0, source: str = "<statement>") -> Statement:
    """Parse one statement such as ``"work=>'-'=>>live=>'-'"`` with its weight."""
    parser = TermParser(text, source)
    term = parser.expression()
    if not parser.at_end():
        raise parser.error("the end of the statement")
    try:
        return statement_from_term(term, weight)
    except TermShapeError as shape:
        raise parser.error(str(shape), index=0, found=f"'{text.strip()}'") from None


# -- formatting -------------------------------------------------------------------------


def format_atom(atom: str) -> str:
    """An atom as the reader reads it back: bare when possible, else quoted."""
    if _PLAIN_ATOM.match(atom) and not atom[0].isupper():
        return atom
    escaped = (
        atom.replace("\\", "\\\\").replace("'", "\\'").replace("\n", "\\n").replace("\t", "\\t")
    )
    return f"'{escaped}'"


def format_value(value: Value) -> str:
    """A value in KB syntax."""
    if isinstance(value, str):
        return format_atom(value)
    if isinstance(value, tuple):
        return "[" + ",".join(format_value(item) for item in value) + "]"
    return repr(value)


def format_literal(literal: Literal) -> str:
    """``p``, ``p=>v``, ``not(p)`` or ``not(p=>v)``."""
    text = format_atom(literal.name)
    if literal.value is not None:
        text = f"{text}=>{format_value(literal.value)}"
    return f"not({text})" if literal.negated else text


def format_statement(statement: Statement) -> str:
    """A literal or ``Antecedent=>>Consequent`` (without the weight)."""
    if isinstance(statement, Literal):
        return format_literal(statement)
    antecedents = statement.antecedents
    if not antecedents:
        left = "'-'"
    elif len(antecedents) == 1:
        left = format_literal(antecedents[0])
    else:
        left = "[" + ",".join(format_literal(a) for a in antecedents) + "]"
    return f"{left}=>>{format_literal(statement.consequent)}"


def format_entry(statement: Statement) -> str:
    """``[Statement,Weight]`` as it appears in a property or relation list."""
    weight = statement.weight if isinstance(statement, Preference) else 0
    return f"[{format_statement(statement)},{weight}]"
