"""The home domain: the paper's Table 1 shape, states from beliefs (not truth), tidy, the tray."""

from __future__ import annotations

import pytest

from homebot.beliefs import Beliefs
from homebot.errors import PlanningError
from homebot.htn import (
    Goal,
    Names,
    find_cheapest_plan,
    find_plan,
    find_plans,
    goals_from_steps,
    home_domain,
    state_from_beliefs,
)
from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.task import Step
from homebot.world import DisturbanceModel, World


def _plans(world: World, task: str, args: list[str], beliefs: Beliefs | None = None) -> list:
    domain = home_domain()
    beliefs = beliefs or Beliefs.from_world(world)
    state, names = state_from_beliefs(world, beliefs, world.robot.pose.xy())
    goal = Goal.of(task, args, world, names, domain)
    for atom in goal.atoms:
        state.add(atom)
    return find_plans(domain, state, [goal.task]).plans


def test_table_1_bring_object(apartment: World) -> None:
    plans = _plans(apartment, "bring_object", ["pringles", "Alex"])
    assert len(plans) == 3
    assert min(len(plan) for plan in plans) == 8
    assert len({tuple(plan.actions()) for plan in plans}) == 1  # identical action sequences
    fetches = {node.how for plan in plans for node in plan.network if node.task[0] == "fetch"}
    assert fetches == {"where-seen", "where-told", "where-it-belongs"}  # different networks
    assert [step.operator for step in plans[0]] == [
        "!announce", "!move_base", "!find_object", "!grasp", "!move_base", "!find_person",
        "!hand_over", "!report"]


def test_table_1_guide_robot(apartment: World) -> None:
    plans = _plans(apartment, "guide_person", ["Alex", "bedroom"])
    assert [len(plan) for plan in plans] == [5]
    assert plans[0].actions()[3] == ("!guide", "robot", "Alex", "bedroom")


def test_state_comes_from_beliefs_not_truth(apartment: World,
                                            apartment_navigator: Navigator) -> None:
    simulation = Simulation(apartment, seed=1, disturbances=DisturbanceModel(object_moved=1.0),
                            navigator=apartment_navigator)
    assert simulation.object_location["pringles"] != "pantry"  # the truth moved on
    beliefs = Beliefs.from_world(apartment)
    plan = _plans(apartment, "bring_object", ["pringles", "Alex"], beliefs)[0]
    assert ("!find_object", "robot", "pringles", "pantry") in plan.actions()
    beliefs.missed_object("pringles", "pantry")  # the robot looked and did not see it
    replanned = _plans(apartment, "bring_object", ["pringles", "Alex"], beliefs)
    assert len(replanned) == 1  # neither where told nor where it belongs: search the home
    assert replanned[0].actions()[1:3] == [("!search_object", "robot", "pringles"),
                                           ("!grasp", "robot", "pringles", "pringles")]
    beliefs.saw_object("pringles", "coffee table")  # found elsewhere: fetch from there
    seen = _plans(apartment, "bring_object", ["pringles", "Alex"], beliefs)
    assert [plan.actions()[2] for plan in seen] == [
        ("!find_object", "robot", "pringles", "coffee_table")]


def test_holding_the_object_skips_the_fetch(apartment: World) -> None:
    beliefs = Beliefs.from_world(apartment)
    beliefs.took("cola", "left")
    plan = _plans(apartment, "bring_object", ["cola", "Maria"], beliefs)[0]
    assert [step.operator for step in plan] == ["!announce", "!move_base", "!find_person",
                                                "!hand_over", "!report"]


def test_tray_brings_two_objects_in_one_trip(apartment: World) -> None:
    plan = _plans(apartment, "bring_objects", ["operator", "cola", "pringles"])[0]
    operators = [step.operator for step in plan]
    assert operators.count("!grasp") == 2 and operators.count("!find_person") == 1
    assert operators.index("!grasp", operators.index("!grasp") + 1) < operators.index(
        "!hand_over")


def test_tidy_puts_misplaced_objects_where_they_belong(apartment: World) -> None:
    plan = _plans(apartment, "tidy", [])[0]
    put = [args for operator, *args in plan.actions() if operator == "!put_down"]
    assert put == [["robot", "red_wine", "fridge"], ["robot", "rubik_cube", "bookshelf"]]


