"""JSHOP2 / SHOP2 domain and problem files: ``(defdomain ...)`` and ``(defproblem ...)``.

Supported, as JSHOP2 reads them (its ten example domains plan):

- ``(:operator HEAD PRE DEL ADD [COST])``. A delete or add list holds atoms,
  variables bound to an atom or to a list of atoms (``(!!assert ?g)`` with add list
  ``(?g)``), ``(forall (?v...) CONDITION (ATOM...))`` evaluated when the operator
  applies, and ``(:protection ATOM)`` (protect in the add list, lift in the delete
  list; an operator that would delete a protected atom does not apply). The whole
  list may be one variable bound to a list of atoms.
- ``(:method HEAD [NAME] PRE TASKS ...)``; a subtask variable bound neither by the
  head nor by the precondition is left open and bound by the first operator that
  binds it (JSHOP2's propagation), e.g. ``(!producer ?in ?out)`` with precondition
  ``((assign ?out v))``.
- ``(:- HEAD [NAME] TAIL ...)``; preconditions with ``and``, ``or``, ``not``,
  ``imply``, ``forall``, ``call``, ``assign``, ``:first`` and ``(:sort-by ?v [<|>|FN]
  EXPR)``; list terms with dotted tails (``(?first . ?rest)``; ``nil`` is the empty
  list); calls inside terms and lists.
- Task lists with ``:ordered``, ``:unordered`` (planned in the order written, which
  is the order JSHOP2 tries first; other orders are not tried on backtracking) and
  ``:immediate`` tasks (in a total order, the next task is already immediate); tasks
  may be marked ``(:task NAME ARG...)``.
- Symbols are case-insensitive, as in JSHOP2: every symbol is read in lower case.
- A primitive task a method names but no operator defines is allowed (JSHOP2 compiles
  it; it never applies): ``Domain.notes`` says which.
- ``call`` functions beyond JSHOP2's standard library (JSHOP2 takes them as Java
  classes) come from Python: ``read_domain(path, functions={"checknull": f})``, or
  ``homebot plan --functions FILE.py``.

Every error names file, line and column.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any, TypeVar

from homebot.errors import PlanningError
from homebot.files import read_text_file
from homebot.htn.domain import Domain, Layout, Method, Operator, Problem, task_data
from homebot.htn.logic import Functions
from homebot.htn.sexpr import Form, plain, read_forms

__all__ = ["read_domain", "read_domain_text", "read_problem_text", "read_problems"]

_UNSUPPORTED: dict[str, str] = {}

T = TypeVar("T")


def _at(form: Any, source: str, build: Callable[..., T], *args: Any) -> T:
    """Run ``build(*args)``; a ``PlanningError`` it raises is prefixed by the form's place."""
    try:
        return build(*args)
    except PlanningError as error:
        if isinstance(form, Form) and not str(error).startswith(source):
            raise PlanningError(f"{form.where(source)}: {error}") from None
        raise


def _check_unsupported(value: Any, source: str) -> None:
    if isinstance(value, Form):
        for item in value.items:
            if isinstance(item, str) and item.lower() in _UNSUPPORTED:
                raise PlanningError(f"{value.where(source)}: {item} is not supported; "
                                    f"{_UNSUPPORTED[item.lower()]}")
            _check_unsupported(item, source)


def _head(form: Form, source: str, keyword: str) -> Form:
    if len(form.items) < 2 or not isinstance(form.items[1], Form):
        raise PlanningError(f"{form.where(source)}: ({keyword} ...) needs a head such as "
                            "(name ?arg ...)")
    return form.items[1]


def _tasks(value: Any) -> list[Any]:
    return _network(value)[0]


def _network(value: Any) -> tuple[list[Any], Layout | None]:
    """A task list's tasks in the order written, and its layout (None: plainly ordered)."""
    data = plain(value)
    if data == "nil" or data == []:
        return [], None
    if not isinstance(data, list):
        raise PlanningError(f"a task list is ((task ...) ...), got '{data}'")
    tasks: list[Any] = []
    layout = _layout(data, tasks)
    plain_list = layout[0] == "ordered" and all(
        isinstance(item, tuple) and item[0] == "task" and not item[2] for item in layout[1])
    return tasks, None if plain_list else layout


