"""Terms and formulas of Golog programs: fluents, constants, comparisons, connectives.

Expressions are frozen dataclasses, so a program built from Python and the same
program read from text compare equal. A name (``Fn``) is resolved when it is
evaluated: a fluent of the theory, else a function of the theory, else the name
itself (a symbol such as ``red`` or ``p1``). Variables bound by ``pi``,
``pickBest``, ``exists`` or a procedure's parameters are substituted by
constants before evaluation.
"""

from __future__ import annotations

import operator
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from homebot.errors import GologError

if TYPE_CHECKING:
    from homebot.golog.program import Program
    from homebot.golog.theory import State, Theory

__all__ = [
    "And",
    "Arith",
    "Compare",
    "Const",
    "Exists",
    "Expr",
    "Fn",
    "Forall",
    "Not",
    "Or",
    "PProj",
    "Possible",
    "SetOf",
    "as_expr",
]

Substitution = Mapping[str, "Expr"]

_COMPARISONS: dict[str, Callable[[Any, Any], bool]] = {
    "=": operator.eq, "!=": operator.ne, "<": operator.lt, "<=": operator.le,
    ">": operator.gt, ">=": operator.ge}
_ARITHMETIC: dict[str, Callable[[Any, Any], Any]] = {
    "+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv}


class Expr:
    """A term or formula; ``evaluate`` gives its value in a state of a theory."""

    __slots__ = ()

    def evaluate(self, theory: Theory, state: State) -> Any:
        raise NotImplementedError

    def substitute(self, bindings: Substitution) -> Expr:
        raise NotImplementedError

    def holds(self, theory: Theory, state: State) -> bool:
        """The truth value of this formula in ``state``."""
        return bool(self.evaluate(theory, state))

    def __and__(self, other: Any) -> Expr:
        left = self.operands if isinstance(self, And) else (self,)
        return And((*left, as_expr(other)))

    def __or__(self, other: Any) -> Expr:
        left = self.operands if isinstance(self, Or) else (self,)
        return Or((*left, as_expr(other)))

    def __invert__(self) -> Expr:
        return Not(self)


def as_expr(value: Any) -> Expr:
    """An expression from a Python value: strings become names, others constants."""
    if isinstance(value, Expr):
        return value
    if isinstance(value, str):
        return Fn(value)
    if isinstance(value, list):
        return SetOf(tuple(as_expr(item) for item in value))
    if isinstance(value, set | frozenset):
        return SetOf(tuple(as_expr(item) for item in sorted(value, key=repr)))
    return Const(value)


@dataclass(frozen=True, slots=True, eq=False)
class Const(Expr):
    """A constant value (a number, a quoted string, a tuple); ``1``, ``1.0`` and ``true``
    are different constants, as they are different program texts."""

    value: Any

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Const) and type(self.value) is type(other.value)
                and self.value == other.value)

    def __hash__(self) -> int:
        return hash((type(self.value).__name__, self.value))

    def evaluate(self, theory: Theory, state: State) -> Any:
        return self.value

    def substitute(self, bindings: Substitution) -> Expr:
        return self

    def __str__(self) -> str:
        if isinstance(self.value, bool):
            return str(self.value).lower()
        return f'"{self.value}"' if isinstance(self.value, str) else str(self.value)


@dataclass(frozen=True, slots=True)
class Fn(Expr):
    """A name with arguments: a fluent, a function of the theory, a variable or a symbol."""

    name: str
    args: tuple[Expr, ...] = ()

    def evaluate(self, theory: Theory, state: State) -> Any:
        values = tuple([arg.evaluate(theory, state) for arg in self.args]) if self.args else ()
        fluent = theory.fluents.get(self.name)
        if fluent is not None:
            return state.values.get((self.name, *values), fluent.default)
        function = theory.functions.get(self.name)
        if function is not None:
            return function(state, *values)
        if values:
            raise GologError(f"'{self.name}' is neither a fluent nor a function of the theory "
                             f"'{theory.name}'; declare it with theory.fluent(...) or "
                             f"theory.function(...)")
        return self.name

    def substitute(self, bindings: Substitution) -> Expr:
        if not self.args:
            return bindings.get(self.name, self)
        return Fn(self.name, tuple(arg.substitute(bindings) for arg in self.args))

    def __str__(self) -> str:
        if not self.args:
            return self.name
        return f"{self.name}({', '.join(str(arg) for arg in self.args)})"


@dataclass(frozen=True, slots=True)
class SetOf(Expr):
    """A finite set of values, written ``{a, b, c}`` (kept in the order written)."""

    items: tuple[Expr, ...]

    def evaluate(self, theory: Theory, state: State) -> Any:
        return tuple(item.evaluate(theory, state) for item in self.items)

    def substitute(self, bindings: Substitution) -> Expr:
        return SetOf(tuple(item.substitute(bindings) for item in self.items))

    def __str__(self) -> str:
        return "{" + ", ".join(str(item) for item in self.items) + "}"


@dataclass(frozen=True, slots=True)
class Not(Expr):
    """Negation."""

    operand: Expr

    def evaluate(self, theory: Theory, state: State) -> Any:
        return not self.operand.evaluate(theory, state)

    def substitute(self, bindings: Substitution) -> Expr:
        return Not(self.operand.substitute(bindings))

    def __str__(self) -> str:
        return f"not {_wrapped(self.operand)}"


@dataclass(frozen=True, slots=True)
class And(Expr):
    """Conjunction of two or more formulas."""

    operands: tuple[Expr, ...]

    def evaluate(self, theory: Theory, state: State) -> Any:
        return all(operand.evaluate(theory, state) for operand in self.operands)

    def substitute(self, bindings: Substitution) -> Expr:
        return And(tuple(operand.substitute(bindings) for operand in self.operands))

    def __str__(self) -> str:
        return " and ".join(_wrapped(operand) for operand in self.operands)


