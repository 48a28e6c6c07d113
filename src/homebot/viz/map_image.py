"""``render_map``: the world as a picture, drawn in layers, with a legend and a scale bar.

Each layer is one function ``_draw_<layer>(canvas, ...)`` over a ``Canvas`` (the image,
its drawing context and the world-to-pixel transform), called in order by
``render_map``: rooms, doors, furniture, path, embodied run (``homebot.viz.embodied``),
objects, robot, people, room labels, then the legend strip below the map. A new
layer is one more function and one more line in ``render_map``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from PIL import Image, ImageDraw, ImageFont

from homebot.viz.embodied import EMBODIED_COLOURS, EmbodiedRun, draw_embodied_run
from homebot.world import DoorState, PlacementKind, World

__all__ = ["Canvas", "FinalState", "final_state", "render_map"]

_PIXELS_PER_METRE = 60
_MARGIN = 36
_LEGEND_HEIGHT = 64
_COLOURS: dict[Any, tuple[int, int, int]] = {
    "room": (245, 243, 236), "wall": (60, 60, 60), "furniture": (190, 160, 120),
    "spot": (160, 200, 160), "object": (40, 90, 200), "person": (210, 60, 60),
    "robot": (20, 150, 90), "path": (20, 150, 90), "text": (30, 30, 30),
    "label": (255, 255, 255), "carried": (120, 60, 170),
    DoorState.OPEN: (120, 200, 120), DoorState.CLOSED: (230, 150, 40),
    DoorState.LOCKED: (200, 40, 40),
}
# Fonts that draw every Latin letter ("Patrícia", "Søren", "crème brûlée"), looked up in
# the system's font folders; Pillow's own default font draws ASCII only.
_FONTS = ("DejaVuSans.ttf", "NotoSans-Regular.ttf", "LiberationSans-Regular.ttf", "Arial.ttf")
_FONT_SIZE = 11


@cache
def _font(size: int = _FONT_SIZE) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    """The first of ``_FONTS`` installed, else Pillow's default (accents may then drop)."""
    for name in _FONTS:
        try:
            return ImageFont.truetype(name, size)
        except OSError:
            continue
    return ImageFont.load_default()


@dataclass(frozen=True, slots=True)
class FinalState:
    """Where a run left things (the simulator's ``sim.final`` event): for drawing only."""

    objects: Mapping[str, str | None] = field(default_factory=dict)  #: name -> where
    people: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    doors: Mapping[str, str] = field(default_factory=dict)  #: name -> open/closed/locked
    robot: tuple[float, float, float] | None = None  #: x, y, heading


def final_state(events: Iterable[Mapping[str, Any]], world: str) -> FinalState | None:
    """The last ``sim.final`` event of ``world`` in an event log, or None.

    Raises ``ValueError`` (or ``TypeError``/``KeyError``) on a malformed event; the
    caller names the file.
    """
    last: Mapping[str, Any] | None = None
    for event in events:
        if event.get("kind") == "sim.final" and event.get("world") == world:
            last = event
    if last is None:
        return None
    robot = last.get("robot")
    pose = tuple(float(value) for value in robot) if robot is not None else None
    if pose is not None and (len(pose) != 3 or not all(map(math.isfinite, pose))):
        raise ValueError("sim.final robot must be [x, y, heading]")
    people = {str(name): (float(xy[0]), float(xy[1]))
              for name, xy in dict(last.get("people", {})).items()}
    return FinalState(objects={str(k): (None if v is None else str(v))
                               for k, v in dict(last.get("objects", {})).items()},
                      people=people,
                      doors={str(k): str(v) for k, v in dict(last.get("doors", {})).items()},
                      robot=pose if pose is None else (pose[0], pose[1], pose[2]))


@dataclass
class Canvas:
    """An image of a world with its drawing context and world-to-pixel transform."""

    image: Image.Image
    draw: ImageDraw.ImageDraw
    world: World
    map_height: int  #: pixels above the legend strip
    _origin: tuple[float, float] = (0.0, 0.0)
    taken: list[tuple[float, float, float, float]] = field(default_factory=list)

    @classmethod
    def for_world(cls, world: World) -> Canvas:
        min_x, min_y, max_x, max_y = world.bounds()
        width = max(int((max_x - min_x) * _PIXELS_PER_METRE) + 2 * _MARGIN, 520)
        map_height = int((max_y - min_y) * _PIXELS_PER_METRE) + 2 * _MARGIN
        image = Image.new("RGB", (width, map_height + _LEGEND_HEIGHT), "white")
        draw = ImageDraw.Draw(image)
        draw.font = _font()
        return cls(image, draw, world, map_height, (min_x, min_y))

    def px(self, x: float, y: float) -> tuple[float, float]:
        """Pixel of a world point (x east, y north; the image's y grows downwards)."""
        return (_MARGIN + (x - self._origin[0]) * _PIXELS_PER_METRE,
                self.map_height - _MARGIN - (y - self._origin[1]) * _PIXELS_PER_METRE)

    def text_box(self, xy: tuple[float, float], text: str) -> tuple[float, float, float, float]:
        left, top, right, bottom = self.draw.textbbox(xy, text)
        return (left - 2, top - 1, right + 2, bottom + 1)


