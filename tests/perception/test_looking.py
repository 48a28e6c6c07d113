"""In the loop: the embodied robot sees objects on a placement through its camera pipeline."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("sklearn")
pytest.importorskip("cv2")

from homebot.app.embodied import embodied_robot_in
from homebot.embodied import BodyRobot
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.world import World, catalogue_entry

WORLD = """\
name: corner
rooms:
  - {name: kitchen, polygon: [[0, 0], [6, 0], [6, 4], [0, 4]]}
categories:
  - {name: drink, plural: drinks}
  - {name: food, plural: foods}
  - {name: fruit, plural: fruits}
placements:
  - {name: table, category: table, room: kitchen, center: [3, 2], size: [1.2, 0.7],
     approach: [3, 1.28, 1.5708]}
  - {name: shelf, category: storage, room: kitchen, center: [0.5, 3.5], size: [0.6, 0.6]}
objects:
  - {name: cola, category: drink, placement: table, position: [2.7, 2.0]}
  - {name: cereal, category: food, placement: table, position: [3.05, 2.1]}
  - {name: apple, category: fruit, placement: table, position: [3.3, 1.9]}
  - {name: soup, category: food, placement: shelf}
robot:
  pose: [3, 1.28, 1.5708]
"""


def test_the_embodied_robot_sees_what_stands_on_the_table() -> None:
    world = World.from_yaml_text(WORLD)
    simulation = Simulation(world, navigator=Navigator(world), seed=1)
    robot = embodied_robot_in(simulation, Navigator(world))
    before = simulation.clock.now()
    detections = robot.perceive_objects("table")
    assert simulation.clock.now() > before  # looking takes time
    assert sorted(d.label for d in detections) == ["apple", "cereal", "cola"]
    assert len({d.handle for d in detections}) == len(detections)  # the robot's own handles
    for detection in detections:
        assert detection.position is not None
        truth = min(simulation.objects_on("table"), key=lambda name: math.dist(
            detection.position or (0.0, 0.0), simulation.object_position[name]))
        assert truth == detection.label
        assert detection.category == world.objects[detection.label].category
        assert detection.position is not None
        assert math.dist(detection.position, simulation.object_position[truth]) < 0.03
        assert detection.size is not None and detection.mass is not None
    by_estimate = max(detections, key=lambda d: d.size or 0.0).label
    assert by_estimate == max(("apple", "cereal", "cola"),
                              key=lambda name: catalogue_entry(world, name).size)
    assert robot.perceive_objects("shelf") == []  # too far away to see it


def test_a_robot_lost_elsewhere_sees_nothing_on_the_table() -> None:
    world = World.from_yaml_text(WORLD)
    simulation = Simulation(world, navigator=Navigator(world), seed=1)
    robot = embodied_robot_in(simulation, Navigator(world))
    assert isinstance(robot, BodyRobot)
    robot.localisation.initialise(Pose(1.0, 1.0, 0.0), spread=0.01, angle_spread=0.01)
    assert robot.perceive_objects("table") == []


@pytest.mark.parametrize(("closer", "turned"), [(0.12, 0.2), (-0.1, -0.2)])
def test_objects_at_the_near_edge_are_seen_from_an_imprecise_approach(closer: float,
                                                                      turned: float) -> None:
    text = WORLD.replace("  - {name: soup,", "  - {name: lemon, category: fruit, placement: table, "
                         "position: [3.4, 1.72]}\n  - {name: soup,")
    world = World.from_yaml_text(text)
    simulation = Simulation(world, navigator=Navigator(world), seed=3)
    robot = embodied_robot_in(simulation, Navigator(world))
    assert isinstance(robot, BodyRobot)
    stand = world.placements["table"].approach
    x, y, theta = stand.x, stand.y, stand.theta
    pose = Pose(x + closer * math.cos(theta), y + closer * math.sin(theta), theta + turned)
    simulation.robot_pose = (pose.x, pose.y, pose.theta)
    robot.localisation.initialise(pose, spread=0.01, angle_spread=0.01)
    seen = robot.perceive_objects("table")
    assert sorted(d.label for d in seen) == ["apple", "cereal", "cola", "lemon"]


def test_the_table_is_seen_from_its_far_side_too() -> None:
    # Stepping round a table to reach an object, the robot looks again from there.
    world = World.from_yaml_text(WORLD)
    simulation = Simulation(world, navigator=Navigator(world), seed=1)
    robot = embodied_robot_in(simulation, Navigator(world))
    assert isinstance(robot, BodyRobot)
    pose = Pose(3.0, 2.75, -math.pi / 2)
    simulation.robot_pose = (pose.x, pose.y, pose.theta)
    robot.localisation.initialise(pose, spread=0.01, angle_spread=0.01)
    seen = robot.perceive_objects("table")
    assert sorted(d.label for d in seen) == ["apple", "cereal", "cola"]
    for detection in seen:
        assert detection.position is not None
        assert math.dist(detection.position, simulation.object_position[detection.label]) < 0.03