def test_tidy_of_200_objects(apartment: World) -> None:
    data = apartment.to_dict()
    holders = [p for p in apartment.placements.values() if p.holds]
    data["objects"] = [{"name": f"thing {i:03d}", "category": holders[i % len(holders)].holds[0],
                        "placement": "desk"} for i in range(200)]
    messy = World.from_dict(data)
    state, names = state_from_beliefs(messy, Beliefs.from_world(messy), messy.robot.pose.xy())
    plan = find_plan(home_domain(), state, [Goal.of("tidy", [], messy, names).task]).plan
    put = [step for step in plan if step.operator == "!put_down"]
    assert len(put) == 200
    # Two at a time on the tray: two drives per pair (an odd one out per category).
    trips = sum(1 for step in plan if step.operator == "!move_base")
    assert trips <= 2 * (100 + len(holders))


def test_cheapest_plan_and_serve_a_category(apartment: World) -> None:
    domain = home_domain()
    state, names = state_from_beliefs(apartment, Beliefs.from_world(apartment),
                                      apartment.robot.pose.xy())
    goal = Goal.of("serve", ["drink", "John"], apartment, names, domain)
    cheapest = find_cheapest_plan(domain, state, [goal.task])
    assert cheapest.plan.cost == 6 and cheapest.plan.actions()[3][:2] == ("!grasp", "robot")


def test_goal_errors(apartment: World) -> None:
    with pytest.raises(PlanningError, match="did you mean 'pringles'"):
        Goal.of("bring_object", ["pringels", "Alex"], apartment)
    with pytest.raises(PlanningError, match="takes 2 arguments"):
        Goal.of("guide_person", ["Alex"], apartment)
    with pytest.raises(PlanningError, match="neither an operator nor a method"):
        Goal.of("fly", [], apartment, Names(), home_domain())


def test_goals_from_gpsr_steps(apartment: World) -> None:
    bring = [Step("find_object", {"object": "drink"}), Step("pick", {"object": "drink"}),
             Step("navigate", {"to": "operator"}), Step("give", {"person": "operator"})]
    guide = [Step("navigate", {"to": "couch"}), Step("find_person", {"person": {"name": "Alex"}}),
             Step("guide", {"to": "bedroom"})]
    goals = goals_from_steps([*bring, *guide], apartment)
    assert [goal.task for goal in goals] == [("serve", "robot", "drink", "Alex"),
                                             ("guide_person", "robot", "Alex", "bedroom")]
    assert goals_from_steps([Step("count", {"room": "kitchen"})], apartment) is None


def test_where_things_belong_comes_from_the_knowledge_base(apartment: World) -> None:
    from homebot.knowledge import KnowledgeBase

    knowledge = KnowledgeBase.load("apartment_places")
    domain = home_domain()
    beliefs = Beliefs.from_world(apartment)
    beliefs.saw_object("red wine", "coffee table")

    def tidy(kb: KnowledgeBase | None) -> list[tuple[str, ...]]:
        state, names = state_from_beliefs(apartment, beliefs, apartment.robot.pose.xy(),
                                          knowledge=kb)
        plan = find_plan(domain, state, [Goal.of("tidy", [], apartment, names).task]).plan
        return [(args[1], args[2]) for operator, *args in plan.actions()
                if operator == "!put_down"]

    # Told (the world file): drinks go in the fridge, toys on a toy shelf.
    assert tidy(None) == [("red_wine", "fridge"), ("rubik_cube", "bookshelf")]
    # The KB's exceptions: red wine is kept on the counter, the rubik cube on the desk.
    assert tidy(knowledge) == [("red_wine", "kitchen_counter")]


def test_tidy_one_room(apartment: World) -> None:
    office = _plans(apartment, "tidy_room", ["office"])[0]
    assert [a for a in office.actions() if a[0] == "!put_down"] == [
        ("!put_down", "robot", "rubik_cube", "bookshelf")]
    assert len(_plans(apartment, "tidy_room", ["bedroom"])[0]) == 0
