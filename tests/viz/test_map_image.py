"""``world show --png``: legend, scale bar, the robot's heading, labels in view, final positions."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from homebot.cli import main
from homebot.viz import Canvas, FinalState, map_image, render_map
from homebot.world import World

OBJECT = (40, 90, 200)
CARRIED = (120, 60, 170)
ROBOT = (20, 150, 90)


def _count(image: np.ndarray, colour: tuple[int, int, int]) -> int:
    return int(np.all(image == np.array(colour, dtype=np.uint8), axis=-1).sum())


def test_the_legend_and_the_scale_bar_are_drawn(apartment: World) -> None:
    canvas = Canvas.for_world(apartment)
    picture = np.asarray(render_map(apartment))
    legend = picture[canvas.map_height + 1:]
    assert legend.shape[0] > 40
    for colour in ((120, 200, 120), (230, 150, 40), (200, 40, 40), (210, 60, 60), OBJECT):
        assert _count(legend, colour) > 5, colour  # door states, people, objects
    # The scale bar: a dark line of two metres (120 px) in the bottom margin.
    row = picture[int(canvas.map_height - map_image._MARGIN / 2)]
    dark = np.all(row == np.array((30, 30, 30), dtype=np.uint8), axis=-1)
    assert dark.sum() >= 2 * map_image._PIXELS_PER_METRE


@pytest.mark.parametrize("heading", [0.0, math.pi / 2, math.pi, -math.pi / 2])
def test_the_robot_is_drawn_with_its_heading(apartment: World, heading: float) -> None:
    x, y = 6.0, 2.0
    picture = np.asarray(render_map(apartment, final=FinalState(robot=(x, y, heading))))
    canvas = Canvas.for_world(apartment)
    cx, cy = canvas.px(x, y)
    reach = 1.5 * max(8.0, apartment.robot.radius * map_image._PIXELS_PER_METRE)
    ahead = (int(cx + reach * math.cos(heading)), int(cy - reach * math.sin(heading)))
    behind = (int(cx - reach * math.cos(heading)), int(cy + reach * math.sin(heading)))
    assert tuple(picture[ahead[1], ahead[0]]) == ROBOT
    assert tuple(picture[behind[1], behind[0]]) != ROBOT


def test_objects_are_drawn_where_the_run_left_them(apartment: World) -> None:
    before = np.asarray(render_map(apartment))
    after = np.asarray(render_map(apartment, final=FinalState(
        objects={"cola": "person:Alex", "milk": None})))
    canvas = Canvas.for_world(apartment)
    left, bottom, right, top = apartment.placements["fridge"].footprint.bounds
    (x0, y0), (x1, y1) = canvas.px(left, top), canvas.px(right, bottom)
    fridge_before = _count(before[int(y0):int(y1), int(x0):int(x1)], OBJECT)
    fridge_after = _count(after[int(y0):int(y1), int(x0):int(x1)], OBJECT)
    assert fridge_after < fridge_before  # the cola and the drunk milk are off the fridge
    assert _count(after, CARRIED) > _count(before, CARRIED)  # the cola is with Alex


@pytest.mark.parametrize("name", ["apartment", "butler_home", "supermarket"])
def test_room_labels_are_in_their_room_in_view_and_not_on_furniture(name: str) -> None:
    world = World.load(name)
    canvas = Canvas.for_world(world)
    map_image._draw_furniture(canvas)
    furniture = list(canvas.taken[:len(world.placements)])
    before = len(canvas.taken)
    map_image._draw_room_labels(canvas)
    labels = canvas.taken[before:]
    assert len(labels) == len(world.rooms)
    for box in labels:
        assert box[0] >= 0 and box[1] >= 0
        assert box[2] <= canvas.image.width and box[3] <= canvas.map_height
        assert not any(map_image._overlap(box, piece) for piece in furniture), box


def test_world_show_draws_this_projects_last_run_or_the_events_named(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    first, second = tmp_path / "first", tmp_path / "second"
    monkeypatch.setenv("HOMEBOT_PROJECT", str(first))
    assert main(["do", "bring me the cola", "--events", str(tmp_path / "run.jsonl")]) == 0
    assert (first / ".homebot" / "last-run.jsonl").is_file()
    assert main(["world", "show", "--png", str(tmp_path / "first.png")]) == 0
    monkeypatch.setenv("HOMEBOT_PROJECT", str(second))  # another project: no run of its own
    assert main(["world", "show", "--png", str(tmp_path / "second.png")]) == 0
    assert main(["world", "show", "--png", str(tmp_path / "named.png"), "--events",
                 str(tmp_path / "run.jsonl")]) == 0
    from PIL import Image

    def pixels(name: str) -> np.ndarray:
        return np.asarray(Image.open(tmp_path / name).convert("RGB"))

    assert np.array_equal(pixels("first.png"), pixels("named.png"))
    assert not np.array_equal(pixels("first.png"), pixels("second.png"))
    assert _count(pixels("first.png"), CARRIED) > 0  # the cola handed to Alex
