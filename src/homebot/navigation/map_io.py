"""ROS ``map_server`` maps: a world's occupancy grid as a YAML + PGM pair, and back.

The format is the one nav2_map_server (and ROS 1 map_server) loads and map_saver writes:

- the YAML names ``image`` (relative to the YAML's folder, or absolute), ``mode``
  (``trinary``, ``scale`` or ``raw``; trinary when left out), ``resolution`` (m per
  pixel), ``origin`` ``[x, y, yaw]`` (the pose of the image's lower-left pixel in the
  ``map`` frame), ``negate``, ``occupied_thresh`` and ``free_thresh``;
- the image is an 8-bit grey PGM (P5) whose row 0 is the top of the map (largest y).
  A pixel of value v has occupancy p = (255 - v) / 255 (p = v / 255 with ``negate``):
  occupied when p > occupied_thresh, free when p < free_thresh, otherwise unknown.

homebot writes trinary maps as map_saver does: occupied 0 (black), free 254, unknown
205. Its ``free_thresh`` is 0.196, ROS 1 map_saver's, not nav2 map_saver's 0.25: with
0.25 an unknown pixel (p = 50/255 = 0.19608) would read back as *free*; with 0.196 it
reads back unknown in both ROS 1 and nav2.

What is where: walls and furniture (``OccupancyGrid.occupied``, not inflated) are
occupied; the floor of every room is free; the space outside every room, beyond the
walls' thickness, is *unknown*, as on a map a robot built itself (it has never seen
behind the walls, and no route reaches it, since every door joins two rooms).
Reading a map back gives the same three classes; ``RosMap.obstacles`` (occupied or
unknown) equals the world grid's ``occupied``.

Reading reduces the other modes to the same three classes: in ``scale`` mode a
transparent pixel is unknown and a value between the thresholds (a graded
probability) counts as unknown; in ``raw`` mode the value is the occupancy in percent
(0-100, anything above is unknown), compared with the thresholds like p.
"""

from __future__ import annotations

import io
import math
import re
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from PIL import Image, UnidentifiedImageError
from scipy import ndimage

from homebot.errors import MapError
from homebot.files import read_bytes_file
from homebot.geometry import wrap_angle
from homebot.world import OccupancyGrid, World
from homebot.yamlfile import load_yaml_document, short_repr

__all__ = [
    "FREE_PIXEL",
    "MAX_MAP_PIXELS",
    "OCCUPIED_PIXEL",
    "UNKNOWN_PIXEL",
    "RosMap",
    "map_file_stem",
    "read_map",
    "write_map",
]

OCCUPIED_PIXEL = 0  #: black: a wall or furniture
FREE_PIXEL = 254  #: white (254, as map_saver writes it): floor
UNKNOWN_PIXEL = 205  #: grey: outside the home
_OCCUPIED_THRESH = 0.65
_FREE_THRESH = 0.196
_MODES = ("trinary", "scale", "raw")
_REQUIRED = ("image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh")


