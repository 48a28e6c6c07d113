"""RosBody on ``homebot sim serve --body``: the same odometry and scans as SimBody in-process."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator

import numpy as np
import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")
pytest.importorskip("cv2")

from homebot.navigation import Navigator
from homebot.robot import DriveKind, Twist, VelocityLimits
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.transport.node import Node, loopback
from homebot.transport.ros_body import RosBody
from homebot.world import World

COMMANDS = [Twist(0.3, 0.0, 0.0)] * 10 + [Twist(0.2, 0.0, 0.6)] * 10 + [Twist(0.0, 0.0, -0.8)] * 5


@pytest.fixture
def served_body(domain_id: int) -> Iterator[int]:
    process = subprocess.Popen(
        [sys.executable, "-c", "import sys; from homebot.cli import main; sys.exit(main())",
         "sim", "serve", "--body", "--seed", "5", "--domain-id", str(domain_id)],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    yield domain_id
    process.kill()
    process.wait(10)


def test_rosbody_drives_as_simbody_does(served_body: int) -> None:
    world = World.load("apartment")
    here = SimBody(Simulation(world, navigator=Navigator(world), seed=5))
    robot = world.robot
    there = RosBody(Node(loopback(served_body)), drive=DriveKind(robot.drive),
                    limits=VelocityLimits(robot.speed, robot.angular_speed),
                    radius=robot.radius, tick_period=here.tick_period)
    there.connect(60.0)
    assert there.scan().mount == here.scan().mount
    for command in COMMANDS:
        here.command_velocity(command)
        there.command_velocity(command)
        here.tick()
        there.tick()
        assert there.now() == pytest.approx(here.now(), abs=1e-6)
        mine, theirs = here.odometry(), there.odometry()
        assert (theirs.pose.x, theirs.pose.y) == pytest.approx((mine.pose.x, mine.pose.y),
                                                               abs=1e-9)
        assert theirs.pose.theta == pytest.approx(mine.pose.theta, abs=1e-9)
        assert theirs.twist.wz == pytest.approx(mine.twist.wz, abs=1e-9)
        # float32 on the wire: the same ranges to 1e-6 relative, the same returns missing
        np.testing.assert_allclose(there.scan().ranges, here.scan().ranges, rtol=1e-6)
    assert there.odometry().pose.x > 0.2 and there.odometry().pose.theta > 0.2  # it drove
    there.emergency_stop()
    assert there.stopped
