"""The embodied robot: a ``BodyRobot`` wired over a ``Body``, and over a ``SimBody``.

``embodied_robot`` builds the robot from a body and what the robot was told (the
world file: the map, the names of places and people, where things were put; never
where they are now), with its own perception, localisation and arm control. The
simulation reaches the robot only through the ``SimBody``
(``embodied_robot_in``): everything it believes comes through the Body port.
"""

from __future__ import annotations

import importlib.util
import zlib
from typing import TYPE_CHECKING

import numpy as np

from homebot import progress
from homebot.app.fidelity import require_embodied
from homebot.errors import SpeechError
from homebot.events import EventLog
from homebot.navigation import Navigator
from homebot.robot import Body
from homebot.sim import Simulation
from homebot.world import World

if TYPE_CHECKING:
    from homebot.embodied import BodyRobot
    from homebot.sim.hearing import PersonVoice
    from homebot.trials.following import FollowEpisode

__all__ = ["embodied_robot", "embodied_robot_in", "follow_me_episode"]

# Seed stream of the robot's own filter, apart from the simulation's and the body's.
_LOCALISATION_STREAM = 303
_DOOR_STREAM = 505  #: the door perception's RANSAC
_FACE_HALF_ANGLE = 0.25  #: radians off the head's axis within which a face is the one looked at


def embodied_robot_in(simulation: Simulation, navigator: Navigator, *, walkers: int = 0,
                      known_start: bool = True) -> BodyRobot:
    """A ``BodyRobot`` on a ``SimBody`` in ``simulation``: the body is all of the
    simulation the robot is given.

    Args:
        walkers: how many people walk about on their own.
        known_start: the robot is told where it starts (else it localises globally).
    """
    require_embodied()
    from homebot.sim.body import SimBody

    with progress.task("building the embodied robot and its simulated body"):
        body = SimBody(simulation, walkers=walkers, face_half_angle=_FACE_HALF_ANGLE,
                       voice=_people_voice())
        return embodied_robot(body, simulation.world, navigator, seed=simulation.seed,
                              events=simulation.events, known_start=known_start)


def _people_voice() -> PersonVoice | None:
    """How the simulated people sound: each person one of espeak-ng's Klatt voices, by
    name (None without the ``speech`` extra: people then answer nobody aloud)."""
    try:
        from homebot.speech.voice import HELD_OUT_VOICES, VOICES, espeak

        voice = espeak()
    except (ImportError, SpeechError):
        return None
    voices = (*VOICES, *HELD_OUT_VOICES)

    def speak(person: str, text: str) -> np.ndarray:
        return voice.synthesise(text, voices[zlib.crc32(person.encode()) % len(voices)])
    return speak


def embodied_robot(body: Body, world: World, navigator: Navigator, *, seed: int,
                   events: EventLog, known_start: bool = True) -> BodyRobot:
    """A ``BodyRobot`` over ``body``.

    Args:
        world: what the robot was told: the map, the places, the people's names.
        seed: the robot's own random streams (its particle filter, its perception).
        events: where the robot records what it does and sees (it never reads it).
        known_start: the robot is told where it starts (the world file's pose), else it
            localises globally.
    """
    require_embodied()
    from homebot.app.perception import household_faces, perception_for
    from homebot.embodied import BodyRobot, PeopleLook, TableLook
    from homebot.navigation.local_planner import MotionSearchPlanner
    from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
    from homebot.perception.faces import Acquaintances

    localisation = MonteCarloLocalisation(
        navigator.grid, np.random.default_rng([seed, _LOCALISATION_STREAM]),
        MclParameters(odom_model_type=body.drive))
    if known_start:
        localisation.initialise(world.robot.pose, spread=0.05, angle_spread=0.05)
    else:
        localisation.initialise_globally()
    looking = TableLook(body, world, perception_for(world, seed))
    robot: BodyRobot
    if importlib.util.find_spec("mujoco") is None:  # no arm in physics: an armless robot
        robot = BodyRobot(body, world, navigator, localisation, MotionSearchPlanner(),
                          events, looking=looking)
    else:
        from homebot.embodied.door_opening import DoorOpening
        from homebot.embodied.hands import ArmedBodyRobot, SeenObjects
        from homebot.manipulation.control import ArmControl

        seen = SeenObjects(world)
        arm = ArmControl(body, world, seen, seed=seed)
        doors = DoorOpening(body, world, np.random.default_rng([seed, _DOOR_STREAM]))
        robot = ArmedBodyRobot(body, world, navigator, localisation, MotionSearchPlanner(),
                               events, looking=looking, arm=arm, seen=seen, doors=doors)
    # faces: the household is known by face; "my name is ..." enrols the head camera's
    # views of someone new in front
    robot.acquaintances = Acquaintances(lambda: household_faces(world))
    robot.people_look = PeopleLook(body, world, navigator.grid, robot.localise,
                                   acquaintances=robot.acquaintances,
                                   face_images=robot.face_views)
    return robot


def follow_me_episode(world: World, seed: int, navigator: Navigator) -> FollowEpisode:
    """One seeded Follow Me episode (``homebot.trials.following``): the embodied robot,
    told only where it starts, follows the operator until told to stop; the verdict is
    the arena referee's, by the truth."""
    from homebot.embodied.following import FollowParameters
    from homebot.sim.body import SimBody
    from homebot.trials.following import FollowEpisode, follow_me_arena

    arena = follow_me_arena(world, seed, navigator)
    if isinstance(arena, FollowEpisode):
        return arena
    robot = embodied_robot_in(arena.sim, navigator)
    robot.localisation.initialise(arena.robot_pose, spread=0.05, angle_spread=0.05)
    body = robot.body
    assert isinstance(body, SimBody)
    arena.start(body)
    # the walk, its pauses, and time to find the operator again if lost
    result = robot.following(FollowParameters(budget=1.5 * arena.walk_seconds + 60.0)).follow()
    return arena.judge(body, result.end.value, result.lost_count)
