"""Navigation with recovery: what the laser sees that the map lacks, planning round it,
waiting, giving up on someone who stays in the way, and the people's side of it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.errors import NavigationError
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.navigate import StopReason
from homebot.navigation.recovery import ObstacleMemory, RecoveringNavigation, RecoveryPolicy
from homebot.robot import HelpRequest
from homebot.sim.body import SimBody
from homebot.sim.robot import SimRobot
from homebot.sim.simulation import Simulation
from homebot.world import World

pytest.importorskip("cv2")

# The kitchen, north of the table: a corridor between the table and the cabinet.
_CORRIDOR = (8.6, 2.75)
_WEST_OF_IT = Pose(7.6, 2.0, 0.0)
_HALL = Pose(5.5, 5.0, math.pi / 2)
_INSIDE_BATHROOM = (5.5, 6.45)
_AT_THE_SINK = Pose(5.98, 8.0, 0.0)


def _sim(world: World, navigator: Navigator) -> tuple[Simulation, SimBody]:
    simulation = Simulation(world, seed=3, navigator=navigator)
    return simulation, SimBody(simulation)


def _truth(simulation: Simulation) -> Pose:
    return Pose(*simulation.robot_pose)


def test_walls_and_furniture_are_explained_and_a_person_by_a_wall_is_not(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, body = _sim(apartment, apartment_navigator)
    for name in simulation.people:
        simulation.move_person(name, (0.6, 9.4))  # out of sight, in the bedroom corner
    body.teleport(Pose(3.0, 2.4, math.pi / 2))
    memory = ObstacleMemory(apartment_navigator, 0.15, 45.0)
    assert len(memory.unexpected(_truth(simulation), body.scan())) == 0
    # Someone standing against the living room's west wall, in the robot's view.
    simulation.move_person("Alex", (3.0, 3.45))
    body.tick()
    seen = memory.unexpected(_truth(simulation), body.scan())
    assert len(seen) > 0
    assert np.all(np.hypot(seen[:, 0] - 3.0, seen[:, 1] - 3.45) < 0.3)


def test_a_remembered_obstacle_is_forgotten_once_the_laser_sees_past_it(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, body = _sim(apartment, apartment_navigator)
    body.teleport(_WEST_OF_IT)
    simulation.move_person("Maria", _CORRIDOR)
    body.tick()
    memory = ObstacleMemory(apartment_navigator, 0.15, 45.0)
    remembered = memory.observe(body.now(), _truth(simulation), body.scan())
    assert np.any(np.hypot(remembered[:, 0] - _CORRIDOR[0], remembered[:, 1] - _CORRIDOR[1])
                  < 0.3)
    simulation.move_person("Maria", (10.6, 3.0))  # she walked off, out of that beam
    body.tick()
    remembered = memory.observe(body.now(), _truth(simulation), body.scan())
    assert not np.any(np.hypot(remembered[:, 0] - _CORRIDOR[0],
                               remembered[:, 1] - _CORRIDOR[1]) < 0.3)


def test_a_cleared_memory_keeps_only_what_the_laser_sees_again(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, body = _sim(apartment, apartment_navigator)
    body.teleport(_WEST_OF_IT)
    simulation.move_person("Maria", _CORRIDOR)
    body.tick()
    memory = ObstacleMemory(apartment_navigator, 0.15, 45.0)
    assert len(memory.observe(body.now(), _truth(simulation), body.scan()))
    # She walks off while the robot looks away: the memory alone would keep her there.
    simulation.move_person("Maria", (10.6, 3.0))
    body.teleport(Pose(_WEST_OF_IT.x, _WEST_OF_IT.y, math.pi))
    body.tick()
    remembered = memory.observe(body.now(), _truth(simulation), body.scan())
    assert np.any(np.hypot(remembered[:, 0] - _CORRIDOR[0], remembered[:, 1] - _CORRIDOR[1])
                  < 0.3)
    memory.clear()
    remembered = memory.observe(body.now(), _truth(simulation), body.scan())
    assert not np.any(np.hypot(remembered[:, 0] - _CORRIDOR[0],
                               remembered[:, 1] - _CORRIDOR[1]) < 0.3)


def test_a_person_in_the_way_is_driven_round_when_there_is_another_way(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, body = _sim(apartment, apartment_navigator)
    body.teleport(_WEST_OF_IT)
    simulation.move_person("Maria", _CORRIDOR)
    closest = math.inf

    def truth() -> Pose:
        nonlocal closest
        closest = min(closest, math.dist(simulation.robot_pose[:2], _CORRIDOR))
        return _truth(simulation)

    navigation = RecoveringNavigation(body, apartment_navigator, MotionSearchPlanner(), truth)
    target = Pose(9.5, 2.62, -math.pi / 2)
    attempt = navigation.drive(target)
    assert attempt.reached
    assert math.dist(simulation.robot_pose[:2], target.xy()) < 0.3
    assert closest > 0.5  # round the kitchen's other way, not past her
    assert simulation.collisions == []


def test_a_way_round_earns_its_own_time(apartment: World,
                                        apartment_navigator: Navigator) -> None:
    # The first path is 2 m; the way round the kitchen, past Maria, some 12 m: a budget
    # sized by the first path alone (23 s here) runs out on the way round.
    simulation, body = _sim(apartment, apartment_navigator)
    body.teleport(_WEST_OF_IT)
    simulation.move_person("Maria", _CORRIDOR)
    navigation = RecoveringNavigation(body, apartment_navigator, MotionSearchPlanner(),
                                      lambda: _truth(simulation), RecoveryPolicy(wait_budget=10.0))
    attempt = navigation.drive(Pose(9.5, 2.62, -math.pi / 2))
    assert attempt.reached and attempt.replans >= 1
    assert attempt.duration > 2.0 * 6.0 + 10.0  # longer than the first budget
    assert simulation.collisions == []


def _bathroom_doorway_blocked(world: World, navigator: Navigator
                              ) -> tuple[Simulation, SimBody, RecoveringNavigation]:
    """The robot in the hall, someone just inside the bathroom's only door."""
    simulation, body = _sim(world, navigator)
    body.teleport(_HALL)
    simulation.move_person("Maria", _INSIDE_BATHROOM)
    navigation = RecoveringNavigation(body, navigator, MotionSearchPlanner(),
                                      lambda: _truth(simulation), RecoveryPolicy(patience=6.0))
    return simulation, body, navigation


