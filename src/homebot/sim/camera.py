"""The head's RGB-D camera, ray cast against the true home with numpy.

Every pixel's ray meets the floor, the walls, the furniture (boxes from their
footprints up to their surface height), the catalogue objects standing on
them (boxes turned about their vertical axis, upright cylinders, spheres),
people's limbs (``Limb``: a round segment at any slant, for arms held out) and
shut doors (``door_solids``: the leaf and a lever handle on each face, boxes). The
nearest hit gives the depth and a Lambert-shaded colour. Depth is noisy as a
Kinect's is (σ grows with the square of the distance, Nguyen et al. 2012),
returns go missing at depth edges and out of range, and nearer surfaces hide
farther ones. Only the pixels inside a solid's projected bounding box are tested
against it, so a frame takes a few milliseconds.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import shapely

from homebot.geometry import yaw_rotation
from homebot.robot import CameraIntrinsics, HeadState, RgbdFrame
from homebot.world import PlacementKind, Shape, World, surface_height

__all__ = [
    "CAMERA_HEIGHT",
    "DEFAULT_INTRINSICS",
    "CameraSimulator",
    "Limb",
    "SceneGeometry",
    "Solid",
    "camera_pose",
    "door_solids",
    "object_yaw",
]

#: a Kinect-like 320×240 image with a 58° horizontal field of view
DEFAULT_INTRINSICS = CameraIntrinsics(320, 240, 285.0, 285.0, 159.5, 119.5)
CAMERA_HEIGHT = 1.3  #: metres above the floor, on the pan-tilt head over the base's centre
_RANGE = (0.4, 6.0)  #: metres the depth sensor measures between
_WALL_HEIGHT = 2.4
_FLOOR_RGB = (150, 135, 115)
_WALL_RGB = (215, 210, 200)
_FURNITURE_RGB = (140, 100, 62)
_LEAF_RGB = (190, 168, 132)
_HANDLE_RGB = (175, 175, 180)
_LEAF_HEIGHT = 2.0  #: metres: a shut leaf fills its doorway up to here
_LEAF_THICKNESS = 0.04
_LEAF_JAMB_GAP = 0.01  #: metres between a shut leaf's edge and each jamb
_HANDLE = (0.12, 0.025, 0.025)  #: metres: a lever handle's length, depth and height
_HANDLE_HEIGHT = 1.05  #: metres above the floor (DIN 18101)
_HANDLE_IN = 0.1  #: metres from the latch edge to the handle's centre
_HANDLE_STANDOFF = 0.05  #: metres between the leaf's face and the handle's back
_EDGE_JUMP = 0.025  #: metres (plus 2 % of the depth) between neighbours that lose both returns
_DROPOUT = 0.003  #: share of pixels with no return for no reason


@dataclass(frozen=True, slots=True)
class Solid:
    """A catalogue object as the camera sees it: where it stands (map frame) and how it looks."""

    shape: Shape
    extent: tuple[float, float, float]  #: x, y, z in its own frame (diameters for round ones)
    rgb: tuple[int, int, int]
    x: float
    y: float
    z: float  #: its bottom (the surface it stands on)
    yaw: float = 0.0


@dataclass(frozen=True, slots=True)
class Limb:
    """A person's upper arm or forearm as the camera sees it: a round segment (an open
    cylinder) from ``start`` to ``end`` (map frame, metres) at any slant; the joints at
    its ends are spheres of their own."""

    start: tuple[float, float, float]
    end: tuple[float, float, float]
    radius: float
    rgb: tuple[int, int, int]


def object_yaw(name: str, seed: int) -> float:
    """How an object stands turned on its surface: stable for a name and a run's seed."""
    return (zlib.crc32(f"{seed}:{name}".encode()) % 3600) / 3600 * math.pi


@dataclass(frozen=True)
class SceneGeometry:
    """The static home as the camera sees it: wall segments and furniture boxes."""

    walls: np.ndarray  #: (n, 4) segments x0, y0, x1, y1
    furniture: np.ndarray  #: (m, 5) boxes x0, y0, x1, y1, top

    @classmethod
    def of(cls, world: World) -> SceneGeometry:
        # the rooms' outlines but for their doorways: the camera sees through an open
        # door (a shut one is drawn as its leaf, ``door_solids``)
        outlines = shapely.union_all([polygon.exterior
                                      for polygon in world.room_polygons.values()])
        openings = shapely.union_all([shapely.Point(door.position).buffer(door.width / 2)
                                      for door in world.doors.values()])
        walls: list[tuple[float, float, float, float]] = []
        for line in shapely.get_parts(shapely.line_merge(outlines.difference(openings))):
            coordinates = shapely.get_coordinates(line)
            walls.extend((*coordinates[i], *coordinates[i + 1])
                         for i in range(len(coordinates) - 1))
        boxes = []
        for placement in world.placements.values():
            if placement.model.kind is PlacementKind.FURNITURE:
                x0, y0, x1, y1 = placement.footprint.bounds
                boxes.append((x0, y0, x1, y1, surface_height(placement.model)))
        return cls(np.array(walls, dtype=np.float64).reshape(-1, 4),
                   np.array(boxes, dtype=np.float64).reshape(-1, 5))


