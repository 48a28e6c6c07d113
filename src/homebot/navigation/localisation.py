"""Monte Carlo localisation: where the robot is on the map, from its odometry and its laser.

A particle filter (Probabilistic Robotics ch. 8; the parameters are named as ROS
AMCL names them, so a Nav2 tuning carries over):

- **prediction** moves every particle by the odometry delta since the last
  filter update, through the sampled odometry motion model (Table 5.6) or, for an
  omnidirectional base, AMCL's omni model;
- **correction** weighs each particle by a likelihood field (§6.4): each beam's
  end point is looked up in a precomputed table of ``z_hit·N(d; 0, sigma_hit) +
  z_rand/range_max`` over the distance ``d`` to the nearest obstacle, so spurious
  short returns and people's legs cost a bounded penalty instead of killing the
  right particle. Neighbouring beams are not independent; the scan's log-likelihood
  is scaled to count as at most ``laser_independent_beams`` beams;
- **resampling** happens when the effective sample size drops below
  ``resample_threshold``: low-variance resampling into a random order, of which
  KLD-sampling (Fox 2003) keeps just enough particles that the sample-based
  distribution is within ``pf_err`` of the true one with probability ``pf_z``;
- **recovery** (augmented MCL, Table 8.3): short- and long-term averages of the
  measurement likelihood; when the short one falls below the long one (the robot
  was kidnapped, or lost) random poses from free space replace that share of the
  particles.

Everything is vectorised numpy; every random draw comes from the generator
passed in. The filter sees only Body-port types and the map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from statistics import NormalDist

import numpy as np

from homebot.errors import BodyError
from homebot.geometry import Pose, wrap_angle, wrap_angles
from homebot.navigation.likelihood import LikelihoodField
from homebot.robot.body import DriveKind, LaserScan, Odometry
from homebot.world import OccupancyGrid

__all__ = ["MclParameters", "MonteCarloLocalisation"]


@dataclass(frozen=True)
class MclParameters:
    """The filter's tuning; names follow ROS AMCL where AMCL has the parameter."""

    min_particles: int = 500
    max_particles: int = 5000
    pf_err: float = 0.05  #: KLD bound on the distribution's error
    pf_z: float = 0.99  #: probability that the error stays within ``pf_err``
    kld_bin_xy: float = 0.5  #: KLD histogram bin, metres (Fox 2003: 50 cm)
    kld_bin_theta: float = math.radians(10)  #: KLD histogram bin, radians
    odom_model_type: DriveKind = DriveKind.DIFFERENTIAL
    alpha1: float = 0.2  #: rotation noise from rotation
    alpha2: float = 0.2  #: rotation noise from translation
    alpha3: float = 0.2  #: translation noise from translation
    alpha4: float = 0.2  #: translation noise from rotation
    alpha5: float = 0.2  #: strafe noise from translation (omnidirectional model only)
    z_hit: float = 0.9
    z_rand: float = 0.1
    sigma_hit: float = 0.05  #: metres
    laser_likelihood_max_dist: float = 2.0  #: distances beyond this count as this far
    laser_max_beams: int | None = None  #: use at most this many beams (None: the full scan)
    laser_independent_beams: float = 60.0  #: a scan counts as at most this many beams
    short_reading_margin: float = 0.15  #: once converged, drop beams this much shorter than
    #: the map shows from the estimate (0: never)
    long_reading_margin: float = 0.3  #: beams this much longer than the map shows count as
    #: passing its walls (the lost test)
    min_beams: int = 10  #: ... unless fewer than this many beams would be left
    update_min_d: float = 0.05  #: filter only after this much translation, metres
    update_min_a: float = 0.1  #: ... or this much rotation, radians
    resample_threshold: float = 0.5  #: resample when the effective sample size drops below
    #: this share of the particles
    min_ess_share: float = 0.05  #: one correction keeps at least this effective share
    recovery_alpha_slow: float = 0.001
    recovery_alpha_fast: float = 0.1
    lost_long_share: float = 0.1  #: lost when this share of beams reaches beyond the walls
    lost_random_share: float = 0.2  #: ... and then at least this share of particles is random
    converged_spread: float = 0.15  #: converged when the particles' position spread is below
    converged_angle: float = 0.2  #: ... and their heading spread below (radians)
    cluster_radius: float = 0.75  #: the estimate averages the heaviest mode within this

    def __post_init__(self) -> None:
        if not (isinstance(self.min_particles, int) and self.min_particles >= 1):
            raise BodyError(f"min_particles must be at least 1, not {self.min_particles!r}")
        if not (isinstance(self.max_particles, int) and self.max_particles >= self.min_particles):
            raise BodyError(f"max_particles must be at least min_particles "
                            f"({self.min_particles}), not {self.max_particles!r}")
        for name in ("pf_err", "kld_bin_xy", "kld_bin_theta", "sigma_hit",
                     "laser_likelihood_max_dist", "laser_independent_beams",
                     "converged_spread", "converged_angle", "cluster_radius"):
            _check(name, getattr(self, name), low=0.0, low_open=True)
        for name in ("pf_z", "resample_threshold", "min_ess_share", "z_hit", "z_rand",
                     "recovery_alpha_slow", "recovery_alpha_fast", "lost_long_share",
                     "lost_random_share"):
            _check(name, getattr(self, name), low=0.0, high=1.0)
        for name in ("alpha1", "alpha2", "alpha3", "alpha4", "alpha5", "short_reading_margin",
                     "long_reading_margin",
                     "update_min_d", "update_min_a"):
            _check(name, getattr(self, name), low=0.0)
        if not 0.0 < self.pf_z < 1.0:
            raise BodyError(f"pf_z must lie strictly between 0 and 1, not {self.pf_z!r}")
        if self.z_hit + self.z_rand <= 0.0:
            raise BodyError("z_hit and z_rand cannot both be 0: the laser model would say nothing")
        if self.laser_max_beams is not None and not (
                isinstance(self.laser_max_beams, int) and self.laser_max_beams >= 1):
            raise BodyError(f"laser_max_beams must be at least 1 or None (the full scan), "
                            f"not {self.laser_max_beams!r}")
        if not (isinstance(self.min_beams, int) and self.min_beams >= 1):
            raise BodyError(f"min_beams must be at least 1, not {self.min_beams!r}")
        DriveKind(self.odom_model_type)

    def describe(self) -> dict[str, object]:
        """The parameters as plain values (for reports and ``--json``)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def _check(name: str, value: float, *, low: float, high: float | None = None,
           low_open: bool = False) -> None:
    ok = isinstance(value, int | float) and math.isfinite(value) and (
        value > low if low_open else value >= low) and (high is None or value <= high)
    if not ok:
        bound = f"above {low}" if low_open else f"at least {low}"
        upper = f" and at most {high}" if high is not None else ""
        raise BodyError(f"localisation parameter {name} must be a number {bound}{upper}, "
                        f"not {value!r}")


def _points(scan: LaserScan, beams: np.ndarray) -> np.ndarray:
    """The end points of ``beams`` in the robot's frame."""
    mount = scan.mount
    angles = scan.angles()[beams] + mount.theta
    ranges = scan.ranges[beams]
    return np.column_stack((mount.x + ranges * np.cos(angles), mount.y + ranges * np.sin(angles)))


