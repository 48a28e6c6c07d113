"""The Python embedding: build Golog programs and formulas from plain Python values.

Strings become names (a fluent, a function, a variable or a symbol, resolved
when evaluated); numbers become constants; use ``const("...")`` for a string
that is data, as a quoted string is in the textual syntax. Example::

    solve(4, f("reward_cup", "P1", "P2", "P3"),
          while_(~(eq("p1", f("pos", "P1")) & eq("p2", f("pos", "P2"))),
                 pick_best("cup", ["red", "green", "blue"],
                           pick_best("to", ["p1", "p2", "p3", "p4"],
                                     do("move_cup", "cup", f("pos", "cup"), "to")))))
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Sequence
from typing import Any

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
    as_expr,
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

__all__ = [
    "add",
    "and_",
    "choice",
    "conc",
    "const",
    "do",
    "eq",
    "exists",
    "f",
    "fail",
    "forall",
    "ge",
    "gt",
    "if_",
    "le",
    "lt",
    "ne",
    "nil",
    "not_",
    "or_",
    "pi",
    "pick_best",
    "pproj",
    "prob",
    "proc",
    "procedure",
    "search",
    "seq",
    "solve",
    "star",
    "sub",
    "test",
    "wait_for",
    "while_",
    "with_ctrl",
    "with_pol",
]


def f(name: str, *args: Any) -> Fn:
    """A fluent, function, variable or symbol, with arguments."""
    return Fn(name, tuple(as_expr(arg) for arg in args))


def const(value: Any) -> Const:
    """A constant (a string here stays data, never a name)."""
    return Const(value)


def _compare(op: str, left: Any, right: Any) -> Compare:
    return Compare(op, as_expr(left), as_expr(right))


def eq(left: Any, right: Any) -> Compare:
    return _compare("=", left, right)


def ne(left: Any, right: Any) -> Compare:
    return _compare("!=", left, right)


def lt(left: Any, right: Any) -> Compare:
    return _compare("<", left, right)


def le(left: Any, right: Any) -> Compare:
    return _compare("<=", left, right)


def gt(left: Any, right: Any) -> Compare:
    return _compare(">", left, right)


def ge(left: Any, right: Any) -> Compare:
    return _compare(">=", left, right)


def add(left: Any, right: Any) -> Arith:
    return Arith("+", as_expr(left), as_expr(right))


def sub(left: Any, right: Any) -> Arith:
    return Arith("-", as_expr(left), as_expr(right))


def and_(*operands: Any) -> Expr:
    return And(tuple(as_expr(operand) for operand in operands))


def or_(*operands: Any) -> Expr:
    return Or(tuple(as_expr(operand) for operand in operands))


def not_(operand: Any) -> Expr:
    return Not(as_expr(operand))


def exists(variable: str, domain: Any, body: Any) -> Expr:
    return Exists(variable, as_expr(domain), as_expr(body))


def forall(variable: str, domain: Any, body: Any) -> Expr:
    return Forall(variable, as_expr(domain), as_expr(body))


def pproj(condition: Any, program: Program) -> Expr:
    return PProj(as_expr(condition), program)


nil = Nil()
fail = Test(Const(False))


def do(name: str, *args: Any) -> Call:
    """A primitive action or a procedure call."""
    return Call(name, tuple(as_expr(arg) for arg in args))


def _program(part: Program | str) -> Program:
    if part == "nil":
        return nil
    if part == "fail":
        return fail
    return do(part) if isinstance(part, str) else part


def seq(*parts: Program | str) -> Program:
    """``δ1; δ2; ...`` (one part is itself, none is ``nil``)."""
    if len(parts) <= 1:
        return _program(parts[0]) if parts else nil
    return Seq(tuple(_program(part) for part in parts))


def test(condition: Any) -> Test:
    return Test(as_expr(condition))


def if_(condition: Any, then: Program | str, otherwise: Program | str = nil) -> If:
    return If(as_expr(condition), _program(then), _program(otherwise))


def while_(condition: Any, body: Program | str) -> While:
    return While(as_expr(condition), _program(body))


def choice(*options: Program | str) -> Choice:
    return Choice(tuple(_program(option) for option in options))


def star(body: Program | str) -> Star:
    return Star(_program(body))


def search(body: Program | str) -> Search:
    """IndiGolog's Σ: online, take only steps from which ``body`` can still end."""
    return Search(_program(body))


def pi(variable: str, domain: Any, body: Program | str) -> Pi:
    return Pi(variable, as_expr(domain), _program(body))


def pick_best(variable: str, domain: Any, body: Program | str) -> PickBest:
    return PickBest(variable, as_expr(domain), _program(body))


def conc(high: Program | str, low: Program | str) -> Conc:
    return Conc(_program(high), _program(low))


def with_pol(policy: Program | str, program: Program | str) -> WithPol:
    return WithPol(_program(policy), _program(program))


def with_ctrl(condition: Any, body: Program | str) -> WithCtrl:
    return WithCtrl(as_expr(condition), _program(body))


def wait_for(condition: Any) -> WaitFor:
    return WaitFor(as_expr(condition))


def prob(probability: Any, first: Program | str, second: Program | str) -> Prob:
    return Prob(as_expr(probability), _program(first), _program(second))


def solve(horizon: Any, reward: Any, body: Program | str) -> Solve:
    return Solve(as_expr(horizon), as_expr(reward), _program(body))


def proc(name: str, parameters: Sequence[str], body: Program | str) -> Procedure:
    return Procedure(name, tuple(parameters), _program(body))


def procedure(function: Callable[..., Program | str]) -> Procedure:
    """A procedure from a Python function: its name and parameters, the program it builds.

    The function is called once with each parameter standing for itself, so::

        @procedure
        def go_floor(N):
            return while_(ne(f("floor"), N), if_(lt(f("floor"), N), "up", "down"))

    is the same procedure as ``proc go_floor(N) while floor != N do ... endproc``.
    """
    parameters = tuple(inspect.signature(function).parameters)
    return Procedure(function.__name__, parameters,
                     _program(function(*(Fn(name) for name in parameters))))
