"""Fetch-and-deliver trials: seeded tasks for a world, and a referee of the delivery."""

from __future__ import annotations

import random
from dataclasses import dataclass

from homebot.sim import PERSON_PREFIX, Simulation
from homebot.skills import OPERATOR
from homebot.task import Step, Task
from homebot.world import World

__all__ = ["FetchTask", "delivered", "fetch_tasks"]


@dataclass(frozen=True, slots=True)
class FetchTask:
    """Bring ``obj`` from where the robot believes it is to ``person``."""

    obj: str
    person: str
    task: Task


def fetch_tasks(world: World, count: int, seed: int) -> list[FetchTask]:
    """``count`` tasks over the world's objects and people, the same for the same seed."""
    chooser = random.Random(seed)
    objects = sorted(world.objects)
    people = sorted(world.people)
    tasks = []
    for _ in range(count):
        obj = chooser.choice(objects)
        person = chooser.choice([OPERATOR, *people])
        placement = world.objects[obj].placement
        steps = (
            Step("navigate", {"to": placement}),
            Step("find_object", {"object": obj, "placement": placement}),
            Step("pick", {"object": obj}),
            Step("navigate", {"to": person}),
            Step("give", {"person": person}),
        )
        tasks.append(FetchTask(obj, person, Task(steps, f"bring the {obj} to {person}")))
    return tasks


def delivered(simulation: Simulation, fetch: FetchTask) -> bool:
    """Ground truth: does the person now hold the object?"""
    person = simulation.world.model.operator if fetch.person == OPERATOR else fetch.person
    return simulation.object_location.get(fetch.obj) == PERSON_PREFIX + str(person)
