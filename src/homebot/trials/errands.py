"""Everyday errands: fetching and handing over, taking from a person, asking and telling.

The fetch trials (``homebot.trials.fetch``) bring an object to someone. A home robot's day
also has it take something a person holds out and put it away (Cosero §7.3.1's receiving),
and ask someone a question and tell the operator the answer. ``errands`` mixes the three
kinds, seeded; each errand says how the arena is set before it (``arrange``: a person holds
the object to be taken) and how the referee judges it from the simulator's truth
(``done``), never from the robot's report.
"""

from __future__ import annotations

import math
import random
import re
from dataclasses import dataclass
from enum import StrEnum

from homebot.sim import PERSON_PREFIX, Simulation
from homebot.skills import OPERATOR
from homebot.task import Step, Task
from homebot.text import fold
from homebot.trials.fetch import FetchTask, delivered, fetch_tasks
from homebot.world import World, surface_height

__all__ = ["Errand", "ErrandKind", "errands"]

#: The share of each kind in a mix (the rest are fetches).
_TAKE_SHARE = 0.25
_ASK_SHARE = 0.25
_NAME_QUESTION = "what is your name"
#: metres from the operator within which the robot's words reach them
_TELLING_DISTANCE = 2.5


class ErrandKind(StrEnum):
    """What an errand asks of the robot."""

    FETCH = "fetch"  #: bring an object from its placement to a person (hand it over)
    TAKE = "take"  #: take an object from a person's hand and put it on a placement
    ASK = "ask"  #: ask a person a question and tell the operator the answer


@dataclass(frozen=True, slots=True)
class Errand:
    """One errand: its task, and what the arena and the referee need to know of it."""

    kind: ErrandKind
    task: Task
    person: str  #: whom the robot hands to, takes from or asks (a name, or ``operator``)
    obj: str | None = None  #: the object fetched or taken
    placement: str | None = None  #: where a taken object is to go
    question: str | None = None

    def arrange(self, simulation: Simulation) -> None:
        """Set the arena before the run: the person of a TAKE errand holds the object."""
        if self.kind is ErrandKind.TAKE and self.obj is not None:
            simulation.object_location[self.obj] = PERSON_PREFIX + _named(simulation,
                                                                          self.person)

    def done(self, simulation: Simulation) -> bool:
        """Ground truth: did the errand happen? FETCH: the person holds the object. TAKE:
        the object stands on the placement. ASK: the robot said the person's true answer
        aloud, standing near the operator."""
        if self.kind is ErrandKind.FETCH:
            assert self.obj is not None
            return delivered(simulation, FetchTask(self.obj, self.person, self.task))
        if self.kind is ErrandKind.TAKE:
            return simulation.object_location.get(self.obj or "") == self.placement
        return self._told(simulation)

    def _told(self, simulation: Simulation) -> bool:
        person = simulation.person_state(self.person)
        operator = simulation.person_state(str(simulation.world.model.operator))
        if person is None or operator is None or self.question is None:
            return False
        answer = simulation.responder(person.model, self.question)
        if not answer:
            return False
        wanted = _words(answer)
        said = [_words(str(event.data.get("text", "")))
                for event in simulation.events.events if event.kind == "sim.speech"]
        # Words after the robot last asked the question carry the answer (not the question
        # itself, which may hold the answer: "Sophie, what is your name?"), and the robot
        # ends near the operator.
        question = _words(self.question)
        asked = max((index for index, text in enumerate(said) if question in text), default=-1)
        near = math.dist(simulation.robot_pose[:2], operator.position) <= _TELLING_DISTANCE
        return near and asked >= 0 and any(wanted in text for text in said[asked + 1:])


def _words(text: str) -> str:
    """``text`` as words only, folded: what is compared of what was said."""
    return " ".join(re.findall(r"[a-z0-9']+", fold(text)))


def _named(simulation: Simulation, person: str) -> str:
    return str(simulation.world.model.operator) if person == OPERATOR else person


def errands(world: World, count: int, seed: int) -> list[Errand]:
    """``count`` errands over the world's objects, placements and people, the same for
    the same seed: a quarter taking from a person, a quarter asking (when someone in the
    world can be asked), the rest fetching (``fetch_tasks``' own draw)."""
    chooser = random.Random(f"errands:{seed}")
    fetches = iter(fetch_tasks(world, count, seed))
    people = sorted(world.people)
    placements = sorted(name for name, p in world.placements.items()
                        if surface_height(p.model) > 0)
    objects = sorted(world.objects)
    made: list[Errand] = []
    for _ in range(count):
        draw = chooser.random()
        if draw < _TAKE_SHARE and people and placements and objects:
            made.append(_take(chooser, people, objects, placements))
        elif draw < _TAKE_SHARE + _ASK_SHARE and people:
            made.append(_ask(chooser, world, people))
        else:
            fetch = next(fetches)
            made.append(Errand(ErrandKind.FETCH, fetch.task, fetch.person, fetch.obj))
    return made


def _take(chooser: random.Random, people: list[str], objects: list[str],
          placements: list[str]) -> Errand:
    person, obj, placement = (chooser.choice(people), chooser.choice(objects),
                              chooser.choice(placements))
    steps = (
        Step("navigate", {"to": person}),
        Step("receive", {"person": person, "object": obj}),
        Step("navigate", {"to": placement}),
        Step("place", {"placement": placement, "object": obj}),
    )
    return Errand(ErrandKind.TAKE, Task(steps, f"take the {obj} from {person} and put it "
                                               f"on the {placement}"),
                  person, obj, placement)


def _ask(chooser: random.Random, world: World, people: list[str]) -> Errand:
    person = chooser.choice(people)
    scripted = sorted(world.people[person].answers)
    question = chooser.choice([*scripted, _NAME_QUESTION]).rstrip("?") + "?"
    steps = (
        Step("navigate", {"to": person}),
        Step("ask", {"person": person, "question": question}),
        Step("navigate", {"to": OPERATOR}),
        Step("say", {"text": "$answer"}),
    )
    return Errand(ErrandKind.ASK, Task(steps, f"ask {person} {question.rstrip('?')} and "
                                              "tell me"),
                  person, question=question)
