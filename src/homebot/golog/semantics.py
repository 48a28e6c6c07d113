"""Transition semantics (ConGolog's Trans and Final) for online execution and projection.

``transitions(δ, s)`` lists the single steps δ can take in state s, in order of
preference, each with the program that remains. A step is an action, a test,
a chance event (``prob``), a plan (``solve``), a sensing result, or a replan
(a policy marker whose value changed). Policies from ``solve`` run as
``Running(policy, origin)`` nodes, so they nest anywhere in a program.

Choices where the references differ: ``σ1 || σ2`` may end when either part may
end (CAESAR §3.1.1; ConGolog's ``>>`` needs both), which is what makes
``withPol(σ1, σ2) = (σ1; ?(false)) || σ2`` end with σ2; ``withCtrl φ do σ``
and a false test block rather than end, so the program waits (for exogenous
actions) or a lower-priority branch runs; a ``pickBest`` outside any ``solve``
is planned as ``solve(DEFAULT_HORIZON, reward, ...)`` with the theory's
``reward`` function.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from homebot.errors import GologError
from homebot.golog.expressions import Const, Expr, Fn, Possible
from homebot.golog.policy import PChance, PDo, PMarker, PNil, Policy, PSense, Result
from homebot.golog.program import (
    Call,
    Choice,
    Conc,
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
    WaitFor,
    While,
    WithCtrl,
    WithPol,
)
from homebot.golog.theory import GroundAction, State, Theory

__all__ = [
    "ActionStep",
    "ChanceStep",
    "PlanStep",
    "ReplanStep",
    "Running",
    "SenseStep",
    "Step",
    "TestStep",
    "final",
    "ground",
    "probability_of",
    "sequence",
    "transitions",
]

#: horizon for a ``pickBest`` met outside any ``solve`` (it is planned on its own)
DEFAULT_HORIZON = 6
#: unfolding depth beyond which a procedure is taken to recurse without acting
_MAX_UNFOLD = 200
#: how many steps ``search`` looks ahead for a way to the end, and how many it tries
SEARCH_DEPTH = 60
SEARCH_BUDGET = 20_000


@dataclass(frozen=True, slots=True)
class ActionStep:
    """Execute a primitive action; ``fallback`` is where to go if it fails (a policy's solve)."""

    action: GroundAction
    fallback: Program | None = None


@dataclass(frozen=True, slots=True)
class TestStep:
    """A test (or a marker) that held as expected."""

    condition: Expr
    value: bool = True


@dataclass(frozen=True, slots=True)
class ChanceStep:
    """One outcome of ``prob(p, ...)`` with its probability."""

    probability: float


@dataclass(frozen=True, slots=True)
class PlanStep:
    """``solve`` planned a policy."""

    result: Result


@dataclass(frozen=True, slots=True)
class SenseStep:
    """After a stochastic action, sensing told which outcome happened."""

    nature: GroundAction


@dataclass(frozen=True, slots=True)
class ReplanStep:
    """A marker's value changed since planning: the policy is invalid."""

    condition: Expr
    expected: bool


Step = ActionStep | TestStep | ChanceStep | PlanStep | SenseStep | ReplanStep


@dataclass(frozen=True, slots=True)
class Running(Program):
    """A policy being executed, and the ``solve`` to plan again if a marker fails."""

    policy: Policy
    origin: Solve

    def substitute(self, bindings: Any) -> Program:
        return self


def sequence(first: Program, rest: Program) -> Program:
    """``first; rest`` without needless nesting."""
    if isinstance(first, Nil):
        return rest
    if isinstance(rest, Nil):
        return first
    head = first.parts if isinstance(first, Seq) else (first,)
    tail = rest.parts if isinstance(rest, Seq) else (rest,)
    return Seq(head + tail)


def ground(call: Call, theory: Theory, state: State) -> GroundAction:
    """The ground action of a primitive action call in ``state``."""
    return (call.name, *(arg.evaluate(theory, state) for arg in call.args))


def unfold(call: Call, theory: Theory, state: State) -> Program:
    """The body of a called procedure with its arguments' values (call by value)."""
    procedure = theory.procedures[call.name]
    if len(call.args) != len(procedure.parameters):
        raise GologError(f"{call}: procedure '{procedure.name}' takes "
                         f"{len(procedure.parameters)} argument(s), not {len(call.args)}")
    values = {name: Const(arg.evaluate(theory, state))
              for name, arg in zip(procedure.parameters, call.args, strict=True)}
    return procedure.body.substitute(values)


def probability_of(expr: Expr, theory: Theory, state: State) -> float:
    """The value of a probability; anything but a number from 0 to 1 raises ``GologError``."""
    value = expr.evaluate(theory, state)
    if isinstance(value, bool) or not isinstance(value, int | float) or not 0 <= value <= 1:
        raise GologError(f"the probability {expr} is {value!r}; write a number from 0 to 1")
    return float(value)


def domain_values(domain: Expr, theory: Theory, state: State) -> tuple[Any, ...]:
    """The values of a finite domain."""
    values = domain.evaluate(theory, state)
    if isinstance(values, str) or not hasattr(values, "__iter__"):
        raise GologError(f"the domain {domain} is not a finite set; write it as {{a, b}}")
    return tuple(values)


def transitions(program: Program, state: State, theory: Theory,
                depth: int = 0) -> list[tuple[Step, Program]]:
    """Every single step ``program`` can take in ``state``, in order of preference."""
    if depth > _MAX_UNFOLD:
        raise GologError("a procedure recurses without ever acting; put an action or a test "
                         "that fails before the recursive call")
    match program:
        case Call(name=name) if name in theory.procedures:
            return transitions(unfold(program, theory, state), state, theory, depth + 1)
        case Call():
            action = ground(program, theory, state)
            return [(ActionStep(action), Nil())] if theory.possible(action, state) else []
        case Seq(parts=()):
            return []
        case Seq(parts=(first, *others)):
            rest = Seq(tuple(others)) if len(others) > 1 else (others[0] if others else Nil())
            found = _mapped(transitions(first, state, theory, depth),
                            lambda remaining: sequence(remaining, rest))
            if final(first, state, theory):
                found += transitions(rest, state, theory, depth)
            return found
        case Test(condition=condition) | WaitFor(condition=condition):
            return [(TestStep(condition), Nil())] if condition.holds(theory, state) else []
        case If(condition=condition, then=then, otherwise=otherwise):
            branch = then if condition.holds(theory, state) else otherwise
            return transitions(branch, state, theory, depth)
        case While(condition=condition, body=body):
            if not condition.holds(theory, state):
                return []
            return _mapped(transitions(body, state, theory, depth),
                           lambda remaining: sequence(remaining, program))
        case Star(body=body):
            return _mapped(transitions(body, state, theory, depth),
                           lambda remaining: sequence(remaining, program))
        case Choice(options=options):
            return [found for option in options
                    for found in transitions(option, state, theory, depth)]
        case Pi(variable=variable, domain=domain, body=body):
            return [found for value in domain_values(domain, theory, state)
                    for found in transitions(body.substitute({variable: Const(value)}),
                                             state, theory, depth)]
        case PickBest():
            planned = Solve(Const(DEFAULT_HORIZON), Fn("reward"), program)
            return transitions(planned, state, theory, depth)
        case Conc(high=high, low=low):
            first_choice = transitions(high, state, theory, depth)
            if first_choice:
                return _mapped(first_choice, lambda remaining: Conc(remaining, low))
            return _mapped(transitions(low, state, theory, depth),
                           lambda remaining: Conc(high, remaining))
        case WithPol():
            return transitions(_with_pol(program), state, theory, depth)
        case WithCtrl(condition=condition, body=body):
            if not condition.holds(theory, state):
                return []
            return _mapped(transitions(body, state, theory, depth),
                           lambda remaining: WithCtrl(condition, remaining))
        case Prob(probability=probability, first=first, second=second):
            chance = probability_of(probability, theory, state)
            return [(ChanceStep(chance), first), (ChanceStep(1.0 - chance), second)]
        case Solve():
            from homebot.golog.planner import plan

            result = plan(theory, program, state)
            return [(PlanStep(result), Running(result.policy, program))]
        case Running():
            return _policy_transitions(program, state, theory)
        case Search(body=body):
            chosen = _first_step_to_the_end(body, state, theory, SEARCH_DEPTH)
            return [] if chosen is None else [(chosen[0], Search(chosen[1]))]
    return []


def _first_step_to_the_end(program: Program, state: State, theory: Theory,
                           depth: int) -> tuple[Step, Program] | None:
    """The first step of an execution of ``program`` that ends (offline, depth first).

    Only deterministic steps are searched: a stochastic action or a chance event
    cannot be promised to lead to the end. The search gives up (None) after
    ``SEARCH_BUDGET`` steps, so a program with no end cannot hang the robot.
    """
    budget = [SEARCH_BUDGET]

    def ends(program: Program, state: State, depth: int) -> tuple[Step, Program] | None:
        if depth <= 0:
            return None
        for step, remaining in transitions(program, state, theory):
            budget[0] -= 1
            if budget[0] < 0:
                return None
            if isinstance(step, ChanceStep):
                continue
            after = state
            if isinstance(step, ActionStep):
                if theory.schema(step.action).stochastic:
                    continue
                after = theory.do(step.action, state)
            if final(remaining, after, theory) or ends(remaining, after, depth - 1):
                return step, remaining
        return None

    return ends(program, state, depth)


def _mapped(found: list[tuple[Step, Program]],
            wrap: Callable[[Program], Program]) -> list[tuple[Step, Program]]:
    """Steps with what remains wrapped, an action's fallback wrapped the same way."""
    wrapped: list[tuple[Step, Program]] = []
    for step, remaining in found:
        if isinstance(step, ActionStep) and step.fallback is not None:
            step = ActionStep(step.action, wrap(step.fallback))
        wrapped.append((step, wrap(remaining)))
    return wrapped


def _with_pol(program: WithPol) -> Conc:
    return Conc(sequence(program.policy, Test(Const(False))), program.program)


def _policy_transitions(running: Running, state: State,
                        theory: Theory) -> list[tuple[Step, Program]]:
    policy, origin = running.policy, running.origin
    if isinstance(policy, PMarker):
        if policy.condition.holds(theory, state) == policy.value:
            return [(TestStep(policy.condition, policy.value), Running(policy.then, origin))]
        return [(ReplanStep(policy.condition, policy.value), origin)]
    if isinstance(policy, PDo):
        if theory.possible(policy.action, state):
            return [(ActionStep(policy.action, origin), Running(policy.then, origin))]
        return [(ReplanStep(Possible(policy.action), True), origin)]
    if isinstance(policy, PSense):
        for branch in policy.branches:
            if branch.condition.holds(theory, state):
                return [(SenseStep(branch.nature), Running(branch.policy, origin))]
        return [(ReplanStep(Const(False), True), origin)]
    if isinstance(policy, PChance):
        return [(ChanceStep(policy.probability), Running(policy.first, origin)),
                (ChanceStep(1.0 - policy.probability), Running(policy.second, origin))]
    return []


def final(program: Program, state: State, theory: Theory, depth: int = 0) -> bool:
    """Whether ``program`` may legally stop in ``state``."""
    match program:
        case Nil() | Star():
            return True
        case Call(name=name) if name in theory.procedures and depth <= _MAX_UNFOLD:
            return final(unfold(program, theory, state), state, theory, depth + 1)
        case Seq(parts=parts):
            return all(final(part, state, theory, depth) for part in parts)
        case If(condition=condition, then=then, otherwise=otherwise):
            branch = then if condition.holds(theory, state) else otherwise
            return final(branch, state, theory, depth)
        case While(condition=condition, body=body):
            return not condition.holds(theory, state) or final(body, state, theory, depth)
        case Choice(options=options):
            return any(final(option, state, theory, depth) for option in options)
        case Pi(variable=variable, domain=domain, body=body):
            return any(final(body.substitute({variable: Const(value)}), state, theory, depth)
                       for value in domain_values(domain, theory, state))
        case Conc(high=high, low=low):
            return final(high, state, theory, depth) or final(low, state, theory, depth)
        case WithPol():
            return final(_with_pol(program), state, theory, depth)
        case WithCtrl(body=body):
            return final(body, state, theory, depth)
        case Running(policy=policy):
            return isinstance(policy, PNil)
        case Search(body=body):
            return final(body, state, theory, depth)
    return False