def door_solids(world: World, door: str) -> list[Solid]:
    """A shut door's leaf in its doorway and a lever handle on each face near the latch
    edge, as boxes; the hinge is the world's (``World.door_hinge_direction``)."""
    model = world.doors[door]
    hinge_x, hinge_y = world.door_hinge_direction(door)
    tx, ty = -hinge_x, -hinge_y  # from the middle to the latch jamb
    cx, cy = model.position
    yaw = math.atan2(ty, tx)
    leaf = Solid(Shape.BOX, (model.width - 2 * _LEAF_JAMB_GAP, _LEAF_THICKNESS, _LEAF_HEIGHT),
                 _LEAF_RGB, cx, cy, 0.0, yaw)
    latch = model.width / 2 - _LEAF_JAMB_GAP - _HANDLE_IN
    off = _LEAF_THICKNESS / 2 + _HANDLE_STANDOFF + _HANDLE[1] / 2
    handles = [Solid(Shape.BOX, _HANDLE, _HANDLE_RGB, cx + tx * latch - ty * side * off,
                     cy + ty * latch + tx * side * off, _HANDLE_HEIGHT - _HANDLE[2] / 2, yaw)
               for side in (1.0, -1.0)]
    return [leaf, *handles]



def camera_pose(head: HeadState, height: float = CAMERA_HEIGHT) -> np.ndarray:
    """The 4×4 transform from the optical frame to the base frame for a head pose."""
    cp, sp = math.cos(head.pan), math.sin(head.pan)
    ct, st = math.cos(head.tilt), math.sin(head.tilt)
    forward = np.array([cp * ct, sp * ct, -st])
    right = np.array([sp, -cp, 0.0])
    down = np.cross(forward, right)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2] = right, down, forward
    pose[:3, 3] = (0.0, 0.0, height)
    return pose


class _Buffers:
    """Depth (ray parameter = depth, rays have unit optical z), the colour seen (an index
    into ``colours``) and its shading."""

    def __init__(self, shape: tuple[int, int], norms: np.ndarray) -> None:
        self.norms = norms  #: each pixel's ray length
        self.depth = np.full(shape, np.inf, dtype=np.float32)
        self.colour = np.zeros(shape, dtype=np.int16)
        self.colours: list[Sequence[int]] = [(0, 0, 0)]
        self.shade = np.ones(shape, dtype=np.float32)

    def write(self, window: tuple[slice, slice], t: np.ndarray, rgb: Sequence[int],
              shade: np.ndarray) -> None:
        depth = self.depth[window]
        nearer = t < depth
        np.copyto(depth, t, where=nearer)
        self.colours.append(rgb)
        np.copyto(self.colour[window], len(self.colours) - 1, where=nearer)
        np.copyto(self.shade[window], shade, where=nearer)

    def rgb(self) -> np.ndarray:
        """The base colour of every pixel, (h, w, 3)."""
        palette = np.array(self.colours, dtype=np.float32)
        image: np.ndarray = palette[self.colour]
        return image


