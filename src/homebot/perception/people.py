"""People from the laser: leg detection and multi-person tracking (Cosero §7.1.1).

Legs: the scan is cut into segments where neighbouring ranges jump; a segment
whose endpoints are a leg's width apart (7–25 cm, with at least three returns)
is a leg, its centre half a radius behind the mean of its returns. Furniture legs
are thinner; walls and bodies are wider.

Tracking: one constant-velocity Kalman filter per person. Each sweep, legs are
assigned to tracks with the Hungarian method (``scipy.optimize.linear_sum_
assignment``), every track offering two slots (both legs of a person may be
seen, as Cosero allows several leg detections per hypothesis; single legs are
candidates of their own). A leg's cost for a track is its negative log
likelihood under the track's predicted covariance (Mahalanobis distance plus the
log-determinant, so an uncertain track pays for its spread), gated at the 99 %
chi-square bound. A track is corrected with the mean of its legs. Legs no track
takes are paired (two legs of a person are at most 45 cm apart) and start
tentative tracks; a track is confirmed after ``confirm`` sweeps with legs, a
tentative one dies at its first miss, a confirmed one after ``coast`` seconds
unseen (a person hidden behind another is predicted through). A track confirmed
where an unseen one (ended lately, or still coasting) could have walked to takes
that one's identity: people come back from behind others. Of two confirmed
tracks that keep within 25 cm, the younger goes.

Posture and clothes colour come from what a camera would give for a track (a
vertical height profile and a torso colour patch), not from the truth; both are
crude (see ``posture_from_profile`` and ``clothes_colour``).

Frames: detections are on the map (``pose``: the robot's pose estimate), metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linear_sum_assignment

from homebot.geometry import Pose, from_frame, wrap_angle
from homebot.robot import LaserScan

__all__ = [
    "COLOURS",
    "STATIC_CLEARANCE",
    "PeopleTracker",
    "Track",
    "TrackerParameters",
    "clothes_colour",
    "detect_legs",
    "pair_legs",
    "posture_from_profile",
    "segment_scan",
]

_LEG_WIDTH = (0.07, 0.25)  #: metres between a leg segment's endpoints
_LEG_POINTS = 3
_TWO_LEGS = 0.45  #: metres: a wider round segment is no person's legs
_NEARER_SIDES = 2  #: a segment with nearer returns on this many sides is glimpsed, not free
_BULGE = 0.008  #: metres: a leg's returns lie this far in front of their chord, on average
_PAIR = 0.45  #: metres: two legs of one person are at most this far apart
_UNASSIGNED = 1e6
STATIC_CLEARANCE = 0.15  #: metres: a leg this close to the map's furniture is the furniture's


def segment_scan(scan: LaserScan, jump: float = 0.08, per_metre: float = 0.03
                 ) -> list[np.ndarray]:
    """Runs of neighbouring beams with returns whose ranges differ by less than
    ``jump + per_metre * range``; each run as the indices of its beams."""
    valid = scan.valid()
    ranges = scan.ranges
    indices = np.flatnonzero(valid)
    if len(indices) == 0:
        return []
    gaps = np.abs(np.diff(ranges[indices]))
    limit = jump + per_metre * np.minimum(ranges[indices][1:], ranges[indices][:-1])
    breaks = (gaps > limit) | (np.diff(indices) > 1)
    return np.split(indices, np.flatnonzero(breaks) + 1)


def detect_legs(scan: LaserScan, pose: Pose | None = None,
                static: np.ndarray | None = None) -> np.ndarray:
    """Leg centres seen in ``scan``, as (n, 2) on the map (robot frame without ``pose``).

    A segment one leg wide is one leg; a round segment up to two legs wide (one leg
    half behind the other, no range jump between them) is split into two halves.
    ``static``: (m, 2) map points of what the map holds (furniture legs, walls); a leg
    within ``STATIC_CLEARANCE`` of one is the furniture's, not a person's."""
    angles = scan.angles() + scan.mount.theta
    legs: list[tuple[float, float]] = []
    for segment in segment_scan(scan):
        if len(segment) < _LEG_POINTS:
            continue
        ranges = scan.ranges[segment]
        xs = scan.mount.x + ranges * np.cos(angles[segment])
        ys = scan.mount.y + ranges * np.sin(angles[segment])
        width = math.hypot(xs[-1] - xs[0], ys[-1] - ys[0])
        if not _LEG_WIDTH[0] <= width <= _TWO_LEGS or not _round(xs, ys, scan.mount):
            continue
        if not _in_front(scan, segment):
            continue
        halves = [slice(None)] if width <= _LEG_WIDTH[1] else [
            slice(None, len(segment) // 2), slice(len(segment) // 2, None)]
        for half in halves:
            legs.append(_centre(xs[half], ys[half], scan.mount, min(width, _LEG_WIDTH[1])))
    points = np.asarray(legs, dtype=float).reshape(-1, 2)
    if pose is None or len(points) == 0:
        return points
    points = from_frame(pose, points)
    if static is not None and len(static):
        gaps = np.linalg.norm(points[:, None, :] - np.asarray(static)[None, :, :2], axis=2)
        points = points[gaps.min(axis=1) > STATIC_CLEARANCE]
    return points


def _in_front(scan: LaserScan, segment: np.ndarray) -> bool:
    """Whether the segment stands free: no neighbouring beam returns nearer (a piece of
    wall glimpsed between two people's shadows has nearer returns on both sides)."""
    ranges = scan.ranges
    nearer = 0
    for end, beside in ((segment[0], segment[0] - 1), (segment[-1], segment[-1] + 1)):
        if 0 <= beside < len(ranges) and np.isfinite(ranges[beside]) and \
                ranges[beside] < ranges[end]:
            nearer += 1
    return nearer < _NEARER_SIDES


def _round(xs: np.ndarray, ys: np.ndarray, mount: Pose) -> bool:
    """Whether the returns bulge towards the sensor from the chord between the ends
    (a leg is round; a piece of wall or a flat board is not)."""
    if len(xs) < 3:
        return False
    ax, ay, bx, by = xs[0], ys[0], xs[-1], ys[-1]
    length = math.hypot(bx - ax, by - ay)
    # signed distance from the chord, positive on the sensor's side
    normal = np.array([-(by - ay), bx - ax]) / length
    if float(normal @ np.array([mount.x - ax, mount.y - ay])) < 0:
        normal = -normal
    inner = slice(1, -1)
    sagitta = (xs[inner] - ax) * normal[0] + (ys[inner] - ay) * normal[1]
    return float(sagitta.mean()) >= _BULGE


def _centre(xs: np.ndarray, ys: np.ndarray, mount: Pose, width: float) -> tuple[float, float]:
    """A leg's centre: its returns lie on its near side, the centre further along the ray."""
    dx, dy = float(xs.mean()) - mount.x, float(ys.mean()) - mount.y
    reach = math.hypot(dx, dy)
    push = (reach + width / 4) / reach
    return (mount.x + dx * push, mount.y + dy * push)


def pair_legs(legs: np.ndarray, reach: float = _PAIR) -> list[np.ndarray]:
    """Legs grouped into people: nearest pairs first (each within ``reach``), then the
    legs left alone; each group as the (1 or 2, 2) array of its legs."""
    count = len(legs)
    pairs = sorted((float(np.linalg.norm(legs[i] - legs[j])), i, j)
                   for i in range(count) for j in range(i + 1, count))
    used: set[int] = set()
    groups = []
    for distance, i, j in pairs:
        if distance > reach:
            break
        if i in used or j in used:
            continue
        used.update((i, j))
        groups.append(legs[[i, j]])
    groups.extend(legs[[i]] for i in range(count) if i not in used)
    return groups


@dataclass(frozen=True, slots=True)
class TrackerParameters:
    """How the tracker predicts, gates, starts and ends tracks."""

    acceleration: float = 2.0  #: m/s², the white-noise acceleration of walking people
    # Measured on crowd scenes of a seed no figure uses (3): one leg lies 0.12 m (RMS per
    # axis) from the person's centre, the mean of both legs 0.016 m. The filter allows
    # more: legs paired with someone else's, a leg seen half behind another.
    leg_noise: float = 0.08  #: m, a person's centre from the mean of both legs
    one_leg_noise: float = 0.15  #: m, from one leg
    gate: float = 0.45  #: m: a returning person this far from where they were heading
    confirm: int = 3  #: sweeps with legs before a track is reported
    tentative: float = 0.35  #: s an unconfirmed track survives unseen
    coast: float = 1.0  #: s a confirmed track survives unseen where the laser sees past it
    hidden: float = 5.0  #: s it survives unseen in the shadow of something nearer
    unseen_slowing: float = 0.7  #: s: an unseen track's velocity decays with this time constant
    remember: float = 3.0  #: s an ended track's identity waits for its person to come back
    duplicate: float = 0.25  #: m; two confirmed tracks this close for long are one person
    max_speed: float = 2.0  #: m/s; faster velocity estimates are clipped
    gate_chi2: float = 9.21  #: squared Mahalanobis distance of a leg from a track (99 %)
    gate_max: float = 1.5  #: m: and never further than this
    tentative_cost: float = 0.5  #: added to an unconfirmed track's cost (log-likelihood units)
    second_leg_cost: float = 0.5  #: added to a track's second leg's cost
    reidentify_after: float = 0.3  #: s unseen before a coasting track's identity may move
    reidentify_speed: float = 1.5  #: m/s: how fast an unseen person's reach grows


@dataclass
class Track:
    """One tracked person: a Kalman filter over position and velocity on the map."""

    id: int
    state: np.ndarray  #: x, y, vx, vy
    covariance: np.ndarray
    born: float
    seen: float
    hits: int = 1
    confirmed: bool = False
    close_since: float | None = field(default=None, repr=False)
    last_seen: np.ndarray | None = field(default=None, repr=False)  #: state when last seen

    @property
    def position(self) -> tuple[float, float]:
        return (float(self.state[0]), float(self.state[1]))

    @property
    def velocity(self) -> tuple[float, float]:
        return (float(self.state[2]), float(self.state[3]))


class PeopleTracker:
    """Tracks people from leg detections, sweep after sweep.

    Args:
        parameters: noise, gating, confirmation and coasting.
    """

    def __init__(self, parameters: TrackerParameters | None = None) -> None:
        self.parameters = parameters or TrackerParameters()
        self.tracks: list[Track] = []
        self.stamp: float | None = None
        self._next_id = 1
        self._lost: list[Track] = []  #: confirmed tracks ended lately, who may come back
        self._retired: list[Track] = []  #: coasting tracks whose identity moved this sweep

    def confirmed(self) -> list[Track]:
        """The tracks reported as people."""
        return [track for track in self.tracks if track.confirmed]

    def update(self, stamp: float, legs: np.ndarray, scan: LaserScan | None = None,
               pose: Pose | None = None) -> list[Track]:
        """Predict every track to ``stamp``, assign ``legs`` (n, 2) on the map, correct,
        start and end tracks; the confirmed tracks.

        With the ``scan`` the legs came from and the robot's ``pose``, a track nobody
        is seen at survives longer when something nearer hides it from the laser."""
        p = self.parameters
        dt = 0.0 if self.stamp is None else max(0.0, stamp - self.stamp)
        self.stamp = stamp
        for track in self.tracks:
            self._predict(track, dt)
            if stamp - track.seen > 0.3 and p.unseen_slowing > 0:
                # unseen, a person may have stopped or turned: trust the velocity less
                track.state[2:] *= math.exp(-dt / p.unseen_slowing)
        legs = np.asarray(legs, dtype=float).reshape(-1, 2)
        assigned = self._assign(legs)
        taken: set[int] = set()
        for track, indices in zip(self.tracks, assigned, strict=True):
            if not indices:
                continue
            taken.update(indices)
            noise = p.leg_noise if len(indices) == 2 else p.one_leg_noise
            self._correct(track, legs[indices].mean(axis=0), noise)
            track.seen = stamp
            track.last_seen = track.state.copy()
            track.hits += 1
            if track.hits >= p.confirm and not track.confirmed:
                track.confirmed = True
                self._revive(stamp, track)
        if self._retired:
            self.tracks = [track for track in self.tracks
                           if all(track is not gone for gone in self._retired)]
            self._retired = []
        self._end_tracks(stamp, scan, pose)
        free = np.array([i for i in range(len(legs)) if i not in taken], dtype=int)
        for group in pair_legs(legs[free]):
            self._start(stamp, group.mean(axis=0))
        self._merge_duplicates(stamp)
        return self.confirmed()

    # ------------------------------------------------------------ Kalman filter

    def _predict(self, track: Track, dt: float) -> None:
        if dt <= 0:
            return
        q = self.parameters.acceleration ** 2
        f = np.eye(4)
        f[0, 2] = f[1, 3] = dt
        g = np.array([[dt * dt / 2, 0], [0, dt * dt / 2], [dt, 0], [0, dt]])
        track.state = f @ track.state
        track.covariance = f @ track.covariance @ f.T + q * g @ g.T

    def _correct(self, track: Track, measured: np.ndarray, noise: float) -> None:
        h = np.zeros((2, 4))
        h[0, 0] = h[1, 1] = 1.0
        innovation = measured - h @ track.state
        s = h @ track.covariance @ h.T + noise ** 2 * np.eye(2)
        gain = track.covariance @ h.T @ np.linalg.inv(s)
        track.state = track.state + gain @ innovation
        track.covariance = (np.eye(4) - gain @ h) @ track.covariance
        speed = math.hypot(track.state[2], track.state[3])
        if speed > self.parameters.max_speed:
            track.state[2:] *= self.parameters.max_speed / speed

    # ------------------------------------------------------------ data association

    def _assign(self, legs: np.ndarray) -> list[list[int]]:
        """For each track, the legs it takes (at most two), by the Hungarian method."""
        tracks = self.tracks
        assigned: list[list[int]] = [[] for _ in tracks]
        if not tracks or not len(legs):
            return assigned
        p = self.parameters
        centres = np.array([track.state[:2] for track in tracks])
        offsets = legs[:, None, :] - centres[None, :, :]  # (legs, tracks, 2)
        # the innovation's covariance for one leg: the track's spread and a leg's offset
        spreads = np.array([track.covariance[:2, :2] for track in tracks]) + \
            p.one_leg_noise ** 2 * np.eye(2)[None, :, :]
        inverse = np.linalg.inv(spreads)
        mahalanobis = np.einsum("ltj,tjk,ltk->lt", offsets, inverse, offsets)
        distance = np.linalg.norm(offsets, axis=2)
        within = (mahalanobis <= p.gate_chi2) & (distance <= p.gate_max)
        # the negative log likelihood: an uncertain track pays for its spread
        likelihood = mahalanobis + np.log(np.linalg.det(spreads))[None, :]
        # Two slots per track; the second costs a little more, so a lone leg near two
        # tracks goes to the one that has none yet. Confirmed tracks are preferred.
        penalty = np.array([0.0 if track.confirmed else p.tentative_cost for track in tracks])
        cost = np.hstack((likelihood + penalty, likelihood + penalty + p.second_leg_cost))
        within = np.hstack((within, within))
        cost = np.where(within, cost, _UNASSIGNED)
        rows, columns = linear_sum_assignment(cost)
        for leg, slot in zip(rows, columns, strict=True):
            if cost[leg, slot] < _UNASSIGNED:
                assigned[slot % len(tracks)].append(int(leg))
        return assigned

    # ------------------------------------------------------------ birth and death

    def _start(self, stamp: float, where: np.ndarray) -> None:
        covariance = np.diag([0.15 ** 2, 0.15 ** 2, 1.0, 1.0])
        self.tracks.append(Track(self._next_id, np.array([where[0], where[1], 0.0, 0.0]),
                                 covariance, stamp, stamp))
        self._next_id += 1

    def _end_tracks(self, stamp: float, scan: LaserScan | None, pose: Pose | None) -> None:
        p = self.parameters
        kept = []
        for track in self.tracks:
            unseen = stamp - track.seen
            if not track.confirmed:
                alive = unseen <= p.tentative
            elif unseen <= p.coast:
                alive = True
            else:
                alive = unseen <= p.hidden and scan is not None and pose is not None and \
                    _hidden(track.position, scan, pose)
            if alive:
                kept.append(track)
            elif track.confirmed:
                self._lost.append(track)
        self.tracks = kept
        self._lost = [track for track in self._lost if stamp - track.seen <= p.remember]

    def _revive(self, stamp: float, track: Track) -> None:
        """A new track confirmed where an unseen one would have walked to since it was
        last seen takes the unseen one's identity (a person back from behind someone):
        an ended track, or a confirmed one still coasting (its prediction may have
        stalled while the hidden person walked on), which then ends."""
        p = self.parameters
        best, best_gap = None, math.inf
        coasting = [other for other in self.tracks if other.confirmed and other is not track
                    and stamp - other.seen > p.reidentify_after
                    and all(other is not gone for gone in self._retired)]
        for lost in [*self._lost, *coasting]:
            age = stamp - lost.seen
            walked = min(age, 1.0)
            last = lost.last_seen if lost.last_seen is not None else lost.state
            expected = (last[0] + last[2] * walked, last[1] + last[3] * walked)
            gap = math.dist(expected, track.position)
            if gap <= p.gate + p.reidentify_speed * age and gap < best_gap:
                best, best_gap = lost, gap
        if best is not None:
            if best in self._lost:
                self._lost.remove(best)
            else:
                self._retired.append(best)  # ends after this sweep's corrections
            track.id = best.id
            track.born = best.born

    def _merge_duplicates(self, stamp: float) -> None:
        confirmed = sorted(self.confirmed(), key=lambda track: track.born)
        gone: set[int] = set()
        for index, older in enumerate(confirmed):
            for younger in confirmed[index + 1:]:
                if older.id in gone or younger.id in gone:
                    continue
                if math.dist(older.position, younger.position) < self.parameters.duplicate:
                    if younger.close_since is None:
                        younger.close_since = stamp
                    elif stamp - younger.close_since >= 0.5:
                        gone.add(younger.id)
                else:
                    younger.close_since = None
        if gone:
            self.tracks = [track for track in self.tracks if track.id not in gone]


def _hidden(point: tuple[float, float], scan: LaserScan, pose: Pose) -> bool:
    """Whether the laser's view of ``point`` (a person's centre on the map) is blocked
    by a return well in front of it, or ``point`` lies outside the field of view."""
    sensor = pose.apply(scan.mount.x, scan.mount.y)
    dx, dy = point[0] - sensor[0], point[1] - sensor[1]
    distance = math.hypot(dx, dy)
    if distance < 0.3:
        return False
    bearing = wrap_angle(math.atan2(dy, dx) - pose.theta - scan.mount.theta)
    half = math.atan2(0.2, distance)
    first = math.floor((bearing - half - scan.angle_min) / scan.angle_increment)
    last = math.ceil((bearing + half - scan.angle_min) / scan.angle_increment)
    if last < 0 or first >= len(scan.ranges):
        return True
    window = scan.ranges[max(first, 0):min(last, len(scan.ranges) - 1) + 1]
    return bool(np.any(window < distance - 0.3))


# ------------------------------------------------------------------ posture and clothes

COLOURS: dict[str, tuple[int, int, int]] = {
    "red": (200, 30, 30), "green": (30, 150, 50), "blue": (30, 60, 190),
    "yellow": (225, 205, 40), "black": (25, 25, 25), "white": (235, 235, 235),
    "grey": (128, 128, 128), "orange": (235, 120, 20), "purple": (120, 40, 150),
    "brown": (110, 70, 35),
}


def posture_from_profile(points: np.ndarray) -> str:
    """Standing, sitting or lying from a person's points (n, 3): x, y on the map and
    height z, as a depth camera's cloud over a track gives them.

    Crude rules on three numbers: the cloud's top (98th percentile of z), its length
    along its main horizontal axis, and how far the points below the knees lie from
    those above the hip, sideways (a seated person's feet are forward of the trunk).
    Low and long is lying; tall and upright is standing; anything else is sitting.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    if len(points) < 10:
        return "unknown"
    top = float(np.percentile(points[:, 2], 98))
    length = _length(points[:, :2])
    low, high = points[points[:, 2] < 0.4, :2], points[points[:, 2] > 0.9, :2]
    # a seated person's feet are forward of their trunk; a standing person's are under it
    lean = float(np.linalg.norm(low.mean(axis=0) - high.mean(axis=0))) \
        if len(low) >= 5 and len(high) >= 5 else 0.0
    if top < 1.0 and length > 1.1:
        return "lying"
    if top > 1.3 and lean < 0.2:
        return "standing"
    return "sitting"


def _length(flat: np.ndarray) -> float:
    """The extent (2nd to 98th percentile) of points along their main axis."""
    centred = flat - flat.mean(axis=0)
    _, _, axes = np.linalg.svd(centred, full_matrices=False)
    along = centred @ axes[0]
    return float(np.percentile(along, 98) - np.percentile(along, 2))


def clothes_colour(patch: np.ndarray) -> str:
    """The named colour (``COLOURS``) nearest the torso patch's (h, w, 3 RGB uint8) median,
    after dividing out the brightness: lighting scales the patch, not its chromaticity.

    Crude: black, grey and white differ by brightness alone, so for them the
    brightness is kept.
    """
    median = np.median(np.asarray(patch, dtype=float).reshape(-1, 3), axis=0)
    brightness = float(median.sum()) + 1e-6
    saturation = float(median.max() - median.min()) / (float(median.max()) + 1e-6)

    def distance(named: tuple[int, int, int]) -> float:
        reference = np.asarray(named, dtype=float)
        grey = max(reference) - min(reference) < 30
        if saturation < 0.2:
            # achromatic: black, grey and white by brightness; colours far behind
            return abs(brightness - float(reference.sum())) / 3 + (0.0 if grey else 500.0)
        chroma = median / brightness
        return float(np.linalg.norm(chroma - reference / (reference.sum() + 1e-6))) * 1000

    return min(COLOURS, key=lambda name: distance(COLOURS[name]))
