"""Logical expressions of SHOP2 preconditions and axioms, and their satisfiers in a state.

A precondition is built from plain data, the same for Python domains and for
JSHOP2 files: a sequence whose first item is a string is an atom ``("at", "?r",
"?p")`` or a special form (``and``, ``or``, ``not``, ``imply``, ``forall``,
``call``, ``assign``, ``:first``); any other sequence (or ``nil``) is a
conjunction. ``solve`` yields every binding (a dict from variable to value)
under which the expression holds, lazily, in the order of the state.
"""

from __future__ import annotations

import operator as op
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from homebot.errors import PlanningError
from homebot.htn.state import Atom, State, Term, is_variable

__all__ = [
    "FUNCTIONS",
    "And",
    "Assign",
    "AtomPattern",
    "Axiom",
    "Call",
    "Expression",
    "First",
    "ForAll",
    "Not",
    "Or",
    "Proof",
    "expression",
    "ground",
    "is_ground",
    "list_term",
    "substitute",
    "template",
    "term",
    "unify",
]

Bindings = dict[str, Term]

#: The functions ``call`` knows, as in JSHOP2's standard Lisp calls.
FUNCTIONS: Mapping[str, Callable[..., Any]] = {
    "+": lambda *values: sum(values), "-": lambda a, *b: a - sum(b) if b else -a,
    "*": lambda *values: _product(values), "/": op.truediv, "<": op.lt, ">": op.gt,
    "<=": op.le, ">=": op.ge, "=": op.eq, "/=": op.ne, "eq": op.eq, "equal": op.eq,
    "max": max, "min": min, "abs": abs,
}


def _product(values: Sequence[Any]) -> Any:
    result = 1
    for value in values:
        result *= value
    return result


class Proof(Protocol):
    """What expressions are evaluated against: the state and the domain's axioms."""

    state: State
    axioms: Mapping[tuple[str, int], Sequence[Axiom]]


class Expression:
    """A precondition or axiom body."""

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        """Every extension of ``bindings`` under which the expression holds."""
        raise NotImplementedError

    def holds(self, proof: Proof, bindings: Bindings) -> bool:
        """Whether some binding satisfies the expression."""
        return next(iter(self.solve(proof, bindings)), None) is not None


def term(value: Term, bindings: Mapping[str, Term]) -> Term:
    """A term under ``bindings`` (a variable without a value stays a variable)."""
    if isinstance(value, Call):
        return value.evaluate(bindings)
    if is_variable(value):
        return bindings.get(value, value)
    return value


def is_ground(value: Term) -> bool:
    """Whether a term has no variables (list terms are looked into)."""
    if isinstance(value, tuple):
        for item in value:
            if isinstance(item, str):
                if item[:1] == "?":
                    return False
            elif isinstance(item, tuple) and not is_ground(item):
                return False
        return True
    return not (isinstance(value, str) and value[:1] == "?")


def substitute(value: Term, bindings: Mapping[str, Term]) -> Term:
    """A term under ``bindings``, list terms included (``(?head . ?tail)`` is spliced)."""
    if isinstance(value, str):
        return bindings.get(value, value) if value[:1] == "?" else value
    if isinstance(value, tuple):
        if len(value) >= 2 and value[-2] == ".":
            tail = substitute(value[-1], bindings)
            head = tuple(substitute(item, bindings) for item in value[:-2])
            return head + tail if isinstance(tail, tuple) else (*head, ".", tail)
        return tuple(substitute(item, bindings) for item in value)
    if isinstance(value, Call):
        return value.evaluate(bindings)
    return value


