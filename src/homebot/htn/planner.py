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
from homebot.htn.domain import Domain, task_data
from homebot.htn.logic import Axiom
from homebot.htn.state import Atom, State, Term, is_variable

__all__ = ["DecompositionNode", "Plan", "PlanStep", "Planner", "PlanningResult",
           "find_cheapest_plan", "find_plan", "find_plans"]

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
        return "(" + " ".join(str(item) for item in (self.operator, *self.args)) + ")"


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
    """What expressions are evaluated against: the state and the domain's axioms."""

    __slots__ = ("axioms", "state")

    def __init__(self, state: State,
                 axioms: Mapping[tuple[str, int], Sequence[Axiom]]) -> None:
        self.state = state
        self.axioms = axioms


# An agenda is a linked list: (task, parent node, depth, rest) or None.
_Agenda = tuple[tuple[Term, ...], int, int, Any] | None


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

    def __init__(self, domain: Domain, *, max_depth: int = 100_000,
                 max_expansions: int = 1_000_000, time_limit: float | None = None,
                 clock: Callable[[], float] = time.perf_counter, trace: bool = False) -> None:
        self.domain = domain
        self.max_depth = max_depth
        self.max_expansions = max_expansions
        self.time_limit = time_limit
        self.clock = clock
        self.trace = trace

    def _refine(self, proof: _Proof, task: tuple[Term, ...], parent: int, depth: int,
                rest: _Agenda, plan: list[PlanStep], costs: list[float],
                network: list[DecompositionNode],
                trace: list[str] | None) -> Iterator[_Agenda]:
        """Every way to refine ``task``, each applied when asked for (undone by the caller)."""
        name = task[0]
        operator = self.domain.operators.get(name)
        state = proof.state
        if operator is not None:
            start = operator.bind(task)
            if start is None:
                return
            applied = False
            for bindings in operator.precondition.solve(proof, start):
                applied = True
                if trace is not None:
                    trace.append(f"{'  ' * depth}{_text(task)}: applied")
                deletes, adds = operator.effects(bindings)
                for atom in deletes:
                    state.remove(atom)
                for atom in adds:
                    state.add(atom)
                cost = operator.cost_of(bindings)
                network.append(DecompositionNode(parent, task, None))
                plan.append(PlanStep(name, task[1:], cost, len(network) - 1, tuple(deletes),
                                     tuple(adds)))
                costs.append(costs[-1] + cost)
                yield rest
            if trace is not None and not applied:
                trace.append(f"{'  ' * depth}{_text(task)}: precondition does not hold")
            return
        methods = self.domain.methods.get(name)
        if methods is None:
            self.domain.check_task(task)
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
                    agenda = rest
                    for subtask in reversed(branch.ground_subtasks(bindings)):
                        agenda = (subtask, node, depth + 1, agenda)
                    yield agenda
                if applicable:
                    break
                if trace is not None:
                    trace.append(f"{'  ' * depth}{_text(task)}: {branch.name} does not apply")

    #### find_plan and seek_plan

    def search(self, state: State, tasks: Sequence[Sequence[Any]], *, limit: int | None = 1,
               cheapest: bool = False) -> PlanningResult:
        """Plans for ``tasks`` from ``state`` (left unchanged).

        ``limit`` plans at most (None: every plan); ``cheapest`` keeps searching
        with branch and bound and returns only the cheapest plan.
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
            self._seek(proof, goal, result, limit, cheapest)
        except RecursionError:  # the search is iterative: only a proof can recurse this deep
            raise PlanningError("proving a precondition recursed without end: an axiom proves "
                                "its head from itself (such as (:- (p ?x) ((p ?x)))); put a "
                                "condition that binds or fails before the recursive one") from None
        finally:
            state.undo(mark)
        return result

    def _seek(self, proof: _Proof, goal: list[tuple[Term, ...]], result: PlanningResult,
              limit: int | None, cheapest: bool) -> None:
        state = proof.state
        agenda: _Agenda = None
        for task in reversed(goal):
            agenda = (task, -1, 0, agenda)
        plan: list[PlanStep] = []
        costs: list[float] = [0.0]
        network: list[DecompositionNode] = []
        stack: list[tuple[Iterator[_Agenda], int, int, int]] = []
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
            else:
                task, parent, depth, rest = agenda
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
                    stack.append((self._refine(proof, task, parent, depth, rest, plan, costs,
                                               network, result.trace),
                                  state.mark(), len(plan), len(network)))
            while stack:
                alternatives, mark, planned, noted = stack[-1]
                state.undo(mark)
                del plan[planned:], costs[planned + 1:], network[noted:]
                agenda = next(alternatives, _EXHAUSTED)
                if agenda is not _EXHAUSTED:
                    break
                stack.pop()
            else:
                return


_EXHAUSTED: Any = object()


def _text(task: Sequence[Any]) -> str:
    return "(" + " ".join(str(item) for item in task) + ")"


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
