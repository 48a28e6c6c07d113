"""Plan inference: the paper's pruning rules, two hands, and skill steps."""

from __future__ import annotations

import itertools
from collections.abc import Callable

from homebot.inference import HAND, USER, ActionModel, Carry, plan_carries

Distance = Callable[[str, str], float]


def _kinds(plan: object) -> list[str]:
    return [action.kind for action in plan.actions]  # type: ignore[attr-defined]


def test_no_two_navigation_moves_in_a_row(distance: Distance) -> None:
    carries = [Carry("coke", "s2", USER), Carry("bisquits", "s3", USER)]
    plan = plan_carries(carries, "s1", distance)
    assert plan is not None
    navigation = {"move", "search_user"}
    kinds = _kinds(plan)
    assert not any(a in navigation and b in navigation for a, b in itertools.pairwise(kinds))


def test_two_hands_carry_two_products_in_one_trip(distance: Distance) -> None:
    carries = [Carry("coke", "s3", USER), Carry("bisquits", "s3", USER)]
    plan = plan_carries(carries, "s1", distance)
    assert plan is not None
    assert _kinds(plan).count("search_user") == 1
    assert _kinds(plan).count("move") == 1


def test_one_hand_means_two_trips(distance: Distance) -> None:
    carries = [Carry("coke", "s3", USER), Carry("bisquits", "s3", USER)]
    plan = plan_carries(carries, "s1", distance, hands=1)
    assert plan is not None
    assert _kinds(plan).count("search_user") == 2
    held = 0
    for kind in _kinds(plan):
        held += {"take": 1, "deliver": -1}.get(kind, 0)
        assert 0 <= held <= 1


def test_deliver_only_after_take_and_at_the_destination(distance: Distance) -> None:
    plan = plan_carries([Carry("noodles", "s1", "s2")], "s3", distance)
    assert plan is not None
    assert [str(a) for a in plan.actions] == [
        "move(s1)", "take(noodles)", "move(s2)", "deliver(noodles)"]


def test_an_assumed_source_is_searched_before_the_take(distance: Distance) -> None:
    plan = plan_carries([Carry("coke", "s2", USER, assumed=True)], "s1", distance)
    assert plan is not None
    assert [str(a) for a in plan.actions] == [
        "move(s2)", "search(coke)", "take(coke)", "search(user)", "deliver(coke)"]


def test_no_search_with_both_hands_full(distance: Distance) -> None:
    carries = [Carry("coke", "s2", USER, assumed=True), Carry("noodles", HAND, "s2"),
               Carry("kellogs", HAND, "s2")]
    plan = plan_carries(carries, "s1", distance, holding=["kellogs", "noodles"])
    assert plan is not None
    held = 2
    for action in plan.actions:
        if action.kind == "search":
            assert held < 2
        held += {"take": 1, "deliver": -1}.get(action.kind, 0)


def test_something_in_hand_is_delivered_without_a_take(distance: Distance) -> None:
    plan = plan_carries([Carry("coke", HAND, USER)], "s2", distance, holding=["coke"])
    assert plan is not None
    assert [str(a) for a in plan.actions] == ["search(user)", "deliver(coke)"]


def test_costs_follow_the_action_model(distance: Distance) -> None:
    model = ActionModel(speed=1.0, turn=0.0, take_time=10.0, deliver_time=5.0)
    plan = plan_carries([Carry("noodles", "s1", "s2")], "s1", distance, model=model)
    assert plan is not None
    assert plan.cost == 10.0 + 4.0 + 5.0
    assert 0.0 < plan.probability < 1.0


def test_plans_become_skill_steps(distance: Distance) -> None:
    plan = plan_carries([Carry("coke", "s2", USER, assumed=True)], "s1", distance)
    assert plan is not None
    steps = plan.steps(lambda shelf: f"shelf {shelf}", client="customer")
    assert [s.to_dict() for s in steps] == [
        {"skill": "navigate", "to": "shelf s2"}, {"skill": "look", "placement": "shelf s2"},
        {"skill": "pick", "object": "coke"}, {"skill": "navigate", "to": "customer"},
        {"skill": "give", "person": "customer", "object": "coke"}]
    assert "take(coke)" in repr(plan)
