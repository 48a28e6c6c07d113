"""JSHOP2 / SHOP2 domain and problem files: ``(defdomain ...)`` and ``(defproblem ...)``.

Supported: ``(:operator HEAD PRE DEL ADD [COST])`` (a delete or add list may be
a variable bound to a list of atoms, as SHOP2's ``!!assert ?g``), ``(:method HEAD
[NAME] PRE TASKS ...)``, ``(:- HEAD [NAME] TAIL ...)``, preconditions with
``and``, ``or``, ``not``, ``imply``, ``forall``, ``call``, ``assign`` and
``:first``, list terms with dotted tails (``(?first . ?rest)``; ``nil`` is the
empty list), task lists with an optional ``:ordered`` and tasks with an optional
``:task`` (SHOP2's ``(:task NAME ARG...)``). Not supported
(total-order planning only): ``:unordered``, ``:sort-by``, ``:protection``,
``:immediate`` and ``forall`` in effects; each is reported with its line and
column. Every error names file, line and column. Symbols are case-sensitive.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from homebot.errors import PlanningError
from homebot.htn.domain import Domain, Method, Operator, Problem, task_data
from homebot.htn.sexpr import Form, plain, read_forms

__all__ = ["read_domain", "read_domain_text", "read_problem_text", "read_problems"]

_UNSUPPORTED = {":unordered": "this planner is total-order; list the subtasks in order",
                ":sort-by": "order the alternatives in the state, or use :first",
                ":protection": "protections are not supported; drop them",
                ":immediate": "drop :immediate; tasks run in the order listed"}

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
    data = plain(value)
    if data == "nil" or data == []:
        return []
    if not isinstance(data, list):
        raise PlanningError(f"a task list is ((task ...) ...), got '{data}'")
    if data and isinstance(data[0], str) and data[0].lower() == ":ordered":
        data = data[1:]
    if data and isinstance(data[0], str):
        data = [data]  # a single task written without the outer list
    # SHOP2 may mark each task (:task NAME ARG...)
    return [task[1:] if isinstance(task, list) and task and isinstance(task[0], str)
            and task[0].lower() == ":task" else task for task in data]


def _operator(form: Form, source: str) -> Operator:
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
               plain(head), plain(items[2]), plain(items[3]), plain(items[4]), cost)


def _method(form: Form, source: str) -> Method:
    head = _head(form, source, ":method")
    rest = list(form.items[2:])
    branches: list[tuple[str, Any, Any]] = []
    while rest:
        name = ""
        if isinstance(rest[0], str) and rest[0] != "nil":
            name = rest.pop(0)
        if len(rest) < 2:
            raise PlanningError(f"{form.where(source)}: method branch "
                                f"{name or len(branches) + 1} needs a precondition and a task "
                                "list")
        precondition, tasks = rest.pop(0), rest.pop(0)
        branches.append((name, _at(precondition, source, plain, precondition),
                         _at(tasks, source, _tasks, tasks)))
    if not branches:
        raise PlanningError(f"{form.where(source)}: (:method HEAD [NAME] PRECONDITION TASKS ...)"
                            " needs at least one precondition and task list")
    return _at(form, source, Method.declare, plain(head), *branches)


def _axiom(form: Form, source: str, domain: Domain) -> None:
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
    _at(form, source, domain.declare_axiom, plain(head), *branches)


def _domain(form: Form, source: str) -> Domain:
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
            operator = _operator(item, source)
            _at(item, source, domain.declare_operator, operator)
        elif keyword == ":method":
            methods.append((domain.declare_method(_method(item, source)), item))
        elif keyword == ":-":
            _axiom(item, source, domain)
        else:
            raise PlanningError(f"{item.where(source)}: unknown domain item '{item.items[0]}';"
                                " use :operator, :method or :-")
    for method, method_form in methods:
        for branch in method.branches:
            for subtask in branch.subtasks:
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
    return Problem(items[1], items[2],
                   tuple(_at(atoms_form, source, task_data, atom) for atom in atoms),
                   tuple(_at(tasks_form, source, task_data, task)
                         for task in _at(tasks_form, source, _tasks, tasks_form)))


def _forms(text: str, source: str) -> list[Form]:
    forms = read_forms(text, source)
    for form in forms:
        if not isinstance(form, Form) or not form.items or not isinstance(form.items[0], str):
            raise PlanningError(f"{source}: expected (defdomain ...) or (defproblem ...) at the "
                                f"top level, got '{plain(form)}'")
    return forms


def read_domain_text(text: str, source: str = "<domain>") -> Domain:
    """The one ``(defdomain ...)`` in ``text``."""
    domains = [f for f in _forms(text, source) if f.items[0].lower() == "defdomain"]
    if len(domains) != 1:
        raise PlanningError(f"{source}: expected exactly one (defdomain NAME (...)), found "
                            f"{len(domains)}")
    return _domain(domains[0], source)


def read_problem_text(text: str, source: str = "<problem>") -> list[Problem]:
    """Every ``(defproblem ...)`` in ``text``."""
    return [_problem(f, source) for f in _forms(text, source)
            if f.items[0].lower() == "defproblem"]


def _read(path: str | Path) -> str:
    try:
        return Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise PlanningError(f"cannot read '{path}': {error}; check the path") from None


def read_domain(path: str | Path) -> Domain:
    """Read a JSHOP2 domain file."""
    return read_domain_text(_read(path), str(path))


def read_problems(path: str | Path) -> list[Problem]:
    """Read the problems of a JSHOP2 problem file."""
    return read_problem_text(_read(path), str(path))
