"""``render_map``: the world as a picture — rooms, doors, furniture, objects, people, a path."""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache

from PIL import Image, ImageDraw, ImageFont

from homebot.viz.embodied import EmbodiedRun, draw_embodied_run
from homebot.world import DoorState, PlacementKind, World

__all__ = ["render_map"]

_PIXELS_PER_METRE = 60
_MARGIN = 30
_COLOURS = {
    "room": (245, 243, 236), "wall": (60, 60, 60), "furniture": (190, 160, 120),
    "spot": (160, 200, 160), "object": (40, 90, 200), "person": (210, 60, 60),
    "robot": (20, 150, 90), "path": (20, 150, 90), "text": (30, 30, 30),
    DoorState.OPEN: (120, 200, 120), DoorState.CLOSED: (230, 150, 40),
    DoorState.LOCKED: (200, 40, 40),
}


# Fonts that draw every Latin letter ("Patrícia", "Søren", "crème brûlée"), looked up in
# the system's font folders; Pillow's own default font draws ASCII only.
_FONTS = ("DejaVuSans.ttf", "NotoSans-Regular.ttf", "LiberationSans-Regular.ttf", "Arial.ttf")
_FONT_SIZE = 11


@cache
def _font() -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    """The first of ``_FONTS`` installed, else Pillow's default (accents may then drop)."""
    for name in _FONTS:
        try:
            return ImageFont.truetype(name, _FONT_SIZE)
        except OSError:
            continue
    return ImageFont.load_default()


def render_map(world: World, path: Sequence[tuple[float, float]] = (),
               run: EmbodiedRun | None = None) -> Image.Image:
    """Draw the world (and the robot's path, and an embodied run's trajectory, particles
    and laser, if given) as an RGB image. Pure: writes nothing."""
    min_x, min_y, max_x, max_y = world.bounds()
    width = int((max_x - min_x) * _PIXELS_PER_METRE) + 2 * _MARGIN
    height = int((max_y - min_y) * _PIXELS_PER_METRE) + 2 * _MARGIN
    image = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(image)
    draw.font = _font()

    def px(x: float, y: float) -> tuple[float, float]:
        return (_MARGIN + (x - min_x) * _PIXELS_PER_METRE,
                height - _MARGIN - (y - min_y) * _PIXELS_PER_METRE)

    for name, polygon in world.room_polygons.items():
        corners = [px(x, y) for x, y in polygon.exterior.coords]
        draw.polygon(corners, fill=_COLOURS["room"], outline=_COLOURS["wall"], width=3)
        centre = px(polygon.centroid.x, polygon.centroid.y)
        draw.text((centre[0] - 3 * len(name), centre[1] - 40), name, fill=_COLOURS["text"])
    for door in world.doors.values():
        x, y = door.position
        r = door.width / 2 * _PIXELS_PER_METRE
        cx, cy = px(x, y)
        draw.ellipse((cx - r / 3, cy - r / 3, cx + r / 3, cy + r / 3),
                     fill=_COLOURS[door.state])
    for placement in world.placements.values():
        left, bottom, right, top = placement.footprint.bounds
        colour = _COLOURS["furniture" if placement.model.kind is PlacementKind.FURNITURE
                          else "spot"]
        x0, y0 = px(left, top)
        x1, y1 = px(right, bottom)
        draw.rectangle((x0, y0, x1, y1), fill=colour, outline=_COLOURS["wall"])
        draw.text((x0, y1 + 2), placement.name, fill=_COLOURS["text"])
    counts: dict[str, int] = {}
    for obj in world.objects.values():
        index = counts.get(obj.placement, 0)
        counts[obj.placement] = index + 1
        cx, cy = world.placements[obj.placement].model.center
        ox, oy = px(cx, cy)
        ox += (index % 4) * 8 - 12
        oy += (index // 4) * 8 - 8
        draw.ellipse((ox - 3, oy - 3, ox + 3, oy + 3), fill=_COLOURS["object"])
    for person in world.people.values():
        cx, cy = px(*person.position)
        draw.ellipse((cx - 9, cy - 9, cx + 9, cy + 9), fill=_COLOURS["person"])
        draw.text((cx + 11, cy - 6), person.name, fill=_COLOURS["person"])
    if len(path) > 1:
        draw.line([px(x, y) for x, y in path], fill=_COLOURS["path"], width=3)
    if run:
        draw_embodied_run(draw, px, run)
    rx, ry = px(world.robot.pose[0], world.robot.pose[1])
    draw.rectangle((rx - 8, ry - 8, rx + 8, ry + 8), outline=_COLOURS["robot"], width=3)
    return image