def render_map(world: World, path: Sequence[tuple[float, float]] = (),
               run: EmbodiedRun | None = None, final: FinalState | None = None) -> Image.Image:
    """Draw the world, a run's path, an embodied run's layers and where the run left
    objects, people, doors and the robot, with a legend and a scale bar. Pure: writes
    nothing."""
    canvas = Canvas.for_world(world)
    final = final or FinalState()
    _draw_rooms(canvas)
    _draw_doors(canvas, final.doors)
    _draw_furniture(canvas)
    _draw_path(canvas, path)
    if run:
        draw_embodied_run(canvas.draw, canvas.px, run)
    start = world.robot.pose
    robot = final.robot or (start.x, start.y, start.theta)
    _draw_objects(canvas, final.objects, final.people, robot)
    _draw_robot(canvas, robot)
    _draw_people(canvas, final.people)
    _draw_room_labels(canvas)
    _draw_legend(canvas, bool(path), run)
    _draw_scale_bar(canvas)
    return canvas.image


# ---------------------------------------------------------------- layers


def _draw_rooms(canvas: Canvas) -> None:
    for polygon in canvas.world.room_polygons.values():
        corners = [canvas.px(x, y) for x, y in polygon.exterior.coords]
        canvas.draw.polygon(corners, fill=_COLOURS["room"], outline=_COLOURS["wall"], width=3)


def _door_state(state: str | DoorState) -> DoorState:
    try:
        return DoorState(state)
    except ValueError:
        return DoorState.CLOSED


def _draw_doors(canvas: Canvas, states: Mapping[str, str]) -> None:
    for door in canvas.world.doors.values():
        state = _door_state(states.get(door.name, door.state))
        cx, cy = canvas.px(*door.position)
        r = max(4.0, door.width / 6 * _PIXELS_PER_METRE)
        canvas.draw.ellipse((cx - r, cy - r, cx + r, cy + r), fill=_COLOURS[state],
                            outline=_COLOURS["wall"])


def _draw_furniture(canvas: Canvas) -> None:
    """Furniture and spots, each named just below (or above, near the bottom) itself."""
    for placement in canvas.world.placements.values():
        left, bottom, right, top = placement.footprint.bounds
        colour = _COLOURS["furniture" if placement.model.kind is PlacementKind.FURNITURE
                          else "spot"]
        x0, y0 = canvas.px(left, top)
        x1, y1 = canvas.px(right, bottom)
        canvas.draw.rectangle((x0, y0, x1, y1), fill=colour, outline=_COLOURS["wall"])
        canvas.taken.append((x0, y0, x1, y1))
    for placement in canvas.world.placements.values():
        left, bottom, right, top = placement.footprint.bounds
        x0, y0 = canvas.px(left, top)
        x1, y1 = canvas.px(right, bottom)
        room = canvas.world.room_polygons[placement.room].buffer(-0.04)
        width = canvas.draw.textlength(placement.name)
        height = canvas.text_box((0, 0), placement.name)[3]
        candidates = [(x, y) for y in (y1 + 2, y0 - height - 2)
                      for x in (x0, x1 - width, (x0 + x1 - width) / 2)] + [
            (x0 - width - 4, (y0 + y1 - height) / 2), (x1 + 4, (y0 + y1 - height) / 2)]
        inside = [xy for xy in candidates
                  if room.contains(_box_polygon(canvas, canvas.text_box(xy, placement.name)))]
        free = [xy for xy in inside if not any(
            _overlap(canvas.text_box(xy, placement.name), taken) for taken in canvas.taken)]
        xy = (free or inside or candidates)[0]
        _label(canvas, xy, placement.name, _COLOURS["text"], background=False)
        canvas.taken.append(canvas.text_box(xy, placement.name))


def _draw_path(canvas: Canvas, path: Sequence[tuple[float, float]]) -> None:
    if len(path) > 1:
        canvas.draw.line([canvas.px(x, y) for x, y in path], fill=_COLOURS["path"], width=3)


