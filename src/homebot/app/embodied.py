"""The embodied robot over the simulated body: a ``BodyRobot`` on a ``SimBody``, wired."""

from __future__ import annotations

import importlib.util
import math
from typing import TYPE_CHECKING

import numpy as np

from homebot.app.fidelity import require_embodied
from homebot.navigation import Navigator
from homebot.sim import SimRobot, Simulation

if TYPE_CHECKING:
    from homebot.embodied import BodyRobot
    from homebot.sim.body import SimBody

__all__ = ["embodied_robot"]

# Seed stream of the robot's own filter, apart from the simulation's and the body's.
_LOCALISATION_STREAM = 303
_FACE_HALF_ANGLE = 0.25  #: radians off the head's axis within which a face is the one looked at
_HAND_REACH = 0.08  #: metres from an object's centre within which a grasp closes on it


def embodied_robot(simulation: Simulation, navigator: Navigator, *,
                   walkers: int = 0, known_start: bool = True) -> BodyRobot:
    """A ``BodyRobot`` on a ``SimBody`` in ``simulation``.

    Args:
        walkers: how many people walk about on their own.
        known_start: the robot is told where it starts (else it localises globally).
    """
    require_embodied()
    from homebot.app.perception import household_faces, perception_for
    from homebot.embodied import BodyRobot, PeopleLook, TableLook
    from homebot.navigation.local_planner import MotionSearchPlanner
    from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
    from homebot.perception.faces import Acquaintances
    from homebot.sim.body import SimBody
    from homebot.sim.faces import FaceCamera

    world = simulation.world
    body = SimBody(simulation, walkers=walkers)
    localisation = MonteCarloLocalisation(
        navigator.grid, np.random.default_rng([simulation.seed, _LOCALISATION_STREAM]),
        MclParameters(odom_model_type=body.drive))
    if known_start:
        localisation.initialise(world.robot.pose, spread=0.05, angle_spread=0.05)
    else:
        localisation.initialise_globally()
    percepts = SimRobot(simulation)
    looking = TableLook(body, world, perception_for(world, simulation.seed),
                        _SimulatedObjects(simulation))
    robot: BodyRobot
    if importlib.util.find_spec("mujoco") is None:  # no physics: grasps stay symbolic
        robot = BodyRobot(body, world, navigator, localisation, MotionSearchPlanner(),
                          percepts, percepts, simulation.events, looking=looking)
    else:
        from homebot.embodied.hands import ArmedBodyRobot, SeenObjects
        from homebot.manipulation.control import ArmControl

        seen = SeenObjects(world, _TrueObjectPoses(simulation, body))
        arm = ArmControl(body, world, seen, seed=simulation.seed)
        robot = ArmedBodyRobot(body, world, navigator, localisation, MotionSearchPlanner(),
                               percepts, percepts, simulation.events, looking=looking, arm=arm,
                               seen=seen)
    # faces: the household is known by face; "my name is ..." enrols the head camera's
    # views of someone new in front
    robot.acquaintances = Acquaintances(lambda: household_faces(world))
    # the head turns to each person seen: the close-up is of whoever is on its axis
    robot.face_images = FaceCamera(body, half_angle=_FACE_HALF_ANGLE)
    robot.people_look = PeopleLook(body, world, navigator.grid, robot.localise,
                                   acquaintances=robot.acquaintances,
                                   face_images=robot.face_images)
    return robot


class _TrueObjectPoses:
    """Where objects stand, for the arm's planning scene: the simulator's truth (x, y,
    heading, surface height), standing in until perception reports object poses; a
    detection's own position, when perception gives one, takes precedence for the target."""

    def __init__(self, simulation: Simulation, body: SimBody) -> None:
        self.sim = simulation
        self.body = body

    def __call__(self, name: str) -> tuple[float, float, float, float] | None:
        from homebot.world import surface_height

        where = self.sim.object_location.get(name)
        if where is None or where not in self.sim.world.placements:
            return None
        x, y = self.sim.position_on(name, where)
        return (x, y, self.body.hands.heading(name),
                surface_height(self.sim.world.placements[where].model))


class _SimulatedObjects:
    """What the simulated world does when the robot looks or reaches (``ObjectWorld``)."""

    def __init__(self, simulation: Simulation) -> None:
        self.sim = simulation

    def object_at(self, point: tuple[float, float], placement: str) -> int | None:
        """The object on ``placement`` nearest ``point``, if the hand reaching there meets it."""
        sim = self.sim
        near = sorted((math.dist(point, sim.position_on(name, placement)), name)
                      for name in sim.objects_on(placement))
        if not near or near[0][0] > _HAND_REACH:
            return None
        return sim.object_ids[near[0][1]]

    def looked_at(self, placement: str) -> None:
        self.sim.maybe_move_during_task(placement)
