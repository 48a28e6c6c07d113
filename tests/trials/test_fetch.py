"""Fetch-and-deliver trials: seeded tasks, and a delivery judged where the object truly is."""

from __future__ import annotations

from homebot.navigation import Navigator
from homebot.sim import PERSON_PREFIX, Simulation
from homebot.skills import OPERATOR
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import World


def test_the_same_seed_draws_the_same_tasks_over_the_worlds_objects_and_people() -> None:
    world = World.load("apartment")
    tasks = fetch_tasks(world, 20, seed=4)
    assert tasks == fetch_tasks(world, 20, seed=4)
    assert tasks != fetch_tasks(world, 20, seed=5)
    for fetch in tasks:
        assert fetch.obj in world.objects
        assert fetch.person == OPERATOR or fetch.person in world.people
        assert [step.skill for step in fetch.task.steps] == [
            "navigate", "find_object", "pick", "navigate", "give"]
        assert fetch.task.steps[0].args["to"] == world.objects[fetch.obj].placement


def test_a_delivery_counts_only_when_the_person_truly_holds_the_object() -> None:
    world = World.load("apartment")
    simulation = Simulation(world, seed=0, navigator=Navigator(world))
    fetch = next(task for task in fetch_tasks(world, 20, seed=1) if task.person != OPERATOR)
    assert not delivered(simulation, fetch)
    simulation.object_location[fetch.obj] = PERSON_PREFIX + fetch.person
    assert delivered(simulation, fetch)
    to_operator = next(task for task in fetch_tasks(world, 20, seed=1)
                       if task.person == OPERATOR)
    simulation.object_location[to_operator.obj] = PERSON_PREFIX + str(world.model.operator)
    assert delivered(simulation, to_operator)
