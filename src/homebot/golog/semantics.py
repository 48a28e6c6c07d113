"""Transition semantics (ConGolog's Trans and Final) for online execution and projection.

``transitions(δ, s)`` lists the single steps δ can take in state s, in order of
preference, each with the program that remains. A step is an action, a test,
a chance event (``prob``), a plan (``solve``), a sensing result, or a replan
(a policy marker whose value changed). Policies from ``solve`` run as
``Running(policy, origin)`` nodes, so they nest anywhere in a program.
"""

from __future__ import annotations

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
    "sequence",
    "transitions",
]

#: horizon for a ``pickBest`` met outside any ``solve`` (it is planned on its own)
DEFAULT_HORIZON = 6
#: unfolding depth beyond which a procedure is taken to recurse without acting
_MAX_UNFOLD = 200


@dataclass(frozen=True, slots=True)
class ActionStep:
    """Execute a primitive action."""

    action: GroundAction


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
    kind = type(program)
    if kind is Call:
        call: Call = program  # type: ignore[assignment]
        if call.name in theory.procedures:
            return transitions(unfold(call, theory, state), state, theory, depth + 1)
        action = ground(call, theory, state)
        return [(ActionStep(action), Nil())] if theory.possible(action, state) else []
    if kind is Seq:
        parts = program.parts  # type: ignore[attr-defined]
        if not parts:
            return []
        rest = Seq(parts[1:]) if len(parts) > 2 else (parts[1] if len(parts) == 2 else Nil())
        found = [(step, sequence(remaining, rest))
                 for step, remaining in transitions(parts[0], state, theory, depth)]
        if final(parts[0], state, theory):
            found += transitions(rest, state, theory, depth)
        return found
    if kind is Test:
        condition = program.condition  # type: ignore[attr-defined]
        return [(TestStep(condition), Nil())] if condition.holds(theory, state) else []
    if kind is If:
        branch = program.then if program.condition.holds(  # type: ignore[attr-defined]
            theory, state) else program.otherwise  # type: ignore[attr-defined]
        return transitions(branch, state, theory, depth)
    if kind is While:
        if not program.condition.holds(theory, state):  # type: ignore[attr-defined]
            return []
        return [(step, sequence(remaining, program)) for step, remaining in
                transitions(program.body, state, theory, depth)]  # type: ignore[attr-defined]
    if kind is Choice:
        return [found for option in program.options  # type: ignore[attr-defined]
                for found in transitions(option, state, theory, depth)]
    if kind is Star:
        return [(step, sequence(remaining, program)) for step, remaining in
                transitions(program.body, state, theory, depth)]  # type: ignore[attr-defined]
    if kind is Pi:
        return [found for value in domain_values(program.domain, theory, state)  # type: ignore
                for found in transitions(program.body.substitute(  # type: ignore[attr-defined]
                    {program.variable: Const(value)}), state, theory, depth)]  # type: ignore
    if kind is PickBest:
        planned = Solve(Const(DEFAULT_HORIZON), Fn("reward"), program)
        return transitions(planned, state, theory, depth)
    if kind is Conc:
        high = transitions(program.high, state, theory, depth)  # type: ignore[attr-defined]
        if high:
            return [(step, Conc(remaining, program.low))  # type: ignore[attr-defined]
                    for step, remaining in high]
        return [(step, Conc(program.high, remaining))  # type: ignore[attr-defined]
                for step, remaining in transitions(program.low, state, theory, depth)]  # type: ignore
    if kind is WithPol:
        return transitions(_with_pol(program), state, theory, depth)  # type: ignore[arg-type]
    if kind is WithCtrl:
        if not program.condition.holds(theory, state):  # type: ignore[attr-defined]
            return []
        return [(step, WithCtrl(program.condition, remaining))  # type: ignore[attr-defined]
                for step, remaining in transitions(program.body, state, theory, depth)]  # type: ignore
    if kind is WaitFor:
        condition = program.condition  # type: ignore[attr-defined]
        return [(TestStep(condition), Nil())] if condition.holds(theory, state) else []
    if kind is Prob:
        chance = float(program.probability.evaluate(theory, state))  # type: ignore[attr-defined]
        return [(ChanceStep(chance), program.first),  # type: ignore[attr-defined]
                (ChanceStep(1.0 - chance), program.second)]  # type: ignore[attr-defined]
    if kind is Solve:
        from homebot.golog.planner import plan

        result = plan(theory, program, state)  # type: ignore[arg-type]
        return [(PlanStep(result), Running(result.policy, program))]  # type: ignore[arg-type]
    if kind is Running:
        return _policy_transitions(program, state, theory)  # type: ignore[arg-type]
    return []


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
            return [(ActionStep(policy.action), Running(policy.then, origin))]
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
    kind = type(program)
    if kind is Nil or kind is Star:
        return True
    if kind is Call:
        call: Call = program  # type: ignore[assignment]
        if call.name in theory.procedures and depth <= _MAX_UNFOLD:
            return final(unfold(call, theory, state), state, theory, depth + 1)
        return False
    if kind is Seq:
        return all(final(part, state, theory, depth)
                   for part in program.parts)  # type: ignore[attr-defined]
    if kind is If:
        branch = program.then if program.condition.holds(  # type: ignore[attr-defined]
            theory, state) else program.otherwise  # type: ignore[attr-defined]
        return final(branch, state, theory, depth)
    if kind is While:
        return (not program.condition.holds(theory, state)  # type: ignore[attr-defined]
                or final(program.body, state, theory, depth))  # type: ignore[attr-defined]
    if kind is Choice:
        return any(final(option, state, theory, depth)
                   for option in program.options)  # type: ignore[attr-defined]
    if kind is Pi:
        return any(final(program.body.substitute(  # type: ignore[attr-defined]
            {program.variable: Const(value)}), state, theory, depth)  # type: ignore[attr-defined]
            for value in domain_values(program.domain, theory, state))  # type: ignore
    if kind is Conc:
        return (final(program.high, state, theory, depth)  # type: ignore[attr-defined]
                or final(program.low, state, theory, depth))  # type: ignore[attr-defined]
    if kind is WithPol:
        return final(_with_pol(program), state, theory, depth)  # type: ignore[arg-type]
    if kind is WithCtrl:
        return final(program.body, state, theory, depth)  # type: ignore[attr-defined]
    if kind is Running:
        return isinstance(program.policy, PNil)  # type: ignore[attr-defined]
    return False