@dataclass(frozen=True)
class RosMap:
    """A map as ``map_server`` sees it: occupied, free and unknown cells on a grid.

    ``occupied`` and ``unknown`` are boolean arrays of shape (rows along y, columns
    along x); row 0 is the bottom of the map (smallest y), as in ``OccupancyGrid``
    (the image stores it upside down). ``origin`` is (x, y, yaw) of the lower-left
    cell's corner in the ``map`` frame; ``source`` names the YAML file it came from.
    """

    occupied: np.ndarray
    unknown: np.ndarray
    origin: tuple[float, float, float]
    resolution: float
    source: str = "<map>"

    @property
    def shape(self) -> tuple[int, int]:
        rows, columns = self.occupied.shape
        return (int(rows), int(columns))

    @property
    def free(self) -> np.ndarray:
        """Cells known to be free floor."""
        free: np.ndarray = ~(self.occupied | self.unknown)
        return free

    @property
    def obstacles(self) -> np.ndarray:
        """Cells the robot may not enter: occupied or unknown (``OccupancyGrid.occupied``)."""
        obstacles: np.ndarray = self.occupied | self.unknown
        return obstacles

    def counts(self) -> dict[str, int]:
        """How many cells are free, occupied and unknown."""
        return {"free": int(self.free.sum()), "occupied": int(self.occupied.sum()),
                "unknown": int(self.unknown.sum())}

    def extent(self) -> tuple[float, float, float, float]:
        """(min x, min y, max x, max y) that the map covers, in metres."""
        rows, columns = self.shape
        x, y, _ = self.origin
        return (x, y, x + columns * self.resolution, y + rows * self.resolution)

    @classmethod
    def from_world(cls, world: World) -> RosMap:
        """The world's occupancy grid (walls and furniture, not inflated) as a map."""
        grid = OccupancyGrid.from_world(world)
        rows, columns = grid.shape
        xs = grid.origin[0] + (np.arange(columns) + 0.5) * grid.resolution
        ys = grid.origin[1] + (np.arange(rows) + 0.5) * grid.resolution
        grid_x, grid_y = np.meshgrid(xs, ys)
        home = shapely.union_all(list(world.room_polygons.values()))
        outside = shapely.distance(home, shapely.points(grid_x, grid_y)) > (
            world.model.wall_thickness / 2)
        unknown = grid.occupied & outside
        return cls(grid.occupied & ~unknown, unknown, (grid.origin[0], grid.origin[1], 0.0),
                   grid.resolution, f"<world {world.name}>")

    def to_occupancy_grid(self, robot_radius: float) -> OccupancyGrid:
        """An ``OccupancyGrid`` (obstacles = occupied or unknown) for planning and localising.

        A map carries no doors: ``door_cells`` and ``door_passages`` are empty.
        """
        obstacles = self.obstacles
        clearance = ndimage.distance_transform_edt(~obstacles) * self.resolution
        return OccupancyGrid((self.origin[0], self.origin[1]), self.resolution, self.shape,
                             obstacles, clearance < robot_radius, {}, {})

    def check_covers(self, world: World) -> None:
        """Raise ``MapError`` unless the map covers every room of ``world``."""
        min_x, min_y, max_x, max_y = world.bounds()
        left, bottom, right, top = self.extent()
        slack = self.resolution / 2
        if (left > min_x + slack or bottom > min_y + slack or right < max_x - slack
                or top < max_y - slack):
            rows, columns = self.shape
            raise MapError(
                f"{self.source}: the map's {columns}×{rows} pixels at {self.resolution:g} m "
                f"from origin ({left:g}, {bottom:g}) cover x {left:g}..{right:g}, y "
                f"{bottom:g}..{top:g} m, but world '{world.name}' spans x {min_x:g}..{max_x:g}, "
                f"y {min_y:g}..{max_y:g} m; write the map from this world "
                f"(homebot world map --world WORLD -o DIR) or fix its origin and resolution")


    def differing_cells(self, other: RosMap) -> int | None:
        """How many cells the two maps both cover and see differently (free or not free).

        None when their grids do not line up (other resolution, or origins apart by
        a fraction of a cell).
        """
        if not math.isclose(self.resolution, other.resolution, rel_tol=1e-9):
            return None
        offsets = [(other.origin[i] - self.origin[i]) / self.resolution for i in (1, 0)]
        if any(abs(offset - round(offset)) > 1e-6 for offset in offsets):
            return None
        row, column = (round(offset) for offset in offsets)
        rows = slice(max(row, 0), min(self.shape[0], row + other.shape[0]))
        columns = slice(max(column, 0), min(self.shape[1], column + other.shape[1]))
        mine = self.free[rows, columns]
        theirs = other.free[rows.start - row:rows.stop - row,
                            columns.start - column:columns.stop - column]
        return int(np.count_nonzero(mine != theirs))


def map_file_stem(world: World) -> str:
    """The file name (without suffix) a world's map is written under."""
    return re.sub(r"[^A-Za-z0-9_-]+", "_", world.name).strip("_") or "map"


def write_map(ros_map: RosMap, yaml_path: str | Path) -> tuple[Path, Path]:
    """Write ``ros_map`` as ``yaml_path`` and a PGM beside it; returns both paths."""
    yaml_path = Path(yaml_path)
    pgm_path = yaml_path.with_suffix(".pgm")
    pixels = np.full(ros_map.shape, FREE_PIXEL, dtype=np.uint8)
    pixels[ros_map.unknown] = UNKNOWN_PIXEL
    pixels[ros_map.occupied] = OCCUPIED_PIXEL
    x, y, yaw = ros_map.origin
    text = (f"image: {pgm_path.name}\n"
            "mode: trinary\n"
            f"resolution: {ros_map.resolution!r}\n"
            f"origin: [{_number(x)}, {_number(y)}, {_number(yaw)}]\n"
            "negate: 0\n"
            f"occupied_thresh: {_OCCUPIED_THRESH}\n"
            f"free_thresh: {_FREE_THRESH}\n")
    try:
        yaml_path.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(pixels[::-1], mode="L").save(pgm_path, format="PPM")
        yaml_path.write_text(text, encoding="utf-8")
    except OSError as error:
        raise MapError(f"{error.filename or yaml_path}: cannot be written "
                       f"({error.strerror or error}); choose a folder you can write to"
                       ) from None
    return yaml_path, pgm_path


def _number(value: float) -> str:
    return repr(round(float(value), 6) + 0.0)  # + 0.0: no "-0.0"


