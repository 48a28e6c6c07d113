"""Decision (§8.2): which pending obligations to serve with the client's request, within r_max."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from homebot.inference.planning import ActionModel, Carry, Plan, plan_carries

__all__ = ["Decision", "Rewards", "decide"]


@dataclass(frozen=True, slots=True)
class Rewards:
    """What serving an obligation is worth: the client's request far more than tidying."""

    request: float = 10.0
    put_back: float = 1.0


@dataclass(frozen=True, slots=True)
class Decision:
    """The chosen subset of obligations, its plan, and every subset that was weighed."""

    chosen: tuple[Carry, ...]
    plan: Plan
    value: float
    weighed: tuple[tuple[tuple[str, ...], float, float], ...]  #: (products, r_i, value)
    within_budget: bool

    @property
    def put_backs(self) -> tuple[Carry, ...]:
        return self.chosen[1:]


def decide(request: Carry | None, pending: Sequence[Carry], here: str,
           distance: Callable[[str, str], float], *, r_max: float, holding: Sequence[str] = (),
           hands: int = 2, model: ActionModel | None = None, rewards: Rewards | None = None,
           consider: int = 4) -> Decision | None:
    """Weigh every subset of ``pending`` together with ``request`` (the obligation TO).

    Each subset's cost r_i is the expected time of its best plan (its time over its
    probability of success, so unreliable actions cost more); its value is the sum
    of its rewards. The decision is the subset of greatest value whose cost is
    within ``r_max`` (ties: the cheaper); when even the request alone costs more,
    the request alone (the client comes first). Only the ``consider`` pending
    obligations cheapest to add on their own are weighed, which keeps the number
    of subsets at most 2^consider. Products already in hand must be put
    somewhere, so their obligations are always kept. Returns None when no plan
    exists for the request.
    """
    rewards = rewards or Rewards()
    base = [request] if request is not None else []
    forced = [c for c in pending if c.product in holding]
    free = [c for c in pending if c.product not in holding]
    if len(free) > consider:
        alone = []
        for carry in free:
            plan = plan_carries([*base, *forced, carry], here, distance, holding=holding,
                                hands=hands, model=model)
            alone.append((plan.cost if plan else float("inf"), carry.product, carry))
        free = [carry for _cost, _name, carry in sorted(alone)[:consider]]
    weighed = []
    best: tuple[float, float, tuple[Carry, ...], Plan] | None = None
    cheapest: tuple[float, tuple[Carry, ...], Plan] | None = None
    for size in range(len(free) + 1):
        for subset in itertools.combinations(free, size):
            chosen = (*base, *forced, *subset)
            if not chosen:
                continue
            plan = plan_carries(chosen, here, distance, holding=holding, hands=hands,
                                model=model)
            if plan is None:
                continue
            value = sum(
                rewards.request if carry is request else rewards.put_back for carry in chosen)
            weighed.append((tuple(c.product for c in chosen), round(plan.score, 1), value))
            if cheapest is None or plan.score < cheapest[0]:
                cheapest = (plan.score, chosen, plan)
            if plan.score <= r_max and (best is None or (value, -plan.score) > (best[0], -best[1])):
                best = (value, plan.score, chosen, plan)
    if best is not None:
        return Decision(best[2], best[3], best[0], tuple(weighed), True)
    if cheapest is None or len(cheapest[1]) > len(base) + len(forced):
        return None  # over budget: only what must be done (the request, the hands) goes ahead
    _cost, chosen, plan = cheapest
    value = sum(rewards.request if carry is request else rewards.put_back for carry in chosen)
    return Decision(chosen, plan, value, tuple(weighed), False)