def unify(pattern: Term, value: Term, bindings: Bindings) -> bool:
    """Match a pattern against a ground value, extending ``bindings`` in place."""
    if isinstance(pattern, str) and pattern[:1] == "?":
        previous = bindings.get(pattern)
        if previous is None:
            bindings[pattern] = value
            return True
        return bool(previous == value)
    if isinstance(pattern, tuple):
        if not isinstance(value, tuple):
            return False
        if len(pattern) >= 2 and pattern[-2] == ".":
            fixed = len(pattern) - 2
            return len(value) >= fixed and all(
                unify(p, v, bindings) for p, v in zip(pattern[:fixed], value, strict=False)
            ) and unify(pattern[-1], value[fixed:], bindings)
        return len(pattern) == len(value) and all(
            unify(p, v, bindings) for p, v in zip(pattern, value, strict=True))
    return bool(pattern == value)


def template(items: Sequence[Term]) -> tuple[tuple[Term, ...], tuple[int, ...]]:
    """A pattern and the positions of its variables and list terms with variables."""
    pattern = tuple(items)
    return pattern, tuple(i for i, item in enumerate(pattern)
                          if is_variable(item) or (isinstance(item, tuple)
                                                   and not is_ground(item)))


def ground(pattern: Sequence[Term], bindings: Mapping[str, Term],
           positions: Sequence[int] | None = None) -> Atom:
    """An atom or task with every bound variable replaced by its value.

    ``positions`` (from ``template``) lists where the variables are; without it
    every item is checked.
    """
    if positions is None:
        return tuple(bindings.get(item, item) if is_variable(item) else item
                     for item in pattern)
    if not positions:
        return tuple(pattern)
    items = list(pattern)
    for i in positions:
        item = items[i]
        items[i] = bindings.get(item, item) if isinstance(item, str) else substitute(item, bindings)
    return tuple(items)


class AtomPattern(Expression):
    """An atom with variables, matched against the state and the axioms."""

    __slots__ = ("_constants", "_variables", "args", "computed", "predicate")

    def __init__(self, predicate: str, args: tuple[Term, ...], computed: bool = False) -> None:
        self.predicate = predicate
        self.args = args
        #: some argument is a ``(call ...)`` or a list term with variables
        self.computed = computed or any(isinstance(a, tuple) and not is_ground(a)
                                        for a in args)
        self._variables = tuple((i, a) for i, a in enumerate(args) if is_variable(a))
        self._constants = tuple((i + 1, a) for i, a in enumerate(args)
                                if not is_variable(a) and not isinstance(a, Call))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, AtomPattern) and (self.predicate, self.args) == (
            other.predicate, other.args)

    def __hash__(self) -> int:
        return hash((self.predicate, self.args))

    def __repr__(self) -> str:
        return f"AtomPattern({self.predicate!r}, {self.args!r})"

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        axioms = proof.axioms.get((self.predicate, len(self.args)))
        if self.computed or axioms:
            resolved = tuple(substitute(a, bindings) for a in self.args)
            yield from _match_state(proof.state, self.predicate, resolved, bindings)
            for axiom in axioms or ():
                yield from axiom.prove(proof, resolved, bindings)
            return
        # The common case, kept fast: variables known by position.
        free: list[tuple[int, str]] = []
        bound = list(self._constants)
        for i, name in self._variables:
            value = bindings.get(name)
            if value is None:
                free.append((i + 1, name))
            else:
                bound.append((i + 1, value))
        state = proof.state
        if not free:
            wanted = [self.predicate, *self.args]
            for position, value in bound:
                wanted[position] = value
            if tuple(wanted) in state:
                yield bindings
            return
        for atom in state.candidates(self.predicate, len(self.args), bound):
            for position, value in bound:
                if atom[position] != value:
                    break
            else:
                new = dict(bindings)
                for position, name in free:
                    previous = new.get(name)
                    if previous is None:
                        new[name] = atom[position]
                    elif previous != atom[position]:
                        break
                else:
                    yield new

    def __str__(self) -> str:
        return "(" + " ".join(str(item) for item in (self.predicate, *self.args)) + ")"