def read_map(yaml_path: str | Path) -> RosMap:
    """Read a ``map_server`` YAML and its image; every problem raises ``MapError``."""
    yaml_path = Path(yaml_path)
    document = load_yaml_document(yaml_path, MapError)
    data: Any = document.data
    source = str(yaml_path)
    if not isinstance(data, dict):
        raise MapError(f"{source}: a map YAML is a mapping with {', '.join(_REQUIRED)} "
                       "(and mode); see ROS map_server")
    missing = [key for key in _REQUIRED if key not in data]
    if missing:
        raise MapError(f"{source}: '{missing[0]}' is missing; a map YAML names "
                       f"{', '.join(_REQUIRED)}")

    def where(key: str) -> str:
        return f"{source}: line {document.line_of([key])}: {key}"

    resolution = _finite(data["resolution"], where("resolution"))
    if resolution <= 0:
        raise MapError(f"{where('resolution')}: must be greater than 0 (metres per pixel), "
                       f"got {resolution:g}")
    origin = data["origin"]
    if not isinstance(origin, list) or len(origin) != 3:
        raise MapError(f"{where('origin')}: must be [x, y, yaw] (the lower-left pixel's pose),"
                       f" got {short_repr(origin)}")
    x, y, yaw = (_finite(value, where("origin")) for value in origin)
    if abs(wrap_angle(yaw)) > 1e-9:
        raise MapError(f"{where('origin')}: yaw {yaw:g} is not 0; homebot reads maps whose "
                       "rows run along x (rotate the image instead)")
    occupied_thresh = _finite(data["occupied_thresh"], where("occupied_thresh"))
    free_thresh = _finite(data["free_thresh"], where("free_thresh"))
    if not 0.0 <= free_thresh < occupied_thresh <= 1.0:
        raise MapError(f"{where('free_thresh')}: thresholds must satisfy 0 <= free_thresh "
                       f"< occupied_thresh <= 1, got {free_thresh:g} and {occupied_thresh:g}")
    negate = data["negate"]
    if negate not in (0, 1) or isinstance(negate, float):
        raise MapError(f"{where('negate')}: must be 0 or 1, got {short_repr(negate)}")
    mode = data.get("mode", "trinary")
    if mode not in _MODES:
        raise MapError(f"{where('mode')}: unknown mode {short_repr(mode)}; use one of "
                       f"{', '.join(_MODES)}")
    image = data["image"]
    if not isinstance(image, str) or not image.strip():
        raise MapError(f"{where('image')}: must name the map's image file, got "
                       f"{short_repr(image)}")
    shade, opaque = _read_image(yaml_path.parent / image, where("image"), str(mode))
    occupancy = shade if negate else 1.0 - shade
    if mode == "raw":
        value = np.rint(shade * 255.0)
        occupancy = value / 100.0
        opaque = opaque & (value <= 100)
    occupied = opaque & (occupancy > occupied_thresh)
    free = opaque & (occupancy < free_thresh)
    unknown = ~(occupied | free)
    return RosMap(occupied[::-1].copy(), unknown[::-1].copy(), (x, y, yaw), resolution,
                  source)


def _finite(value: Any, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(
            value):
        raise MapError(f"{where}: must be a finite number, got {short_repr(value)}")
    return float(value)


#: The most pixels a map image may have: reading one costs some 80 bytes a pixel (a
#: 2000×2000 map took 350 MB, 8000×8000 over 2 GB), and a home is far smaller.
MAX_MAP_PIXELS = 2048 * 2048


def _read_image(path: Path, where: str, mode: str) -> tuple[np.ndarray, np.ndarray]:
    """Brightness in [0, 1] per pixel (channels averaged, as map_server does) and opacity."""
    if not path.exists():
        raise MapError(f"{where}: the image {path} does not exist; write it beside the YAML "
                       "or fix the name")
    data = read_bytes_file(path, MapError, "image", "map image")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            image = Image.open(io.BytesIO(data))
        with image:
            width, height = image.size
            if width * height > MAX_MAP_PIXELS:
                raise MapError(f"{where}: {path} has {width}×{height} pixels, more than the "
                               f"{MAX_MAP_PIXELS:,} a map may have (2048×2048, 102 m square "
                               "at 5 cm); crop it or give a coarser resolution")
            image.load()
            if image.mode not in ("1", "L", "LA", "P", "RGB", "RGBA"):
                raise MapError(f"{where}: {path} is a {image.mode} image; give an 8-bit grey "
                               "PGM (P5) or PNG")
            has_alpha = image.mode in ("LA", "RGBA") or (
                image.mode == "P" and "transparency" in image.info)
            rgba = np.asarray(image.convert("RGBA"), dtype=np.float64) / 255.0
    except (Image.DecompressionBombError, Image.DecompressionBombWarning) as error:
        raise MapError(f"{where}: {path} is too large to read ({error})") from None
    except UnidentifiedImageError:  # its message names only an in-memory buffer
        raise MapError(f"{where}: {path} is not an image Pillow can read (no known image "
                       "format); give an 8-bit grey PGM (P5)") from None
    except (SyntaxError, ValueError) as error:
        raise MapError(f"{where}: {path} is not an image Pillow can read ({error}); give an "
                       "8-bit grey PGM (P5)") from None
    except OSError as error:
        raise MapError(f"{where}: {path} cannot be read ({error.strerror or error}); check it "
                       "is a complete PGM file") from None
    if rgba.size == 0:
        raise MapError(f"{where}: {path} has no pixels")
    channels = [rgba[..., 0], rgba[..., 1], rgba[..., 2]]
    if mode == "trinary" and has_alpha:  # map_server averages (inverted) alpha in trinary mode
        channels.append(rgba[..., 3])
    shade = np.mean(channels, axis=0)
    opaque = np.ones(shade.shape, dtype=bool)
    if mode == "scale" and has_alpha:
        opaque = rgba[..., 3] >= 1.0
    return shade, opaque
