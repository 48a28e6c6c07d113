"""``Beliefs``: what the robot thinks is true, kept apart from the simulator's ground truth.

Beliefs start from what the robot was told (the world file: where objects are
kept, where people usually are) and change only with what the robot perceives.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from homebot.events import EventLog
from homebot.world import World

__all__ = ["Beliefs"]

_SAME_SPOT = 0.5  #: metres within which someone seen stands where a mistake was made


@dataclass
class Beliefs:
    """The robot's picture of the home."""

    object_at: dict[str, str | None] = field(default_factory=dict)
    not_at: dict[str, set[str]] = field(default_factory=dict)
    closed_doors: set[str] = field(default_factory=set)
    person_at: dict[str, tuple[float, float]] = field(default_factory=dict)
    #: where someone taken for a person proved not to be them (they did not take what
    #: was handed to that person): a face misread there is not believed again
    mistaken_for: dict[str, list[tuple[float, float]]] = field(default_factory=dict)
    holding: dict[str, str | None] = field(default_factory=dict)
    seen: set[str] = field(default_factory=set)  # objects whose place the robot saw itself
    last_taken: str | None = None  # the object picked up last ("give it" hands that one)
    events: EventLog | None = None

    @classmethod
    def from_world(cls, world: World, events: EventLog | None = None) -> Beliefs:
        """What the robot is told before it starts: the world file as written."""
        return cls(
            object_at={name: obj.placement for name, obj in world.objects.items()},
            person_at={name: person.position for name, person in world.people.items()},
            holding={hand: None for hand in world.robot.hands},
            closed_doors={name for name, door in world.doors.items() if door.state != "open"},
            events=events,
        )

    def _note(self, what: str, **data: object) -> None:
        if self.events is not None:
            self.events.record("belief", what=what, **data)

    def saw_object(self, name: str, placement: str) -> None:
        """Perception saw ``name`` on ``placement``."""
        self.seen.add(name)
        if self.object_at.get(name) != placement:
            self.object_at[name] = placement
            self._note("object_at", object=name, placement=placement)
        self.not_at.get(name, set()).discard(placement)

    def missed_object(self, name: str, placement: str) -> None:
        """Perception looked at ``placement`` and did not see ``name``."""
        self.not_at.setdefault(name, set()).add(placement)
        if self.object_at.get(name) == placement:
            self.object_at[name] = None
            self._note("object_not_at", object=name, placement=placement)

    def took(self, name: str, hand: str) -> None:
        self.holding[hand] = name
        self.last_taken = name
        self.object_at[name] = f"hand:{hand}"
        self._note("holding", object=name, hand=hand)

    def let_go(self, hand: str, placement: str | None) -> None:
        name = self.holding.get(hand)
        self.holding[hand] = None
        if name is not None:
            self.object_at[name] = placement
            self._note("released", object=name, placement=placement)

    def door_closed(self, door: str) -> None:
        if door not in self.closed_doors:
            self.closed_doors.add(door)
            self._note("door_closed", door=door)

    def door_open(self, door: str) -> None:
        if door in self.closed_doors:
            self.closed_doors.discard(door)
            self._note("door_open", door=door)

    def saw_person(self, name: str, position: tuple[float, float]) -> None:
        self.person_at[name] = position

    def mistook(self, name: str, position: tuple[float, float]) -> None:
        """Whoever stands at ``position`` is not ``name``, whatever their face said."""
        self.mistaken_for.setdefault(name, []).append(position)
        self._note("mistook", person=name, position=position)

    def is_mistaken(self, name: str, position: tuple[float, float]) -> bool:
        return any(math.dist(position, spot) <= _SAME_SPOT
                   for spot in self.mistaken_for.get(name, ()))

    def free_hand(self) -> str | None:
        return next((hand for hand, held in self.holding.items() if held is None), None)

    def hand_holding(self, name: str | None = None) -> str | None:
        """The hand holding ``name`` (or anything, when None)."""
        return next((hand for hand, held in self.holding.items()
                     if held is not None and (name is None or held == name)), None)