def _tempered(prior: np.ndarray, log_likelihood: np.ndarray, floor: float) -> np.ndarray:
    """Posterior weights ∝ prior · likelihood^β with the largest β ≤ 1 whose ESS stays ≥ floor.

    Adaptive tempering: one scan may not pick a single particle out of thousands
    (the filter would collapse onto whichever happened to lie best, often a wrong
    place during global localisation); the evidence is then spread over several
    updates instead.
    """
    def weights(beta: float) -> tuple[np.ndarray, float]:
        logs = prior + beta * log_likelihood
        logs -= logs.max()
        w = np.exp(logs)
        w /= w.sum()
        return w, float(1.0 / np.dot(w, w))

    best, ess = weights(1.0)
    if ess >= floor:
        return best
    low, high = 0.0, 1.0
    best, _ = weights(0.0)
    for _ in range(12):
        middle = (low + high) / 2
        candidate, ess = weights(middle)
        if ess >= floor:
            low, best = middle, candidate
        else:
            high = middle
    return best


class MonteCarloLocalisation:
    """Adaptive Monte Carlo localisation on an occupancy grid.

    Args:
        grid: the map; ``occupied`` is what the laser sees, ``blocked`` where the robot
            cannot stand (no particle is drawn there at random).
        rng: every random draw.
        parameters: the tuning (``MclParameters()`` by default).

    Raises:
        BodyError: a parameter is out of range, or the map has no free space.
    """

    def __init__(self, grid: OccupancyGrid, rng: np.random.Generator,
                 parameters: MclParameters | None = None) -> None:
        self.grid = grid
        self.rng = rng
        self.parameters = parameters or MclParameters()
        self.field = LikelihoodField.from_grid(
            grid, max_distance=self.parameters.laser_likelihood_max_dist)
        self._free_cells = np.flatnonzero(~grid.blocked.ravel())
        if self._free_cells.size == 0:
            raise BodyError("the map has no free cell for the robot; localisation needs a map "
                            "with room to stand")
        self._kld_z = NormalDist().inv_cdf(self.parameters.pf_z)
        self._tables: dict[float, np.ndarray] = {}
        self._particles = np.zeros((0, 3))
        self._weights = np.zeros(0)
        self._w_slow = 0.0
        self._w_fast = 0.0
        self._odom_at_update: Pose | None = None  # odometry at the last filter update
        self._odom_last: Pose | None = None  # the latest odometry seen
        self._estimate = Pose(0.0, 0.0, 0.0)
        self._covariance = np.zeros((3, 3))
        self._converged = False
        self._long_share = 0.0  # smoothed share of beams reaching beyond the map's walls
        self._initialised = False
        self.updates = 0  #: filter updates (prediction + correction) so far
        self.resamplings = 0
        self.beams_used = 0  #: beams weighed in the last correction
        self.spread = math.inf  #: the particles' position spread (weighted), metres

    ####################################################################################
    # Starting
    ####################################################################################

    def initialise(self, pose: Pose, spread: float = 0.1, angle_spread: float = 0.1) -> None:
        """Track from a known start: particles drawn around ``pose`` (standard deviations)."""
        if not (math.isfinite(spread) and spread >= 0 and math.isfinite(angle_spread)
                and angle_spread >= 0):
            raise BodyError(f"the initial spread must be non-negative numbers, not "
                            f"{spread!r} m and {angle_spread!r} rad")
        count = self.parameters.max_particles
        particles = np.column_stack((
            self.rng.normal(pose.x, spread, count), self.rng.normal(pose.y, spread, count),
            wrap_angles(self.rng.normal(pose.theta, angle_spread, count))))
        self._start(particles)

    def initialise_globally(self) -> None:
        """An unknown start: particles uniform over the map's free space."""
        self._start(self._random_poses(self.parameters.max_particles))

    def _start(self, particles: np.ndarray) -> None:
        keep = self._kld_count(particles)
        self._particles = particles[:keep].copy()
        self._weights = np.full(keep, 1.0 / keep)
        self._w_slow = self._w_fast = 0.0
        self._long_share = 0.0
        self._odom_at_update = None
        self._initialised = True
        self._summarise()

    def _random_poses(self, count: int) -> np.ndarray:
        cells = self._free_cells[self.rng.integers(0, self._free_cells.size, count)]
        rows, columns = np.divmod(cells, self.grid.shape[1])
        resolution = self.grid.resolution
        x = self.grid.origin[0] + (columns + self.rng.random(count)) * resolution
        y = self.grid.origin[1] + (rows + self.rng.random(count)) * resolution
        return np.column_stack((x, y, self.rng.uniform(-np.pi, np.pi, count)))

    ####################################################################################
    # The filter step
    ####################################################################################

    def update(self, odometry: Odometry, scan: LaserScan) -> Pose:
        """Predict by the odometry since the last filter update, weigh by ``scan``, resample.

        The filter runs only once the robot has moved ``update_min_d`` or turned
        ``update_min_a`` since its last run (as AMCL does: the same scan seen again
        from the same place is no new evidence); between runs the estimate follows
        the odometry. Without an ``initialise`` call first, the start is unknown.

        Returns:
            The pose estimate on the map.
        """
        if not self._initialised:
            self.initialise_globally()
        odom = odometry.pose
        self._odom_last = odom
        if self._odom_at_update is not None:
            moved = odom.relative_to(self._odom_at_update)
            if math.hypot(moved.x, moved.y) < self.parameters.update_min_d and \
                    abs(moved.theta) < self.parameters.update_min_a:
                return self.estimate()
            self._predict(self._odom_at_update, odom)
        predicted = self.estimate()  # the last estimate, moved on by the odometry
        self._odom_at_update = odom
        self._correct(scan, predicted)
        self._summarise()
        self._resample_if_needed()
        self.updates += 1
        return self._estimate

    def _predict(self, before: Pose, after: Pose) -> None:
        p = self.parameters
        particles = self._particles
        n = len(particles)
        dx, dy = after.x - before.x, after.y - before.y
        trans = math.hypot(dx, dy)
        theta = particles[:, 2]
        normal = self.rng.standard_normal((n, 3))
        if p.odom_model_type is DriveKind.OMNIDIRECTIONAL:
            rot = wrap_angle(after.theta - before.theta)
            trans_sd = math.sqrt(p.alpha3 * trans ** 2 + p.alpha1 * rot ** 2)
            rot_sd = math.sqrt(p.alpha4 * rot ** 2 + p.alpha2 * trans ** 2)
            strafe_sd = math.sqrt(p.alpha1 * rot ** 2 + p.alpha5 * trans ** 2)
            bearing = theta + (wrap_angle(math.atan2(dy, dx) - before.theta)
                               if trans > 1e-9 else 0.0)
            trans_hat = trans + trans_sd * normal[:, 0]
            strafe_hat = strafe_sd * normal[:, 1]
            c, s = np.cos(bearing), np.sin(bearing)
            particles[:, 0] += trans_hat * c + strafe_hat * s
            particles[:, 1] += trans_hat * s - strafe_hat * c
            particles[:, 2] = wrap_angles(theta + rot + rot_sd * normal[:, 2])
            return
        rot1 = wrap_angle(math.atan2(dy, dx) - before.theta) if trans > 0.01 else 0.0
        rot2 = wrap_angle(after.theta - before.theta - rot1)
        # Driving backwards is not a half turn: noise from the smaller of the two readings.
        rot1_n = min(abs(rot1), abs(wrap_angle(rot1 - math.pi)))
        rot2_n = min(abs(rot2), abs(wrap_angle(rot2 - math.pi)))
        rot1_hat = rot1 - math.sqrt(p.alpha1 * rot1_n ** 2 + p.alpha2 * trans ** 2) * normal[:, 0]
        trans_hat = trans - math.sqrt(p.alpha3 * trans ** 2 + p.alpha4 * (
            rot1_n ** 2 + rot2_n ** 2)) * normal[:, 1]
        rot2_hat = rot2 - math.sqrt(p.alpha1 * rot2_n ** 2 + p.alpha2 * trans ** 2) * normal[:, 2]
        heading = theta + rot1_hat
        particles[:, 0] += trans_hat * np.cos(heading)
        particles[:, 1] += trans_hat * np.sin(heading)
        particles[:, 2] = wrap_angles(heading + rot2_hat)

    def _table(self, range_max: float) -> np.ndarray:
        """Log-likelihood of a beam ending in each fine cell, for a laser of this range."""
        if range_max not in self._tables:
            p = self.parameters
            d = self.field.distances.astype(np.float64)
            hit = p.z_hit * np.exp(-0.5 * (d / p.sigma_hit) ** 2) / (
                p.sigma_hit * math.sqrt(2 * math.pi))
            self._tables[range_max] = np.log(hit + p.z_rand / range_max).astype(
                np.float32).ravel()
        return self._tables[range_max]

    def _beams(self, scan: LaserScan) -> np.ndarray:
        """Indices of the beams to weigh: those with a return, at most ``laser_max_beams``."""
        beams = np.flatnonzero(scan.valid())
        limit = self.parameters.laser_max_beams
        if limit is not None and len(beams) > limit:
            beams = beams[np.linspace(0, len(beams) - 1, limit).round().astype(int)]
        return beams

    def _check_against_map(self, scan: LaserScan, beams: np.ndarray,
                           predicted: Pose) -> np.ndarray:
        """Which of ``beams`` end well short of what the map shows from the estimate.

        A person's legs, a spurious return or anything else not on the map ends a
        beam early. The likelihood field cannot tell (it never looks along the
        beam), and short returns scattered through free space pull the particles
        towards whatever furniture they happen to land near. Once the filter has
        converged, the map is ray-cast from the estimate, and a beam shorter than
        expected by more than ``short_reading_margin`` is left out: an estimate off
        by less than the margin keeps every beam that saw the mapped world.

        The same ray-cast says whether the filter is lost: nothing in the home ends
        a beam *later* than the map's walls, so many beams reaching well beyond them
        (share ``lost_long_share``, smoothed over updates) mean the estimate is in
        the wrong place, however well the particles agree.
        """
        p = self.parameters
        origin = predicted.compose(scan.mount)
        angles = origin.theta + scan.angles()
        ranges = np.where(np.isnan(scan.ranges), 0.0, scan.ranges)
        # Only what lies within the farthest return (and the margin) can tell.
        reach = scan.range_max if not np.isfinite(ranges).all() else min(
            scan.range_max, float(ranges.max()) + max(p.short_reading_margin,
                                                      p.long_reading_margin))
        expected = self.field.raycast(origin.x, origin.y, angles, reach)
        seen = np.isfinite(expected)
        long = seen & (ranges > expected + p.long_reading_margin)
        share = float(long.sum() / max(int(seen.sum()), 1))
        self._long_share += 0.5 * (share - self._long_share)
        short: np.ndarray = scan.ranges[beams] < expected[beams] - p.short_reading_margin
        return short

    def log_likelihoods(self, scan: LaserScan, particles: np.ndarray | None = None,
                        beams: np.ndarray | None = None) -> np.ndarray:
        """Each particle's log-likelihood of ``scan`` (before scaling), one table look-up a beam."""
        particles = self._particles if particles is None else particles
        points = _points(scan, self._beams(scan) if beams is None else beams)
        if len(points) == 0:
            return np.zeros(len(particles))
        from homebot.navigation import beams as kernels  # numba: only once it weighs a scan

        table = self._table(scan.range_max)
        field = self.field
        scale = 1.0 / field.resolution
        total: np.ndarray = kernels.log_likelihoods(
            table, (points[:, 0] * scale).astype(np.float32),
            (points[:, 1] * scale).astype(np.float32),
            ((particles[:, 0] - field.origin[0]) * scale).astype(np.float32),
            ((particles[:, 1] - field.origin[1]) * scale).astype(np.float32),
            np.cos(particles[:, 2]).astype(np.float32), np.sin(particles[:, 2]).astype(np.float32),
            field.shape[0], field.shape[1])
        return total

    def _correct(self, scan: LaserScan, predicted: Pose) -> None:
        p = self.parameters
        beams = self._beams(scan)
        if self._converged and p.short_reading_margin > 0 and len(beams):
            short = self._check_against_map(scan, beams, predicted)
            # A lost filter's estimate cannot say which beams are unexpected: leaving
            # out the ones that disagree with it would keep it in the wrong place.
            if not self.lost and (~short).sum() >= p.min_beams:
                beams = beams[~short]
        else:
            self._long_share = 0.0
        self.beams_used = len(beams)
        if len(beams) == 0:
            return  # nothing seen: the prediction stands
        log_likelihood = self.log_likelihoods(scan, beams=beams)
        scaled = log_likelihood * min(1.0, p.laser_independent_beams / len(beams))
        prior = np.log(np.maximum(self._weights, 1e-300))
        self._weights = _tempered(prior, scaled, p.min_ess_share * len(self._weights))
        # Augmented MCL watches how well the filter explains the scan: the likelihood
        # per beam (a geometric mean over each particle's beams, so independent of how
        # many beams returned), averaged with the posterior weights. Thrun's Table 8.3
        # averages with the prior weights instead; then the random particles injected
        # while lost keep the average low after the filter has found the robot again,
        # and it goes on injecting.
        per_beam = np.exp(log_likelihood / len(beams))
        w_avg = float(np.dot(self._weights, per_beam))
        if self._w_slow == 0.0:
            self._w_slow = self._w_fast = w_avg
        else:
            self._w_slow += p.recovery_alpha_slow * (w_avg - self._w_slow)
            self._w_fast += p.recovery_alpha_fast * (w_avg - self._w_fast)

    ####################################################################################
    # Resampling: low variance, KLD-sampling, random particles for recovery
    ####################################################################################

    @property
    def effective_sample_size(self) -> float:
        """1 / Σ w² of the current weights."""
        return float(1.0 / np.dot(self._weights, self._weights))

    @property
    def lost(self) -> bool:
        """Whether the scan says the estimate is in the wrong place (beams pass its walls)."""
        return self._long_share > self.parameters.lost_long_share

    @property
    def random_share(self) -> float:
        """The share of random particles the next resampling injects (augmented MCL)."""
        p = self.parameters
        augmented = 0.0 if self._w_slow <= 0.0 else max(0.0, 1.0 - self._w_fast / self._w_slow)
        return max(augmented, p.lost_random_share if self.lost else 0.0)

    def _resample_if_needed(self) -> None:
        p = self.parameters
        n = len(self._particles)
        if self.effective_sample_size >= p.resample_threshold * n and self.random_share == 0.0:
            return
        count = p.max_particles
        cumulative = np.cumsum(self._weights)
        cumulative[-1] = 1.0
        pointers = (self.rng.random() + np.arange(count)) / count
        chosen = np.minimum(np.searchsorted(cumulative, pointers, side="right"), n - 1)
        candidates = self._particles[self.rng.permutation(chosen)]
        share = self.random_share
        if share > 0.0:
            replace = self.rng.random(count) < share
            candidates[replace] = self._random_poses(int(replace.sum()))
        keep = self._kld_count(candidates)
        self._particles = candidates[:keep].copy()
        self._weights = np.full(keep, 1.0 / keep)
        self.resamplings += 1

    def _kld_count(self, candidates: np.ndarray) -> int:
        """How many of ``candidates`` (in order) KLD-sampling keeps.

        Sequential KLD-sampling draws until ``n`` reaches the bound for the number
        ``k`` of histogram bins its samples occupy; here the draws are made at once
        and the bound is checked for every prefix.
        """
        p = self.parameters
        total = len(candidates)
        ix = np.floor(candidates[:, 0] / p.kld_bin_xy).astype(np.int64)
        iy = np.floor(candidates[:, 1] / p.kld_bin_xy).astype(np.int64)
        it = np.floor((candidates[:, 2] + np.pi) / p.kld_bin_theta).astype(np.int64)
        ix -= ix.min()
        iy -= iy.min()
        bins = (ix * (iy.max() + 1) + iy) * (it.max() + 1) + it
        _, first = np.unique(bins, return_index=True)
        new = np.zeros(total, dtype=bool)
        new[first] = True
        k = np.cumsum(new).astype(np.float64)
        km1 = np.maximum(k - 1.0, 1.0)
        a = 2.0 / (9.0 * km1)
        bound = km1 / (2 * p.pf_err) * (1.0 - a + np.sqrt(a) * self._kld_z) ** 3
        bound[k <= 1] = 0.0
        n = np.arange(1, total + 1)
        enough = (n >= bound) & (n >= p.min_particles)
        return int(np.argmax(enough)) + 1 if enough.any() else total

    ####################################################################################
    # What the filter believes
    ####################################################################################

    def _summarise(self) -> None:
        """The estimate (the heaviest mode's mean), its covariance and convergence."""
        p = self.parameters
        x, y, theta = self._particles.T
        w = self._weights
        cell = p.kld_bin_xy
        ix = np.floor((x - self.grid.origin[0]) / cell).astype(np.int64)
        iy = np.floor((y - self.grid.origin[1]) / cell).astype(np.int64)
        ix = np.clip(ix, 0, None)
        iy = np.clip(iy, 0, None)
        bins = ix * (iy.max() + 1) + iy
        heaviest = int(np.argmax(np.bincount(bins, weights=w)))
        members = bins == heaviest
        centre = (np.average(x[members], weights=w[members] + 1e-300),
                  np.average(y[members], weights=w[members] + 1e-300))
        for _ in range(2):  # mean shift: re-centre on the mode's neighbourhood
            near = (np.hypot(x - centre[0], y - centre[1]) <= p.cluster_radius) | members
            weights = w[near] + 1e-300
            centre = (np.average(x[near], weights=weights), np.average(y[near], weights=weights))
        heading = math.atan2(float(np.dot(weights, np.sin(theta[near]))),
                             float(np.dot(weights, np.cos(theta[near]))))
        self._estimate = Pose(float(centre[0]), float(centre[1]), heading)
        offsets = np.column_stack((x[near] - centre[0], y[near] - centre[1],
                                   wrap_angles(theta[near] - heading)))
        normalised = weights / weights.sum()
        self._covariance = (offsets * normalised[:, None]).T @ offsets
        mean_x, mean_y = float(np.dot(w, x)), float(np.dot(w, y))
        spread = math.sqrt(float(np.dot(w, (x - mean_x) ** 2 + (y - mean_y) ** 2)))
        resultant = math.hypot(float(np.dot(w, np.cos(theta))), float(np.dot(w, np.sin(theta))))
        angle_spread = math.sqrt(max(-2.0 * math.log(max(resultant, 1e-12)), 0.0))
        self._converged = spread <= p.converged_spread and angle_spread <= p.converged_angle
        self.spread = spread

    def estimate(self) -> Pose:
        """The pose on the map: the filter's last estimate moved on by the odometry since."""
        if self._odom_at_update is None or self._odom_last is None:
            return self._estimate
        return self._estimate.compose(self._odom_last.relative_to(self._odom_at_update))

    @property
    def covariance(self) -> np.ndarray:
        """3×3 covariance (x, y, heading) of the heaviest mode at the last filter update."""
        return self._covariance.copy()

    @property
    def particles(self) -> np.ndarray:
        """The particles as an (n, 3) array of x, y, heading (a copy, for drawing)."""
        return self._particles.copy()

    @property
    def weights(self) -> np.ndarray:
        """The particles' normalised weights."""
        return self._weights.copy()

    @property
    def converged(self) -> bool:
        """Whether the particles agree (position and heading spread below the thresholds) and
        the scan does not say they agree on the wrong place."""
        return self._converged and not self.lost
