"""Layers of an embodied run on the map: the driven trajectory, the particle cloud, the laser.

``BodyRobot`` logs what it drove and saw as events (world frame, metres, radians):

- ``robot.trajectory`` ``{"points": [[x, y], ...]}``: the true driven path, sampled
  every ~0.1 m; a run may log it in several pieces, drawn joined in order;
- ``robot.particles`` ``{"points": [[x, y, theta], ...]}``: the localiser's particles
  (at most a few hundred); the last such event is drawn;
- ``robot.laser`` ``{"points": [[x, y], ...]}``: the last scan's returns placed on the
  map; the last such event is drawn.

``embodied_run`` reads them from event dictionaries (as the JSON lines of an event
log hold them); the ``draw_*`` functions draw one layer each with a world-to-pixel
function, so ``render_map`` stays a pure function of the world and the run.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from PIL import ImageDraw

__all__ = [
    "EMBODIED_COLOURS",
    "EmbodiedRun",
    "draw_embodied_run",
    "draw_laser",
    "draw_particles",
    "draw_trajectory",
    "embodied_run",
]

ToPixel = Callable[[float, float], tuple[float, float]]

#: colours of the layers, for a legend
EMBODIED_COLOURS: Mapping[str, tuple[int, int, int]] = {
    "trajectory": (90, 50, 180), "particles": (245, 140, 0), "laser": (235, 0, 130),
}
_PARTICLE_TICK = 7  # pixels from a particle's dot along its heading


@dataclass(frozen=True, slots=True)
class EmbodiedRun:
    """What an embodied run drove and saw, for drawing: all in the world (map) frame."""

    trajectory: tuple[tuple[float, float], ...] = ()
    particles: tuple[tuple[float, float, float], ...] = ()
    laser: tuple[tuple[float, float], ...] = ()

    def __bool__(self) -> bool:
        return bool(self.trajectory or self.particles or self.laser)


def embodied_run(events: Iterable[Mapping[str, Any]], world: str | None = None) -> EmbodiedRun:
    """The trajectory (joined), the last particle cloud and the last scan in ``events``.

    An event that names a ``world`` other than ``world`` is skipped (a log of a run in
    another home). Raises ``ValueError`` when such an event's points are not lists of
    finite numbers (the caller names the file).
    """
    trajectory: list[tuple[float, float]] = []
    particles: tuple[tuple[float, float, float], ...] = ()
    laser: tuple[tuple[float, float], ...] = ()
    for event in events:
        kind = event.get("kind")
        if world is not None and event.get("world", world) != world:
            continue
        if kind == "robot.trajectory":
            trajectory.extend(_pairs(event["points"]))
        elif kind == "robot.particles":
            particles = tuple((x, y, theta) for x, y, theta in _points(event["points"], 3))
        elif kind == "robot.laser":
            laser = _pairs(event["points"])
    return EmbodiedRun(tuple(trajectory), particles, laser)


def _pairs(points: Any) -> tuple[tuple[float, float], ...]:
    return tuple((x, y) for x, y in _points(points, 2))


def _points(points: Any, size: int) -> list[tuple[float, ...]]:
    if not isinstance(points, list):
        raise ValueError(f"points must be a list, not {type(points).__name__}")
    result = []
    for point in points:
        if not isinstance(point, (list, tuple)) or len(point) != size:
            raise ValueError(f"each point has {size} numbers")
        values = tuple(float(value) for value in point)
        if not all(math.isfinite(value) for value in values):
            raise ValueError("points must be finite numbers")
        result.append(values)
    return result


def draw_trajectory(draw: ImageDraw.ImageDraw, px: ToPixel,
                    points: Sequence[tuple[float, float]]) -> None:
    """The driven path as a line, with a dot where it ends."""
    if not points:
        return
    colour = EMBODIED_COLOURS["trajectory"]
    if len(points) > 1:
        draw.line([px(x, y) for x, y in points], fill=colour, width=2, joint="curve")
    ex, ey = px(*points[-1])
    draw.ellipse((ex - 3, ey - 3, ex + 3, ey + 3), fill=colour)


def draw_particles(draw: ImageDraw.ImageDraw, px: ToPixel,
                   particles: Sequence[tuple[float, float, float]]) -> None:
    """Each particle as a dot with a short tick along its heading."""
    colour = EMBODIED_COLOURS["particles"]
    for x, y, theta in particles:
        cx, cy = px(x, y)
        tip = (cx + _PARTICLE_TICK * math.cos(theta), cy - _PARTICLE_TICK * math.sin(theta))
        draw.line([(cx, cy), tip], fill=colour, width=1)
        draw.ellipse((cx - 1.5, cy - 1.5, cx + 1.5, cy + 1.5), fill=colour)


def draw_laser(draw: ImageDraw.ImageDraw, px: ToPixel,
               points: Sequence[tuple[float, float]]) -> None:
    """The last scan's returns as small dots."""
    colour = EMBODIED_COLOURS["laser"]
    for x, y in points:
        cx, cy = px(x, y)
        draw.rectangle((cx - 1, cy - 1, cx + 1, cy + 1), fill=colour)


def draw_embodied_run(draw: ImageDraw.ImageDraw, px: ToPixel, run: EmbodiedRun) -> None:
    """Trajectory, then particles, then laser returns on top."""
    draw_trajectory(draw, px, run.trajectory)
    draw_particles(draw, px, run.particles)
    draw_laser(draw, px, run.laser)