def _match_state(state: State, predicate: str, resolved: tuple[Term, ...],
                 bindings: Bindings) -> Iterator[Bindings]:
    """The general matcher: any argument may be a variable or a list term with variables."""
    open_positions = [i for i, a in enumerate(resolved) if not is_ground(a)]
    if not open_positions:
        if (predicate, *resolved) in state:
            yield bindings
        return
    bound = [(i + 1, a) for i, a in enumerate(resolved) if i not in open_positions]
    for atom in state.candidates(predicate, len(resolved), bound):
        if any(atom[position] != value for position, value in bound):
            continue
        new = dict(bindings)
        if all(unify(resolved[i], atom[i + 1], new) for i in open_positions):
            yield new


@dataclass(frozen=True, slots=True)
class And(Expression):
    """Every part holds, bindings flowing left to right."""

    parts: tuple[Expression, ...]

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        return self._from(0, proof, bindings)

    def _from(self, index: int, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        if index == len(self.parts):
            yield bindings
            return
        if index == len(self.parts) - 1:
            yield from self.parts[index].solve(proof, bindings)
            return
        for extended in self.parts[index].solve(proof, bindings):
            yield from self._from(index + 1, proof, extended)


@dataclass(frozen=True, slots=True)
class Or(Expression):
    """Some part holds; the satisfiers of each part in turn."""

    parts: tuple[Expression, ...]

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        for part in self.parts:
            yield from part.solve(proof, bindings)


@dataclass(frozen=True, slots=True)
class Not(Expression):
    """Negation as failure: holds, binding nothing, when the part has no satisfier."""

    part: Expression

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        if not self.part.holds(proof, bindings):
            yield bindings


@dataclass(frozen=True, slots=True)
class First(Expression):
    """SHOP2's ``:first``: only the first satisfier of the part."""

    part: Expression

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        found = next(iter(self.part.solve(proof, bindings)), None)
        if found is not None:
            yield found


@dataclass(frozen=True, slots=True)
class ForAll(Expression):
    """``(forall (?v...) condition consequent)``: every satisfier of one satisfies the other."""

    condition: Expression
    consequent: Expression

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        for extended in self.condition.solve(proof, bindings):
            if not self.consequent.holds(proof, extended):
                return
        yield bindings


@dataclass(frozen=True, slots=True)
class Call(Expression):
    """``(call FUNCTION ARG...)``: a value in a term, a test in a precondition."""

    function: str
    args: tuple[Term, ...]

    def evaluate(self, bindings: Mapping[str, Term]) -> Any:
        values = [term(a, bindings) for a in self.args]
        if any(is_variable(v) for v in values):
            raise PlanningError(f"(call {self.function} ...) uses an unbound variable; bind "
                                "it earlier in the precondition")
        try:
            return FUNCTIONS[self.function](*values)
        except (TypeError, ValueError, ZeroDivisionError) as error:
            raise PlanningError(f"(call {self.function} {' '.join(map(str, values))}) "
                                f"failed: {error}") from None

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        if self.evaluate(bindings):
            yield bindings


@dataclass(frozen=True, slots=True)
class Assign(Expression):
    """``(assign ?v TERM)``: binds the variable (or checks an existing value)."""

    variable: str
    value: Term

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        value = term(self.value, bindings)
        previous = bindings.get(self.variable)
        if previous is None:
            yield {**bindings, self.variable: value}
        elif previous == value:
            yield bindings


@dataclass(frozen=True, slots=True)
class Axiom:
    """``(:- HEAD [name] TAIL ...)``: the first tail with a satisfier proves the head."""

    predicate: str
    args: tuple[Term, ...]
    branches: tuple[tuple[str, Expression], ...]

    def prove(self, proof: Proof, goal: tuple[Term, ...],
              bindings: Bindings) -> Iterator[Bindings]:
        """Bindings of the goal's free variables under which the head is derived."""
        local: Bindings = {}
        links: list[tuple[Term, Term]] = []
        for head, wanted in zip(self.args, goal, strict=True):
            if not is_ground(wanted):
                links.append((wanted, head))
            elif not unify(head, wanted, local):
                return
        for _, tail in self.branches:
            proved = False
            for solution in tail.solve(proof, local):
                proved = True
                if not links:
                    yield bindings
                    continue
                result = dict(bindings)
                for wanted, head in links:
                    value = substitute(head, solution)
                    if is_ground(value) and not unify(wanted, value, result):
                        break
                else:
                    yield result
            if proved:
                return


_SPECIAL = {"and", "or", "not", "imply", "forall", "call", "assign", ":first"}


def expression(data: Any) -> Expression:
    """Build an expression from plain data (see the module docstring); raises ``PlanningError``."""
    if data is None or data == "nil":
        return And(())
    if isinstance(data, str) or not isinstance(data, Sequence):
        raise PlanningError(f"expected an atom or a list of conditions, got '{data}'; "
                            "write (predicate arg...) or ((condition) (condition) ...)")
    items = list(data)
    if not items:
        return And(())
    head = items[0]
    if not isinstance(head, str):
        return _conjunction(items)
    keyword = head.lower()
    if keyword not in _SPECIAL:
        if head == "nil" and len(items) == 1:
            return And(())
        for item in items[1:]:
            _check_term(item, head)
        args = tuple(_term_data(item) for item in items[1:])
        return AtomPattern(head, args, any(isinstance(a, Call) for a in args))
    rest = items[1:]
    if keyword == "and":
        return _conjunction(rest)
    if keyword == ":first":
        return First(_conjunction(rest))
    if keyword == "or":
        return Or(tuple(expression(item) for item in rest))
    if keyword == "not":
        _arity(keyword, rest, 1)
        return Not(expression(rest[0]))
    if keyword == "imply":
        _arity(keyword, rest, 2)
        return Or((Not(expression(rest[0])), expression(rest[1])))
    if keyword == "forall":
        _arity(keyword, rest, 3)
        return ForAll(expression(rest[1]), expression(rest[2]))
    if keyword == "assign":
        _arity(keyword, rest, 2)
        if not is_variable(rest[0]):
            raise PlanningError(f"assign needs a variable first, got '{rest[0]}'")
        return Assign(rest[0], _term_data(rest[1]))
    return call(rest)


def call(rest: Sequence[Any]) -> Call:
    """``(call FUNCTION ARG...)`` from its items after ``call``."""
    if not rest or not isinstance(rest[0], str):
        raise PlanningError("call needs a function name: (call + ?x 1)")
    name = rest[0][2:] if rest[0].startswith("#'") else rest[0]
    if name not in FUNCTIONS:
        raise PlanningError(f"unknown function '{name}' in call; known: "
                            f"{' '.join(sorted(FUNCTIONS))}")
    return Call(name, tuple(_term_data(item) for item in rest[1:]))


def _conjunction(items: Sequence[Any]) -> Expression:
    parts = tuple(expression(item) for item in items)
    return parts[0] if len(parts) == 1 else And(parts)


def _arity(keyword: str, rest: Sequence[Any], count: int) -> None:
    if len(rest) != count:
        raise PlanningError(f"'{keyword}' takes {count} argument{'s' * (count > 1)}, "
                            f"got {len(rest)}")


def _check_term(item: Any, predicate: str) -> None:
    if isinstance(item, str | int | float | Sequence):
        return
    raise PlanningError(f"the arguments of ({predicate} ...) must be names, numbers, "
                        f"variables or lists, got '{item}'")


def _term_data(item: Any) -> Term:
    if isinstance(item, Sequence) and not isinstance(item, str) and item and item[0] == "call":
        return call(item[1:])
    return list_term(item)


def list_term(item: Any) -> Term:
    """A term from plain data: lists become tuples (list terms), ``nil`` the empty list."""
    if item == "nil":
        return ()
    if isinstance(item, str | int | float):
        return item
    if isinstance(item, Sequence):
        items = tuple(list_term(part) for part in item)
        if "." in items[:-2] or (items[-1:] == (".",)):
            raise PlanningError(f"a dotted list is (item ... . ?rest), got '{item}'")
        return items
    raise PlanningError(f"expected a name, number, variable or list, got '{item}'")