class CameraSimulator:
    """Renders RGB-D frames of the home from the robot's head.

    Args:
        geometry: the walls and furniture.
        rng: the sensor's noise.
        intrinsics: the pinhole model (default: 320×240, 58° across).
        noise: whether depth and colour are noisy (off: a perfect sensor, for tests).
    """

    def __init__(self, geometry: SceneGeometry, rng: np.random.Generator, *,
                 intrinsics: CameraIntrinsics = DEFAULT_INTRINSICS, noise: bool = True) -> None:
        self.geometry = geometry
        self.rng = rng
        self.intrinsics = intrinsics
        self.noise = noise
        self._rays = intrinsics.rays()
        #: each ray's length (a rotation keeps it), for the shading's cosines
        self._norms = np.linalg.norm(self._rays, axis=-1).astype(np.float32)

    def render(self, stamp: float, robot: tuple[float, float, float], head: HeadState,
               solids: Sequence[Solid | Limb]) -> RgbdFrame:
        """The frame the camera takes with the base at ``robot`` (x, y, heading; map frame)."""
        pose = camera_pose(head)
        x, y, theta = robot
        base_to_map = yaw_rotation(theta)
        rotation = base_to_map @ pose[:3, :3]  # optical -> map
        origin = base_to_map @ pose[:3, 3] + (x, y, 0.0)
        # (h, w, 3) map-frame directions, unit optical depth
        rays = (self._rays @ rotation.T).astype(np.float32)
        shape = rays.shape[:2]
        buffers = _Buffers(shape, self._norms)
        everywhere = (slice(0, shape[0]), slice(0, shape[1]))
        self._floor(buffers, origin, rays)
        self._walls(buffers, origin, rays, rotation, everywhere)
        for x0, y0, x1, y1, top in self.geometry.furniture:
            corners = _box_corners(x0, y0, x1, y1, 0.0, top)
            window = self._window(corners, origin, rotation, everywhere)
            if window is None:
                continue
            _box(buffers, window, origin, rays, (x0, y0, 0.0), (x1, y1, top), _FURNITURE_RGB)
        for solid in solids:
            if isinstance(solid, Limb):
                self._limb(buffers, solid, origin, rays, rotation, everywhere)
            else:
                self._solid(buffers, solid, origin, rays, rotation, everywhere)
        return self._frame(stamp, buffers, pose)

    # ------------------------------------------------------------ surfaces

    def _floor(self, buffers: _Buffers, origin: np.ndarray, rays: np.ndarray) -> None:
        down = rays[..., 2] < -1e-9
        t = np.where(down, -origin[2] / np.where(down, rays[..., 2], -1.0), np.inf)
        buffers.write((slice(None), slice(None)), t, _FLOOR_RGB, -rays[..., 2] / buffers.norms)

    def _walls(self, buffers: _Buffers, origin: np.ndarray, rays: np.ndarray,
               rotation: np.ndarray, everywhere: tuple[slice, slice]) -> None:
        walls = self.geometry.walls
        if not len(walls):
            return
        near = _segment_distance(walls, origin[:2]) < _RANGE[1]
        for x0, y0, x1, y1 in walls[near]:
            corners = np.array([(x0, y0, 0.0), (x1, y1, 0.0), (x0, y0, _WALL_HEIGHT),
                                (x1, y1, _WALL_HEIGHT)])
            window = self._window(corners, origin, rotation, everywhere)
            if window is None:
                continue
            self._wall(buffers, window, origin, rays[window], (x0, y0, x1, y1))

    def _wall(self, buffers: _Buffers, window: tuple[slice, slice], origin: np.ndarray,
              rays: np.ndarray, segment: tuple[float, float, float, float]) -> None:
        x0, y0, x1, y1 = segment
        dx, dy = rays[..., 0], rays[..., 1]
        norm = buffers.norms[window]
        ex, ey = x1 - x0, y1 - y0
        ax, ay = x0 - origin[0], y0 - origin[1]
        denominator = dx * ey - dy * ex
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (ax * ey - ay * ex) / denominator
            along = (ax * dy - ay * dx) / denominator
        z = origin[2] + t * rays[..., 2]
        hit = (t > 0) & (along >= 0) & (along <= 1) & (z >= 0) & (z <= _WALL_HEIGHT)
        length = math.hypot(ex, ey) or 1.0
        facing = np.abs(dx * ey - dy * ex) / (length * norm)
        buffers.write(window, np.where(hit, t, np.inf), _WALL_RGB, facing)

    def _solid(self, buffers: _Buffers, solid: Solid, origin: np.ndarray, rays: np.ndarray,
               rotation: np.ndarray, everywhere: tuple[slice, slice]) -> None:
        ex, ey, ez = solid.extent
        reach = math.hypot(ex, ey) / 2
        corners = _box_corners(solid.x - reach, solid.y - reach, solid.x + reach,
                               solid.y + reach, solid.z, solid.z + ez)
        window = self._window(corners, origin, rotation, everywhere)
        if window is None:
            return
        if solid.shape is Shape.BOX:
            turn = yaw_rotation(solid.yaw).T  # map -> object
            local_origin = turn @ (origin - (solid.x, solid.y, solid.z))
            local_rays = rays[window] @ turn.T
            _box(buffers, window, local_origin, local_rays, (-ex / 2, -ey / 2, 0.0),
                 (ex / 2, ey / 2, ez), solid.rgb, windowed=True)
        elif solid.shape is Shape.CYLINDER:
            _cylinder(buffers, window, origin, rays[window], solid)
        else:
            _sphere(buffers, window, origin, rays[window], solid)

    def _limb(self, buffers: _Buffers, limb: Limb, origin: np.ndarray, rays: np.ndarray,
              rotation: np.ndarray, everywhere: tuple[slice, slice]) -> None:
        ends = np.array([limb.start, limb.end])
        low, high = ends.min(axis=0) - limb.radius, ends.max(axis=0) + limb.radius
        corners = _box_corners(low[0], low[1], high[0], high[1], low[2], high[2])
        window = self._window(corners, origin, rotation, everywhere)
        if window is not None:
            _open_cylinder(buffers, window, origin, rays[window], limb)

    def _window(self, corners: np.ndarray, origin: np.ndarray, rotation: np.ndarray,
                everywhere: tuple[slice, slice]) -> tuple[slice, slice] | None:
        """The pixels a box's corners span: None when the camera cannot see it (behind
        it, out of the picture or out of range), the whole image when it reaches behind."""
        optical = (corners - origin) @ rotation  # map -> optical
        if np.all(optical[:, 2] < 0.05) or np.min(np.linalg.norm(optical, axis=1)) > _RANGE[1]:
            return None
        if np.any(optical[:, 2] < 0.05):
            return everywhere
        k = self.intrinsics
        u = k.fx * optical[:, 0] / optical[:, 2] + k.cx
        v = k.fy * optical[:, 1] / optical[:, 2] + k.cy
        u0, u1 = max(int(u.min()) - 1, 0), min(int(u.max()) + 2, k.width)
        v0, v1 = max(int(v.min()) - 1, 0), min(int(v.max()) + 2, k.height)
        if u0 >= u1 or v0 >= v1:
            return None
        return (slice(v0, v1), slice(u0, u1))

    # ------------------------------------------------------------ the sensor

    def _frame(self, stamp: float, buffers: _Buffers, pose: np.ndarray) -> RgbdFrame:
        depth = buffers.depth
        if self.noise:
            sigma = 0.0012 + 0.0019 * np.square(np.nan_to_num(depth, posinf=0.0) - 0.4)
            depth = depth + self.rng.standard_normal(depth.shape) * sigma
        depth = np.where((depth >= _RANGE[0]) & (depth <= _RANGE[1]), depth, np.nan)
        if self.noise:
            filled = np.nan_to_num(depth, nan=0.0)
            limit = _EDGE_JUMP + 0.02 * filled
            jump_x = np.abs(np.diff(filled, axis=1)) > limit[:, 1:]
            jump_y = np.abs(np.diff(filled, axis=0)) > limit[1:, :]
            edges = np.zeros(depth.shape, dtype=bool)
            edges[:, 1:] |= jump_x
            edges[:, :-1] |= jump_x
            edges[1:, :] |= jump_y
            edges[:-1, :] |= jump_y
            edges |= self.rng.random(depth.shape) < _DROPOUT
            depth = np.where(edges, np.nan, depth)
        shade = 0.45 + 0.55 * np.clip(buffers.shade, 0.0, 1.0)
        rgb = buffers.rgb() * shade[..., None]
        if self.noise:
            rgb = rgb + self.rng.normal(0.0, 3.0, rgb.shape)
        return RgbdFrame(stamp, np.clip(rgb, 0, 255).astype(np.uint8),
                         depth.astype(np.float32), self.intrinsics, pose)


