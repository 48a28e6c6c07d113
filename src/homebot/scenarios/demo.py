"""The demo: representative tasks in the apartment, each meeting a different disturbance."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from homebot.errors import WorldError
from homebot.events import Event
from homebot.executive import RunReport
from homebot.executive.taskfile import validate_task
from homebot.navigation import Navigator
from homebot.scenarios.running import RunBuilder, ScenarioRun
from homebot.sim import Simulation
from homebot.task import Step, Task
from homebot.world import DoorState, World

__all__ = ["DEMO_TASKS", "DemoTask", "run_demo"]


@dataclass(frozen=True)
class DemoTask:
    """A task, and what goes wrong in the home before it starts."""

    title: str
    task: Task
    setup: Callable[[Simulation], None]
    seed: int = 0


def _bring(obj: str, placement: str, person: str) -> Task:
    return Task((Step("navigate", {"to": placement}),
                 Step("find_object", {"object": obj, "placement": placement}),
                 Step("pick", {"object": obj}),
                 Step("navigate", {"to": person}),
                 Step("give", {"person": person})), f"bring the {obj} to {person}")


def _nothing(simulation: Simulation) -> None:
    """No extra disturbance."""


def _close_kitchen(simulation: Simulation) -> None:
    for door in ("kitchen arch", "kitchen door"):
        simulation.door_state[door] = DoorState.CLOSED


def _someone_in_the_office_door(simulation: Simulation) -> None:
    simulation.place_person_in_doorway("office door", "Maria")


def _cola_moved(simulation: Simulation) -> None:
    simulation.object_location["cola"] = "coffee table"


def _slippery(simulation: Simulation) -> None:
    simulation.disturbances = simulation.disturbances.model_copy(update={"grasp_slip": 0.6})


def _gone(simulation: Simulation) -> None:
    simulation.object_location["red wine"] = None


# What the disturbances above change, so ``run_demo`` can check a world has them.
_SETUP_NAMES = ("kitchen arch", "kitchen door", "office door", "Maria", "cola", "coffee table",
                "red wine")

DEMO_TASKS: tuple[DemoTask, ...] = (
    DemoTask("Bring the orange juice to Alex (nothing goes wrong)",
             _bring("orange juice", "fridge", "operator"), _nothing),
    DemoTask("Bring the apple to Alex: the kitchen doors are shut",
             _bring("apple", "kitchen table", "operator"), _close_kitchen),
    DemoTask("Bring the teddy bear to Alex: Maria stands in the office door",
             _bring("teddy bear", "office shelf", "operator"), _someone_in_the_office_door),
    DemoTask("Bring the cola to Sophie: someone took it to the living room",
             _bring("cola", "fridge", "Sophie"), _cola_moved),
    DemoTask("Bring the biscuits to Alex: a slippery packet",
             _bring("biscuits", "pantry", "operator"), _slippery, seed=5),
    DemoTask("Bring the red wine to Alex: it has run out",
             _bring("red wine", "kitchen counter", "operator"), _gone),
    DemoTask("Count the drinks in the fridge and report",
             Task((Step("navigate", {"to": "fridge"}),
                   Step("count", {"object": "drink", "placement": "fridge"}),
                   Step("navigate", {"to": "operator"}), Step("say", {"text": "$result"})),
                  "count the drinks in the fridge"), _nothing),
    DemoTask("Guide John from the bedroom to the living room",
             Task((Step("navigate", {"to": "bedroom"}),
                   Step("find_person", {"person": {"name": "John"}, "room": "bedroom"}),
                   Step("guide", {"to": "living room"})), "guide John to the living room"),
             _nothing),
)


def run_demo(world: World, build: RunBuilder,
             on_event: Callable[[Event], None] | None = None,
             on_task: Callable[[DemoTask], None] | None = None, level: float = 0.5,
             ) -> list[tuple[DemoTask, RunReport[None], ScenarioRun]]:
    """Run every demo task in a fresh home (built by ``build``) with light random
    disturbances on top.

    Raises ``WorldError`` or ``TaskError`` when ``world`` lacks what the tasks name.
    """
    known = {*world.doors, *world.people, *world.objects, *world.placements}
    missing = [name for name in _SETUP_NAMES if name not in known]
    if missing:
        raise WorldError(f"{world.source}: the demo is written for the apartment and needs "
                         f"{', '.join(missing)}; leave out --world, or add them")
    for demo in DEMO_TASKS:
        validate_task(demo.task, world, f"demo task '{demo.title}'")
    navigator = Navigator(world)
    results = []
    for demo in DEMO_TASKS:
        run = build(world, seed=demo.seed, level=level if demo.setup is _nothing else 0.0,
                    navigator=navigator)
        demo.setup(run.simulation)
        if on_task is not None:
            on_task(demo)
        if on_event is not None:
            run.simulation.events.listeners.append(on_event)
        results.append((demo, run.run(demo.task), run))
    return results
