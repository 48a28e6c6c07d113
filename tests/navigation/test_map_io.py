"""ROS map_server maps: write a world's grid as YAML + PGM, read it back, refuse bad maps."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml
from PIL import Image

from homebot.errors import MapError
from homebot.navigation.map_io import (
    FREE_PIXEL,
    OCCUPIED_PIXEL,
    UNKNOWN_PIXEL,
    RosMap,
    read_map,
    write_map,
)
from homebot.world import OccupancyGrid, World

L_SHAPED = """\
name: l shape
rooms:
  - {name: hall, polygon: [[0, 0], [4, 0], [4, 2], [0, 2]]}
  - {name: study, polygon: [[0, 2], [2, 2], [2, 4], [0, 4]]}
doors:
  - {name: study door, rooms: [hall, study], position: [1, 2]}
placements:
  - {name: table, category: table, room: hall, center: [3, 1], size: [0.5, 0.5]}
robot:
  pose: [1, 1, 0]
"""


@pytest.fixture(scope="module")
def l_shape() -> World:
    return World.from_yaml_text(L_SHAPED, "l.yaml")


def _write(tmp_path: Path, ros_map: RosMap) -> Path:
    yaml_path, _ = write_map(ros_map, tmp_path / "map.yaml")
    return yaml_path


def test_round_trip_gives_the_same_grid(tmp_path: Path, l_shape: World) -> None:
    written = RosMap.from_world(l_shape)
    read = read_map(_write(tmp_path, written))
    assert np.array_equal(read.occupied, written.occupied)
    assert np.array_equal(read.unknown, written.unknown)
    assert read.origin == written.origin and read.resolution == written.resolution
    grid = OccupancyGrid.from_world(l_shape)
    assert np.array_equal(read.obstacles, grid.occupied)
    assert read.shape == grid.shape


def test_the_file_pair_is_what_map_server_reads(tmp_path: Path, l_shape: World) -> None:
    ros_map = RosMap.from_world(l_shape)
    yaml_path, pgm_path = write_map(ros_map, tmp_path / "home.yaml")
    meta = yaml.safe_load(yaml_path.read_text(encoding="utf-8"))
    assert meta == {"image": "home.pgm", "mode": "trinary", "resolution": 0.05,
                    "origin": [-0.2, -0.2, 0.0], "negate": 0, "occupied_thresh": 0.65,
                    "free_thresh": 0.196}
    raw = pgm_path.read_bytes()
    rows, columns = ros_map.shape
    assert raw.startswith(f"P5\n{columns} {rows}\n255\n".encode())
    pixels = np.frombuffer(raw[-rows * columns:], dtype=np.uint8).reshape(rows, columns)
    assert set(np.unique(pixels)) == {OCCUPIED_PIXEL, UNKNOWN_PIXEL, FREE_PIXEL}
    grid = OccupancyGrid.from_world(l_shape)
    # Row 0 of the image is the top of the map: the study's corner at (1, 3.5) is free,
    # the empty quarter at (3, 3.5) beside it is unknown, the table at (3, 1) occupied.
    for x, y, value in [(1.0, 3.5, FREE_PIXEL), (3.0, 3.5, UNKNOWN_PIXEL),
                        (3.0, 1.0, OCCUPIED_PIXEL), (2.0, 3.0, OCCUPIED_PIXEL)]:
        row, column = grid.cell_of(x, y)
        assert pixels[rows - 1 - row, column] == value, (x, y)


def test_pixel_values_follow_map_server_thresholds(tmp_path: Path) -> None:
    # p = (255 - v) / 255: occupied when p > 0.65 (v < 89.25), free when p < 0.196.
    values = np.array([[0, 89, 90, 204, 205, 206, 254, 255]], dtype=np.uint8)
    Image.fromarray(values, mode="L").save(tmp_path / "m.pgm")
    (tmp_path / "m.yaml").write_text(
        "image: m.pgm\nresolution: 0.1\norigin: [1.0, 2.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n", encoding="utf-8")
    read = read_map(tmp_path / "m.yaml")
    assert read.occupied[0].tolist() == [True, True] + [False] * 6
    assert read.unknown[0].tolist() == [False, False, True, True, True, False, False, False]
    assert read.extent() == pytest.approx((1.0, 2.0, 1.8, 2.1))
    negated = (tmp_path / "m.yaml").read_text(encoding="utf-8").replace("negate: 0",
                                                                         "negate: 1")
    (tmp_path / "n.yaml").write_text(negated, encoding="utf-8")
    read = read_map(tmp_path / "n.yaml")  # p = v / 255: occupied when v > 165.75
    assert read.occupied[0].tolist() == [False] * 3 + [True] * 5
    assert read.free[0].tolist() == [True] + [False] * 7


def test_image_rows_are_flipped_to_grid_rows(tmp_path: Path) -> None:
    image = np.full((3, 2), FREE_PIXEL, dtype=np.uint8)
    image[0, 1] = OCCUPIED_PIXEL  # top right in the picture: the largest y
    Image.fromarray(image, mode="L").save(tmp_path / "m.pgm")
    (tmp_path / "m.yaml").write_text(
        "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n", encoding="utf-8")
    read = read_map(tmp_path / "m.yaml")
    assert np.argwhere(read.occupied).tolist() == [[2, 1]]
    grid = read.to_occupancy_grid(robot_radius=0.5)
    assert grid.occupied[grid.cell_of(1.5, 2.5)]
    assert not grid.occupied[grid.cell_of(0.5, 0.5)]


def test_raw_and_scale_modes_reduce_to_three_classes(tmp_path: Path) -> None:
    values = np.array([[0, 50, 100, 200, 250]], dtype=np.uint8)
    Image.fromarray(values, mode="L").save(tmp_path / "m.pgm")
    base = ("image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    (tmp_path / "raw.yaml").write_text(base + "mode: raw\n", encoding="utf-8")
    raw = read_map(tmp_path / "raw.yaml")  # the value is the occupancy in percent
    assert raw.free[0].tolist() == [True, False, False, False, False]
    assert raw.occupied[0].tolist() == [False, False, True, False, False]
    assert raw.unknown[0].tolist() == [False, True, False, True, True]
    (tmp_path / "scale.yaml").write_text(base + "mode: scale\n", encoding="utf-8")
    scale = read_map(tmp_path / "scale.yaml")
    assert scale.occupied[0].tolist() == [True, True, False, False, False]
    assert scale.unknown[0].tolist() == [False, False, True, True, False]  # graded: unknown


def test_a_map_too_small_for_the_world_is_refused(tmp_path: Path, l_shape: World) -> None:
    small = World.from_yaml_text(L_SHAPED.replace("[4, 0], [4, 2]", "[3, 0], [3, 2]").replace(
        "center: [3, 1]", "center: [2.5, 1]"), "small.yaml")
    read = read_map(_write(tmp_path, RosMap.from_world(small)))
    read.check_covers(small)
    with pytest.raises(MapError, match=r"map\.yaml: the map's 68×88 pixels at 0\.05 m .* "
                                       r"world 'l shape' spans x 0\.\.4"):
        read.check_covers(l_shape)


@pytest.mark.parametrize(("change", "expected"), [
    (("image: map.pgm", "image: gone.pgm"), "line 1: image: the image .*gone.pgm does not exist"),
    (("resolution: 0.05", "resolution: 0"), "line 3: resolution: must be greater than 0"),
    (("resolution: 0.05", "resolution: -1"), "resolution: must be greater than 0"),
    (("resolution: 0.05\n", ""), "'resolution' is missing"),
    (("origin: [-0.2, -0.2, 0.0]\n", ""), "'origin' is missing"),
    (("origin: [-0.2, -0.2, 0.0]", "origin: [1, 2]"), "origin: must be \\[x, y, yaw\\]"),
    (("origin: [-0.2, -0.2, 0.0]", "origin: [a, 2, 0]"), "origin: must be a finite number"),
    (("origin: [-0.2, -0.2, 0.0]", "origin: [0, 0, 0.5]"), "yaw 0.5 is not 0"),
    (("mode: trinary", "mode: ternary"), "line 2: mode: unknown mode 'ternary'; use one of "
                                         "trinary, scale, raw"),
    (("negate: 0", "negate: 2"), "negate: must be 0 or 1"),
    (("free_thresh: 0.196", "free_thresh: 0.9"), "0 <= free_thresh < occupied_thresh <= 1"),
    (("image: map.pgm", "image: [map.pgm]"), "image: must name the map's image file"),
    (("mode: trinary", "mode: [trinary"), "YAML syntax error"),
    (("negate: 0", "negate: 0\nnegate: 1"), "'negate' appears twice"),
])
def test_bad_map_yaml_is_a_map_error(tmp_path: Path, l_shape: World,
                                     change: tuple[str, str], expected: str) -> None:
    yaml_path = _write(tmp_path, RosMap.from_world(l_shape))
    text = yaml_path.read_text(encoding="utf-8")
    assert change[0] in text
    yaml_path.write_text(text.replace(*change), encoding="utf-8")
    with pytest.raises(MapError, match=expected) as error:
        read_map(yaml_path)
    assert str(error.value).startswith(str(yaml_path))


@pytest.mark.parametrize(("content", "expected"), [
    (b"P5\n10 10\n255\n" + bytes(20), "cannot be read|not an image"),
    (b"not an image at all", r"not an image Pillow can read \(no known image format\)"),
    (b"P5\n10000 10000\n255\n", "too large to read"),
    (b"P5\n100000 100000\n255\n", "too large to read"),
    (b"P5\n8000 8000\n255\n" + bytes(64), r"8000×8000 pixels, more than the 4,194,304"),
])
def test_a_broken_image_is_a_map_error(tmp_path: Path, l_shape: World, content: bytes,
                                       expected: str) -> None:
    yaml_path = _write(tmp_path, RosMap.from_world(l_shape))
    (tmp_path / "map.pgm").write_bytes(content)
    with pytest.raises(MapError, match=expected):
        read_map(yaml_path)


def test_a_16_bit_image_is_refused(tmp_path: Path, l_shape: World) -> None:
    yaml_path = _write(tmp_path, RosMap.from_world(l_shape))
    Image.fromarray(np.zeros((4, 4), dtype=np.uint16)).save(tmp_path / "map.png")
    yaml_path.write_text(yaml_path.read_text(encoding="utf-8").replace("map.pgm", "map.png"),
                         encoding="utf-8")
    with pytest.raises(MapError, match="give an 8-bit grey PGM"):
        read_map(yaml_path)


def test_writing_to_an_unwritable_place_is_a_map_error(tmp_path: Path, l_shape: World) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("x", encoding="utf-8")
    with pytest.raises(MapError, match="cannot be written"):
        write_map(RosMap.from_world(l_shape), blocker / "map.yaml")


def test_differing_cells_compare_maps_cell_by_cell(l_shape: World) -> None:
    base = RosMap.from_world(l_shape)
    assert base.differing_cells(base) == 0
    with_box = World.from_yaml_text(L_SHAPED.replace(
        "robot:", "  - {name: box, category: box, room: hall, center: [0.5, 0.5], "
                  "size: [0.2, 0.2]}\nrobot:"), "box.yaml")
    assert base.differing_cells(RosMap.from_world(with_box)) == 16  # 0.2 m square at 5 cm
    # The same grid two cells over: only where the overlap's contents differ.
    shifted = RosMap(base.occupied, base.unknown, (base.origin[0] + 0.1, base.origin[1], 0.0),
                     base.resolution)
    differing = base.differing_cells(shifted)
    rows, columns = base.shape  # shifted's cell (r, c) lies on base's cell (r, c + 2)
    expected = sum(base.free[r, c + 2] != base.free[r, c]
                   for r in range(rows) for c in range(columns - 2))
    assert differing == expected > 0
    assert base.differing_cells(RosMap(base.occupied, base.unknown,
                                       (base.origin[0] + 0.01, base.origin[1], 0.0),
                                       base.resolution)) is None
    assert base.differing_cells(RosMap(base.occupied, base.unknown, base.origin, 0.1)) is None
