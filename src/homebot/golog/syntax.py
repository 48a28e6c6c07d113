"""The textual syntax of Golog programs, as the paper's listings write them.

::

    proc sort_cups(P1, P2, P3, H),
      solve(H, reward_cup(P1, P2, P3),
        while not (p1 = pos(P1) and p2 = pos(P2) and p3 = pos(P3)) do
          pickBest(cup, {red, green, blue},
            pickBest(to, {p1, p2, p3, p4}, move_cup(cup, pos(cup), to)))
        endwhile)
    endproc

Statements are joined by ``;`` (or ``,`` outside argument lists); ``|`` is
nondeterministic choice and ``||`` prioritised concurrency (choice binds
loosest). Constructs: ``nil``, ``fail``, ``?(φ)``, ``if φ then δ [else δ] endif``,
``while φ do δ endwhile``, ``star(δ)``, ``search(δ)``, ``pi(x, D, δ)``, ``pickBest(x, D, δ)``,
``solve(h, reward, δ)``, ``prob(p, δ1, δ2)``, ``withPol(δ1, δ2)``,
``withCtrl φ do δ endwithCtrl``, ``waitFor(φ)``, ``name(args)`` (an action or a
procedure). Formulas use ``and & ∧``, ``or | ∨``, ``not ! ¬``, ``= != ≠ < <= >
>=``, ``+ - * /``, ``exists x in D: φ``, ``forall x in D: φ``, ``pproj(φ, δ)``,
``{a, b}`` sets, numbers, ``"quoted strings"``, ``true``, ``false``. Comments
start with ``%`` or ``#``. Errors name the line and column and show the line.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass

from homebot.errors import GologError
from homebot.golog.expressions import (
    And,
    Arith,
    Compare,
    Const,
    Exists,
    Expr,
    Fn,
    Forall,
    Not,
    Or,
    PProj,
    SetOf,
)
from homebot.golog.program import (
    Call,
    Choice,
    Conc,
    If,
    Nil,
    Pi,
    PickBest,
    Prob,
    Procedure,
    Program,
    Search,
    Seq,
    Solve,
    Star,
    Test,
    WaitFor,
    While,
    WithCtrl,
    WithPol,
)

__all__ = ["parse_procedures", "parse_program"]

_TOKEN = re.compile(r"""
    (?P<space>[ \t\r\n]+) | (?P<comment>[%#][^\n]*)
  | (?P<number>\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)
  | (?P<string>"[^"\n]*"|“[^”\n]*”)
  | (?P<name>[^\W\d]\w*)
  | (?P<symbol>\|\||!=|<=|>=|[|;,(){}?=<>&!+\-*/:∧∨¬≠])
""", re.VERBOSE)
_SYMBOL_ALIASES = {"∧": "&", "∨": "|", "¬": "!", "≠": "!=", "and": "&", "or": "|", "not": "!"}
_END_OF_SEQUENCE = frozenset({"endproc", "endwhile", "endif", "else", "endwithCtrl", ")", "|",
                              "||", "<end>"})

_KEYWORDS = frozenset({"proc", "endproc", "while", "do", "endwhile", "if", "then", "else",
                       "endif", "withCtrl", "endwithCtrl", "in"})


@dataclass(frozen=True, slots=True)
class _Token:
    kind: str
    text: str
    line: int
    column: int


def _tokens(text: str, source: str) -> list[_Token]:
    tokens: list[_Token] = []
    position, line, line_start = 0, 1, 0
    while position < len(text):
        match = _TOKEN.match(text, position)
        if match is None:
            column = position - line_start + 1
            raise _error(text, source, line, column,
                         f"unexpected character {text[position]!r}",
                         "remove it, or quote it inside \"...\"")
        kind = match.lastgroup or ""
        value = match.group()
        if kind not in ("space", "comment"):
            if kind == "name" and value in _SYMBOL_ALIASES:
                kind, value = "symbol", _SYMBOL_ALIASES[value]
            elif kind == "symbol":
                value = _SYMBOL_ALIASES.get(value, value)
            tokens.append(_Token(kind, value, line, position - line_start + 1))
        newlines = value.count("\n")
        if newlines:
            line += newlines
            line_start = match.start() + value.rindex("\n") + 1
        position = match.end()
    tokens.append(_Token("end", "<end>", line, position - line_start + 1))
    return tokens


def _error(text: str, source: str, line: int, column: int, message: str,
           fix: str) -> GologError:
    lines = text.splitlines() or [""]
    shown = lines[min(line, len(lines)) - 1]
    return GologError(f"{source}:{line}:{column}: {message}; {fix}\n  {shown}\n  "
                      f"{' ' * (column - 1)}^")


class _Parser:
    def __init__(self, text: str, source: str) -> None:
        self.text, self.source = text, source
        self.tokens = _tokens(text, source)
        self.index = 0

    # ------------------------------------------------------------ helpers

    @property
    def token(self) -> _Token:
        return self.tokens[self.index]

    def at(self, *texts: str) -> bool:
        return self.token.text in texts and self.token.kind in ("symbol", "name", "end")

    def advance(self) -> _Token:
        token = self.token
        self.index += 1
        return token

    def expect(self, text: str, fix: str = "") -> _Token:
        if not self.at(text):
            raise self.fail(f"expected '{text}' but found '{self.token.text}'",
                            fix or f"add '{text}'")
        return self.advance()

    def name(self, what: str) -> str:
        if self.token.kind != "name":
            raise self.fail(f"expected {what} but found '{self.token.text}'",
                            f"write {what} here")
        return self.advance().text

    def fail(self, message: str, fix: str) -> GologError:
        token = self.token
        return _error(self.text, self.source, token.line, token.column, message, fix)

    # ------------------------------------------------------------ programs

    def procedures(self) -> list[Procedure]:
        found: list[Procedure] = []
        while not self.at("<end>"):
            if not self.at("proc"):
                raise self.fail(f"expected 'proc' but found '{self.token.text}'",
                                "a program file is a list of 'proc NAME ... endproc'")
            self.advance()
            if any(self.token.text == earlier.name for earlier in found):
                raise self.fail(f"procedure '{self.token.text}' is defined twice in this file",
                                "rename or remove one of them")
            header = self.token
            name = self.name("the procedure's name")
            parameters: list[str] = []
            if self.at("(") and self._parameter_list_follows():
                self.advance()
                while not self.at(")"):
                    if parameters:
                        self.expect(",", "separate the parameters with ','")
                    if self.token.text in parameters:
                        raise self.fail(f"parameter '{self.token.text}' is named twice",
                                        "give each parameter its own name")
                    parameters.append(self.name("a parameter"))
                self.expect(")", "close the parameter list with ')'")
            if self.at(","):
                self.advance()
            start = self.index
            body = self.program(commas=True)
            places: dict[str, str] = {}
            for token in self.tokens[start:self.index]:
                if token.kind == "name":
                    places.setdefault(token.text, f"{self.source}:{token.line}:{token.column}")
            places.setdefault(name, f"{self.source}:{header.line}:{header.column}")
            self.expect("endproc", f"end procedure '{name}' with 'endproc'")
            found.append(Procedure(name, tuple(parameters), body, places))
        return found

    def _parameter_list_follows(self) -> bool:
        after = self.tokens[self.index + 1: self.index + 3]
        return len(after) == 2 and (after[0].text == ")" or (
            after[0].kind == "name" and after[1].text in (",", ")")))

    def program(self, *, commas: bool) -> Program:
        options = [self.concurrent(commas)]
        while self.at("|"):
            self.advance()
            options.append(self.concurrent(commas))
        return options[0] if len(options) == 1 else Choice(tuple(options))

    def concurrent(self, commas: bool) -> Program:
        program = self.sequence(commas)
        while self.at("||"):
            self.advance()
            program = Conc(program, self.sequence(commas))
        return program

    def sequence(self, commas: bool) -> Program:
        separators = (";", ",") if commas else (";",)
        parts = [self.statement()]
        while self.at(*separators):
            self.advance()
            if self.at(*_END_OF_SEQUENCE) or (not commas and self.at(",")):
                break
            parts.append(self.statement())
        return parts[0] if len(parts) == 1 else Seq(tuple(parts))

    def statement(self) -> Program:
        token = self.token
        if token.kind == "symbol":
            if token.text == "?":
                self.advance()
                self.expect("(", "write a test as ?(condition)")
                condition = self.expr()
                self.expect(")", "close the test with ')'")
                return Test(condition)
            if token.text == "(":
                self.advance()
                inner = self.program(commas=True)
                self.expect(")", "close the group with ')'")
                return inner
            raise self.fail(f"expected a statement but found '{token.text}'",
                            "write an action, a test ?(...) or a construct such as while")
        if token.kind != "name":
            raise self.fail(f"expected a statement but found '{token.text}'",
                            "write an action name, a test or a construct")
        keyword = token.text
        handler = getattr(self, f"_statement_{keyword}", None)
        if handler is not None:
            self.advance()
            return handler()  # type: ignore[no-any-return]
        if keyword.startswith("end"):
            raise self.fail(f"'{keyword}' closes nothing here",
                            "check that every if/while/proc is closed by its own end word")
        self.advance()
        return Call(keyword, self.arguments())

    def arguments(self) -> tuple[Expr, ...]:
        if not self.at("("):
            return ()
        self.advance()
        args: list[Expr] = []
        if not self.at(")"):
            args.append(self.expr())
            while self.at(","):
                self.advance()
                args.append(self.expr())
        self.expect(")", "close the argument list with ')'")
        return tuple(args)

    def _statement_nil(self) -> Program:
        return Nil()

    def _statement_fail(self) -> Program:
        return Test(Const(False))

    def _statement_if(self) -> Program:
        condition = self.expr()
        self.expect("then", "write 'if CONDITION then ...'")
        then = self.program(commas=True)
        otherwise: Program = Nil()
        if self.at("else"):
            self.advance()
            otherwise = self.program(commas=True)
        self.expect("endif", "close the if with 'endif'")
        return If(condition, then, otherwise)

    def _statement_while(self) -> Program:
        condition = self.expr()
        self.expect("do", "write 'while CONDITION do ... endwhile'")
        body = self.program(commas=True)
        self.expect("endwhile", "close the loop with 'endwhile'")
        return While(condition, body)

    def _statement_withCtrl(self) -> Program:
        condition = self.expr()
        self.expect("do", "write 'withCtrl CONDITION do ... endwithCtrl'")
        body = self.program(commas=True)
        self.expect("endwithCtrl", "close it with 'endwithCtrl'")
        return WithCtrl(condition, body)

    def _open(self, construct: str) -> None:
        self.expect("(", f"write {construct}(...)")

    def _next(self, construct: str) -> None:
        self.expect(",", f"separate the arguments of {construct} with ','")

    def _close(self, construct: str) -> None:
        self.expect(")", f"close {construct}(...) with ')'")

    def _statement_waitFor(self) -> Program:
        self._open("waitFor")
        condition = self.expr()
        self._close("waitFor")
        return WaitFor(condition)

    def _statement_star(self) -> Program:
        self._open("star")
        body = self.program(commas=False)
        self._close("star")
        return Star(body)

    def _statement_search(self) -> Program:
        self._open("search")
        body = self.program(commas=False)
        self._close("search")
        return Search(body)

    def _binder(self, construct: str) -> tuple[str, Expr, Program]:
        self._open(construct)
        variable = self.name("a variable")
        self._next(construct)
        domain = self.expr()
        self._next(construct)
        body = self.program(commas=False)
        self._close(construct)
        return variable, domain, body

    def _statement_pi(self) -> Program:
        return Pi(*self._binder("pi"))

    def _statement_pickBest(self) -> Program:
        return PickBest(*self._binder("pickBest"))

    def _statement_solve(self) -> Program:
        self._open("solve")
        horizon = self.expr()
        self._next("solve")
        reward = self.expr()
        self._next("solve")
        body = self.program(commas=False)
        self._close("solve")
        return Solve(horizon, reward, body)

    def _statement_prob(self) -> Program:
        self._open("prob")
        probability = self.expr()
        self._next("prob")
        first = self.program(commas=False)
        self._next("prob")
        second = self.program(commas=False)
        self._close("prob")
        return Prob(probability, first, second)

    def _statement_withPol(self) -> Program:
        self._open("withPol")
        policy = self.program(commas=False)
        self._next("withPol")
        program = self.program(commas=False)
        self._close("withPol")
        return WithPol(policy, program)

    # ------------------------------------------------------------ formulas

    def expr(self) -> Expr:
        operands = [self.conjunction()]
        while self.at("|"):
            self.advance()
            operands.append(self.conjunction())
        return operands[0] if len(operands) == 1 else Or(tuple(operands))

    def conjunction(self) -> Expr:
        operands = [self.unary()]
        while self.at("&"):
            self.advance()
            operands.append(self.unary())
        return operands[0] if len(operands) == 1 else And(tuple(operands))

    def unary(self) -> Expr:
        if self.at("!"):
            self.advance()
            return Not(self.unary())
        left = self.sum()
        if self.at("=", "!=", "<", "<=", ">", ">="):
            op = self.advance().text
            return Compare(op, left, self.sum())
        return left

    def sum(self) -> Expr:
        left = self.product()
        while self.at("+", "-"):
            op = self.advance().text
            left = Arith(op, left, self.product())
        return left

    def product(self) -> Expr:
        left = self.atom()
        while self.at("*", "/"):
            op = self.advance().text
            left = Arith(op, left, self.atom())
        return left

    def atom(self) -> Expr:
        token = self.token
        if token.kind == "number":
            whole = not any(mark in token.text for mark in ".eE")
            if whole and len(token.text) > sys.get_int_max_str_digits():
                raise self.fail(f"a number of {len(token.text)} digits, too long to read",
                                "write a smaller number")
            self.advance()
            return Const(int(token.text) if whole else float(token.text))
        if token.kind == "string":
            self.advance()
            return Const(token.text[1:-1])
        if self.at("-"):
            self.advance()
            inner = self.atom()
            if isinstance(inner, Const) and isinstance(inner.value, int | float):
                return Const(-inner.value)
            return Arith("-", Const(0), inner)
        if self.at("("):
            self.advance()
            inner = self.expr()
            self.expect(")", "close the parenthesis")
            return inner
        if self.at("{"):
            self.advance()
            items: list[Expr] = []
            if not self.at("}"):
                items.append(self.expr())
                while self.at(","):
                    self.advance()
                    items.append(self.expr())
            self.expect("}", "close the set with '}'")
            return SetOf(tuple(items))
        if token.kind != "name" or token.text in _KEYWORDS:
            raise self.fail(f"expected a term but found '{token.text}'",
                            "write a name, a number, a quoted string or (formula)")
        self.advance()
        if token.text in ("true", "false"):
            return Const(token.text == "true")
        if token.text in ("exists", "forall"):
            variable = self.name("a variable")
            self.expect("in", f"write '{token.text} x in {{...}}: formula'")
            domain = self.atom()
            self.expect(":", f"write '{token.text} x in {{...}}: formula'")
            body = self.expr()
            return (Exists if token.text == "exists" else Forall)(variable, domain, body)
        if token.text == "pproj":
            self._open("pproj")
            condition = self.expr()
            self._next("pproj")
            program = self.program(commas=False)
            self._close("pproj")
            return PProj(condition, program)
        return Fn(token.text, self.arguments())


def parse_program(text: str, source: str = "<program>") -> Program:
    """One program; raises ``GologError`` naming line and column when it is malformed."""
    parser = _Parser(text, source)
    try:
        program = parser.program(commas=True)
    except RecursionError:
        raise parser.fail("the program is nested too deeply to read",
                          "split it into procedures") from None
    if not parser.at("<end>"):
        raise parser.fail(f"unexpected '{parser.token.text}' after the program",
                          "join statements with ';' or remove what follows")
    return program


def parse_procedures(text: str, source: str = "<program>") -> list[Procedure]:
    """The procedures of a program file (``proc NAME(PARAMS) BODY endproc`` ...)."""
    parser = _Parser(text, source)
    try:
        return parser.procedures()
    except RecursionError:
        raise parser.fail("the program is nested too deeply to read",
                          "split it into procedures") from None
