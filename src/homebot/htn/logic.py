"""Logical expressions of SHOP2 preconditions and axioms, and their satisfiers in a state.

A precondition is built from plain data, the same for Python domains and for
JSHOP2 files: a sequence whose first item is a string is an atom ``("at", "?r",
"?p")`` or a special form (``and``, ``or``, ``not``, ``imply``, ``forall``,
``call``, ``assign``, ``:first``, ``:sort-by``); any other sequence (or ``nil``) is a
conjunction. ``solve`` yields every binding (a dict from variable to value)
under which the expression holds, lazily, in the order of the state.

``call`` knows JSHOP2's standard library (``FUNCTIONS``: ``+ - * / ^ < <= > >= = !=
member``, comparisons chained over every argument as JSHOP2's do) and any function a
domain is given (``homebot plan --functions FILE.py``), looked up case-insensitively. A
call holds as a precondition unless it returns false, None or the empty list (``nil``),
as in JSHOP2, where 0 is true.
"""

from __future__ import annotations

import operator as op
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cmp_to_key
from itertools import pairwise
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
    "Functions",
    "Not",
    "Or",
    "Proof",
    "SortBy",
    "expression",
    "ground",
    "is_ground",
    "list_term",
    "substitute",
    "template",
    "term",
    "term_data",
    "term_text",
    "unify",
]

Bindings = dict[str, Term]
Functions = Mapping[str, Callable[..., Any]]  #: function names (lower case) to callables


def _product(values: Sequence[Any]) -> Any:
    result = 1
    for value in values:
        result *= value
    return result


def _fold(function: Callable[[Any, Any], Any]) -> Callable[..., Any]:
    def folded(first: Any, *rest: Any) -> Any:
        for value in rest:
            first = function(first, value)
        return first
    return folded


def _chain(relation: Callable[[Any, Any], Any]) -> Callable[..., bool]:
    """A comparison over every neighbouring pair, as JSHOP2's ``(call < 1 2 3)``."""
    def chained(*values: Any) -> bool:
        return all(relation(a, b) for a, b in pairwise(values))
    return chained


def _member(value: Any, items: Any) -> bool:
    return isinstance(items, tuple) and value in items


#: The functions ``call`` knows: JSHOP2's standard library and a few of Lisp's.
FUNCTIONS: Functions = {
    "+": lambda *values: sum(values), "-": lambda a, *b: a - sum(b) if b else -a,
    "*": lambda *values: _product(values), "/": _fold(op.truediv), "^": _fold(op.pow),
    "<": _chain(op.lt), ">": _chain(op.gt), "<=": _chain(op.le), ">=": _chain(op.ge),
    "=": _chain(op.eq), "!=": _chain(op.ne), "/=": _chain(op.ne), "eq": op.eq,
    "equal": op.eq, "member": _member, "max": max, "min": min, "abs": abs,
}


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
    if isinstance(value, tuple):
        return substitute(value, bindings)
    return value


def term_text(value: Term) -> str:
    """A term as JSHOP2 writes it: a list term ``(a b . c)``, the empty list ``nil``."""
    if isinstance(value, tuple):
        return "(" + " ".join(term_text(item) for item in value) + ")" if value else "nil"
    if isinstance(value, Call):
        return "(call " + " ".join(term_text(a) for a in (value.function, *value.args)) + ")"
    return str(value)


def is_ground(value: Term) -> bool:
    """Whether a term has no variables (list terms are looked into)."""
    if isinstance(value, tuple):
        for item in value:
            if isinstance(item, str):
                if item[:1] == "?":
                    return False
            elif (isinstance(item, tuple) and not is_ground(item)) or isinstance(item, Call):
                return False
        return True
    return not ((isinstance(value, str) and value[:1] == "?") or isinstance(value, Call))


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
                          if is_variable(item) or isinstance(item, Call) or (
                              isinstance(item, tuple) and not is_ground(item)))


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
        return "(" + " ".join(term_text(item) for item in (self.predicate, *self.args)) + ")"


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
class SortBy(Expression):
    """JSHOP2's ``(:sort-by ?v [<|>|COMPARATOR] EXPR)``: every satisfier, sorted by ``?v``.

    ``compare`` is None for ascending numbers (``<``, the default), or a function
    ``(a, b) -> int`` over two values of the variable (``>`` is descending).
    """

    variable: str
    compare: Callable[[Any, Any], int] | None
    part: Expression

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        found = list(self.part.solve(proof, bindings))
        variable = self.variable
        if self.compare is None:
            found.sort(key=lambda solution: solution.get(variable, 0))
        else:
            compare = self.compare
            found.sort(key=cmp_to_key(lambda a, b: compare(a.get(variable), b.get(variable))))
        yield from found


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
    run: Callable[..., Any] = field(default=_product, compare=False, repr=False)

    def evaluate(self, bindings: Mapping[str, Term]) -> Any:
        values = [substitute(a, bindings) for a in self.args]
        try:
            # An unbound variable is passed as it is, as JSHOP2 does: (call = 4 ?x) is
            # false; arithmetic on it is an error.
            return self.run(*values)
        except (TypeError, ValueError, ZeroDivisionError, OverflowError) as error:
            if any(not is_ground(v) for v in values):
                raise PlanningError(f"(call {self.function} ...) uses an unbound variable; "
                                    "bind it earlier in the precondition") from None
            raise PlanningError(f"(call {self.function} {' '.join(map(str, values))}) "
                                f"failed: {error}") from None

    def solve(self, proof: Proof, bindings: Bindings) -> Iterator[Bindings]:
        value = self.evaluate(bindings)
        if value is not None and value is not False and value != () and value != "nil":
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
            if not _link(head, wanted, local, links):
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


