"""Seeing people with the body's sensors: legs in the laser, bodies and faces in the head camera.

A look at the people around (Cosero §7.1, CAESAR §2.4), standing still:

1. For a second the robot watches. Every laser sweep's leg detections
   (``perception.people.detect_legs``; legs near the map's walls and furniture are
   theirs) feed a Kalman tracker with Hungarian assignment, which reports the
   people seen in several sweeps, walking or not. Meanwhile the head pans round
   and the RGB-D camera's points that stand clear of the map (above the floor and
   the furniture's tops, off the walls) are clustered: a cluster tall enough, or
   long enough, is a person's body: seated behind a table, or lying on a bed, where
   the laser sees no legs.
2. Laser tracks and camera bodies within ``_SAME_PERSON`` of each other are one
   person; those in the room the robot stands in are kept, as the symbolic robot's
   look keeps them.
3. Each body gives posture (``posture_from_profile``) and clothes colours
   (``clothes_colour``, on its trunk's and legs' pixels). The head turns to each
   person, nearest first, and watches them for a second: the depth frames give
   their head, shoulders and arms and so the gesture (``gesture_from_depth``),
   and within face range the face is recognised among the people the robot has
   met (``Acquaintances``); else the person is nameless.

Nothing is read from the simulator's truth here: only the ``Body`` port's laser,
head camera and face close-ups.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely
from scipy import ndimage

from homebot.errors import PartMissing
from homebot.geometry import Pose, from_frame, wrap_angle
from homebot.perception.body_parts import looking_tilt
from homebot.perception.faces import Acquaintances
from homebot.perception.gestures import gesture_from_depth
from homebot.perception.people import (
    STATIC_CLEARANCE,
    PeopleTracker,
    clothes_colour,
    detect_legs,
    posture_from_profile,
)
from homebot.robot import Body, CameraIntrinsics, PersonPercept, RgbdFrame, Twist
from homebot.world import OccupancyGrid, PlacementKind, World, surface_height

__all__ = ["UNREAD", "PeopleLook"]

#: ``PeopleLook.clothes_at`` of someone whose clothes the camera could not read
UNREAD = ("unread",)

_WATCH = 1.0  #: seconds of sweeps the robot watches for legs
_STOPPING = 1.0  #: seconds the base may take to come to rest before it looks
_PANS = (0.0, 1.0, 2.0, 2.6, -2.6, -2.0, -1.0)  #: head pans of the camera's sweep
#: radians down: level, for heads and trunks; low, for legs, laps and the floor near by
_TILTS = (0.0, 0.5)
_VIEWS = tuple((pan, tilt) for tilt in _TILTS for pan in (_PANS if tilt == _TILTS[0]
                                                           else reversed(_PANS)))
_TRUNK_DEPTH = 0.15  #: metres from a trunk's seen surface back to its middle
_POINT_STEP = 2  #: every second row and column of the depth image
_HEAD_TURN = 0.3  #: seconds the head takes to turn to a person and settle
_GESTURE_FRAMES = 10  #: head-camera frames watched for a gesture ...
_GESTURE_EVERY = 0.1  #: ... one every so many seconds
_FACE_RANGE = 2.5  #: metres within which the head camera's close-up shows a face
_FACE_VIEWS = 6  #: face views weighed together to name a person (identify_views)
_PAN_LIMIT = 2.6  #: radians the head turns either way
_SAME_PERSON = 0.6  #: metres between a laser track and a camera body of one person
_ABOVE_SURFACE = 0.15  #: metres above floor or furniture top that a body's point stands
_OFF_WALL = 0.15  #: metres from a wall's middle line that a body's point stands
_FURNITURE_MARGIN = 0.1  #: metres round furniture whose top still counts
_CELL = 0.1  #: metres: the grid the camera's points are clustered on
_MIN_POINTS = 25  #: points of a body at ``_POINT_STEP``
_UPRIGHT = (0.35, 0.9)  #: metres: a standing or seated body's least height span and top
_LYING_LENGTH = 1.0  #: metres: a lying body's least length
_HEAD = 0.25  #: metres from the top of a body down to its shoulders
_HIDDEN_LEGS = 0.4  #: metres: a body seen no lower than this has its legs hidden
_SEATED_TOP = 1.5  #: metres: a body whose top is lower sits (adults stand taller)
_EDGE = 0.08  #: metres below the picture's top edge where a body's top may be cut off
_HEAD_COLUMN = 0.15  #: metres round a body's middle where its head's points lie
_MIN_COLUMN = 5  #: points of a head
_ABOVE_HEAD_TOP = 0.05  #: metres over the head's top a body's own points still reach


@dataclass(frozen=True, slots=True)
class _Body:
    """A person's body in the camera's points (map frame) with their colours."""

    points: np.ndarray
    colours: np.ndarray
    cut: bool  #: its top runs out of the picture (seen from too near): its height unknown

    @property
    def position(self) -> tuple[float, float]:
        top = float(self.points[:, 2].max())
        trunk = self.points[self.points[:, 2] > top - 0.6]  # the trunk stands over the feet
        return (float(np.median(trunk[:, 0])), float(np.median(trunk[:, 1])))


@dataclass(frozen=True, slots=True)
class _Seen:
    """A person before the head turns to them: where, and their body if the camera saw it."""

    position: tuple[float, float]
    distance: float
    bearing: float  #: radians in the robot's frame
    body: _Body | None


class PeopleLook:
    """Looks at the people around a robot standing still.

    Args:
        body: the sensors.
        world: the map, whose rooms say who is in the robot's room and whose furniture
            says what in the camera's view is no one.
        grid: the static map; legs this close to its walls and furniture are theirs.
        localise: the robot's pose estimate after feeding it the latest sensors.
        acquaintances: the people met, to name faces (None: nobody is named).
        face_images: the head camera's close-ups of the face in front, so many a call
            (None: faces unseen).
    """

    def __init__(self, body: Body, world: World, grid: OccupancyGrid,
                 localise: Callable[[], Pose], *, acquaintances: Acquaintances | None = None,
                 face_images: Callable[[int], list[np.ndarray]] | None = None) -> None:
        self.body = body
        self.world = world
        self.grid = grid
        self.localise = localise
        self.acquaintances = acquaintances
        self.face_images = face_images
        resolution = grid.resolution
        self._clearance = ndimage.distance_transform_edt(~grid.occupied) * resolution
        # a margin round the furniture: depth noise spills its sides over its footprint
        margin = 2 * round(_FURNITURE_MARGIN / resolution) + 1
        self._tops = ndimage.grey_dilation(_furniture_tops(world, grid), size=(margin, margin))
        self._off_walls = _distance_to_walls(world, grid)
        self._intrinsics: CameraIntrinsics | None = None  #: the head camera's, once seen

    def look(self) -> list[PersonPercept]:
        """The people in the robot's room, as its sensors show them (nearest first)."""
        self._come_to_rest()
        pose = self.localise()
        tracked, bodies = self._watch(pose)
        spots: list[tuple[tuple[float, float], _Body | None]] = []
        for body in bodies:
            # the camera sees the near side of a body: its middle lies farther on
            x, y = body.position
            away = math.atan2(y - pose.y, x - pose.x)
            spots.append(((x + _TRUNK_DEPTH * math.cos(away), y + _TRUNK_DEPTH * math.sin(away)),
                          body))
        for spot in tracked:
            near = [index for index, (where, _) in enumerate(spots)
                    if math.dist(where, spot) <= _SAME_PERSON]
            if near:  # the laser places a person better than the camera's points
                spots[near[0]] = (spot, spots[near[0]][1])
            else:
                spots.append((spot, None))
        room = self.world.room_at(*pose.xy())
        seen = sorted((_seen_from(pose, where, body) for where, body in spots
                       if self._in_room(where, room)),
                      key=lambda person: person.distance)
        percepts = [self._percept(person, room or "", pose) for person in seen]
        self.body.point_head(0.0, 0.0)
        return percepts

    def clothes_at(self, pose: Pose, spot: tuple[float, float]) -> tuple[str, ...] | None:
        """What the person the head camera sees at ``spot`` (map frame) from ``pose``
        wears ("red top", ...), the head turned to them: () when the camera sees nobody
        there, ``UNREAD`` when it sees someone but not their clothes, None when the head
        cannot turn so far (or there is no camera). For telling a person one follows from
        others who come near them, or from a thing the laser took for legs."""
        bearing = wrap_angle(math.atan2(spot[1] - pose.y, spot[0] - pose.x) - pose.theta)
        if abs(bearing) > _PAN_LIMIT:
            return None
        self.body.point_head(bearing, 0.0)
        seen = self._camera_points(pose)
        if seen is None:
            return None
        near = [body for body in _bodies(*seen)
                if math.dist(body.position, spot) <= _SAME_PERSON]
        if not near:
            return ()
        nearest = min(near, key=lambda body: math.dist(body.position, spot))
        return _appearance(nearest)[1] or UNREAD

    def _come_to_rest(self) -> None:
        """Stop the base: sweeps placed by one pose must be taken from that pose."""
        body = self.body
        body.command_velocity(Twist())
        for _ in range(round(_STOPPING / body.tick_period)):
            if body.odometry().twist.is_zero():
                return
            body.tick()

    def _in_room(self, where: tuple[float, float], room: str | None) -> bool:
        """Whether someone at ``where`` is in ``room``, or stands in one of its doorways."""
        if self.world.room_at(*where) == room:
            return True
        return any(room in door.rooms and math.dist(where, door.position) <= door.width / 2
                   for door in self.world.doors.values())

    def _watch(self, pose: Pose) -> tuple[list[tuple[float, float]], list[_Body]]:
        """Where the laser tracked people over ``_WATCH`` seconds of sweeps, and the bodies
        the camera saw as the head panned round meanwhile."""
        body = self.body
        tracker = PeopleTracker()
        ticks = max(len(_VIEWS), round(_WATCH / body.tick_period))
        every = ticks // len(_VIEWS)
        points: list[np.ndarray] = []
        colours: list[np.ndarray] = []
        edges: list[np.ndarray] = []
        for tick in range(ticks):
            if tick % every == 0 and tick // every < len(_VIEWS):
                body.point_head(*_VIEWS[tick // every])
            body.tick()
            scan = body.scan()
            legs = detect_legs(scan, pose)
            tracker.update(body.now(), legs[self.off_the_map(legs)], scan, pose)
            if tick % every == every - 1 and tick // every < len(_VIEWS):
                seen = self._camera_points(pose)
                if seen is not None:
                    points.append(seen[0])
                    colours.append(seen[1])
                    edges.append(seen[2])
        bodies = _bodies(np.concatenate(points), np.concatenate(colours),
                         np.concatenate(edges)) if points else []
        return [track.position for track in tracker.confirmed()], bodies

    def _camera_points(self, pose: Pose) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """The camera's points (map frame) that stand clear of the map, their colours, and
        which lie at the picture's top edge."""
        try:
            frame = self.body.camera()
        except PartMissing:
            return None
        self._intrinsics = frame.intrinsics
        base, rgb = frame.points(_POINT_STEP)
        on_map = from_frame(pose, base[:, :2])
        xs, ys = on_map[:, 0], on_map[:, 1]
        row, column = self._cells(xs, ys)
        clear = (base[:, 2] > self._tops[row, column] + _ABOVE_SURFACE) & (
            self._off_walls[row, column] > _OFF_WALL)
        # the highest a point can be seen at its distance: the picture's top edge
        half_view = math.atan2(frame.intrinsics.cy, frame.intrinsics.fy)
        reach = np.hypot(base[:, 0], base[:, 1])
        ceiling = frame.camera_pose[2, 3] + reach * math.tan(half_view - self.body.head().tilt)
        edge = base[:, 2] > ceiling - _EDGE
        return np.column_stack((xs, ys, base[:, 2]))[clear], rgb[clear], edge[clear]

    def _cells(self, xs: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        rows, columns = self.grid.shape
        column = np.clip(((xs - self.grid.origin[0]) / self.grid.resolution).astype(int),
                         0, columns - 1)
        row = np.clip(((ys - self.grid.origin[1]) / self.grid.resolution).astype(int),
                      0, rows - 1)
        return row, column

    def off_the_map(self, legs: np.ndarray) -> np.ndarray:
        """Which legs stand clear of the map's walls and furniture."""
        if len(legs) == 0:
            return np.zeros(0, dtype=bool)
        row, column = self._cells(legs[:, 0], legs[:, 1])
        clear: np.ndarray = self._clearance[row, column] > STATIC_CLEARANCE
        return clear

    def _percept(self, person: _Seen, room: str, pose: Pose) -> PersonPercept:
        """Turn the head to ``person``: their gesture and, from near, who they are."""
        body = self.body
        name: str | None = None
        posture, gesture = "unknown", "none"
        clothes: tuple[str, ...] = ()
        if person.body is not None:
            posture, clothes = _appearance(person.body)
        if abs(person.bearing) <= _PAN_LIMIT:
            body.point_head(person.bearing, looking_tilt(person.distance, self._intrinsics)
                            if self._intrinsics is not None else 0.0)
            body.tick(max(1, round(_HEAD_TURN / body.tick_period)))
            frames = self._burst()
            if frames:
                gesture = gesture_from_depth(frames, [pose] * len(frames), person.position)
            body.point_head(person.bearing, 0.0)
            if person.distance <= _FACE_RANGE:
                name = self._name()
        return PersonPercept(name, posture, gesture, clothes, person.position, room)

    def _burst(self) -> list[RgbdFrame]:
        """About a second of head-camera frames, the body ticking between them (none
        without a camera)."""
        body = self.body
        frames = []
        for _ in range(_GESTURE_FRAMES):
            body.tick(max(1, round(_GESTURE_EVERY / body.tick_period)))
            try:
                frames.append(body.camera())
            except PartMissing:
                return []
        return frames

    def _name(self) -> str | None:
        if self.acquaintances is None or self.face_images is None:
            return None
        images = self.face_images(_FACE_VIEWS)
        if not images:
            return None
        # the memory of the people the robot was taught is built on the first face seen
        memory = self.acquaintances.memory
        return memory.identify_views(images) if memory.people else None


def _furniture_tops(world: World, grid: OccupancyGrid) -> np.ndarray:
    """The height of the furniture top over each cell of ``grid`` (0: no furniture)."""
    tops = np.zeros(grid.shape)
    rows = grid.origin[1] + (np.arange(grid.shape[0]) + 0.5) * grid.resolution
    columns = grid.origin[0] + (np.arange(grid.shape[1]) + 0.5) * grid.resolution
    for placement in world.placements.values():
        if placement.model.kind is not PlacementKind.FURNITURE:
            continue
        x0, y0, x1, y1 = placement.footprint.bounds
        inside_rows = (rows >= y0) & (rows <= y1)
        inside_columns = (columns >= x0) & (columns <= x1)
        block = np.ix_(inside_rows, inside_columns)
        tops[block] = np.maximum(tops[block], surface_height(placement.model))
    return tops


def _distance_to_walls(world: World, grid: OccupancyGrid) -> np.ndarray:
    """Metres from each cell of ``grid`` to the nearest wall line, doorways included (the
    camera sees the door frames and what is beyond a doorway is another room)."""
    ys = grid.origin[1] + (np.arange(grid.shape[0]) + 0.5) * grid.resolution
    xs = grid.origin[0] + (np.arange(grid.shape[1]) + 0.5) * grid.resolution
    points = shapely.points(*np.meshgrid(xs, ys))
    lines = shapely.union_all([polygon.exterior for polygon in world.room_polygons.values()])
    return np.asarray(shapely.distance(lines, points), dtype=float)


def _bodies(points: np.ndarray, colours: np.ndarray, edge: np.ndarray) -> list[_Body]:
    """People's bodies among points that stand clear of the map: clusters on a
    ``_CELL`` grid that are tall (standing, seated) or long and low (lying)."""
    if len(points) == 0:
        return []
    origin = points[:, :2].min(axis=0)
    cells = ((points[:, :2] - origin) / _CELL).astype(int)
    occupied = np.zeros(tuple(cells.max(axis=0) + 1), dtype=bool)
    occupied[cells[:, 0], cells[:, 1]] = True
    labels, count = ndimage.label(occupied, structure=np.ones((3, 3)))
    of_point = labels[cells[:, 0], cells[:, 1]]
    bodies = []
    for label in range(1, count + 1):
        mine = of_point == label
        if np.count_nonzero(mine) < _MIN_POINTS:
            continue
        cluster = points[mine]
        span = float(np.ptp(cluster[:, 2]))
        top = float(cluster[:, 2].max())
        length = float(np.linalg.norm(np.ptp(cluster[:, :2], axis=0)))
        if (span >= _UPRIGHT[0] and top >= _UPRIGHT[1]) or length >= _LYING_LENGTH:
            cut = bool(np.any(edge[mine] & (cluster[:, 2] > top - _EDGE)))
            bodies.append(_Body(cluster, colours[mine], cut))
    return bodies


def _seen_from(pose: Pose, spot: tuple[float, float], body: _Body | None) -> _Seen:
    bearing = wrap_angle(math.atan2(spot[1] - pose.y, spot[0] - pose.x) - pose.theta)
    return _Seen(spot, math.dist(spot, pose.xy()), bearing, body)


def _below_the_head(body: _Body) -> _Body:
    """The body without what rises above the head's top (a raised hand makes no one
    taller): the head is the top of the points round the body's middle."""
    x, y = body.position
    flat = np.hypot(body.points[:, 0] - x, body.points[:, 1] - y)
    column = body.points[flat < _HEAD_COLUMN, 2]
    if len(column) < _MIN_COLUMN:
        return body
    keep = body.points[:, 2] <= float(np.percentile(column, 98)) + _ABOVE_HEAD_TOP
    return _Body(body.points[keep], body.colours[keep], body.cut)


def _appearance(body: _Body) -> tuple[str, tuple[str, ...]]:
    """Posture and clothes colours from the camera's points on a person's body."""
    body = _below_the_head(body)
    posture = posture_from_profile(body.points)
    z = body.points[:, 2]
    top = float(z.max())
    if posture == "standing" and not body.cut and float(z.min()) > _HIDDEN_LEGS and \
            top < _SEATED_TOP:
        # legs hidden (behind a table), head in view: no adult standing is this short
        posture = "sitting"
    if posture == "lying":
        trunk = np.ones(len(z), dtype=bool)
        legs = np.zeros(len(z), dtype=bool)
    else:
        trunk = (z < top - _HEAD) & (z > top - _HEAD - 0.45)
        legs = z < 0.35 * top
    clothes = []
    if np.count_nonzero(trunk) >= 5:
        clothes.append(f"{clothes_colour(body.colours[trunk][:, None, :])} top")
    if posture == "standing" and np.count_nonzero(legs) >= 5:
        clothes.append(f"{clothes_colour(body.colours[legs][:, None, :])} trousers")
    return posture, tuple(clothes)
