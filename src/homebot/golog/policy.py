"""Policies that ``solve`` produces: conditional programs with execution-monitoring markers.

A marker ``M(φ, v)`` stores a condition the planner evaluated and the truth
value it had at planning time (CAESAR §3.1.4). Tests, branch conditions and the
precondition of every planned action become markers; at run time a marker
whose value changed invalidates the policy and the ``solve`` is planned anew.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from itertools import islice

from homebot.golog.expressions import Expr
from homebot.golog.theory import GroundAction, action_text

__all__ = [
    "Branch",
    "PChance",
    "PDo",
    "PMarker",
    "PNil",
    "PSense",
    "PStop",
    "Policy",
    "Result",
    "policy_actions",
    "policy_text",
]


class Policy:
    """A node of a policy."""

    __slots__ = ()


@dataclass(frozen=True, slots=True)
class PNil(Policy):
    """Nothing more to do: the policy ends here."""


@dataclass(frozen=True, slots=True)
class PStop(Policy):
    """The program cannot go on here (DTGolog's ``stop``): failure."""


@dataclass(frozen=True, slots=True)
class PDo(Policy):
    """Do a primitive action, then the rest."""

    action: GroundAction
    then: Policy


@dataclass(frozen=True, slots=True)
class PMarker(Policy):
    """``M(φ, v)``: φ had truth value v at planning time."""

    condition: Expr
    value: bool
    then: Policy


@dataclass(frozen=True, slots=True)
class Branch:
    """One of nature's outcomes: its sensing condition, probability and sub-policy."""

    nature: GroundAction
    condition: Expr
    probability: float
    policy: Policy


@dataclass(frozen=True, slots=True)
class PSense(Policy):
    """After a stochastic action: sense which outcome happened and follow its branch."""

    action: GroundAction
    branches: tuple[Branch, ...]


@dataclass(frozen=True, slots=True)
class PChance(Policy):
    """From ``prob(p, σ1, σ2)``: the first sub-policy with probability p."""

    probability: float
    first: Policy
    second: Policy


@dataclass(frozen=True, slots=True)
class Result:
    """A policy with its expected value and its probability of successful termination."""

    value: float
    probability: float
    policy: Policy

    def __bool__(self) -> bool:
        """True when the policy can succeed at all."""
        return self.probability > 0.0


def policy_actions(policy: Policy) -> list[GroundAction]:
    """The actions along the most likely path of a policy."""
    actions: list[GroundAction] = []
    while True:
        if isinstance(policy, PDo):
            actions.append(policy.action)
            policy = policy.then
        elif isinstance(policy, PMarker):
            policy = policy.then
        elif isinstance(policy, PSense) and policy.branches:
            policy = max(policy.branches, key=lambda branch: branch.probability).policy
        elif isinstance(policy, PChance):
            policy = policy.first if policy.probability >= 0.5 else policy.second
        else:
            return actions


def policy_text(policy: Policy, *, markers: bool = True, limit: int | None = None) -> str:
    """The policy as an indented conditional program, one step a line.

    A policy is a tree that can grow exponentially with the horizon when written
    out; ``limit`` keeps the first lines and says how the text was cut.
    """
    lines = list(islice(_lines(policy, 0, markers), None if limit is None else limit + 1))
    if limit is not None and len(lines) > limit:
        lines[limit:] = [f"... (cut after {limit} lines: the policy branches on every outcome)"]
    return "\n".join(lines) or "nil"


def _lines(policy: Policy, depth: int, markers: bool) -> Iterator[str]:
    pad = "  " * depth
    while True:
        if isinstance(policy, PDo):
            yield f"{pad}{action_text(policy.action)}"
            policy = policy.then
        elif isinstance(policy, PMarker):
            if markers:
                yield f"{pad}M({policy.condition}, {str(policy.value).lower()})"
            policy = policy.then
        elif isinstance(policy, PSense):
            yield f"{pad}senseEffect({action_text(policy.action)})"
            for branch in policy.branches:
                yield f"{pad}if {branch.condition} (p={branch.probability:g}) then"
                yield from _lines(branch.policy, depth + 1, markers)
            return
        elif isinstance(policy, PChance):
            yield f"{pad}with p={policy.probability:g}:"
            yield from _lines(policy.first, depth + 1, markers)
            yield f"{pad}otherwise:"
            yield from _lines(policy.second, depth + 1, markers)
            return
        elif isinstance(policy, PStop):
            yield f"{pad}stop"
            return
        else:
            return
