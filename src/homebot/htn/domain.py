"""``Domain``: operators, methods and axioms of an HTN domain, declared as data.

####  The model, as in SHOP2/JSHOP2

An operator ``(!name ?p...)`` has a precondition, a delete list, an add list and
a cost, all declared, so the executive can predict every effect and check it.
Operators whose names start with ``!!`` are internal (bookkeeping): planned but
not executed. A method for a task has one or more branches, each a precondition
and an ordered list of subtasks; the branches of one method are if-then-else
(a later branch is tried only when no earlier precondition holds), while the
several methods of one task are alternatives tried in order with backtracking.
An axiom derives a predicate from the state.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from homebot.errors import PlanningError
from homebot.htn.logic import (
    Axiom,
    Call,
    Expression,
    Functions,
    Proof,
    expression,
    ground,
    is_ground,
    substitute,
    template,
    term,
    term_data,
    term_text,
    unify,
)
from homebot.htn.state import Atom, Term, is_variable

__all__ = ["Branch", "Domain", "Layout", "Method", "Operator", "Problem", "task_data"]

#: How a task list is ordered, for JSHOP2's ``:unordered`` and ``:immediate``:
#: ``("ordered" | "unordered", (item, ...))``, an item being ``("task", INDEX, IMMEDIATE)``
#: (INDEX into the flat list of subtasks) or a nested layout. None: plainly ordered.
Layout = tuple[str, tuple[Any, ...]]


def _name_and_params(head: Sequence[Any], what: str) -> tuple[str, tuple[Term, ...]]:
    if not isinstance(head, str | Sequence):
        raise PlanningError(f"a {what} head is (NAME ?param ...), got '{head}'")
    items = list(head) if not isinstance(head, str) else head.split()
    if not items or not isinstance(items[0], str):
        raise PlanningError(f"a {what} head is (NAME ?param ...), got '{head}'")
    return items[0], tuple(term_data(item) for item in items[1:])


def _positions(patterns: tuple[Any, ...]) -> tuple[tuple[int, ...], ...]:
    return tuple(template(pattern)[1] if isinstance(pattern, tuple) else ()
                 for pattern in patterns)


def _bind_head(params: tuple[Term, ...], variables: tuple[bool, ...],
               task: Atom) -> dict[str, Term] | None:
    """Bindings that make a head with ``params`` match the ground task, or None."""
    if len(params) != len(task) - 1:
        return None
    bindings: dict[str, Term] = {}
    for param, variable, value in zip(params, variables, task[1:], strict=True):
        if variable:
            previous = bindings.get(param)
            if previous is None:
                bindings[param] = value
            elif previous != value:
                return None
        elif isinstance(param, tuple):
            if not unify(param, value, bindings):
                return None
        elif param != value:
            return None
    return bindings


def task_data(task: Sequence[Any], functions: Functions | None = None) -> tuple[Term, ...]:
    """A task or atom from plain data: names, numbers, variables, lists (``nil`` is ``()``).

    An argument ``(call F ARG...)`` is a call, evaluated when the task or atom is made
    ground (``functions`` adds to the functions it may name).
    """
    if not isinstance(task, str | Sequence):
        raise PlanningError(f"a task is (NAME ARG...), got '{task}'")
    items = tuple(task.split()) if isinstance(task, str) else tuple(task)
    if not items or not isinstance(items[0], str):
        raise PlanningError(f"a task is (NAME ARG...), got '{task}'")
    return (items[0], *(term_data(item, functions) for item in items[1:]))


@dataclass(frozen=True)
class Operator:
    """A primitive task: precondition, delete and add lists (atoms with variables), cost.

    Preconditions: ``precondition``. Effects: ``delete`` then ``add``.
    """

    name: str
    params: tuple[Term, ...]
    precondition: Expression
    delete: tuple[Any, ...] = ()  #: atom patterns, or variables bound to lists of atoms
    add: tuple[Any, ...] = ()
    cost: Term = 1.0
    _delete_variables: tuple[tuple[int, ...], ...] = field(init=False, repr=False,
                                                            compare=False)
    _add_variables: tuple[tuple[int, ...], ...] = field(init=False, repr=False, compare=False)
    _param_variables: tuple[bool, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_delete_variables", _positions(self.delete))
        object.__setattr__(self, "_add_variables", _positions(self.add))
        object.__setattr__(self, "_param_variables", tuple(map(is_variable, self.params)))

    def effects(self, bindings: dict[str, Term]) -> tuple[list[Atom], list[Atom]]:
        """The ground delete and add lists under ``bindings`` (atoms only: no forall)."""
        return (_effect_atoms(self.name, self.delete, self._delete_variables, bindings),
                _effect_atoms(self.name, self.add, self._add_variables, bindings))

    def apply(self, proof: Proof, bindings: dict[str, Term]
              ) -> tuple[list[Atom], list[Atom]] | None:
        """Apply the effects to ``proof.state``: the atoms deleted and added, as JSHOP2 does.

        The delete list goes first, then the add list, each element in order; a
        ``forall`` effect is evaluated in the state as it is when its turn comes. None
        (with the state partly changed: the caller undoes it) when the operator would
        delete a protected atom.
        """
        state = proof.state
        deletes: list[Atom] = []
        for pattern, where in zip(self.delete, self._delete_variables, strict=True):
            if isinstance(pattern, Protection):
                state.unprotect(pattern.atom(self.name, bindings))
                continue
            for atom in _element_atoms(self.name, pattern, where, proof, bindings):
                if state.is_protected(atom):
                    return None
                if atom in state:
                    state.remove(atom)
                    deletes.append(atom)
        adds: list[Atom] = []
        for pattern, where in zip(self.add, self._add_variables, strict=True):
            if isinstance(pattern, Protection):
                state.protect(pattern.atom(self.name, bindings))
                continue
            for atom in _element_atoms(self.name, pattern, where, proof, bindings):
                if atom not in state:
                    state.add(atom)
                    adds.append(atom)
        return deletes, adds

    @classmethod
    def declare(cls, head: Sequence[Any], precondition: Any = (), delete: Iterable[Any] = (),
                add: Iterable[Any] = (), cost: Any = 1.0,
                functions: Functions | None = None) -> Operator:
        """An operator from plain data: ``Operator.declare(("!pickup", "?o"), [...], ...)``.

        An effect element is an atom, a variable bound to an atom or to a list of
        atoms, ``(forall (?v...) CONDITION (ATOM...))`` or ``(:protection ATOM)``.
        """
        name, params = _name_and_params(head, "operator")
        if not name.startswith("!"):
            raise PlanningError(f"operator '{name}' must start with '!' (e.g. '!{name}')")
        cost_term: Term = cost
        if isinstance(cost, Sequence) and not isinstance(cost, str):
            made = expression(cost, functions)
            if not isinstance(made, Call):
                raise PlanningError(f"the cost of '{name}' must be a number, a variable or "
                                    "(call ...)")
            cost_term = made
        elif not isinstance(cost, int | float) and not is_variable(cost):
            raise PlanningError(f"the cost of '{name}' must be a number, got '{cost}'")
        return cls(name, params, expression(precondition, functions),
                   _effect_list(name, delete, functions), _effect_list(name, add, functions),
                   cost_term)

    @property
    def internal(self) -> bool:
        """Internal (``!!``) operators are planned for bookkeeping and never executed."""
        return self.name.startswith("!!")

    def bind(self, task: Atom) -> dict[str, Term] | None:
        return _bind_head(self.params, self._param_variables, task)

    def cost_of(self, bindings: dict[str, Term]) -> float:
        value = term(self.cost, bindings)
        if not isinstance(value, int | float):
            raise PlanningError(f"the cost of '{self.name}' is not a number: '{value}'")
        return float(value)


@dataclass(frozen=True)
class ForAllEffect:
    """``(forall (?v...) CONDITION (ATOM...))`` in a delete or add list."""

    condition: Expression
    atoms: tuple[tuple[Term, ...], ...]


@dataclass(frozen=True)
class Protection:
    """``(:protection ATOM)``: protects the atom (add list) or lifts a protection (delete)."""

    pattern: Any  #: an atom pattern, or a variable bound to an atom

    def atom(self, operator: str, bindings: dict[str, Term]) -> Atom:
        value = substitute(self.pattern, bindings)
        if not isinstance(value, tuple) or not value or not is_ground(value):
            raise PlanningError(f"operator '{operator}': (:protection {self.pattern}) needs a "
                                f"ground atom, got '{value}'")
        return value


def _effect_list(operator: str, data: Any, functions: Functions | None = None
                 ) -> tuple[Any, ...]:
    """Effect elements; a variable stands for an atom or a list of atoms bound by then."""
    if is_variable(data):
        return (data,)
    effects: list[Any] = []
    for atom in _atoms(data):
        if is_variable(atom):
            effects.append(atom)
            continue
        made = task_data(atom, functions)
        keyword = made[0].lower()
        if keyword == "forall":
            if len(made) != 4:
                raise PlanningError(f"operator '{operator}': write a forall effect as "
                                    "(forall (?v ...) CONDITION (ATOM ...))")
            effects.append(ForAllEffect(expression(atom[2], functions),
                                        tuple(task_data(a, functions) for a in _atoms(atom[3]))))
        elif keyword == ":protection":
            if len(made) != 2:
                raise PlanningError(f"operator '{operator}': write (:protection ATOM)")
            effects.append(Protection(made[1]))
        else:
            effects.append(made)
    return tuple(effects)


def _element_atoms(operator: str, pattern: Any, where: tuple[int, ...], proof: Proof,
                   bindings: dict[str, Term]) -> list[Atom]:
    """The ground atoms one effect element stands for under ``bindings``."""
    if isinstance(pattern, ForAllEffect):
        atoms: list[Atom] = []
        for solution in list(pattern.condition.solve(proof, bindings)):
            atoms.extend(_effect_atoms(operator, pattern.atoms, _positions(pattern.atoms),
                                       solution))
        return atoms
    return _effect_atoms(operator, (pattern,), (where,), bindings)


def _effect_atoms(operator: str, patterns: tuple[Any, ...], positions: tuple[tuple[int, ...], ...],
                  bindings: dict[str, Term]) -> list[Atom]:
    atoms: list[Atom] = []
    for pattern, where in zip(patterns, positions, strict=True):
        if isinstance(pattern, str):
            value = bindings.get(pattern)
            if isinstance(value, tuple) and value and isinstance(value[0], str) and is_ground(
                    value):
                atoms.append(value)  # one atom, as (!!assert (goal ?g)) with add list (?g)
                continue
            if not isinstance(value, tuple) or not all(
                    isinstance(atom, tuple) and atom for atom in value):
                raise PlanningError(f"operator '{operator}': {pattern} must be bound to an atom "
                                    f"or a list of atoms, got '{value}'")
            atoms.extend(value)
        else:
            atom = ground(pattern, bindings, where)
            # an open variable of a method (``?v#N``) may stay, as JSHOP2's VAR0 does
            if not all(is_ground(atom[i]) or "#" in str(atom[i]) for i in where):
                raise PlanningError(f"operator '{operator}' has an effect {atom} with an unbound"
                                    " variable; bind it in the head or the precondition")
            atoms.append(atom)
    return atoms


def _variables(data: Any) -> set[str]:
    """Every variable written anywhere in plain data."""
    if is_variable(data):
        return {data}
    if isinstance(data, str) or not isinstance(data, Iterable):
        return set()
    return set().union(*(_variables(item) for item in data))


def _atoms(data: Iterable[Any]) -> list[Any]:
    if data is None or data == "nil":
        return []
    if isinstance(data, str) or not isinstance(data, Sequence):
        raise PlanningError(f"expected a list of atoms or tasks, got '{data}'")
    return list(data)


@dataclass(frozen=True)
class Branch:
    """One branch of a method: a name, a precondition and ordered subtasks."""

    name: str
    precondition: Expression
    subtasks: tuple[tuple[Term, ...], ...]
    #: variables of the subtasks bound neither by the head nor by the precondition: left
    #: open, to be bound by a later operator (JSHOP2's propagation of bindings)
    open_variables: tuple[str, ...] = ()
    layout: Layout | None = None  #: None: the subtasks in order, none immediate
    _variables: tuple[tuple[int, ...], ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_variables", _positions(self.subtasks))

    def ground_subtasks(self, bindings: dict[str, Term]) -> list[tuple[Term, ...]]:
        """The subtasks under ``bindings``."""
        return [ground(task, bindings, positions)
                for task, positions in zip(self.subtasks, self._variables, strict=True)]


@dataclass(frozen=True)
class Method:
    """A way to decompose ``task``: if-then-else branches tried in order."""

    task: str
    params: tuple[Term, ...]
    branches: tuple[Branch, ...]
    _param_variables: tuple[bool, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_param_variables", tuple(map(is_variable, self.params)))

    @classmethod
    def declare(cls, head: Sequence[Any], *branches: tuple[Any, ...],
                functions: Functions | None = None, open_variables: bool = False) -> Method:
        """A method from plain data: ``Method.declare(("bring", "?o"), (name, pre, tasks))``.

        A subtask variable bound neither by the head nor by the precondition is an
        error, unless ``open_variables`` (JSHOP2 files): then a later operator binds it.
        """
        task, params = _name_and_params(head, "method")
        if task.startswith("!"):
            raise PlanningError(f"method head '{task}' names an operator; methods decompose "
                                "compound tasks (names without '!')")
        if not branches:
            raise PlanningError(f"method '{task}' needs at least one branch: "
                                "a precondition and a list of subtasks")
        built = []
        for index, (name, precondition, subtasks, *layout) in enumerate(branches):
            made = tuple(task_data(sub, functions) for sub in _atoms(subtasks))
            unbound = _variables(made) - _variables(params) - _variables(precondition)
            branch = Branch(name or f"{task}-{index + 1}", expression(precondition, functions),
                            made, tuple(sorted(unbound)) if open_variables else (),
                            layout[0] if layout else None)
            if unbound and not open_variables:
                raise PlanningError(f"method '{task}' branch '{branch.name}': the subtasks use "
                                    f"{', '.join(sorted(unbound))}, bound neither by the head "
                                    "nor by the precondition; bind it there")
            built.append(branch)
        return cls(task, params, tuple(built))

    def bind(self, task: Atom) -> dict[str, Term] | None:
        return _bind_head(self.params, self._param_variables, task)


@dataclass
class Domain:
    """A named set of operators, methods (per task, in order) and axioms (per predicate)."""

    name: str
    operators: dict[str, Operator] = field(default_factory=dict)
    methods: dict[str, list[Method]] = field(default_factory=dict)
    axioms: dict[tuple[str, int], list[Axiom]] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)  #: what a reader accepted but may surprise

    #### declare

    def declare_operator(self, operator: Operator) -> Operator:
        """Add an operator; a second one with the same name raises ``PlanningError``."""
        if operator.name in self.operators:
            raise PlanningError(f"operator '{operator.name}' is declared twice; rename one")
        self.operators[operator.name] = operator
        return operator

    def declare_method(self, method: Method) -> Method:
        """Add a method after the task's other methods (tried in declaration order)."""
        self.methods.setdefault(method.task, []).append(method)
        return method

    def declare_axiom(self, head: Sequence[Any], *branches: tuple[str, Any],
                      functions: Functions | None = None) -> Axiom:
        """Add an axiom: ``declare_axiom(("same", "?x", "?x"), ("", ()))``."""
        predicate, params = _name_and_params(head, "axiom")
        axiom = Axiom(predicate, params, tuple(
            (name or f"{predicate}-{index + 1}", expression(tail, functions))
            for index, (name, tail) in enumerate(branches or (("", ()),))))
        self.axioms.setdefault((predicate, len(params)), []).append(axiom)
        return axiom

    def operator(self, head: Sequence[Any], precondition: Any = (), delete: Iterable[Any] = (),
                 add: Iterable[Any] = (), cost: Any = 1.0) -> Operator:
        """Declare an operator from plain data (see ``Operator.declare``)."""
        return self.declare_operator(Operator.declare(head, precondition, delete, add, cost))

    def method(self, head: Sequence[Any], *branches: tuple[str, Any, Iterable[Any]]) -> Method:
        """Declare a method from plain data (see ``Method.declare``)."""
        return self.declare_method(Method.declare(head, *branches))

    #### checks

    def is_task(self, name: str) -> bool:
        return name in self.operators or name in self.methods

    def check_task(self, task: Sequence[Any], where: str = "") -> None:
        """Raise ``PlanningError`` when ``task`` names neither an operator nor a method."""
        name = task[0] if task else ""
        if isinstance(name, str) and self.is_task(name):
            operator = self.operators.get(name)
            heads = [operator.params] if operator else [m.params for m in self.methods[name]]
            if len(task) - 1 not in {len(params) for params in heads}:
                prefix = f"{where}: " if where else ""
                forms = " or ".join(sorted({"(" + " ".join(map(str, (name, *params))) + ")"
                                            for params in heads}))
                raise PlanningError(f"{prefix}{_text(task)} has {len(task) - 1} argument(s); "
                                    f"'{name}' is {forms}")
            return
        known = sorted({*self.operators, *self.methods})
        guess = difflib.get_close_matches(str(name), known, n=1)
        hint = f"did you mean '{guess[0]}'?" if guess else (
            f"tasks of domain '{self.name}': {', '.join(known) or 'none'}")
        prefix = f"{where}: " if where else ""
        raise PlanningError(f"{prefix}'{name}' is neither an operator nor a method of domain "
                            f"'{self.name}'; {hint}")

    def check(self) -> None:
        """Every subtask of every method names a declared operator or method."""
        for methods in self.methods.values():
            for method in methods:
                for branch in method.branches:
                    for subtask in branch.subtasks:
                        self.check_task(subtask, f"method '{method.task}' branch '{branch.name}'")

    def __repr__(self) -> str:
        count = sum(len(m) for m in self.methods.values())
        return (f"Domain({self.name!r}: {len(self.operators)} operators, {count} methods, "
                f"{sum(len(a) for a in self.axioms.values())} axioms)")


@dataclass(frozen=True)
class Problem:
    """A planning problem: a name, its domain's name, initial atoms and the tasks to do."""

    name: str
    domain: str
    atoms: tuple[Atom, ...]
    tasks: tuple[tuple[Term, ...], ...]
    layout: Layout | None = None  #: how the tasks are ordered (None: in order)
    place: str = ""  #: where it was written (``file:line:column``)


def _text(task: Sequence[Any]) -> str:
    return "(" + " ".join(term_text(item) for item in task) + ")"
