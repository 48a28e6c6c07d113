"""``SimulatedRun``: a simulated home, a robot in it, its beliefs, and an executive."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from homebot.beliefs import Beliefs
from homebot.cancel import CancelToken
from homebot.executive import Executive, RunReport
from homebot.executive.recovery import Protocol
from homebot.navigation import Navigator
from homebot.navigation.localisation import MonteCarloLocalisation
from homebot.robot import Body, Robot
from homebot.scenarios.embodied import Fidelity, embodied_robot
from homebot.sim import PlanCache, Responder, SimRobot, Simulation
from homebot.skills import SkillContext
from homebot.task import Task
from homebot.world import DisturbanceModel, World

__all__ = ["SimulatedRun", "disturbance_level", "disturbed", "probability"]


def disturbed(level: float = 1.0) -> DisturbanceModel:
    """The disturbance model used by the demo and the robustness benchmark, scaled by ``level``.

    At level 1: 15 % of grasps slip, 10 % of detections miss and 5 % confuse,
    each door is shut with 15 %, someone stands in a doorway with 5 %, objects
    were moved (10 %), are moved while the robot comes (10 %) or are gone (2 %).
    """
    return DisturbanceModel(
        grasp_slip=0.15 * level, detection_miss=0.10 * level,
        detection_confusion=0.05 * level, door_closed=0.15 * level,
        person_in_way=0.05 * level, object_moved=0.10 * level,
        object_moved_during_task=0.10 * level, object_missing=0.02 * level)


def disturbance_level(text: str) -> float:
    """An argparse type: a level for ``disturbed``, 0 (none) to 6 (90 % of grasps slip)."""
    return _number_between(text, 0.0, 6.0, "a disturbance level")


def probability(text: str) -> float:
    """An argparse type: a probability, 0 to 1."""
    return _number_between(text, 0.0, 1.0, "a probability")


def _number_between(text: str, low: float, high: float, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not low <= value <= high:  # also false for nan
        raise argparse.ArgumentTypeError(f"{what} is a number from {low:g} to {high:g}, "
                                         f"not '{text}'")
    return value


@dataclass
class SimulatedRun:
    """Everything one run needs, wired: simulation, robot, beliefs, context, executive.

    ``body`` and ``localisation`` are the embodied robot's body and particle filter (the
    console drives the one and shows the other); None in the symbolic fidelity.
    """

    world: World
    simulation: Simulation
    robot: Robot
    context: SkillContext
    executive: Executive
    body: Body | None = None
    localisation: MonteCarloLocalisation | None = None

    @classmethod
    def create(cls, world: World, *, seed: int = 0,
               disturbances: DisturbanceModel | None = None, monitoring: bool = True,
               recovery: bool = True, responder: Responder | None = None,
               navigator: Navigator | None = None,
               plans: PlanCache | None = None,
               retries: Mapping[str, int] | None = None,
               inference: Protocol | None = None,
               time_limit: float | None = None,
               fidelity: Fidelity = Fidelity.SYMBOLIC, walkers: int = 0) -> SimulatedRun:
        """Build a run. Pass a shared ``navigator`` to skip rasterising the world again,
        and shared ``plans`` (of that navigator) to skip planning legs driven before.

        ``inference`` plugs the daily-life inference cycle into the executive;
        ``time_limit`` is each task's budget in simulated seconds (None: none).
        ``fidelity`` embodied puts a ``BodyRobot`` on a ``SimBody`` under the skills, with
        ``walkers`` people walking about on their own.
        """
        navigator = navigator or Navigator(world)
        simulation = Simulation(world, seed=seed, disturbances=disturbances,
                                responder=responder, navigator=navigator, plans=plans)
        embodied = None if fidelity is Fidelity.SYMBOLIC else \
            embodied_robot(simulation, navigator, walkers=walkers)
        robot: Robot = SimRobot(simulation) if embodied is None else embodied
        beliefs = Beliefs.from_world(world, simulation.events)
        context = SkillContext(robot=robot, world=world, navigator=navigator, beliefs=beliefs,
                               events=simulation.events, monitoring=monitoring,
                               retries=dict(retries or {}))
        executive = Executive(context, recovery=recovery, inference=inference,
                              time_limit=time_limit)
        if embodied is None:
            return cls(world, simulation, robot, context, executive)
        return cls(world, simulation, robot, context, executive, embodied.body,
                   embodied.localisation)

    def run(self, task: Task, *, interrupt: Callable[[], bool] | None = None,
            cancel: CancelToken | None = None) -> RunReport[None]:
        """Run a task in this home; ``interrupt`` (asked between steps) or ``cancel`` can
        stop it."""
        return self.executive.run(task, interrupt=interrupt, cancel=cancel)

    def path(self) -> list[tuple[float, float]]:
        """Where the robot has been during the run, from the log of its motions."""
        return list(self.simulation.trail)