# ---------------------------------------------------------------- ray casting


def _box_corners(x0: float, y0: float, x1: float, y1: float, z0: float,
                 z1: float) -> np.ndarray:
    return np.array([(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)])


def _box(buffers: _Buffers, window: tuple[slice, slice], origin: np.ndarray,
         rays: np.ndarray, low: Sequence[float], high: Sequence[float], rgb: Sequence[int],
         *, windowed: bool = False) -> None:
    """Slab test of an axis-aligned box (in the rays' frame) for the rays in ``window``."""
    d = rays if windowed else rays[window]
    if d.size == 0:
        return
    enter = np.full(d.shape[:2], -np.inf)
    leave = np.full(d.shape[:2], np.inf)
    facing = np.zeros(d.shape[:2])
    for axis in range(3):
        component = d[..., axis]
        with np.errstate(divide="ignore", invalid="ignore"):
            inverse = 1.0 / component
        t_low = (low[axis] - origin[axis]) * inverse
        t_high = (high[axis] - origin[axis]) * inverse
        near = np.fmin(t_low, t_high)
        later = near > enter
        enter = np.where(later, near, enter)
        facing = np.where(later, np.abs(component), facing)
        leave = np.fmin(leave, np.fmax(t_low, t_high))
    hit = (enter <= leave) & (enter > 0)
    buffers.write(window, np.where(hit, enter, np.inf), rgb, facing / buffers.norms[window])


