"""A run: a simulated home, a robot in it in either fidelity, its beliefs and an executive.

``build_run(RunSettings(world=...))`` is how every interface gets one: the command line,
the web console, the ROS 2 nodes, the benchmarks, and the scenarios they start.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from datetime import datetime

from homebot.app.embodied import embodied_robot_in
from homebot.app.fidelity import Fidelity
from homebot.beliefs import Beliefs
from homebot.cancel import CancelToken
from homebot.clock import DEFAULT_START
from homebot.events import EventLog
from homebot.executive import Executive, RunReport
from homebot.executive.recovery import Protocol
from homebot.navigation import Navigator
from homebot.navigation.localisation import MonteCarloLocalisation
from homebot.robot import Body, Robot
from homebot.sim import InteractiveResponder, PlanCache, Responder, SimRobot, Simulation
from homebot.skills import SkillContext
from homebot.task import Task
from homebot.world import DisturbanceModel, World

__all__ = ["Run", "RunSettings", "build_run", "disturbed"]


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


@dataclass(frozen=True, kw_only=True)
class RunSettings:
    """What a run is made of: plain values, whoever asks for it (no command line here)."""

    world: World
    seed: int = 0
    fidelity: Fidelity = Fidelity.SYMBOLIC
    start: datetime = DEFAULT_START  #: the calendar date and time at simulated time 0
    #: how often things go wrong (``disturbed(level)``); None: nothing does
    disturbances: DisturbanceModel | None = None
    walkers: int = 0  #: embodied: how many people walk about on their own
    monitoring: bool = True  #: skills check their effects by sensing
    recovery: bool = True  #: the executive's recovery protocols
    retries: Mapping[str, int] = field(default_factory=dict)  #: extra attempts per skill
    time_limit: float | None = None  #: each task's budget in simulated seconds (None: none)
    inference: Protocol | None = None  #: the daily-life inference cycle, when plugged in
    #: who answers the robot's questions (None: the simulated people, by their own rules)
    responder: Responder | None = None
    interactive: bool = False  #: a person types the answers (when no ``responder`` is given)
    #: shared between runs of one world: skips rasterising it again
    navigator: Navigator | None = None
    plans: PlanCache | None = None  #: shared plans of that navigator: legs driven before


@dataclass
class Run:
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

    @property
    def events(self) -> EventLog:
        """The run's event log: every skill, status, speech act and belief update."""
        return self.simulation.events

    def run(self, task: Task, *, interrupt: Callable[[], bool] | None = None,
            cancel: CancelToken | None = None) -> RunReport[None]:
        """Run a task in this home; ``interrupt`` (asked between steps) or ``cancel`` can
        stop it."""
        return self.executive.run(task, interrupt=interrupt, cancel=cancel)

    def path(self) -> list[tuple[float, float]]:
        """Where the robot has been during the run, from the log of its motions."""
        return list(self.simulation.trail)

    def record_final_state(self) -> None:
        """Log where the run left things (``sim.final``: the simulator's truth), for the map."""
        sim = self.simulation
        sim.events.record("sim.final", world=sim.world.name,
                          objects=dict(sim.object_location),
                          people={name: [round(value, 3) for value in state.position]
                                  for name, state in sim.people.items()},
                          doors={name: str(state) for name, state in sim.door_state.items()},
                          robot=[round(value, 4) for value in sim.robot_pose])


def build_run(settings: RunSettings) -> Run:
    """Build a run as ``settings`` say: the symbolic ``SimRobot`` or, embodied, a
    ``BodyRobot`` on a ``SimBody`` under the skills."""
    world = settings.world
    navigator = settings.navigator or Navigator(world)
    responder = settings.responder or (InteractiveResponder() if settings.interactive else None)
    simulation = Simulation(world, seed=settings.seed, disturbances=settings.disturbances,
                            responder=responder, navigator=navigator, plans=settings.plans)
    embodied = None if settings.fidelity is Fidelity.SYMBOLIC else \
        embodied_robot_in(simulation, navigator, walkers=settings.walkers)
    robot: Robot = SimRobot(simulation) if embodied is None else embodied
    beliefs = Beliefs.from_world(world, simulation.events)
    context = SkillContext(robot=robot, world=world, navigator=navigator, beliefs=beliefs,
                           events=simulation.events, monitoring=settings.monitoring,
                           retries=dict(settings.retries), started_at=settings.start)
    executive = Executive(context, recovery=settings.recovery, inference=settings.inference,
                          time_limit=settings.time_limit)
    if embodied is None:
        return Run(world, simulation, robot, context, executive)
    return Run(world, simulation, robot, context, executive, embodied.body,
               embodied.localisation)
