"""Monte Carlo localisation against the simulated body's truth: tracking, global, kidnapping."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.cli import main
from homebot.errors import BodyError, HomebotError
from homebot.geometry import Pose
from homebot.navigation import (
    LikelihoodField,
    MclParameters,
    MonteCarloLocalisation,
    Navigator,
)
from homebot.robot import DriveKind, LaserScan, Odometry, Twist
from homebot.sim.body import SimBody
from homebot.sim.simulation import Simulation
from homebot.world import LaserModel, OccupancyGrid, World


def _body(world: World, navigator: Navigator, seed: int, *, walkers: int = 0,
          spurious: float = 0.0) -> tuple[Simulation, SimBody]:
    simulation = Simulation(world, seed=seed, navigator=navigator)
    laser = LaserModel(**{**world.robot.laser.model_dump(), "spurious": spurious})
    return simulation, SimBody(simulation, walkers=walkers, laser=laser)


def _error(mcl: MonteCarloLocalisation, simulation: Simulation) -> float:
    estimate = mcl.estimate()
    return math.dist(estimate.xy(), simulation.robot_pose[:2])


def _wander(scan: LaserScan) -> Twist:
    """Forward into the most open direction; turn on the spot when something is close."""
    angles = scan.angles() + scan.mount.theta
    ranges = np.where(np.isfinite(scan.ranges), scan.ranges, scan.range_max)
    front = ranges[np.abs(angles) < 0.45].min()
    sideways = np.abs(angles) < 1.7
    smooth = np.convolve(ranges, np.ones(15) / 15, mode="same")
    opening = float(angles[int(np.argmax(np.where(sideways, smooth, -1.0)))])
    if front < 0.6:
        return Twist(0.0, 0.0, 0.9)
    return Twist(min(0.4, 0.5 * (front - 0.45)), 0.0, max(-0.9, min(0.9, 1.5 * opening)))


def _drive(body: SimBody, mcl: MonteCarloLocalisation, simulation: Simulation,
           seconds: float) -> list[float]:
    """Wander for ``seconds``, updating the filter every tick; the errors against the truth."""
    errors = []
    end = body.now() + seconds
    while body.now() < end:
        body.command_velocity(_wander(body.scan()))
        body.tick()
        mcl.update(body.odometry(), body.scan())
        errors.append(_error(mcl, simulation))
    return errors


@pytest.fixture(scope="module")
def grid(apartment_navigator: Navigator) -> OccupancyGrid:
    return apartment_navigator.grid


def test_tracks_the_robot_from_a_known_start_with_people_walking(
        apartment: World, apartment_navigator: Navigator, grid: OccupancyGrid) -> None:
    simulation, body = _body(apartment, apartment_navigator, seed=1, walkers=3)
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(1))
    mcl.initialise(Pose(*simulation.robot_pose), 0.05, 0.05)
    errors = _drive(body, mcl, simulation, 10.0)
    assert body.odometry().pose != Pose(0.0, 0.0, 0.0)
    assert math.dist(simulation.robot_pose[:2], apartment.robot.pose.xy()) > 0.5
    assert float(np.median(errors)) < 0.05
    assert max(errors) < 0.15
    assert mcl.converged


def test_half_the_beams_spurious_still_tracks(apartment: World, apartment_navigator: Navigator,
                                             grid: OccupancyGrid) -> None:
    simulation, body = _body(apartment, apartment_navigator, seed=2, spurious=0.5)
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(2))
    mcl.initialise(Pose(*simulation.robot_pose), 0.05, 0.05)
    errors = _drive(body, mcl, simulation, 10.0)
    assert float(np.median(errors)) < 0.1
    assert max(errors) < 0.25


def test_global_localisation_from_an_unknown_start(apartment: World,
                                                   apartment_navigator: Navigator,
                                                   grid: OccupancyGrid) -> None:
    simulation, body = _body(apartment, apartment_navigator, seed=3)
    body.teleport(Pose(9.5, 2.62, 0.5))  # the kitchen
    parameters = MclParameters(max_particles=4000)
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(3), parameters)
    mcl.initialise_globally()
    assert len(mcl.particles) == 4000  # KLD keeps every particle of a uniform cloud
    assert not mcl.converged
    errors = _drive(body, mcl, simulation, 15.0)
    assert max(errors[-40:]) < 0.2  # localised, and has stayed so for the last 2 s
    assert mcl.converged
    assert len(mcl.particles) < 4000  # KLD sampling needs fewer once it is sure


def test_recovers_after_kidnapping(apartment: World, apartment_navigator: Navigator,
                                   grid: OccupancyGrid) -> None:
    simulation, body = _body(apartment, apartment_navigator, seed=4)
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(4))
    mcl.initialise(Pose(*simulation.robot_pose), 0.05, 0.05)
    assert max(_drive(body, mcl, simulation, 3.0)) < 0.1
    body.teleport(Pose(2.17, 8.6, 0.0))  # the bedroom, across the home; the wheels never knew
    noticed = False
    end = body.now() + 20.0
    errors = []
    while body.now() < end:
        body.command_velocity(_wander(body.scan()))
        body.tick()
        mcl.update(body.odometry(), body.scan())
        noticed |= mcl.lost or not mcl.converged
        errors.append(_error(mcl, simulation))
    assert noticed
    assert max(errors[-40:]) < 0.2


def _run_filter(world: World, grid: OccupancyGrid, seed: int) -> np.ndarray:
    simulation = Simulation(world, navigator=Navigator(world), seed=0)
    body = SimBody(simulation)
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(seed),
                                 MclParameters(min_particles=200, max_particles=1000))
    mcl.initialise(Pose(*simulation.robot_pose), 0.2, 0.2)
    for _ in range(10):
        body.command_velocity(Twist(0.3, 0.0, 0.5))
        body.tick()
        mcl.update(body.odometry(), body.scan())
    return mcl.particles


def test_the_same_seed_gives_the_same_particles(apartment: World, grid: OccupancyGrid) -> None:
    first, again = _run_filter(apartment, grid, 5), _run_filter(apartment, grid, 5)
    other = _run_filter(apartment, grid, 6)
    assert np.array_equal(first, again)
    assert first.shape != other.shape or not np.array_equal(first, other)


def test_the_filter_waits_for_motion_and_the_estimate_follows_the_odometry(
        grid: OccupancyGrid) -> None:
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(0))
    mcl.initialise(Pose(6.0, 2.0, math.pi / 2), 0.02, 0.02)
    scan = LaserScan(0.0, -1.0, 0.1, 0.05, 10.0, np.full(21, np.inf))
    mcl.update(Odometry(0.0, Pose(0.0, 0.0, 0.0), Twist()), scan)
    updates = mcl.updates
    pose = mcl.update(Odometry(0.1, Pose(0.02, 0.0, 0.0), Twist()), scan)
    assert mcl.updates == updates  # 2 cm is below update_min_d: no new evidence
    assert pose.y == pytest.approx(mcl.estimate().y) and pose.y > 2.0  # moved 2 cm "north"


def test_a_scan_with_no_returns_leaves_the_prediction(grid: OccupancyGrid) -> None:
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(0))
    mcl.initialise(Pose(6.0, 2.0, 0.0), 0.05, 0.05)
    scan = LaserScan(0.0, -1.0, 0.1, 0.05, 10.0, np.full(21, np.inf))
    pose = mcl.update(Odometry(0.0, Pose(0.0, 0.0, 0.0), Twist()), scan)
    assert math.dist(pose.xy(), (6.0, 2.0)) < 0.05
    assert mcl.beams_used == 0


@pytest.mark.parametrize("settings", [
    {"min_particles": 0},
    {"min_particles": 100, "max_particles": 50},
    {"sigma_hit": -0.1},
    {"sigma_hit": math.nan},
    {"pf_z": 1.0},
    {"pf_err": 0.0},
    {"z_hit": 0.0, "z_rand": 0.0},
    {"alpha1": -1.0},
    {"laser_max_beams": 0},
])
def test_bad_parameters_are_body_errors(settings: dict[str, float]) -> None:
    with pytest.raises(BodyError):
        MclParameters(**settings)  # type: ignore[arg-type]


def test_bad_spread_and_a_map_without_room_are_errors(grid: OccupancyGrid) -> None:
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(0))
    with pytest.raises(HomebotError, match="spread"):
        mcl.initialise(Pose(6.0, 2.0), -0.1)
    full = np.ones((10, 10), dtype=bool)
    solid = OccupancyGrid((0.0, 0.0), 0.05, (10, 10), full, full, {}, {})
    with pytest.raises(BodyError, match="no free cell"):
        MonteCarloLocalisation(solid, np.random.default_rng(0))


def test_the_likelihood_field_measures_to_the_surface_and_ray_casts() -> None:
    occupied = np.zeros((40, 40), dtype=bool)
    occupied[:, 30:] = True  # a wall whose surface is at x = 1.5 m
    grid = OccupancyGrid((0.0, 0.0), 0.05, (40, 40), occupied, occupied, {}, {})
    field = LikelihoodField.from_grid(grid)
    xs = np.array([1.5, 1.0, 0.5, 1.6])
    distances = field.distance_at(xs, np.full(4, 1.0))
    assert distances == pytest.approx([0.0, 0.5, 1.0, 0.1], abs=0.03)
    ranges = field.raycast(0.5, 1.0, np.array([0.0, math.pi / 6, math.pi]), 10.0)
    assert ranges[0] == pytest.approx(1.0, abs=0.03)
    assert ranges[1] == pytest.approx(1 / math.cos(math.pi / 6), abs=0.04)
    assert ranges[2] == math.inf  # nothing that way within range


def test_the_compiled_beam_kernels_are_their_plain_python(
        apartment: World, apartment_navigator: Navigator, grid: OccupancyGrid,
        monkeypatch: pytest.MonkeyPatch) -> None:
    # One implementation: the numba kernels' own Python functions give the same figures.
    pytest.importorskip("numba")
    from homebot.navigation import beams

    _, body = _body(apartment, apartment_navigator, 3)
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(0))
    mcl.initialise(body.true_pose(), spread=0.3, angle_spread=0.3)
    scan = body.scan()
    x, y, _ = body.sim.robot_pose
    angles = np.linspace(-math.pi, math.pi, 50)
    compiled = (mcl.log_likelihoods(scan), mcl.field.raycast(x, y, angles, 8.0))
    with monkeypatch.context() as patch:
        patch.setattr(beams, "log_likelihoods", beams.log_likelihoods.py_func)
        patch.setattr(beams, "raycast", beams.raycast.py_func)
        plain = (mcl.log_likelihoods(scan), mcl.field.raycast(x, y, angles, 8.0))
    np.testing.assert_array_equal(plain[0], compiled[0])
    np.testing.assert_array_equal(plain[1], compiled[1])
    assert np.isfinite(compiled[1]).all() and compiled[0].std() > 0


@pytest.mark.parametrize(("drive", "moved", "expected"), [
    (DriveKind.DIFFERENTIAL, Pose(0.1, 0.0, 0.2), Pose(6.0, 2.1, math.pi / 2 + 0.2)),
    (DriveKind.DIFFERENTIAL, Pose(-0.1, 0.0, 0.0), Pose(6.0, 1.9, math.pi / 2)),  # reversing
    (DriveKind.OMNIDIRECTIONAL, Pose(0.0, 0.1, 0.0), Pose(5.9, 2.0, math.pi / 2)),  # sideways
])
def test_without_noise_the_particles_move_exactly_by_the_odometry(
        grid: OccupancyGrid, drive: DriveKind, moved: Pose, expected: Pose) -> None:
    quiet = MclParameters(min_particles=10, max_particles=10, odom_model_type=drive,
                          alpha1=0.0, alpha2=0.0, alpha3=0.0, alpha4=0.0, alpha5=0.0)
    mcl = MonteCarloLocalisation(grid, np.random.default_rng(0), quiet)
    mcl.initialise(Pose(6.0, 2.0, math.pi / 2), 0.0, 0.0)
    blind = LaserScan(0.0, -1.0, 0.1, 0.05, 10.0, np.full(21, np.inf))
    mcl.update(Odometry(0.0, Pose(0.0, 0.0, 0.0), Twist()), blind)
    mcl.update(Odometry(1.0, moved, Twist()), blind)
    assert mcl.updates == 2
    for x, y, theta in mcl.particles:
        assert (x, y, theta) == pytest.approx((expected.x, expected.y, expected.theta), abs=1e-9)


@pytest.mark.parametrize("argv", [["--runs", "0"], ["--phase", "10"], ["--seconds", "-1"]])
def test_the_benchmark_refuses_bad_sizes(argv: list[str],
                                         capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "localisation", *argv]) == 2
    assert capsys.readouterr().err.count("\n") == 1  # one line, no traceback