def _cylinder(buffers: _Buffers, window: tuple[slice, slice], origin: np.ndarray,
              d: np.ndarray, solid: Solid) -> None:
    if d.size == 0:
        return
    radius, height = solid.extent[0] / 2, solid.extent[2]
    ox, oy = origin[0] - solid.x, origin[1] - solid.y
    a = d[..., 0] ** 2 + d[..., 1] ** 2
    b = 2 * (ox * d[..., 0] + oy * d[..., 1])
    c = ox * ox + oy * oy - radius * radius
    disc = b * b - 4 * a * c
    root = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        t_side = (-b - root) / (2 * a)
    z_side = origin[2] + t_side * d[..., 2]
    side = (disc >= 0) & (t_side > 0) & (z_side >= solid.z) & (z_side <= solid.z + height)
    top = solid.z + height
    with np.errstate(divide="ignore", invalid="ignore"):
        t_top = (top - origin[2]) / d[..., 2]
    px, py = ox + t_top * d[..., 0], oy + t_top * d[..., 1]
    cap = (t_top > 0) & (px * px + py * py <= radius * radius)
    t = np.where(side, t_side, np.inf)
    t = np.where(cap & (t_top < t), t_top, t)
    norm = buffers.norms[window]
    hx, hy = ox + t_side * d[..., 0], oy + t_side * d[..., 1]
    side_facing = np.abs(hx * d[..., 0] + hy * d[..., 1]) / (radius * norm)
    facing = np.where(cap & (t == t_top), np.abs(d[..., 2]) / norm, side_facing)
    buffers.write(window, t, solid.rgb, np.nan_to_num(facing))


def _open_cylinder(buffers: _Buffers, window: tuple[slice, slice], origin: np.ndarray,
                   d: np.ndarray, limb: Limb) -> None:
    """The round side of a slanted segment (no caps: the joints' spheres close it)."""
    if d.size == 0:
        return
    start = np.asarray(limb.start)
    axis = np.asarray(limb.end) - start
    length = float(np.linalg.norm(axis))
    if length < 1e-9:
        return
    axis /= length
    m = origin - start
    du = d @ axis
    mu = float(m @ axis)
    a = np.einsum("...i,...i->...", d, d) - du * du
    b = d @ m - mu * du  # half the quadratic's linear term
    c = float(m @ m) - mu * mu - limb.radius ** 2
    disc = b * b - a * c
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (-b - np.sqrt(np.maximum(disc, 0.0))) / a
    along = mu + t * du
    hit = (disc >= 0) & (t > 0) & (along >= 0) & (along <= length)
    points = m + t[..., None] * d - along[..., None] * axis
    facing = np.abs(np.einsum("...i,...i->...", points, d)) / (
        limb.radius * buffers.norms[window])
    buffers.write(window, np.where(hit, t, np.inf), limb.rgb, np.nan_to_num(facing))


def _sphere(buffers: _Buffers, window: tuple[slice, slice], origin: np.ndarray,
            d: np.ndarray, solid: Solid) -> None:
    if d.size == 0:
        return
    radius = solid.extent[0] / 2
    centre = np.array([solid.x, solid.y, solid.z + radius])
    o = origin - centre
    a = np.einsum("...i,...i->...", d, d)
    b = 2 * (d @ o)
    c = float(o @ o) - radius * radius
    disc = b * b - 4 * a * c
    t = (-b - np.sqrt(np.maximum(disc, 0.0))) / (2 * a)
    hit = (disc >= 0) & (t > 0)
    points = o + t[..., None] * d
    facing = np.abs(np.einsum("...i,...i->...", points, d)) / (radius * buffers.norms[window])
    buffers.write(window, np.where(hit, t, np.inf), solid.rgb, facing)


def _segment_distance(segments: np.ndarray, point: np.ndarray) -> np.ndarray:
    """Distance from ``point`` to each (x0, y0, x1, y1) segment."""
    start, end = segments[:, :2], segments[:, 2:]
    along = end - start
    length = np.maximum(np.einsum("ij,ij->i", along, along), 1e-12)
    t = np.clip(np.einsum("ij,ij->i", point - start, along) / length, 0.0, 1.0)
    nearest = start + t[:, None] * along
    distance: np.ndarray = np.linalg.norm(nearest - point, axis=1)
    return distance
