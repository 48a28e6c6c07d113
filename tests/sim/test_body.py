"""SimBody: the kinematic base, the ray-cast laser, drifting odometry and people who walk."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.errors import BodyError
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.robot import DriveKind, Twist, VelocityLimits
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.world import DisturbanceModel, LaserModel, World

QUIET_LASER = LaserModel(noise=0.0)


def _body(world: World, navigator: Navigator, seed: int = 0, **options: object) -> SimBody:
    return SimBody(Simulation(world, seed=seed, navigator=navigator), **options)  # type: ignore[arg-type]


def test_the_laser_measures_the_distance_to_a_wall(apartment: World,
                                                   apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator, laser=QUIET_LASER)
    # In the corridor (y from 4 to 6, walls 0.1 m thick), facing north from y = 5.
    body.teleport(Pose(1.0, 5.0, math.pi / 2))
    scan = body.scan()
    straight_ahead = len(scan.ranges) // 2
    # The sensor sits 0.15 m ahead of the centre; the wall's face is at y = 5.95.
    assert scan.ranges[straight_ahead] == pytest.approx(0.95 - 0.15, abs=0.02)
    # Facing east along the corridor, the far wall is at x = 11.95.
    body.teleport(Pose(1.0, 5.0, 0.0))
    assert body.scan().ranges[straight_ahead] == pytest.approx(10.8, abs=0.03) or \
        math.isinf(body.scan().ranges[straight_ahead])


def test_the_compiled_laser_is_its_plain_python(apartment: World,
                                               apartment_navigator: Navigator,
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    # One implementation: the numba ray march's own Python function casts the same ranges.
    pytest.importorskip("numba")
    from homebot.sim import laser

    body = _body(apartment, apartment_navigator, laser=QUIET_LASER)
    for pose in (Pose(1.0, 5.0, 0.3), Pose(2.0, 1.5, -2.0)):
        body.teleport(pose)
        compiled = body.scan().ranges
        with monkeypatch.context() as patch:
            patch.setattr(laser, "_march_beams", laser._march_beams.py_func)
            body.teleport(pose)  # not the scan of this tick again: a new sweep
            plain = body.scan().ranges
        np.testing.assert_array_equal(plain, compiled)
        assert np.isfinite(compiled).sum() > len(compiled) // 2


def test_the_laser_skips_only_samples_that_are_free_for_sure(
        apartment: World, apartment_navigator: Navigator,
        monkeypatch: pytest.MonkeyPatch) -> None:
    # Passing over the samples far from anything solid changes no range: the same sweeps
    # as sampling every cell, from anywhere in the home (inside furniture too).
    from homebot.sim import laser

    body = _body(apartment, apartment_navigator, laser=QUIET_LASER)
    rng = np.random.default_rng(2)
    free_runs = laser._free_runs
    for _ in range(40):
        pose = Pose(rng.uniform(-0.5, 12.5), rng.uniform(-0.5, 8.5), rng.uniform(-3.1, 3.1))
        body.teleport(pose)
        skipping = body.scan().ranges
        with monkeypatch.context() as patch:
            patch.setattr(laser, "_free_runs", lambda solid: np.zeros(solid.shape, np.int32))
            body.laser._free_runs.clear()
            body.teleport(pose)
            sampled = body.scan().ranges
        body.laser._free_runs.clear()
        np.testing.assert_array_equal(skipping, sampled)
    # 5 cells from the edge: the samples 1 to 3 on are less than 5 cells away.
    assert free_runs(np.zeros((9, 9), np.uint8))[4, 4] == 3


def test_people_are_seen_by_their_legs(apartment: World, apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator, laser=QUIET_LASER)
    body.teleport(Pose(1.0, 5.0, 0.0))
    ahead = len(body.scan().ranges) // 2
    before = body.scan().ranges[ahead]
    body.sim.move_person("Sophie", (3.0, 5.1))  # she stands (John lies: see below)
    body.teleport(Pose(1.0, 5.0, 0.0))
    assert body.scan().ranges[ahead] < min(before, 2.0)


def test_spurious_readings_are_the_configured_share(apartment: World,
                                                    apartment_navigator: Navigator) -> None:
    clean = _body(apartment, apartment_navigator, laser=QUIET_LASER).scan().ranges
    noisy = _body(apartment, apartment_navigator,
                  laser=LaserModel(noise=0.0, spurious=0.5)).scan().ranges
    both = np.isfinite(clean) & np.isfinite(noisy)
    share = float(np.mean(np.abs(noisy[both] - clean[both]) > 1e-6))
    assert 0.35 < share < 0.65


def test_commands_are_clipped_and_a_differential_base_does_not_slide(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator)
    assert body.drive is DriveKind.DIFFERENTIAL
    body.teleport(Pose(6.0, 5.0, 0.0))
    body.command_velocity(Twist(5.0, 1.0, 0.0))
    body.tick(40)  # two seconds: enough to reach the limit
    x, y, _ = body.sim.robot_pose
    assert body.odometry().twist.vx == pytest.approx(apartment.robot.speed)
    assert y == pytest.approx(5.0)
    assert 6.5 < x < 7.0


def test_the_emergency_stop_acts_within_one_tick(apartment: World,
                                                 apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator)
    body.teleport(Pose(2.0, 5.0, 0.0))
    body.command_velocity(Twist(0.5, 0.0, 0.0))
    body.tick(30)
    body.emergency_stop()
    body.tick()
    assert body.odometry().twist.is_zero()
    stopped_at = body.sim.robot_pose
    body.command_velocity(Twist(0.5, 0.0, 0.0))  # ignored while the stop is engaged
    body.tick(10)
    assert body.sim.robot_pose == stopped_at
    body.emergency_stop(False)
    body.command_velocity(Twist(0.5, 0.0, 0.0))
    body.tick(10)
    assert body.sim.robot_pose[0] > stopped_at[0]


def test_the_bumper_stops_the_base_at_a_wall_and_counts_a_collision(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator)
    body.teleport(Pose(1.0, 5.0, math.pi / 2))
    body.command_velocity(Twist(0.5, 0.0, 0.0))
    body.tick(100)
    assert len(body.sim.collisions) == 1
    assert body.sim.collisions[0]["with"] == "wall or furniture"
    # The footprint never enters the wall (its face is at y = 5.95).
    assert body.sim.robot_pose[1] <= 5.95 - apartment.robot.radius + 1e-9


def test_odometry_drifts_from_the_truth(apartment: World,
                                        apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator)
    body.teleport(Pose(0.5, 5.0, 0.0))
    body.command_velocity(Twist(0.5, 0.0, 0.0))
    body.tick(20 * 20)
    true_x = body.sim.robot_pose[0] - 0.5
    odometry = body.odometry().pose
    assert odometry.x == pytest.approx(true_x, rel=0.05)
    assert (odometry.x, odometry.y) != (pytest.approx(true_x, abs=1e-6), 0.0)


def test_people_walk_on_seeded_schedules(apartment: World,
                                         apartment_navigator: Navigator) -> None:
    def positions(seed: int) -> dict[str, tuple[float, float]]:
        body = _body(apartment, apartment_navigator, seed=seed, walkers=3)
        body.tick(20 * 90)
        return {name: state.position for name, state in body.sim.people.items()}

    start = {name: person.position for name, person in apartment.people.items()}
    after = positions(3)
    assert after == positions(3)
    moved = [name for name in after if after[name] != start[name]]
    assert len(moved) >= 2
    assert apartment.model.operator not in moved  # the operator walks last


def test_someone_the_robot_came_up_to_can_still_step_away_from_it(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator, walkers=["John"])
    body.teleport(Pose(1.0, 5.0, 0.0))  # in the corridor, facing east
    body.sim.move_person("John", (1.5, 5.0))  # within the robot's radius + personal space
    john = body.people.walkers[0]
    john.path = [(4.0, 5.0)]  # his way leads east, away from the robot
    body.tick(20)
    assert body.sim.people["John"].position[0] > 1.8
    # Towards the robot, nobody steps nearer than that.
    john.path = [(0.0, 5.0)]
    john.waiting_since = -math.inf  # past his patience: he would go round at once
    body.sim.move_person("John", (1.5, 5.0))
    body.tick(20)
    assert math.dist(body.sim.people["John"].position, (1.0, 5.0)) >= 0.5 - 1e-9


def test_bad_body_settings_are_errors(apartment: World, apartment_navigator: Navigator) -> None:
    with pytest.raises(BodyError, match="20 Hz"):
        _body(apartment, apartment_navigator, tick_rate=5.0)
    with pytest.raises(BodyError, match="unknown walker"):
        _body(apartment, apartment_navigator, walkers=["Nobody"])
    with pytest.raises(BodyError, match="limit of 0"):
        VelocityLimits(linear=0.0)


def test_an_omnidirectional_base_moves_sideways(apartment: World) -> None:
    data = apartment.to_dict()
    data["robot"]["drive"] = "omnidirectional"
    world = World.from_dict(data, "apartment, omnidirectional")
    body = SimBody(Simulation(world, navigator=Navigator(world), seed=0))
    assert body.drive is DriveKind.OMNIDIRECTIONAL
    body.teleport(Pose(6.0, 5.0, 0.0))
    body.command_velocity(Twist(0.0, 0.3, 0.0))
    body.tick(40)
    x, y, theta = body.sim.robot_pose
    assert x == pytest.approx(6.0) and theta == pytest.approx(0.0)
    assert 5.4 < y < 5.7


def test_driving_into_someone_is_a_collision_with_them(apartment: World,
                                                        apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator)
    body.sim.move_person("John", (3.0, 5.0))
    body.teleport(Pose(1.5, 5.0, 0.0))
    body.command_velocity(Twist(0.5, 0.0, 0.0))
    body.tick(100)
    assert [c["with"] for c in body.sim.collisions] == ["person John"]
    assert body.sim.robot_pose[0] < 3.0 - apartment.robot.radius


def test_someone_lying_is_a_long_body_on_the_floor_and_hidden_on_a_bed(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator, laser=QUIET_LASER)
    john = body.sim.people["John"]
    assert john.posture.value == "lying"  # on the bed, as the world file has him
    assert not [leg for name, leg in body.people.named_legs() if name == "John"]
    # Fallen in the corridor: the laser sees the length of him, not two legs.
    john.position, john.room = (3.0, 5.0), "corridor"
    body.teleport(Pose(1.0, 5.0, 0.0))
    outline = [leg for name, leg in body.people.named_legs() if name == "John"]
    spread = max(math.dist(a, b) for a in outline for b in outline)
    assert spread >= 1.5 and body.scan().ranges[len(body.scan().ranges) // 2] < 2.0


def test_a_walker_who_sets_off_has_got_up(apartment: World,
                                         apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator, seed=3, walkers=["John"])
    assert body.sim.people["John"].posture.value == "lying"
    body.tick(20 * 90)
    assert body.people.walkers[0].destination is not None  # he went somewhere
    assert body.sim.people["John"].posture.value == "standing"
    assert len([leg for name, leg in body.people.named_legs() if name == "John"]) == 2


def _a_run_maybe_watched(world: World, navigator: Navigator, *, watched: bool
                         ) -> tuple[list[object], list[float]]:
    """A short embodied run by the fridge and the kitchen table, someone moving an object at
    each first look; a watcher's ``view`` drawn before each tick when ``watched``. What the
    robot sensed and did, and the views' stamps."""
    moving = DisturbanceModel(object_moved_during_task=1.0)
    body = SimBody(Simulation(world, seed=7, navigator=navigator, disturbances=moving),
                   walkers=2)
    stamps: list[float] = []
    sensed: list[object] = []

    def tick(ticks: int) -> None:
        for _ in range(ticks):
            if watched:  # the watcher looks at the fridge, where the robot never looks
                stamps.append(body.view().stamp)
            body.tick()
        sensed.extend([body.scan().ranges.tobytes(), body.odometry().pose])

    body.teleport(Pose(10.88, 3.4, 0.0))  # before the fridge
    body.command_velocity(Twist(0.0, 0.0, 0.5))
    tick(6)
    body.teleport(Pose(9.5, 2.62, -math.pi / 2))  # before the kitchen table
    body.command_velocity(Twist(0.1, 0.0, 0.0))
    tick(4)
    frame = body.camera()  # the robot's own look: its first at the table
    tick(2)
    again = body.camera()
    sim = body.sim
    sensed += [frame.rgb.tobytes(), frame.depth.tobytes(), again.rgb.tobytes(),
               dict(sim.object_location), [event.to_dict() for event in sim.events.events]]
    assert body.last_camera() is again  # the robot's latest image is its own, not a view
    return sensed, stamps


def test_a_watched_run_is_the_run_unwatched(apartment: World,
                                            apartment_navigator: Navigator) -> None:
    unwatched, _ = _a_run_maybe_watched(apartment, apartment_navigator, watched=False)
    watched, stamps = _a_run_maybe_watched(apartment, apartment_navigator, watched=True)
    assert len(stamps) == 12 and stamps == sorted(stamps) and stamps[0] < stamps[-1]
    assert watched == unwatched  # the same scans, poses, images, objects and events


def test_the_view_shows_the_home_as_the_head_camera_sees_it_now(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _body(apartment, apartment_navigator)
    body.teleport(Pose(10.88, 3.4, 0.0))  # before the fridge
    view, frame = body.view(), body.camera()
    assert view.stamp == frame.stamp and view.rgb.shape == frame.rgb.shape
    # the same scene under other noise: close, not equal
    difference = np.abs(view.rgb.astype(float) - frame.rgb.astype(float))
    assert 0.0 < difference.mean() < 6.0
    body.point_head(1.2, 0.0)  # the head turned: the view turns with it
    turned = body.view()
    assert np.abs(turned.rgb.astype(float) - view.rgb.astype(float)).mean() > 10.0