def test_someone_who_stays_in_the_only_way_makes_the_robot_wait_then_give_up(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, _, navigation = _bathroom_doorway_blocked(apartment, apartment_navigator)
    attempt = navigation.drive(_AT_THE_SINK)
    assert not attempt.reached
    assert attempt.reason is StopReason.BLOCKED
    assert attempt.waits >= 1
    assert simulation.collisions == []


def test_asked_to_step_aside_the_person_clears_the_way_and_the_robot_gets_there(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, _, navigation = _bathroom_doorway_blocked(apartment, apartment_navigator)
    assert not navigation.drive(_AT_THE_SINK)
    assert SimRobot(simulation).request("Maria", HelpRequest.STEP_ASIDE, "")
    moved = simulation.people["Maria"].position
    assert math.dist(moved, _INSIDE_BATHROOM) >= 0.8
    assert math.dist(moved, simulation.robot_pose[:2]) >= 1.0
    assert navigation.drive(_AT_THE_SINK)
    assert math.dist(simulation.robot_pose[:2], _AT_THE_SINK.xy()) < 0.3
    assert simulation.collisions == []


def test_someone_who_just_stopped_in_a_doorway_steps_aside_when_asked_by_the_door(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Not put there to block the door (a passer-by), yet asked about it by name.
    simulation, _, navigation = _bathroom_doorway_blocked(apartment, apartment_navigator)
    assert simulation.people["Maria"].blocking_door is None
    assert not navigation.drive(_AT_THE_SINK)
    assert SimRobot(simulation).request("Maria", HelpRequest.STEP_ASIDE, "bathroom door")
    assert math.dist(simulation.people["Maria"].position, _INSIDE_BATHROOM) >= 0.8
    assert navigation.drive(_AT_THE_SINK)
    assert simulation.collisions == []


def test_with_someone_standing_on_the_target_the_robot_comes_as_near_as_it_can_and_waits(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, body = _sim(apartment, apartment_navigator)
    body.teleport(Pose(2.7, 2.0, 0.0))  # in the living room, facing east
    # She stays, between the robot and the target; her legs 0.3 m from it.
    simulation.move_person("Maria", (3.6, 2.0))
    target = Pose(3.9, 2.0, 0.0)
    navigation = RecoveringNavigation(body, apartment_navigator, MotionSearchPlanner(),
                                      lambda: _truth(simulation),
                                      RecoveryPolicy(patience=6.0, wait_budget=10.0))
    attempt = navigation.drive(target)
    assert not attempt.reached and attempt.reason is not StopReason.REACHED
    assert attempt.waits >= 1
    # Round her, as near to the target as her legs and the goal tolerance allow (before,
    # it waited on its own side of her, 0.9 m off).
    assert simulation.robot_pose[0] > 3.6 + 0.3
    assert math.dist(simulation.robot_pose[:2], target.xy()) < 0.45
    assert simulation.collisions == []


def test_waiting_in_a_doorway_for_someone_the_robot_steps_out_of_their_way(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, body = _sim(apartment, apartment_navigator)
    door = apartment.doors["office door"].position
    body.teleport(Pose(door[0], door[1], -math.pi / 2))  # in the office door, facing south
    simulation.move_person("Maria", (door[0], door[1] - 0.75))  # just outside, waiting
    navigation = RecoveringNavigation(body, apartment_navigator, MotionSearchPlanner(),
                                      lambda: _truth(simulation))
    body.tick()
    seen = navigation.memory.observe(body.now(), _truth(simulation), body.scan())
    assert navigation.make_way(_truth(simulation), seen, frozenset()) > 0.3
    here = simulation.robot_pose[:2]
    assert math.dist(here, door) >= 0.9
    assert math.dist(here, simulation.people["Maria"].position) > 1.0
    assert simulation.collisions == []
    # Nobody near: nothing to make way for.
    assert navigation.make_way(_truth(simulation), np.zeros((0, 2)), frozenset()) == 0.0


def test_after_waiting_for_the_wide_way_the_robot_may_take_a_narrow_one(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Living room: the wide way round the coffee table's east side, or the gap between
    # the couch and the table (0.4 m from both, narrower than 0.25 + 0.2 here).
    simulation, body = _sim(apartment, apartment_navigator)
    navigation = RecoveringNavigation(body, apartment_navigator, MotionSearchPlanner(),
                                      lambda: _truth(simulation),
                                      RecoveryPolicy(static_margin=0.2))
    here, there = Pose(1.325, 3.3, 0.0), Pose(1.325, 0.9, 0.0)
    nobody = np.zeros((0, 2))
    wide = navigation.plan_wide(here, there, frozenset(), nobody)
    assert wide is not None and max(x for x, _ in wide) > 2.5  # round the table
    people = np.array([(x, 2.0) for x in np.arange(2.5, 4.45, 0.05)])  # across the east side
    assert navigation.plan_wide(here, there, frozenset(), people) is None  # wait for them
    narrow = navigation.plan_wide(here, there, frozenset(), people, squeeze=True)
    assert narrow is not None and max(x for x, _ in narrow) < 1.5  # between couch and table


def test_a_target_off_the_map_is_a_navigation_error(
        apartment: World, apartment_navigator: Navigator) -> None:
    simulation, body = _sim(apartment, apartment_navigator)
    navigation = RecoveringNavigation(body, apartment_navigator, MotionSearchPlanner(),
                                      lambda: _truth(simulation))
    with pytest.raises(NavigationError, match="no path"):
        navigation.drive(Pose(-50.0, -50.0, 0.0))


@pytest.mark.parametrize("field", ["stuck_after", "patience", "wait", "make_way_after"])
def test_a_policy_with_a_non_positive_time_is_refused(field: str) -> None:
    with pytest.raises(NavigationError, match=field):
        RecoveryPolicy(**{field: 0.0})


# A dining room off a 1.0 m corridor through a 0.8 m door near its west wall (as in
# benchmarks/flats/flat_narrow), a sideboard against that wall.
_DINING = """
name: dining_off_a_corridor
rooms:
  - {name: corridor, polygon: [[0, 3], [8, 3], [8, 4], [0, 4]]}
  - {name: dining room, polygon: [[3.5, 0], [7, 0], [7, 3], [3.5, 3]]}
doors:
  - {name: dining room door, rooms: [dining room, corridor], position: [4.2, 3], width: 0.8}
categories:
  - {name: dish, plural: dishes}
placements:
  - {name: sideboard, category: storage, room: dining room, center: [3.75, 1.3],
     size: [0.45, 1.2], holds: [dish]}
  - {name: dining table, category: table, room: dining room, center: [5.7, 1.3],
     size: [1.4, 0.9]}
objects:
  - {name: cup, category: dish, placement: sideboard}
people:
  - {name: Mei, room: dining room, position: [4.5, 2.3]}
robot:
  pose: [6.5, 3.5, 3.14]
"""


def test_making_way_just_past_a_doorway_never_goes_back_through_it() -> None:
    # Just through the door, someone stands a step ahead in the robot's way: it may step
    # aside in the dining room, but going back out to the corridor and in again is the
    # shuttling seen in flat_narrow (five times through the same door in one task).
    world = World.from_yaml_text(_DINING)
    navigator = Navigator(world)
    simulation, body = _sim(world, navigator)
    body.teleport(Pose(4.07, 2.58, -1.4))
    navigation = RecoveringNavigation(body, navigator, MotionSearchPlanner(),
                                      lambda: _truth(simulation))
    body.tick()
    seen = navigation.memory.observe(body.now(), _truth(simulation), body.scan())
    assert len(seen) and float(np.min(np.hypot(*(seen - (4.5, 2.3)).T))) < 0.3
    navigation.make_way(_truth(simulation), seen, frozenset())
    assert world.room_at(*simulation.robot_pose[:2]) == "dining room"
    assert simulation.robot_pose[1] < 3.0 - 0.3  # never into the doorway either
    assert simulation.collisions == []


class _SqueezeThroughHer(RecoveringNavigation):
    """A narrow way that always seems to open once the robot has waited, straight
    through the person who stays in the doorway (it never leads anywhere)."""

    def plan_wide(self, here: Pose, target: Pose, avoid_doors: frozenset[str],
                  obstacles: np.ndarray, squeeze: bool = False,
                  extended: np.ndarray | None = None,
                  ) -> tuple[tuple[float, float], ...] | None:
        wide = super().plan_wide(here, target, avoid_doors, obstacles, False, extended)
        if wide is not None or not squeeze:
            return wide
        return here.xy(), _INSIDE_BATHROOM, target.xy()


def test_narrow_ways_that_bring_the_robot_no_nearer_do_not_restart_its_patience(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Before, every narrow way tried restarted the wait: the robot stood behind her until
    # the goal's whole budget ran out, and was never blocked long enough to ask her.
    simulation, body = _sim(apartment, apartment_navigator)
    body.teleport(_HALL)
    simulation.move_person("Maria", _INSIDE_BATHROOM)
    policy = RecoveryPolicy(patience=6.0, make_way_after=2.0, stuck_after=2.0)
    navigation = _SqueezeThroughHer(body, apartment_navigator, MotionSearchPlanner(),
                                    lambda: _truth(simulation), policy)
    attempt = navigation.drive(_AT_THE_SINK)
    assert attempt.reason is StopReason.BLOCKED
    assert attempt.replans >= 2  # the narrow way was tried
    assert attempt.duration < 3 * policy.patience
    assert simulation.collisions == []