def _layout(data: list[Any], tasks: list[Any]) -> Layout:
    """The layout of a task list (``:ordered`` / ``:unordered``, nested), tasks appended."""
    kind = "ordered"
    if data and isinstance(data[0], str) and data[0].lower() in (":ordered", ":unordered"):
        kind = data[0].lower()[1:]
        data = data[1:]
    if data and isinstance(data[0], str):
        data = [data]  # a single task written without the outer list
    items: list[Any] = []
    for item in data:
        if isinstance(item, list) and item and (isinstance(item[0], list) or (
                isinstance(item[0], str) and item[0].lower() in (":ordered", ":unordered"))):
            items.append(_layout(item, tasks))  # a nested task list
        else:
            task, immediate = _task(item)
            items.append(("task", len(tasks), immediate))
            tasks.append(task)
    return (kind, tuple(items))


def _task(task: Any) -> tuple[Any, bool]:
    """A task without SHOP2's ``:task`` and ``:immediate`` marks, and whether it is immediate."""
    immediate = False
    while isinstance(task, list) and task and isinstance(task[0], str) and task[0].lower() in (
            ":task", ":immediate"):
        immediate = immediate or task[0].lower() == ":immediate"
        task = task[1:]
    return task, immediate


def _operator(form: Form, source: str, functions: Functions | None) -> Operator:
    head = _head(form, source, ":operator")
    items = form.items
    if len(items) not in (5, 6):
        raise PlanningError(f"{form.where(source)}: (:operator HEAD PRECONDITION DELETE ADD "
                            f"[COST]) has 4 or 5 parts after :operator, got {len(items) - 1}")
    for part in items[2:5]:
        if not isinstance(part, Form) and part != "nil" and not (
                isinstance(part, str) and part.startswith("?")):
            raise PlanningError(f"{form.where(source)}: the precondition, delete and add lists "
                                f"of an operator are lists or nil, got '{part}'")
    cost = plain(items[5]) if len(items) == 6 else 1.0
    return _at(form, source, Operator.declare,
               plain(head), plain(items[2]), plain(items[3]), plain(items[4]), cost, functions)


def _method(form: Form, source: str, functions: Functions | None) -> Method:
    head = _head(form, source, ":method")
    rest = list(form.items[2:])
    branches: list[tuple[str, Any, Any, Layout | None]] = []
    while rest:
        name = ""
        if isinstance(rest[0], str) and rest[0] != "nil":
            name = rest.pop(0)
        if len(rest) < 2:
            raise PlanningError(f"{form.where(source)}: method branch "
                                f"{name or len(branches) + 1} needs a precondition and a task "
                                "list")
        precondition, tasks = rest.pop(0), rest.pop(0)
        subtasks, layout = _at(tasks, source, _network, tasks)
        branches.append((name, _at(precondition, source, plain, precondition), subtasks, layout))
    if not branches:
        raise PlanningError(f"{form.where(source)}: (:method HEAD [NAME] PRECONDITION TASKS ...)"
                            " needs at least one precondition and task list")
    return _at(form, source, partial(Method.declare, functions=functions, open_variables=True),
               plain(head), *branches)


def _axiom(form: Form, source: str, domain: Domain, functions: Functions | None) -> None:
    head = _head(form, source, ":-")
    rest = list(form.items[2:])
    branches: list[tuple[str, Any]] = []
    while rest:
        name = ""
        if isinstance(rest[0], str) and rest[0] != "nil":
            name = rest.pop(0)
            if not rest:
                raise PlanningError(f"{form.where(source)}: axiom branch '{name}' has no tail")
        branches.append((name, plain(rest.pop(0))))
    _at(form, source, partial(domain.declare_axiom, functions=functions), plain(head),
        *branches)


