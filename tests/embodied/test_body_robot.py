"""BodyRobot: skills on a body that localises from its laser and drives reactively.

Success is judged by the simulation's truth: where the robot really is, who
really holds the object, whether it ever touched anything.
"""

from __future__ import annotations

import math

import pytest

from homebot.app import Fidelity, Run, RunSettings, build_run
from homebot.embodied.hands import ArmedBodyRobot
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.robot import Blocker
from homebot.sim import PERSON_PREFIX
from homebot.skills import Status, skill_named
from homebot.task import Step, Task
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import DoorState, World

pytest.importorskip("cv2")


def _run(world: World, navigator: Navigator, seed: int = 0, walkers: int = 0) -> Run:
    return build_run(RunSettings(
        world=world, seed=seed, navigator=navigator, fidelity=Fidelity.EMBODIED, walkers=walkers))


def test_navigate_really_drives_and_the_pose_is_an_estimate(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    report = run.run(Task((Step("navigate", {"to": "bed"}),)))
    assert report.success
    truth = run.simulation.robot_pose
    goal = apartment.placements["bed"].approach
    assert math.dist(truth[:2], goal.xy()) < 0.3
    assert run.simulation.collisions == []
    estimate = run.robot.pose()
    assert estimate.xy() != truth[:2]  # the robot knows only its estimate ...
    assert math.dist(estimate.xy(), truth[:2]) < 0.15  # ... and it is a good one
    kinds = {event.kind for event in run.simulation.events.events}
    assert {"robot.trajectory", "robot.laser", "robot.particles"} <= kinds
    # Driving takes simulated time by the robot's speed, not a jump.
    assert report.sim_time > math.dist(apartment.robot.pose.xy(), goal.xy()) / apartment.robot.speed


def test_a_fetch_and_deliver_task_succeeds_by_ground_truth(
        apartment: World, apartment_navigator: Navigator) -> None:
    fetch = fetch_tasks(apartment, 1, seed=5)[0]
    run = _run(apartment, apartment_navigator, seed=5)
    report = run.run(fetch.task)
    assert report.success
    assert delivered(run.simulation, fetch)
    assert run.simulation.collisions == []


def test_a_closed_door_stops_the_robot_in_front_and_someone_asked_opens_it(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    # The arm would push this door open (tests/embodied/test_doors_opened_by_the_arm.py);
    # here the robot's arm opens no doors, so it asks.
    if isinstance(run.robot, ArmedBodyRobot):
        run.robot.doors = None
    run.simulation.door_state["bedroom door"] = DoorState.CLOSED
    # someone in the corridor, a step from the door, hears the robot ask
    run.simulation.move_person("Sophie", run.simulation.free_floor_near((2.8, 5.4)))
    report = run.run(Task((Step("navigate", {"to": "bed"}),)))
    assert report.success, report.reason
    kinds = [(event.kind, event.data.get("door")) for event in run.simulation.events.events]
    assert ("robot.blocked", "bedroom door") in kinds
    assert ("sim.person", "bedroom door") in kinds  # she opened it, asked aloud
    assert run.simulation.door_state["bedroom door"] is DoorState.OPEN
    assert run.simulation.collisions == []


def test_the_robot_reports_a_shut_door_it_cannot_pass(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.door_state["bedroom door"] = DoorState.LOCKED
    report = run.robot.move_to(apartment.placements["bed"].approach)
    assert not report.reached
    assert report.blocker is Blocker.DOOR_CLOSED
    assert report.door == "bedroom door"
    assert math.dist(run.simulation.robot_pose[:2], apartment.doors["bedroom door"].position) < 1.2


def test_embodied_runs_are_deterministic_by_seed(apartment: World,
                                                apartment_navigator: Navigator) -> None:
    def drive(seed: int) -> tuple[float, float, float]:
        run = _run(apartment, apartment_navigator, seed=seed, walkers=2)
        run.run(Task((Step("navigate", {"to": "coat rack"}),)))
        return run.simulation.robot_pose

    assert drive(2) == drive(2)


@pytest.mark.parametrize("door_state", [DoorState.OPEN, DoorState.LOCKED])
def test_a_door_ahead_that_someone_stands_in_is_what_stops_the_robot(
        apartment: World, apartment_navigator: Navigator, door_state: DoorState) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.door_state["bedroom door"] = door_state
    run.simulation.place_person_in_doorway("bedroom door", "Maria")
    report = run.robot.move_to(apartment.placements["bed"].approach)
    assert not report.reached
    assert report.door == "bedroom door"
    assert report.blocker in (Blocker.PERSON, Blocker.DOOR_CLOSED)
    assert report.person in (None, "Maria")  # named when the robot sees who it is
    assert run.simulation.collisions == []


def test_someone_asked_out_of_a_doorway_gets_out_and_the_robot_passes(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Before, the robot waited right before the doorway: she could not come its way, and
    # asked four times she never moved.
    from homebot.robot import HelpRequest
    run = _run(apartment, apartment_navigator)
    run.simulation.place_person_in_doorway("bedroom door", "Maria")
    bed = apartment.placements["bed"].approach
    blocked = run.robot.move_to(bed)
    assert not blocked.reached and blocked.door == "bedroom door"
    assert run.robot.request("Maria", HelpRequest.STEP_ASIDE, "bedroom door")
    report = run.robot.move_to(bed)
    assert report.reached, report
    assert math.dist(run.simulation.robot_pose[:2], bed.xy()) < 0.3
    assert run.simulation.collisions == []


def test_the_robot_comes_up_to_someone_far_off_before_asking_them_to_step_aside(
        apartment: World, apartment_navigator: Navigator) -> None:
    from homebot.embodied import BodyRobot
    from homebot.robot import HelpRequest

    run = _run(apartment, apartment_navigator)
    robot, simulation = run.robot, run.simulation
    assert isinstance(robot, BodyRobot)
    start = Pose(11.0, 1.0, math.pi)
    assert apartment.footprint_problem(start.x, start.y) is None
    simulation.robot_pose = (start.x, start.y, start.theta)
    robot.localisation.initialise(start, spread=0.01, angle_spread=0.01)
    simulation.move_person("Maria", (7.8, 2.9))  # across the kitchen: too far to be heard
    assert math.dist(simulation.robot_pose[:2], (7.8, 2.9)) > 3.0
    assert robot.request("Maria", HelpRequest.STEP_ASIDE, "")
    assert math.dist(simulation.robot_pose[:2], (7.8, 2.9)) < 2.0
    assert math.dist(simulation.people["Maria"].position, (7.8, 2.9)) >= 0.8
    assert simulation.collisions == []


def test_what_a_person_hands_the_robot_ends_up_between_its_fingers(
        apartment: World, apartment_navigator: Navigator) -> None:
    pytest.importorskip("mujoco")
    run = _run(apartment, apartment_navigator)
    run.simulation.object_location["cola"] = PERSON_PREFIX + apartment.model.operator
    outcome = skill_named("receive").run(run.context, {"person": "operator"})
    assert outcome.status is Status.VERIFIED, outcome.message
    assert run.simulation.hands[outcome.data["hand"]] == "cola"
    assert run.simulation.object_location["cola"].startswith("hand:")
    assert run.robot.arm.gripper_holds()  # type: ignore[attr-defined]


def test_a_yes_begun_before_the_robot_listens_is_heard(
        apartment: World, apartment_navigator: Navigator) -> None:
    from homebot.embodied import BodyRobot

    pytest.importorskip("pocketsphinx")
    run = _run(apartment, apartment_navigator)
    robot, simulation = run.robot, run.simulation
    assert isinstance(robot, BodyRobot)
    start = Pose(9.0, 2.9, math.pi)
    simulation.robot_pose = (start.x, start.y, start.theta)
    robot.localisation.initialise(start, spread=0.01, angle_spread=0.01)
    simulation.move_person("Maria", (7.8, 2.9))  # near: asked from here
    robot.say("Excuse me, Maria, could you please let me through?")
    # She answers at once; the robot spends a while looking round before it listens (as
    # in flat_narrow: her "yes, sure" was over by then and drained with its own voice)
    robot.body.tick(round(2.5 / robot.body.tick_period))
    assert robot.conversation.agreed()
