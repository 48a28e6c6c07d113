"""Runs across ROS 2: the executive here with the robot there (``RosRobot``), and the
simulated body served to a robot there (``BodyServer``).

Imported by the ROS 2 commands only, after they checked the ``ros`` extra is installed.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from homebot.app.fidelity import require_embodied
from homebot.app.run import RunSettings
from homebot.beliefs import Beliefs
from homebot.events import EventLog
from homebot.executive import Executive, RunReport
from homebot.navigation import Navigator
from homebot.skills import SkillContext
from homebot.task import Task
from homebot.transport.node import Node
from homebot.transport.ros_body import BodyServer
from homebot.transport.ros_robot import RobotMapping, RosRobot
from homebot.world import World

__all__ = ["RosRun", "RosRunSettings", "build_ros_run", "serve_simulated_body"]

MAX_WALKERS = 50  #: people walking about on their own in a served body's home, at most


@dataclass(frozen=True, kw_only=True)
class RosRunSettings:
    """A run whose robot is on ROS 2: the home it is in, and how to reach it."""

    world: World
    mapping: Path | None = None  #: the mapping file of ROS 2 names (None: homebot's own)
    connect_timeout: float = 20.0  #: seconds (wall clock) to wait for the robot
    monitoring: bool = True  #: skills check their effects by sensing
    retries: Mapping[str, int] = field(default_factory=dict)  #: extra attempts per skill
    time_limit: float | None = None  #: each task's budget in simulated seconds (None: none)


@dataclass
class RosRun:
    """The executive here, over a ``RosRobot`` connected to the robot there."""

    world: World
    robot: RosRobot
    context: SkillContext
    executive: Executive

    @property
    def events(self) -> EventLog:
        """The run's event log, with the robot's own events as they happened there."""
        return self.robot.events

    def run(self, task: Task) -> RunReport[None]:
        """Run a task on the robot, then collect its last events; raises ``RobotLost``
        when the robot stops answering."""
        report = self.executive.run(task)
        self.robot.finish()
        return report


def build_ros_run(node: Node, settings: RosRunSettings) -> RosRun:
    """Connect to the robot on ``node``'s domain (waiting up to ``connect_timeout``) and
    wire an executive over it."""
    mapping = RobotMapping.load(settings.mapping) if settings.mapping else RobotMapping()
    robot = RosRobot(node, mapping)
    robot.connect(settings.connect_timeout)
    world = settings.world
    context = SkillContext(robot=robot, world=world, navigator=Navigator(world),
                           beliefs=Beliefs.from_world(world, robot.events), events=robot.events,
                           monitoring=settings.monitoring, retries=dict(settings.retries))
    return RosRun(world, robot, context, Executive(context, time_limit=settings.time_limit))


def serve_simulated_body(node: Node, settings: RunSettings) -> BodyServer:
    """A ``SimBody`` in the home ``settings`` describe (its world, seed, disturbances and
    walkers), served on ``node`` as a robot's drivers would offer it."""
    require_embodied()
    from homebot.sim import Simulation
    from homebot.sim.body import SimBody

    world = settings.world
    simulation = Simulation(world, navigator=settings.navigator or Navigator(world),
                            seed=settings.seed, disturbances=settings.disturbances)
    body = SimBody(simulation, walkers=max(0, min(settings.walkers, MAX_WALKERS)))
    # The first sweep compiles the laser's kernel (seconds on a fresh install): do it
    # before the drivers appear on the network, not in a client's first tick.
    body.scan()
    return BodyServer(node, body, truth=body.true_pose)