def _draw_objects(canvas: Canvas, where: Mapping[str, str | None],
                  people: Mapping[str, tuple[float, float]], robot: Sequence[float]) -> None:
    """Each object as a dot on the placement the run left it on (else the world file's);
    objects handed to a person or held are drawn below them, gone ones not at all."""
    world = canvas.world
    on: dict[str, list[str]] = {}
    for name, obj in world.objects.items():
        place = where.get(name, obj.placement) if where else obj.placement
        if place is not None:
            on.setdefault(place, []).append(name)
    for place, names in on.items():
        if place in world.placements:
            cx, cy = canvas.px(*world.placements[place].model.center)
            colour = _COLOURS["object"]
        elif place.startswith("person:") and place[7:] in world.people:
            person = people.get(place[7:], world.people[place[7:]].position)
            cx, cy = canvas.px(person[0], person[1])
            cx, cy, colour = cx + 24, cy + 20, _COLOURS["carried"]
        elif place.startswith("hand:"):
            cx, cy = canvas.px(robot[0], robot[1])
            cx, cy, colour = cx + 26, cy + 20, _COLOURS["carried"]
        else:
            continue
        for index, _ in enumerate(sorted(names)):
            ox = cx + (index % 4) * 8 - 12
            oy = cy + (index // 4) * 8 - 8
            canvas.draw.ellipse((ox - 3, oy - 3, ox + 3, oy + 3), fill=colour)


def _draw_people(canvas: Canvas, positions: Mapping[str, tuple[float, float]]) -> None:
    for person in canvas.world.people.values():
        cx, cy = canvas.px(*positions.get(person.name, person.position))
        canvas.draw.ellipse((cx - 9, cy - 9, cx + 9, cy + 9), fill=_COLOURS["person"])
        width = canvas.draw.textlength(person.name)
        spots = [(cx + 11, cy - 7), (cx - 11 - width, cy - 7), (cx - width / 2, cy - 24),
                 (cx - width / 2, cy + 10)]
        spot = next((xy for xy in spots if not any(
            _overlap(canvas.text_box(xy, person.name), taken) for taken in canvas.taken)),
            spots[0])
        canvas.taken.append((cx - 9, cy - 9, cx + 9, cy + 9))
        canvas.taken.append(_label(canvas, spot, person.name, _COLOURS["person"],
                                   background=True))


def _draw_robot(canvas: Canvas, pose: Sequence[float]) -> None:
    """The robot as a circle with a line along its heading."""
    x, y, heading = pose[0], pose[1], pose[2]
    cx, cy = canvas.px(x, y)
    radius = max(8.0, canvas.world.robot.radius * _PIXELS_PER_METRE)
    canvas.draw.ellipse((cx - radius, cy - radius, cx + radius, cy + radius),
                        outline=_COLOURS["robot"], width=3)
    tip = (cx + 1.8 * radius * math.cos(heading), cy - 1.8 * radius * math.sin(heading))
    canvas.draw.line([(cx, cy), tip], fill=_COLOURS["robot"], width=3)
    canvas.draw.ellipse((tip[0] - 3, tip[1] - 3, tip[0] + 3, tip[1] + 3), fill=_COLOURS["robot"])
    reach = 1.8 * radius + 3
    canvas.taken.append((cx - reach, cy - reach, cx + reach, cy + reach))


def _draw_room_labels(canvas: Canvas) -> None:
    """Each room's name on a white box: inside its room where it fits, off furniture and
    other labels, and always inside the image (a narrow hallway's name may stick out)."""
    font = _font(13)
    for name, polygon in canvas.world.room_polygons.items():
        left, bottom, right, top = polygon.bounds
        centre = polygon.centroid
        inner = polygon.buffer(-0.1)
        best: tuple[float, tuple[float, float]] | None = None
        steps = 10
        for i in range(steps + 1):
            for j in range(steps + 1):
                x = left + (right - left) * i / steps
                y = bottom + (top - bottom) * j / steps
                px, py = canvas.px(x, y)
                box = canvas.draw.textbbox((px, py), name, font=font, anchor="mm")
                if box[0] < 2 or box[1] < 2 or box[2] > canvas.image.width - 2 or (
                        box[3] > canvas.map_height - 2):
                    continue
                outside = 0.0 if inner.contains(_box_polygon(canvas, box)) else 1.0
                overlap = sum(_overlap(box, taken) for taken in canvas.taken)
                score = outside * 1e6 + overlap * 100 + math.dist((x, y), (centre.x, centre.y))
                if best is None or score < best[0]:
                    best = (score, (px, py))
        if best is None:
            best = (0.0, canvas.px(centre.x, centre.y))
        box = canvas.draw.textbbox(best[1], name, font=font, anchor="mm")
        canvas.draw.rectangle((box[0] - 3, box[1] - 2, box[2] + 3, box[3] + 2),
                              fill=_COLOURS["label"], outline=_COLOURS["wall"])
        canvas.draw.text(best[1], name, fill=_COLOURS["text"], font=font, anchor="mm")
        canvas.taken.append(box)


def _draw_legend(canvas: Canvas, path: bool, run: EmbodiedRun | None) -> None:
    """A strip below the map: door states, people, objects, the robot (and run layers)."""
    top = canvas.map_height + 4
    draw = canvas.draw
    draw.line([(0, canvas.map_height), (canvas.image.width, canvas.map_height)],
              fill=_COLOURS["wall"])
    entries: list[tuple[str, Callable[[float, float], None]]] = []

    def dot(colour: tuple[int, int, int], radius: float) -> Callable[[float, float], None]:
        return lambda x, y: draw.ellipse((x - radius, y - radius, x + radius, y + radius),
                                         fill=colour, outline=_COLOURS["wall"])

    for state in DoorState:
        entries.append((f"door {state.value}", dot(_COLOURS[state], 5)))
    entries.append(("person", dot(_COLOURS["person"], 6)))
    entries.append(("object", dot(_COLOURS["object"], 3)))
    entries.append(("object handed over or held", dot(_COLOURS["carried"], 3)))

    def robot(x: float, y: float) -> None:
        draw.ellipse((x - 6, y - 6, x + 6, y + 6), outline=_COLOURS["robot"], width=2)
        draw.line([(x, y), (x + 11, y)], fill=_COLOURS["robot"], width=2)

    entries.append(("robot, heading", robot))
    if path:
        entries.append(("path", lambda x, y: draw.line([(x - 7, y), (x + 7, y)],
                                                       fill=_COLOURS["path"], width=3)))
    if run:
        for layer, colour in EMBODIED_COLOURS.items():
            entries.append((layer, dot(colour, 3)))
    x, y = 14.0, top + 12.0
    for text, symbol in entries:
        width = draw.textlength(text) + 34
        if x + width > canvas.image.width - 4:
            x, y = 14.0, y + 20
        symbol(x, y)
        draw.text((x + 14, y - 7), text, fill=_COLOURS["text"])
        x += width


def _draw_scale_bar(canvas: Canvas) -> None:
    """A bar of a round number of metres in the map's bottom-left margin."""
    metres = 1 if canvas.image.width < 8 * _PIXELS_PER_METRE else 2
    x0, y = _MARGIN, canvas.map_height - _MARGIN / 2
    x1 = x0 + metres * _PIXELS_PER_METRE
    draw = canvas.draw
    draw.line([(x0, y), (x1, y)], fill=_COLOURS["text"], width=3)
    for x in (x0, x1):
        draw.line([(x, y - 5), (x, y + 5)], fill=_COLOURS["text"], width=2)
    draw.text((x1 + 6, y - 7), f"{metres} m", fill=_COLOURS["text"])


# ---------------------------------------------------------------- helpers


def _label(canvas: Canvas, xy: tuple[float, float], text: str,
           colour: tuple[int, int, int], *, background: bool) -> tuple[float, float, float, float]:
    """Text kept inside the image (moved left or up when it would be cut); its box."""
    box = canvas.text_box(xy, text)
    dx = min(0.0, canvas.image.width - 2 - box[2]) + max(0.0, 2 - box[0])
    dy = min(0.0, canvas.map_height - 2 - box[3]) + max(0.0, 2 - box[1])
    x, y = xy[0] + dx, xy[1] + dy
    moved = canvas.text_box((x, y), text)
    if background:
        canvas.draw.rectangle(moved, fill=_COLOURS["label"])
    canvas.draw.text((x, y), text, fill=colour)
    return moved


def _overlap(a: Sequence[float], b: Sequence[float]) -> float:
    width = min(a[2], b[2]) - max(a[0], b[0])
    height = min(a[3], b[3]) - max(a[1], b[1])
    return max(0.0, width) * max(0.0, height)


def _box_polygon(canvas: Canvas, box: Sequence[float]) -> Any:
    from shapely.geometry import box as shapely_box

    (x0, y0), (x1, y1) = _world(canvas, box[0], box[3]), _world(canvas, box[2], box[1])
    return shapely_box(x0, y0, x1, y1)


def _world(canvas: Canvas, px: float, py: float) -> tuple[float, float]:
    return (canvas._origin[0] + (px - _MARGIN) / _PIXELS_PER_METRE,
            canvas._origin[1] + (canvas.map_height - _MARGIN - py) / _PIXELS_PER_METRE)
