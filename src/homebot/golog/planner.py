"""``solve``: DTGolog's forward-search value iteration, with READYLOG's policy markers.

``Planner.best(stack, s, h)`` follows DTGolog's ``bestDo`` (Boutilier et al.
2000): the value of a program is the reward of the current situation plus the
value of what follows; a deterministic action that is not possible, or a test
that fails, ends the branch with ``stop`` (success probability 0); a stochastic
action sums its possible outcomes weighted by their probabilities (from the
last outcome to the first, as DTGolog adds them); nondeterministic choice,
``pi`` and ``pickBest`` take the better branch by DTGolog's comparison, where a
branch that cannot succeed loses to any branch that can and otherwise the
higher value wins, ties going to the later branch. At horizon 0 an action ends
the branch with the current reward and success probability 1. The planner adds
markers: every test and branch condition and every action's precondition,
with the truth value it had while planning.

Beyond DTGolog: the search is memoised on (programs left, state, horizon) by
default, which changes the work but not the answer (DTGolog re-expands equal
subtrees; ``memo=False`` does too); constructs without a DTGolog rule
(concurrency, guards, waiting, ``search``) are planned through their Trans/Final
steps. ``project`` computes ``pproj``: the probability that a condition holds
after a program, projected from a state.
"""

from __future__ import annotations

from homebot.errors import GologError
from homebot.golog.expressions import Const, Expr, Possible
from homebot.golog.policy import (
    Branch,
    PChance,
    PDo,
    PMarker,
    PNil,
    PSense,
    PStop,
    Result,
)
from homebot.golog.program import (
    Call,
    Choice,
    If,
    Nil,
    Pi,
    PickBest,
    Prob,
    Program,
    Search,
    Seq,
    Solve,
    Star,
    Test,
    While,
)
from homebot.golog.semantics import (
    ActionStep,
    ChanceStep,
    PlanStep,
    ReplanStep,
    SenseStep,
    TestStep,
    domain_values,
    final,
    ground,
    probability_of,
    transitions,
    unfold,
)
from homebot.golog.theory import GroundAction, State, Theory

__all__ = ["Planner", "better_second", "horizon_of", "plan", "project"]

_NIL = PNil()
_STOP = PStop()
Stack = tuple[Program, ...]


def better_second(first: Result, second: Result) -> bool:
    """DTGolog's ``lesseq``: whether the second branch is at least as good as the first."""
    if first.probability == 0.0:
        return second.probability != 0.0 or first.value <= second.value
    return second.probability != 0.0 and first.value <= second.value


