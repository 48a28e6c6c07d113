"""The SHOP2-style total-order HTN planner: refinement, plan search and its bounds.

Laid out as GTPyhop's ``gtpyhop.py``: the state and domain come from
``htn.state`` and ``htn.domain``; here are refinement (operators and methods
applied to the first task of the agenda) and ``find_plan`` / ``find_plans`` /
``find_cheapest_plan``; the actor is ``htn.acting``. The search is iterative
depth-first with explicit choice points (no Python recursion, so a tidy-up of
hundreds of objects does not hit the recursion limit) over one state changed in
place and undone on backtracking.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from homebot.errors import PlanningError
from homebot.htn.domain import Domain, Layout, task_data
from homebot.htn.logic import Axiom, substitute, term_text
from homebot.htn.state import Atom, State, Term, is_variable

__all__ = ["DEEPEST_DECOMPOSITION", "DecompositionNode", "Plan", "PlanStep", "Planner",
           "PlanningResult", "find_cheapest_plan", "find_plan", "find_plans"]

#: The largest ``max_depth`` a planner takes (and its default). Each level of decomposition
#: holds a choice point of the depth-first search, about 4 KB: a recursive domain at this
#: depth takes some 400 MB, and a bound of 10^8 took 1.9 GB before the expansions ran out.
DEEPEST_DECOMPOSITION = 100_000

#### plans and task networks


@dataclass(frozen=True, slots=True)
class PlanStep:
    """One ground operator of a plan: its cost, its node in the decomposition tree, and the
    ground effects the planner predicts (what the executive checks after running it)."""

    operator: str
    args: tuple[Term, ...]
    cost: float = 1.0
    node: int = -1
    deletes: tuple[Atom, ...] = ()
    adds: tuple[Atom, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        return {"operator": self.operator, "args": list(self.args)}

    def __str__(self) -> str:
        return "(" + " ".join(term_text(item) for item in (self.operator, *self.args)) + ")"


@dataclass(frozen=True, slots=True)
class DecompositionNode:
    """A task in the task network: its parent node, the ground task, and how it was refined.

    ``how`` is the method branch's name for a compound task and None for an operator.
    """

    parent: int
    task: tuple[Term, ...]
    how: str | None


@dataclass(frozen=True)
class Plan:
    """A plan: operators in order, total cost, and the task network that produced it."""

    steps: tuple[PlanStep, ...]
    cost: float
    network: tuple[DecompositionNode, ...] = ()

    def __len__(self) -> int:
        return len(self.steps)

    def __iter__(self) -> Iterator[PlanStep]:
        return iter(self.steps)

    def actions(self) -> list[tuple[Term, ...]]:
        """The plan as GTPyhop prints one: a list of tuples."""
        return [(step.operator, *step.args) for step in self.steps]

    def to_dicts(self) -> list[dict[str, Any]]:
        return [step.to_dict() for step in self.steps]

    def __repr__(self) -> str:
        return f"Plan(cost={self.cost:g}, [{' '.join(str(step) for step in self.steps)}])"


@dataclass
class PlanningResult:
    """What a search found: plans, how many tasks it refined, and why it stopped early.

    ``stopped`` is None when the search space was explored as far as asked, else
    ``"depth"`` (a branch was cut at the depth bound), ``"expansions"``, ``"time"``
    or ``"plans"`` (enough plans found). True when there is at least one plan.
    """

    plans: list[Plan] = field(default_factory=list)
    expansions: int = 0
    stopped: str | None = None
    trace: list[str] | None = None  #: every refinement tried, with ``Planner(trace=True)``

    def __bool__(self) -> bool:
        return bool(self.plans)

    @property
    def plan(self) -> Plan | None:
        """The first plan found, if any."""
        return self.plans[0] if self.plans else None


#### refinement


class _Proof:
    """What expressions are evaluated against: the state and the domain's axioms.

    ``fresh`` numbers the variables a method leaves open in its subtasks (renamed
    ``?v#N`` so that two applications never share one).
    """

    __slots__ = ("axioms", "fresh", "state")

    def __init__(self, state: State,
                 axioms: Mapping[tuple[str, int], Sequence[Axiom]]) -> None:
        self.state = state
        self.axioms = axioms
        self.fresh = 0


# An agenda is a linked list of nodes (task, parent node, depth, rest, immediate), or None.
# JSHOP2's unordered task lists are group nodes (None, (agenda, ...), 0, rest, False): the
# first task of any of the group's agendas may go next (an immediate one goes first).
_Agenda = tuple[Any, Any, int, Any, bool] | None
_MISSING: Any = object()


def _firsts(agenda: _Agenda) -> list[Any]:
    """The task nodes that may be refined next, in JSHOP2's order (its ``getFirst``)."""
    found: list[Any] = []
    _collect(agenda, found)
    return found


def _collect(agenda: _Agenda, found: list[Any]) -> bool:
    """Add the first task nodes of ``agenda``; True when an immediate one decides alone."""
    while agenda is not None:
        if agenda[0] is not None:
            if agenda[4]:
                found.clear()
                found.append(agenda)
                return True
            found.append(agenda)
            return False
        before = len(found)
        for sub in agenda[1]:
            if _collect(sub, found):
                return True
        if len(found) != before:
            return False
        agenda = agenda[3]  # an exhausted group: the tasks after it
    return False


def _replace(agenda: _Agenda, target: Any, replacement: _Agenda) -> Any:
    """``agenda`` with the node ``target`` and its rest replaced (``_MISSING`` if absent)."""
    if agenda is None:
        return _MISSING
    if agenda is target:
        return replacement
    if agenda[0] is not None:
        return _MISSING  # only a first task can be the target
    subs = agenda[1]
    for index, sub in enumerate(subs):
        new = _replace(sub, target, replacement)
        if new is not _MISSING:
            changed = (*subs[:index], new, *subs[index + 1:])
            if all(item is None for item in changed):
                return agenda[3]
            return (None, changed, 0, agenda[3], False)
    rest = _replace(agenda[3], target, replacement)
    return rest if rest is _MISSING else (None, subs, 0, rest, False)


def _network_agenda(layout: Any, tasks: Sequence[tuple[Term, ...]], parent: int, depth: int,
                    rest: _Agenda) -> _Agenda:
    """The agenda of a task list laid out as ``layout`` (see ``Layout``), before ``rest``."""
    kind, items = layout
    if kind == "unordered":
        subs = tuple(agenda for agenda in (
            _network_agenda(("ordered", (item,)), tasks, parent, depth, None)
            for item in items) if agenda is not None)
        return (None, subs, 0, rest, False) if subs else rest
    agenda = rest
    for item in reversed(items):
        if item[0] == "task":
            agenda = (tasks[item[1]], parent, depth, agenda, item[2])
        else:
            agenda = _network_agenda(item, tasks, parent, depth, agenda)
    return agenda


class Planner:
    """Plans with one domain, within bounds.

    Args:
        domain: the HTN domain.
        max_depth: deepest decomposition (tasks below it are cut; ``stopped="depth"``).
        max_expansions: most task refinements per search (deterministic budget).
        time_limit: seconds of computing per search (None: no limit).
        clock: the clock for ``time_limit`` (``time.perf_counter`` unless given).
        trace: record every refinement tried in ``PlanningResult.trace`` (opt-in; it
            explains why no plan was found and never changes the search).
    """

    def __init__(self, domain: Domain, *, max_depth: int = DEEPEST_DECOMPOSITION,
                 max_expansions: int = 1_000_000, time_limit: float | None = None,
                 clock: Callable[[], float] = time.perf_counter, trace: bool = False) -> None:
        if not 1 <= max_depth <= DEEPEST_DECOMPOSITION:
            raise PlanningError(f"max_depth {max_depth}: give a depth from 1 to "
                                f"{DEEPEST_DECOMPOSITION:,}")
        self.domain = domain
        self.max_depth = max_depth
        self.max_expansions = max_expansions
        self.time_limit = time_limit
        self.clock = clock
        self.trace = trace

    def _refine(self, proof: _Proof, task: tuple[Term, ...], parent: int, depth: int,
                rest: _Agenda, plan: list[PlanStep], costs: list[float],
                network: list[DecompositionNode],
                trace: list[str] | None) -> Iterator[tuple[_Agenda, Any]]:
        """Every way to refine ``task``, each applied when asked for (undone by the caller).

        Each is the new agenda and its focus, what JSHOP2 refines next: after a method,
        the first of its subtasks (a node, or a list of nodes for unordered subtasks);
        after an operator, None (any first task of the whole agenda).
        """
        name = task[0]
        operator = self.domain.operators.get(name)
        state = proof.state
        if operator is not None:
            start = operator.bind(task)
            if start is None:
                return
            # A task argument that is still a variable is bound by the operator.
            links = [(param, value) for param, value in start.items() if is_variable(value)]
            for param, _ in links:
                del start[param]
            applied = False
            for bindings in operator.precondition.solve(proof, start):
                if links:  # what the precondition left unbound stays the task's variable
                    bindings = {**{param: variable for param, variable in links}, **bindings}
                mark = state.mark()
                effects = operator.apply(proof, bindings)
                if effects is None:  # it would delete a protected atom
                    state.undo(mark)
                    continue
                applied = True
                if trace is not None:
                    trace.append(f"{'  ' * depth}{_text(task)}: applied")
                deletes, adds = effects
                cost = operator.cost_of(bindings)
                done = task
                if links:  # the step shows the values; later tasks keep the variable,
                    # as in JSHOP2 (its propagation example plans (!consumer1 VAR0))
                    values = {variable: bindings[param] for param, variable in links
                              if param in bindings}
                    done = tuple(substitute(item, values) for item in task)
                network.append(DecompositionNode(parent, done, None))
                plan.append(PlanStep(name, done[1:], cost, len(network) - 1, tuple(deletes),
                                     tuple(adds)))
                costs.append(costs[-1] + cost)
                yield rest, None
            if trace is not None and not applied:
                trace.append(f"{'  ' * depth}{_text(task)}: precondition does not hold")
            return
        methods = self.domain.methods.get(name)
        if methods is None and not (isinstance(name, str) and name.startswith("!")):
            self.domain.check_task(task)  # an undeclared primitive task just never applies
        for method in methods or ():
            start = method.bind(task)
            if start is None:
                continue
            for branch in method.branches:
                applicable = False
                for bindings in branch.precondition.solve(proof, start):
                    applicable = True
                    if trace is not None:
                        trace.append(f"{'  ' * depth}{_text(task)}: {branch.name}")
                    network.append(DecompositionNode(parent, task, branch.name))
                    node = len(network) - 1
                    if branch.open_variables:
                        bindings = dict(bindings)
                        for variable in branch.open_variables:
                            if variable not in bindings:
                                proof.fresh += 1
                                bindings[variable] = f"{variable}#{proof.fresh}"
                    if branch.layout is None:
                        agenda = rest
                        for subtask in reversed(branch.ground_subtasks(bindings)):
                            agenda = (subtask, node, depth + 1, agenda, False)
                        # JSHOP2 goes on with the first subtask (all tasks when none)
                        yield agenda, agenda if branch.subtasks else None
                    else:
                        sub = _network_agenda(branch.layout, branch.ground_subtasks(bindings),
                                              node, depth + 1, None)
                        focus = _firsts(sub)
                        yield (None, (sub,), 0, rest, False) if sub is not None else rest, (
                            focus or None)
                if applicable:
                    break
                if trace is not None:
                    trace.append(f"{'  ' * depth}{_text(task)}: {branch.name} does not apply")

    def _refine_any(self, proof: _Proof, agenda: _Agenda, firsts: list[Any],
                    plan: list[PlanStep], costs: list[float], network: list[DecompositionNode],
                    trace: list[str] | None) -> Iterator[tuple[_Agenda, Any]]:
        """Every way to refine any of the first tasks of an agenda with unordered groups."""
        for node in firsts:
            task, parent, depth, rest, _ = node
            for tail, focus in self._refine(proof, task, parent, depth, rest, plan, costs,
                                            network, trace):
                yield _replace(agenda, node, tail), focus

    #### find_plan and seek_plan

    def search(self, state: State, tasks: Sequence[Sequence[Any]], *, limit: int | None = 1,
               cheapest: bool = False, layout: Layout | None = None) -> PlanningResult:
        """Plans for ``tasks`` from ``state`` (left unchanged).

        ``limit`` plans at most (None: every plan); ``cheapest`` keeps searching
        with branch and bound and returns only the cheapest plan. ``layout`` orders
        the tasks as a JSHOP2 problem's ``:unordered`` lists do (None: in order).
        """
        goal = [task_data(task) for task in tasks]
        for task in goal:
            self.domain.check_task(task, "goal")
            if any(is_variable(arg) for arg in task[1:]):
                raise PlanningError(f"goal task {task} has a variable; give every argument")
        result = PlanningResult(trace=[] if self.trace else None)
        proof = _Proof(state, self.domain.axioms)
        mark = state.mark()
        try:
            self._seek(proof, goal, result, limit, cheapest, layout)
        except RecursionError:  # the search is iterative: only a proof can recurse this deep
            raise PlanningError("proving a precondition recursed without end: an axiom proves "
                                "its head from itself (such as (:- (p ?x) ((p ?x)))); put a "
                                "condition that binds or fails before the recursive one") from None
        finally:
            state.undo(mark)
        return result

    def _seek(self, proof: _Proof, goal: list[tuple[Term, ...]], result: PlanningResult,
              limit: int | None, cheapest: bool, layout: Layout | None) -> None:
        state = proof.state
        agenda: _Agenda = None
        if layout is None:
            for task in reversed(goal):
                agenda = (task, -1, 0, agenda, False)
        else:
            agenda = _network_agenda(layout, goal, -1, 0, None)
        plan: list[PlanStep] = []
        costs: list[float] = [0.0]
        network: list[DecompositionNode] = []
        stack: list[tuple[Iterator[tuple[_Agenda, Any]], int, int, int]] = []
        focus: Any = None
        began = self.clock() if self.time_limit is not None else 0.0
        best = float("inf")
        while True:
            if agenda is None:
                if not cheapest or costs[-1] < best:
                    found = Plan(tuple(plan), costs[-1], tuple(network))
                    if cheapest:
                        best = costs[-1]
                        result.plans = [found]
                    else:
                        result.plans.append(found)
                        if limit is not None and len(result.plans) >= limit:
                            if stack:
                                result.stopped = "plans" if limit > 1 else None
                            return
            elif cheapest and costs[-1] >= best:
                pass  # branch and bound: this branch cannot beat the best plan
            elif focus is None and agenda[0] is None and not (candidates := _firsts(agenda)):
                agenda = None  # only exhausted groups are left: a plan
                continue
            else:
                firsts: list[Any] | None = None
                if focus is agenda or (focus is None and agenda[0] is not None):
                    task, parent, depth, rest, _ = agenda  # the common, ordered case
                else:  # unordered groups: one choice point over every possible first task
                    firsts = candidates if focus is None else (
                        focus if isinstance(focus, list) else [focus])
                    task, parent, depth, rest, _ = firsts[0]
                if depth > self.max_depth:
                    result.stopped = "depth"
                else:
                    result.expansions += 1
                    if result.expansions > self.max_expansions:
                        result.stopped = "expansions"
                        return
                    if self.time_limit is not None and not result.expansions & 255 and (
                            self.clock() - began > self.time_limit):
                        result.stopped = "time"
                        return
                    alternatives = (self._refine(proof, task, parent, depth, rest, plan, costs,
                                                 network, result.trace) if firsts is None else
                                    self._refine_any(proof, agenda, firsts, plan, costs,
                                                     network, result.trace))
                    stack.append((alternatives, state.mark(), len(plan), len(network)))
            while stack:
                alternatives, mark, planned, noted = stack[-1]
                state.undo(mark)
                del plan[planned:], costs[planned + 1:], network[noted:]
                chosen = next(alternatives, _EXHAUSTED)
                if chosen is not _EXHAUSTED:
                    agenda, focus = chosen
                    break
                stack.pop()
            else:
                return


_EXHAUSTED: Any = object()


def _text(task: Sequence[Any]) -> str:
    return "(" + " ".join(term_text(item) for item in task) + ")"


def find_plan(domain: Domain, state: State, tasks: Sequence[Sequence[Any]],
              **bounds: Any) -> PlanningResult:
    """The first plan SHOP2's depth-first search finds (``result.plan``), if any."""
    return Planner(domain, **bounds).search(state, tasks, limit=1)


def find_plans(domain: Domain, state: State, tasks: Sequence[Sequence[Any]],
               limit: int | None = None, **bounds: Any) -> PlanningResult:
    """Every plan (one per task network, as JSHOP2 counts them), up to ``limit``."""
    return Planner(domain, **bounds).search(state, tasks, limit=limit)


def find_cheapest_plan(domain: Domain, state: State, tasks: Sequence[Sequence[Any]],
                       **bounds: Any) -> PlanningResult:
    """The plan of least total cost (branch and bound over every plan)."""
    return Planner(domain, **bounds).search(state, tasks, limit=None, cheapest=True)
