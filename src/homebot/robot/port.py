"""The ``Robot`` port: everything skills may ask of a robot body, simulated or real.

Skills reach the world only through this interface. Every method reports what
the robot's own sensors and actuators say, never ground truth: a detection may
be wrong, a grasp may close on nothing. ``SimRobot`` implements it over
``homebot.sim``; ROS 2 adapters implement it over a real robot.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from enum import StrEnum

from homebot.cancel import CancelToken
from homebot.geometry import Pose

__all__ = [
    "Blocker",
    "Detection",
    "HelpRequest",
    "MoveReport",
    "PersonPercept",
    "Robot",
]


class Blocker(StrEnum):
    """What stopped a motion."""

    DOOR_CLOSED = "door_closed"  #: a shut (or locked) door is on the way
    PERSON = "person"  #: someone stands in a doorway on the way
    NO_PATH = "no_path"  #: no way exists even with every door open
    OBSTRUCTED = "obstructed"  #: something the map lacks stays in the way, nobody known
    STOPPED = "stopped"  #: the person walking with the robot showed the stop gesture
    CANCELLED = "cancelled"  #: the run's cancel token was cancelled: stopped where it was


@dataclass(frozen=True, slots=True)
class MoveReport:
    """What the base reports after a motion: where it stopped and why."""

    reached: bool
    pose: Pose
    distance: float
    blocker: Blocker | None = None
    door: str | None = None  #: the door where the robot stopped, if blocked at one
    person: str | None = None  #: the person in the way, if any
    doors_passed: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class Detection:
    """An object seen by perception. ``handle`` lets the arm reach that very object;
    ``position`` is where it stands (map frame, metres) when perception tells; ``size``
    (largest dimension, metres), ``mass`` (kg) and ``heading`` are perception's
    estimates, when it makes them (None: ask the world file)."""

    label: str
    category: str
    handle: int
    position: tuple[float, float] | None = None
    size: float | None = None
    mass: float | None = None
    #: radians, map frame: how a box stands turned (its x side), when perception fits it
    heading: float | None = None


@dataclass(frozen=True, slots=True)
class PersonPercept:
    """A person seen by perception, with what the robot can tell of them."""

    name: str | None
    posture: str
    gesture: str
    clothes: tuple[str, ...]
    position: tuple[float, float]
    room: str


class HelpRequest(StrEnum):
    """Things the robot can ask a person to do for it."""

    STEP_ASIDE = "step_aside"
    OPEN_DOOR = "open_door"


class Robot(ABC):
    """The port between skills and a robot body.

    Methods advance the robot's clock by the time the action takes. None of them
    raise for failures in the world; they report what the sensors saw.
    """

    @property
    @abstractmethod
    def hands(self) -> tuple[str, ...]:
        """The robot's hands, by name."""

    @abstractmethod
    def now(self) -> float:
        """Seconds since the robot started, on the robot's (simulated) clock."""

    @abstractmethod
    def pose(self) -> Pose:
        """Where the robot believes it is (localisation)."""

    @abstractmethod
    def move_to(self, goal: Pose, avoid_doors: frozenset[str] = frozenset(),
                escort: str | None = None, *,
                cancel: CancelToken | None = None) -> MoveReport:
        """Drive to ``goal``, not through ``avoid_doors``; ``escort`` walks along.

        Once ``cancel`` is cancelled the motion stops where it is (``Blocker.CANCELLED``).
        """

    @abstractmethod
    def perceive_objects(self, placement: str) -> list[Detection]:
        """Objects seen on a placement the robot stands at (empty when too far away)."""

    @abstractmethod
    def perceive_people(self) -> list[PersonPercept]:
        """People seen in the room the robot is in."""

    @abstractmethod
    def grasp(self, detection: Detection, hand: str) -> str | None:
        """Close ``hand`` on the detected object (the hand sensor tells if it worked).

        A robot that does not even try (out of its arm's reach, too heavy for it) says
        why, in words the robot can say; None when the hand closed."""

    @abstractmethod
    def held(self, hand: str) -> Detection | None:
        """What the hand's camera sees in ``hand``: None when it is empty."""

    @abstractmethod
    def release(self, hand: str, placement: str) -> None:
        """Put what ``hand`` holds on ``placement`` (the robot must stand at it)."""

    @abstractmethod
    def hand_over(self, hand: str, person: str) -> bool:
        """Offer what ``hand`` holds to a nearby person; True when they took it."""

    def receive(self, hand: str, person: str) -> Detection | None:
        """Offer the open ``hand`` to a nearby person and close it on what they put in it;
        what the hand's camera then sees there (None: they gave nothing). A robot whose
        hands cannot take things from people keeps this default and never receives."""
        return None

    @abstractmethod
    def open_door(self, door: str) -> bool:
        """Try to open a door the robot stands at; True when it is open afterwards."""

    @abstractmethod
    def door_is_open(self, door: str) -> bool | None:
        """Whether a door the robot stands at is open (None when it cannot see it)."""

    @abstractmethod
    def say(self, text: str) -> None:
        """Speak ``text`` aloud."""

    @abstractmethod
    def ask(self, person: str, question: str) -> str | None:
        """Ask a nearby person and return what they answered (None: no answer)."""

    @abstractmethod
    def request(self, person: str, request: HelpRequest, target: str) -> bool:
        """Ask a nearby person for help: open the ``target`` door, or step aside from it
        (``target`` empty: step out of the robot's way wherever they stand). ``person``
        empty: the robot does not know their name and asks whoever stands nearest (in
        the ``target`` door, if one is given)."""

    @abstractmethod
    def follow(self, person: str, goal: Pose | None, *,
               cancel: CancelToken | None = None) -> MoveReport:
        """Follow a person until they stop (at ``goal`` when the robot was told it).

        Once ``cancel`` is cancelled the robot stops where it is (``Blocker.CANCELLED``).
        """