class Planner:
    """Forward search over one program for one reward; counts the nodes it expands."""

    def __init__(self, theory: Theory, reward: Expr, *, memo: bool = True) -> None:
        self.theory = theory
        self.reward = reward
        self.nodes = 0  #: nodes of the search tree expanded (memo hits not counted)
        self.memo: dict[tuple[Stack, State, int], Result] | None = {} if memo else None

    def reward_of(self, state: State) -> float:
        value = self.reward.evaluate(self.theory, state)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise GologError(f"the reward {self.reward} is {value!r}, not a number; declare it "
                             f"with theory.function('{self.reward}', lambda state: ...)")
        return float(value)

    def solve(self, program: Program, state: State, horizon: int) -> Result:
        """The best policy for ``program`` from ``state`` within ``horizon`` actions."""
        if horizon < 0:
            raise GologError(f"the horizon of solve must be 0 or more, not {horizon}")
        try:
            return self.best((program,), state, horizon)
        except RecursionError:
            raise GologError(f"the search of solve at horizon {horizon} is too deep: the "
                             f"horizon is too large, or a loop goes round without acting; "
                             f"lower the horizon or put an action in the loop") from None

    def best(self, stack: Stack, state: State, horizon: int) -> Result:
        """DTGolog's ``bestDo`` for the programs on ``stack`` (first to run first).

        With ``memo`` on, a (programs, state, horizon) already searched is not
        searched again: the result is the same, the tree becomes a graph.
        """
        if self.memo is None:
            return self._best(stack, state, horizon)
        key = (stack, state, horizon)
        known = self.memo.get(key)
        if known is None:
            known = self.memo[key] = self._best(stack, state, horizon)
        return known

    def _best(self, stack: Stack, state: State, horizon: int) -> Result:
        self.nodes += 1
        if not stack:
            return Result(self.reward_of(state), 1.0, _NIL)
        head, rest = stack[0], stack[1:]
        theory = self.theory
        match head:
            case Seq(parts=parts):
                return self.best(parts + rest, state, horizon)
            case Nil():
                return self.best(rest, state, horizon)
            case Call(name=name) if name in theory.procedures:
                return self.best((unfold(head, theory, state), *rest), state, horizon)
            case Call():
                return self._action(ground(head, theory, state), rest, state, horizon)
            case Test(condition=condition):
                if condition.holds(theory, state):
                    return self._marked(condition, True, self.best(rest, state, horizon))
                return Result(self.reward_of(state), 0.0, PMarker(condition, False, _STOP))
            case If(condition=condition, then=then, otherwise=otherwise):
                value = condition.holds(theory, state)
                following = ((then if value else otherwise), *rest)
                return self._marked(condition, value, self.best(following, state, horizon))
            case While(condition=condition, body=body):
                value = condition.holds(theory, state)
                following = (body, head, *rest) if value else rest
                return self._marked(condition, value, self.best(following, state, horizon))
            case Choice(options=options):
                return self._best_of([(option, *rest) for option in options], state, horizon)
            case Pi(variable=variable, domain=domain, body=body) | PickBest(
                    variable=variable, domain=domain, body=body):
                values = domain_values(domain, theory, state)
                if not values:
                    return Result(self.reward_of(state), 0.0, _STOP)
                return self._best_of([(body.substitute({variable: Const(value)}), *rest)
                                      for value in values], state, horizon)
            case Star(body=body):
                return self._best_of([rest, (body, head, *rest)], state, horizon)
            case Prob(probability=probability, first=first, second=second):
                chance = probability_of(probability, theory, state)
                one = self.best((first, *rest), state, horizon)
                other = self.best((second, *rest), state, horizon)
                return Result(chance * one.value + (1.0 - chance) * other.value,
                              chance * one.probability + (1.0 - chance) * other.probability,
                              PChance(chance, one.policy, other.policy))
            case Solve(body=body) | Search(body=body):
                return self.best((body, *rest), state, horizon)
        return self._by_transitions(head, rest, state, horizon)

    # ------------------------------------------------------------------ pieces

    @staticmethod
    def _marked(condition: Expr, value: bool, result: Result) -> Result:
        return Result(result.value, result.probability, PMarker(condition, value, result.policy))

    def _best_of(self, stacks: list[Stack], state: State, horizon: int) -> Result:
        """Nondeterministic choice, nested to the right as DTGolog's ``#``."""
        results = [self.best(stack, state, horizon) for stack in stacks]
        chosen = results[-1]
        for result in reversed(results[:-1]):
            if not better_second(result, chosen):
                chosen = result
        return chosen

    def _action(self, action: GroundAction, rest: Stack, state: State,
                horizon: int) -> Result:
        theory = self.theory
        if horizon == 0:
            return Result(self.reward_of(state), 1.0, _NIL)
        reward = self.reward_of(state)
        poss = Possible(action)
        if not theory.possible(action, state):
            return Result(reward, 0.0, PMarker(poss, False, _STOP))
        schema = theory.schema(action)
        if not schema.stochastic:
            result = self.best(rest, theory.do(action, state), horizon - 1)
            return Result(reward + result.value, result.probability,
                          PMarker(poss, True, PDo(action, result.policy)))
        outcomes = [(nature, chance) for nature, chance in theory.outcomes(action, state)
                    if theory.possible(nature, state)]
        if not outcomes:
            return Result(reward, 0.0, PMarker(poss, True, PDo(action, _STOP)))
        value = probability = 0.0
        branches: list[Branch] = []
        for nature, chance in reversed(outcomes):
            sense = theory.sense_condition(nature)
            if sense is None:
                raise GologError(f"nature's action {nature[0]} of the stochastic action "
                                 f"{action[0]} needs a sensing condition: declare it with "
                                 f"theory.action('{nature[0]}', ..., sense=...)")
            result = self.best(rest, theory.do(nature, state), horizon - 1)
            value = value + chance * result.value
            probability = probability + chance * result.probability
            branches.append(Branch(nature, sense, chance, result.policy))
        branches.reverse()
        return Result(reward + value, probability,
                      PMarker(poss, True, PDo(action, PSense(action, tuple(branches)))))

    def _by_transitions(self, head: Program, rest: Stack, state: State,
                        horizon: int) -> Result:
        """Constructs without a DTGolog rule (concurrency, guards, waiting): by Trans/Final."""
        theory = self.theory
        options: list[Result] = []
        if final(head, state, theory):
            options.append(self.best(rest, state, horizon))
        found = transitions(head, state, theory)
        chances = [(step.probability, remaining) for step, remaining in found
                   if isinstance(step, ChanceStep)]
        if chances:  # nature's choice between programs, as prob(p, σ1, σ2) is planned
            results = [(chance, self.best((remaining, *rest), state, horizon))
                       for chance, remaining in chances]
            options.append(Result(sum(chance * result.value for chance, result in results),
                                  sum(chance * result.probability
                                      for chance, result in results),
                                  PChance(chances[0][0], results[0][1].policy,
                                          results[-1][1].policy)))
        for step, remaining in found:
            following = (remaining, *rest)
            if isinstance(step, ActionStep):
                options.append(self._action(step.action, following, state, horizon))
            elif isinstance(step, TestStep):
                options.append(self._marked(step.condition, step.value,
                                            self.best(following, state, horizon)))
            elif isinstance(step, PlanStep | SenseStep | ReplanStep):
                options.append(self.best(following, state, horizon))
        if not options:
            return Result(self.reward_of(state), 0.0, _STOP)
        chosen = options[-1]
        for result in reversed(options[:-1]):
            if not better_second(result, chosen):
                chosen = result
        return chosen