def _link(head: Term, wanted: Term, local: Bindings, links: list[tuple[Term, Term]]) -> bool:
    """Match an axiom's head argument with a goal's: ground parts bind the head's variables,
    the goal's variables are linked to what the head makes of them (calls are evaluated)."""
    if isinstance(head, Call):
        head = head.evaluate(local)
    if is_ground(wanted):
        return unify(head, wanted, local)
    if (isinstance(wanted, tuple) and isinstance(head, tuple) and len(head) == len(wanted)
            and "." not in head and "." not in wanted):
        return all(_link(h, w, local, links) for h, w in zip(head, wanted, strict=True))
    links.append((wanted, head))
    return True


_SPECIAL = {"and", "or", "not", "imply", "forall", "call", "assign", ":first", ":sort-by"}


def expression(data: Any, functions: Functions | None = None) -> Expression:
    """Build an expression from plain data (see the module docstring); raises ``PlanningError``.

    ``functions`` adds to (or overrides) ``FUNCTIONS`` for ``call``.
    """
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
        return _conjunction(items, functions)
    keyword = head.lower()
    if keyword not in _SPECIAL:
        if head == "nil" and len(items) == 1:
            return And(())
        for item in items[1:]:
            _check_term(item, head)
        args = tuple(term_data(item, functions) for item in items[1:])
        return AtomPattern(head, args, any(isinstance(a, Call) for a in args))
    rest = items[1:]
    if keyword == "and":
        return _conjunction(rest, functions)
    if keyword == ":first":
        return First(_conjunction(rest, functions))
    if keyword == ":sort-by":
        return _sort_by(rest, functions)
    if keyword == "or":
        return Or(tuple(expression(item, functions) for item in rest))
    if keyword == "not":
        _arity(keyword, rest, 1)
        return Not(expression(rest[0], functions))
    if keyword == "imply":
        _arity(keyword, rest, 2)
        return Or((Not(expression(rest[0], functions)), expression(rest[1], functions)))
    if keyword == "forall":
        _arity(keyword, rest, 3)
        return ForAll(expression(rest[1], functions), expression(rest[2], functions))
    if keyword == "assign":
        _arity(keyword, rest, 2)
        if not is_variable(rest[0]):
            raise PlanningError(f"assign needs a variable first, got '{rest[0]}'")
        return Assign(rest[0], term_data(rest[1], functions))
    return call(rest, functions)


def _function(name: str, functions: Functions | None) -> Callable[..., Any]:
    """The function called ``name`` (case-insensitively), or ``PlanningError`` naming them all."""
    name = name[2:] if name.startswith("#'") else name
    for table in (functions or {}, FUNCTIONS):
        found = table.get(name, table.get(name.lower()))
        if found is not None:
            return found
    known = sorted({*FUNCTIONS, *(functions or {})})
    raise PlanningError(f"unknown function '{name}' in call; known: {' '.join(known)}; define "
                        "others in a Python file given with --functions")


def call(rest: Sequence[Any], functions: Functions | None = None) -> Call:
    """``(call FUNCTION ARG...)`` from its items after ``call``."""
    if not rest or not isinstance(rest[0], str):
        raise PlanningError("call needs a function name: (call + ?x 1)")
    run = _function(rest[0], functions)
    name = rest[0][2:] if rest[0].startswith("#'") else rest[0]
    return Call(name, tuple(term_data(item, functions) for item in rest[1:]), run)


def _sort_by(rest: Sequence[Any], functions: Functions | None) -> SortBy:
    if len(rest) not in (2, 3) or not is_variable(rest[0]):
        raise PlanningError("write (:sort-by ?VARIABLE [< | > | COMPARATOR] CONDITION)")
    compare: Callable[[Any, Any], int] | None = None
    if len(rest) == 3:
        name = rest[1]
        if not isinstance(name, str):
            raise PlanningError(f":sort-by takes <, > or a comparator's name, got '{name}'")
        if name == ">":
            compare = _descending
        elif name != "<":
            compare = _function(name, functions)
    return SortBy(rest[0], compare, expression(rest[-1], functions))


def _descending(a: Any, b: Any) -> int:
    return -1 if a > b else 1 if a < b else 0


def _conjunction(items: Sequence[Any], functions: Functions | None = None) -> Expression:
    parts = tuple(expression(item, functions) for item in items)
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


def term_data(item: Any, functions: Functions | None = None) -> Term:
    """A term from plain data; ``(call F ARG...)`` is a call (see ``list_term``)."""
    if isinstance(item, Sequence) and not isinstance(item, str) and item and item[0] == "call":
        return call(item[1:], functions)
    return list_term(item, functions)


def list_term(item: Any, functions: Functions | None = None) -> Term:
    """A term from plain data: lists become tuples (list terms), ``nil`` the empty list.

    A ``(call ...)`` inside a list is a call, evaluated when the list is used.
    """
    if item == "nil":
        return ()
    if isinstance(item, str | int | float | Call):
        return item
    if isinstance(item, Sequence):
        items = tuple(term_data(part, functions) for part in item)
        if "." in items[:-2] or (items[-1:] == (".",)):
            raise PlanningError(f"a dotted list is (item ... . ?rest), got '{item}'")
        return items
    raise PlanningError(f"expected a name, number, variable or list, got '{item}'")