@dataclass(frozen=True, slots=True)
class Or(Expr):
    """Disjunction of two or more formulas."""

    operands: tuple[Expr, ...]

    def evaluate(self, theory: Theory, state: State) -> Any:
        return any(operand.evaluate(theory, state) for operand in self.operands)

    def substitute(self, bindings: Substitution) -> Expr:
        return Or(tuple(operand.substitute(bindings) for operand in self.operands))

    def __str__(self) -> str:
        return " or ".join(_wrapped(operand) for operand in self.operands)


@dataclass(frozen=True, slots=True)
class Compare(Expr):
    """``left OP right`` with OP one of = != < <= > >=."""

    op: str
    left: Expr
    right: Expr

    def evaluate(self, theory: Theory, state: State) -> Any:
        left, right = self.left.evaluate(theory, state), self.right.evaluate(theory, state)
        if isinstance(left, bool) is not isinstance(right, bool):  # true is not 1
            if self.op in ("=", "!="):
                return self.op == "!="
            raise _mismatch(self, left, right)
        try:
            return _COMPARISONS[self.op](left, right)
        except TypeError:
            raise _mismatch(self, left, right) from None

    def substitute(self, bindings: Substitution) -> Expr:
        return Compare(self.op, self.left.substitute(bindings), self.right.substitute(bindings))

    def __str__(self) -> str:
        return f"{_wrapped(self.left)} {self.op} {_wrapped(self.right)}"


@dataclass(frozen=True, slots=True)
class Arith(Expr):
    """``left OP right`` with OP one of + - * /."""

    op: str
    left: Expr
    right: Expr

    def evaluate(self, theory: Theory, state: State) -> Any:
        left, right = self.left.evaluate(theory, state), self.right.evaluate(theory, state)
        if isinstance(left, bool) or isinstance(right, bool):
            raise _mismatch(self, left, right)
        try:
            return _ARITHMETIC[self.op](left, right)
        except ZeroDivisionError:
            raise GologError(f"cannot compute {self}: it divides by zero") from None
        except TypeError:
            raise _mismatch(self, left, right) from None

    def substitute(self, bindings: Substitution) -> Expr:
        return Arith(self.op, self.left.substitute(bindings), self.right.substitute(bindings))

    def __str__(self) -> str:
        return f"({self.left} {self.op} {self.right})"


def _mismatch(expr: Expr, left: Any, right: Any) -> GologError:
    return GologError(f"cannot compute {expr}: its sides are {left!r} and {right!r}; compare "
                      f"and add only values of the same kind (numbers with numbers)")


def _values(domain: Expr, theory: Theory, state: State) -> Iterable[Any]:
    values = domain.evaluate(theory, state)
    if isinstance(values, str) or not isinstance(values, Iterable):
        raise GologError(f"the domain {domain} is not a finite set of values; write it as "
                         f"{{a, b, c}} or name a function of the theory that returns one")
    return values


@dataclass(frozen=True, slots=True)
class Exists(Expr):
    """``exists VAR in DOMAIN: BODY`` over a finite domain."""

    variable: str
    domain: Expr
    body: Expr

    def evaluate(self, theory: Theory, state: State) -> Any:
        return any(self.body.substitute({self.variable: Const(value)}).evaluate(theory, state)
                   for value in _values(self.domain, theory, state))

    def substitute(self, bindings: Substitution) -> Expr:
        inner = {name: value for name, value in bindings.items() if name != self.variable}
        return Exists(self.variable, self.domain.substitute(bindings), self.body.substitute(inner))

    def __str__(self) -> str:
        return f"exists {self.variable} in {self.domain}: {self.body}"


@dataclass(frozen=True, slots=True)
class Forall(Expr):
    """``forall VAR in DOMAIN: BODY`` over a finite domain."""

    variable: str
    domain: Expr
    body: Expr

    def evaluate(self, theory: Theory, state: State) -> Any:
        return all(self.body.substitute({self.variable: Const(value)}).evaluate(theory, state)
                   for value in _values(self.domain, theory, state))

    def substitute(self, bindings: Substitution) -> Expr:
        inner = {name: value for name, value in bindings.items() if name != self.variable}
        return Forall(self.variable, self.domain.substitute(bindings), self.body.substitute(inner))

    def __str__(self) -> str:
        return f"forall {self.variable} in {self.domain}: {self.body}"


@dataclass(frozen=True, slots=True)
class Possible(Expr):
    """``Poss(a, s)``: the precondition of a ground action; policies use it as a marker."""

    action: tuple[Any, ...]

    def evaluate(self, theory: Theory, state: State) -> Any:
        return theory.possible(self.action, state)

    def substitute(self, bindings: Substitution) -> Expr:
        return self

    def __str__(self) -> str:
        from homebot.golog.theory import action_text

        return f"poss({action_text(self.action)})"


@dataclass(frozen=True, slots=True)
class PProj(Expr):
    """``pproj(φ, σ)``: the probability that φ holds after projecting σ from this state."""

    condition: Expr
    program: Program

    def evaluate(self, theory: Theory, state: State) -> Any:
        from homebot.golog.planner import project

        return project(theory, self.program, state, self.condition)

    def substitute(self, bindings: Substitution) -> Expr:
        return PProj(self.condition.substitute(bindings), self.program.substitute(bindings))

    def __str__(self) -> str:
        return f"pproj({self.condition}, {self.program})"


def _wrapped(expr: Expr) -> str:
    if isinstance(expr, And | Or | Compare | Not | Exists | Forall):
        return f"({expr})"
    return str(expr)