def horizon_of(theory: Theory, solve: Solve, state: State) -> int:
    """The horizon of a ``solve``; anything but a whole number raises ``GologError``."""
    horizon = solve.horizon.evaluate(theory, state)
    if not isinstance(horizon, int) or isinstance(horizon, bool):
        raise GologError(f"the horizon of {solve} must be a whole number, not {horizon!r}")
    return horizon


def plan(theory: Theory, solve: Solve, state: State, *, memo: bool = True) -> Result:
    """The policy ``solve(h, reward, σ)`` stands for in ``state``."""
    horizon = horizon_of(theory, solve, state)
    return Planner(theory, solve.reward, memo=memo).solve(solve.body, state, horizon)


def project(theory: Theory, program: Program, state: State, condition: Expr,
            *, limit: int = 200) -> float:
    """``pproj``: the probability that ``condition`` holds after ``program`` from ``state``.

    Stochastic actions and ``prob`` branch with their probabilities; any other
    nondeterminism takes its first possible step, as the online interpreter does.
    A branch that blocks, or runs for more than ``limit`` steps, counts as failed.
    """
    return _project(theory, program, state, condition, limit)


def _project(theory: Theory, program: Program, state: State, condition: Expr,
             limit: int) -> float:
    if final(program, state, theory):
        return 1.0 if condition.holds(theory, state) else 0.0
    found = transitions(program, state, theory)
    if not found or limit <= 0:
        return 0.0
    step, remaining = found[0]
    if isinstance(step, ChanceStep):
        return sum(chance.probability * _project(theory, rest, state, condition, limit - 1)
                   for chance, rest in found if isinstance(chance, ChanceStep))
    if isinstance(step, ActionStep):
        total = 0.0
        for nature, chance in theory.outcomes(step.action, state):
            if theory.possible(nature, state):
                total += chance * _project(theory, remaining, theory.do(nature, state),
                                           condition, limit - 1)
        return total
    if isinstance(step, TestStep | PlanStep | SenseStep | ReplanStep):
        return _project(theory, remaining, state, condition, limit - 1)
    return 0.0