def _domain(form: Form, source: str, functions: Functions | None = None) -> Domain:
    items = form.items
    if len(items) != 3 or not isinstance(items[1], str) or not isinstance(items[2], Form):
        raise PlanningError(f"{form.where(source)}: write (defdomain NAME (ITEM ...)) with "
                            ":operator, :method and :- items")
    domain = Domain(items[1])
    methods: list[tuple[Method, Form]] = []
    for item in items[2].items:
        if not isinstance(item, Form) or not item.items or not isinstance(item.items[0], str):
            where = item.where(source) if isinstance(item, Form) else form.where(source)
            raise PlanningError(f"{where}: a domain item is (:operator ...), (:method ...) or "
                                f"(:- ...), got '{plain(item)}'")
        _check_unsupported(item, source)
        keyword = item.items[0].lower()
        if keyword == ":operator":
            operator = _operator(item, source, functions)
            _at(item, source, domain.declare_operator, operator)
        elif keyword == ":method":
            methods.append((domain.declare_method(_method(item, source, functions)), item))
        elif keyword == ":-":
            _axiom(item, source, domain, functions)
        else:
            raise PlanningError(f"{item.where(source)}: unknown domain item '{item.items[0]}';"
                                " use :operator, :method or :-")
    for method, method_form in methods:
        for branch in method.branches:
            for subtask in branch.subtasks:
                name = subtask[0]
                if isinstance(name, str) and name.startswith("!") and not domain.is_task(name):
                    # JSHOP2 compiles a primitive task without an operator; it never applies.
                    domain.notes.append(f"{method_form.where(source)}: method '{method.task}' "
                                        f"names {name}, which no operator defines; it never "
                                        "applies")
                    continue
                _at(method_form, source, domain.check_task, subtask,
                    f"method '{method.task}' branch '{branch.name}'")
    return domain


def _problem(form: Form, source: str) -> Problem:
    items = form.items
    if len(items) < 5 or not isinstance(items[1], str) or not isinstance(items[2], str):
        raise PlanningError(f"{form.where(source)}: write (defproblem NAME DOMAIN (ATOM ...) "
                            "(TASK ...))")
    _check_unsupported(form, source)
    atoms_form, tasks_form = items[3], items[4]
    atoms = [] if atoms_form == "nil" else plain(atoms_form)
    if not isinstance(atoms, list):
        raise PlanningError(f"{form.where(source)}: the initial state is a list of atoms")
    tasks, layout = _at(tasks_form, source, _network, tasks_form)
    return Problem(items[1], items[2],
                   tuple(_at(atoms_form, source, task_data, atom) for atom in atoms),
                   tuple(_at(tasks_form, source, task_data, task) for task in tasks), layout,
                   form.where(source))


def _forms(text: str, source: str) -> list[Form]:
    forms = read_forms(text, source, fold_case=True)
    for form in forms:
        if not isinstance(form, Form) or not form.items or not isinstance(form.items[0], str):
            raise PlanningError(f"{source}: expected (defdomain ...) or (defproblem ...) at the "
                                f"top level, got '{plain(form)}'")
    return forms


def read_domain_text(text: str, source: str = "<domain>",
                     functions: Functions | None = None) -> Domain:
    """The one ``(defdomain ...)`` in ``text``; ``functions`` adds to ``call``'s library."""
    domains = [f for f in _forms(text, source) if f.items[0].lower() == "defdomain"]
    if len(domains) != 1:
        raise PlanningError(f"{source}: expected exactly one (defdomain NAME (...)), found "
                            f"{len(domains)}")
    return _domain(domains[0], source, functions)


def read_problem_text(text: str, source: str = "<problem>") -> list[Problem]:
    """Every ``(defproblem ...)`` in ``text``."""
    return [_problem(f, source) for f in _forms(text, source)
            if f.items[0].lower() == "defproblem"]


def _read(path: str | Path) -> str:
    return read_text_file(path, PlanningError, "text", "JSHOP2 file")


def read_domain(path: str | Path, functions: Functions | None = None) -> Domain:
    """Read a JSHOP2 domain file; ``functions`` adds to ``call``'s library."""
    return read_domain_text(_read(path), str(path), functions)


def read_problems(path: str | Path) -> list[Problem]:
    """Read the problems of a JSHOP2 problem file."""
    return read_problem_text(_read(path), str(path))
