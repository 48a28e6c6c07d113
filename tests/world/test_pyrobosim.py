"""A homebot world from a pyrobosim world YAML (``homebot world from-pyrobosim``)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from homebot.app import RunSettings, build_run
from homebot.cli import main
from homebot.errors import WorldError
from homebot.language import Vocabulary, parse_command
from homebot.sim import PERSON_PREFIX
from homebot.world import DoorState, World
from homebot.world.pyrobosim import import_pyrobosim

DATA = Path(__file__).resolve().parent / "data"
FLAT = DATA / "pyrobosim_flat.yaml"
#: every construct of pyrobosim's world schema, with its location metadata beside it
STUDIO = DATA / "pyrobosim_studio.yaml"


def test_rooms_hallways_locations_and_objects_are_imported() -> None:
    world = World.from_dict(import_pyrobosim(FLAT).data)
    assert world.name == "pyrobosim flat"
    assert {"living room", "kitchen", "bedroom"} <= set(world.rooms)
    # The box footprint (dims 3 x 3.5 at offset 7.5, 1.75) is the kitchen's polygon.
    assert world.room_polygons["kitchen"].bounds == pytest.approx((6.0, 0.0, 9.0, 3.5))
    # Each hallway is a room with a door at each end; a closed hallway closes both.
    assert "living room kitchen hallway" in world.rooms
    doors = {name: door for name, door in world.doors.items()}
    assert len(doors) == 4
    assert {door.state for door in doors.values() if "bedroom" in door.name} == {
        DoorState.CLOSED}
    # Locations are furniture in their parent room; yaw 90 degrees turns the table.
    table = world.placements["kitchen table"]
    assert table.room == "kitchen" and table.model.size == (1.2, 0.9)
    assert world.placements["my desk"].room == "bedroom"  # relative_to the bedroom
    assert world.objects["soda"].category == "coke"
    assert world.objects["soda"].placement == "kitchen table"
    assert world.objects["apple"].placement == "kitchen table"  # unnamed: its category
    assert world.objects["water"].placement == "counter0"  # the most probable choice
    assert world.objects["water 2"].placement == "counter0"
    assert world.objects["banana"].placement == "sofa table"  # the first of a list
    # The operator stands beside the robot, which starts at its pose (yaw in degrees).
    assert world.operator is not None and world.operator.name == "Alex"
    pose = world.robot.pose
    assert (pose.x, pose.y, pose.theta) == pytest.approx((1.0, 1.0, 1.571), abs=1e-3)


def test_a_fetch_task_succeeds_in_the_imported_world(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    output = tmp_path / "flat.yaml"
    assert main(["world", "from-pyrobosim", str(FLAT), "-o", str(output)]) == 0
    assert "position: [" in output.read_text(encoding="utf-8")
    capsys.readouterr()
    assert main(["do", "bring me the soda from the kitchen table", "--world", str(output),
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["success"]
    world = World.load(output)
    run = build_run(RunSettings(world=world))
    command = parse_command("bring me the gala from my desk", Vocabulary.from_world(world))
    report = run.run(command.to_task())
    assert report.success  # through the closed hallway: both doors opened on the way
    assert report.steps[0].recoveries == ("door_closed", "door_closed")
    assert run.simulation.object_location["gala"] == PERSON_PREFIX + "Alex"


def test_every_construct_of_the_schema_is_imported() -> None:
    world = World.from_dict(import_pyrobosim(STUDIO).data)
    rooms = world.room_polygons
    # A box turned 90° by its pose; a box placed relative to that room (its yaw added,
    # the offset turned with it); a circle.
    assert rooms["study"].bounds == pytest.approx((7.0, 0.0, 9.0, 3.0))
    assert rooms["pantry"].bounds == pytest.approx((6.5, 6.0, 8.5, 8.0))
    assert rooms["porch"].area == pytest.approx(math.pi * 1.5**2, rel=0.02)
    # An angle hallway leaves the hall's centroid (2.18, 2.03) shifted 0.37 m sideways.
    corridor = rooms["hall study hallway"]
    assert corridor.bounds == pytest.approx((5.0, 2.396 - 0.45, 7.0, 2.396 + 0.45), abs=2e-3)
    states = {door.name: door.state for door in world.doors.values()}
    assert states["hall study door"] is DoorState.OPEN
    assert states["study pantry door"] is DoorState.CLOSED
    assert states["porch pantry door"] is DoorState.LOCKED
    assert {"hall porch hallway", "pantry porch hallway", "study pantry hallway"} <= set(rooms)
    # Furniture: metadata footprints, turned by yaw, named as pyrobosim names them.
    placements = world.placements
    assert placements["dining table"].model.size == pytest.approx((0.8, 1.2))
    assert placements["dining table"].model.height == pytest.approx(0.74)
    assert placements["counter0"].model.center == pytest.approx((1.0, 0.5))
    assert placements["bin0"].model.center == pytest.approx((3.5, 2.4))  # relative_to
    assert placements["bin0"].model.size == pytest.approx((0.5, 0.5))  # circle, r 0.25
    assert placements["cupboard"].model.center == pytest.approx((7.5, 7.1))
    assert placements["bookshelf"].model.size == pytest.approx((1.066, 0.846), abs=2e-3)
    assert placements["desk"].model.size == (0.6, 0.6)  # not in the metadata
    assert placements["bench"].room == "porch"  # no pose: a free place in its room
    objects = world.objects
    assert objects["soda"].placement == "dining table"
    assert objects["apple"].position == pytest.approx((3.6, 1.4))
    assert objects["water"].placement == "counter0"  # its spawn counter0_left
    assert objects["banana"].placement == "bin0"  # a category
    assert objects["cup"].placement == "bookshelf"  # the first of a list
    assert objects["book"].placement == "bookshelf"  # the most probable choice
    assert objects["milk"].placement == "cupboard"
    assert objects["milk"].position == pytest.approx((7.5, 7.3))  # a quaternion pose
    assert objects["sponge"].placement == "counter0"  # "hall counter": room and category
    # The first robot starts at its room's first nav pose, with its own radius.
    pose = world.robot.pose
    assert (pose.x, pose.y, pose.theta) == pytest.approx((1.0, 4.0, -math.pi / 2), abs=1e-3)
    assert world.robot.radius == pytest.approx(0.15)


def _line_of(text: str, marker: str, after: str | None = None) -> int:
    """The line of ``marker`` (the first after the line ``after``, if given)."""
    lines = text.splitlines()
    start = lines.index(after) if after is not None else 0
    return lines.index(marker, start) + 1


def test_each_approximation_is_warned_with_its_line() -> None:
    warnings = import_pyrobosim(STUDIO).warnings
    text = STUDIO.read_text(encoding="utf-8")
    expected = [
        (_line_of(text, "  - name: bookshelf"), "locations[3] (bookshelf): its footprint is "
                                                "the 1.066 × 0.846 m box around it, turned 30°"),
        (_line_of(text, "    category: writing_desk"),
         "'writing_desk' is in no location metadata read; it is taken as a 0.6 m square"),
        (_line_of(text, "    category: lamp"), "its mesh footprint is not read"),
        (_line_of(text, "  - name: bench"), "has no pose (pyrobosim picks one at random)"),
        (_line_of(text, "    is_open: false", after="  - name: cupboard"),
         "closed: homebot's furniture has no doors"),
        (_line_of(text, "    parent: [bookshelf, desk]"), "homebot puts it on 'bookshelf'"),
        (_line_of(text, "  - name: second"), "only the first of 2 robots is imported"),
        (_line_of(text, "    colour: red"), "rooms[*].colour: not imported: not in "
                                           "pyrobosim's world schema (a typo?)"),
        (_line_of(text, "    path_planner:"), "robots[*].path_planner: not imported"),
    ]
    for line, message in expected:
        assert any(warning.startswith(f"{STUDIO}: line {line}: ") and message in warning
                   for warning in warnings), (line, message, warnings)


@pytest.mark.parametrize(("world_file", "command", "obj", "destination"), [
    (STUDIO, "put the soda on the desk", "soda", "desk"),  # through an angle hallway
    (STUDIO, "put the water on the bench", "water", "bench"),  # the long way round
    (STUDIO, "put the banana on the bookshelf", "banana", "bookshelf"),
    (FLAT, "put the banana on the counter0", "banana", "counter0"),
])
def test_pick_and_place_in_an_imported_world(tmp_path: Path, world_file: Path, command: str,
                                             obj: str, destination: str) -> None:
    output = tmp_path / "world.yaml"
    assert main(["world", "from-pyrobosim", str(world_file), "-o", str(output)]) == 0
    world = World.load(output)
    run = build_run(RunSettings(world=world))
    report = run.run(parse_command(command, Vocabulary.from_world(world)).to_task())
    assert report.success
    assert run.simulation.object_location[obj] == destination  # the simulator's truth


def test_warnings_go_to_stderr_and_the_world_passes_check(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    output = tmp_path / "studio.yaml"
    assert main(["world", "from-pyrobosim", str(STUDIO), "-o", str(output)]) == 0
    captured = capsys.readouterr()
    assert "8 placements, 8 objects" in captured.out
    assert captured.err.count("warning: ") == len(import_pyrobosim(STUDIO).warnings)
    assert main(["world", "check", str(output)]) == 0


def test_a_location_named_as_a_room_is_renamed_and_one_outside_its_room_left_out(
        tmp_path: Path) -> None:
    path = tmp_path / "world.yaml"
    path.write_text(
        "rooms:\n  - {name: trash, footprint: {type: box, dims: [4, 4]}}\n"
        "locations:\n  - {name: trash, category: table, parent: trash, pose: [1, 1]}\n"
        "  - {name: shelf, category: desk, parent: trash, pose: [5, 5]}\n"
        "objects:\n  - {category: apple, parent: trash}\n  - {category: pear, parent: shelf}\n"
        "robots:\n  - {radius: 0.2, pose: [-1, -1]}\n", encoding="utf-8")
    imported = import_pyrobosim(path)
    world = World.from_dict(imported.data)
    assert world.objects["apple"].placement == "trash table"
    assert set(world.placements) == {"trash table"} and set(world.objects) == {"apple"}
    assert any("line 4: locations[0] (trash).name: 'trash' is also a room; the furniture "
               "is called 'trash table'" in warning for warning in imported.warnings)
    assert any("line 5: locations[1] (shelf): does not lie inside room 'trash'" in warning
               for warning in imported.warnings)
    assert any("line 8: objects[1]: its parent 'shelf' was left out, so it is too" in warning
               for warning in imported.warnings)
    assert any("no location metadata is named" in warning for warning in imported.warnings)


def test_rooms_meeting_inside_a_hallway_get_one_door_between_them(tmp_path: Path) -> None:
    path = tmp_path / "world.yaml"
    path.write_text(
        "rooms:\n  - {name: a, footprint: {type: box, dims: [2, 2]}}\n"
        "  - {name: b, footprint: {type: box, dims: [2, 2]}, pose: [2, 0]}\n"
        "hallways:\n  - {room_start: a, room_end: b, width: 0.8}\n", encoding="utf-8")
    world = World.from_dict(import_pyrobosim(path).data)
    assert set(world.rooms) == {"a", "b"}
    (door,) = world.doors.values()
    assert set(door.rooms) == {"a", "b"}
    assert door.position == pytest.approx((1.0, 0.0)) and door.width == pytest.approx(0.8)


_ROOMS = ("rooms:\n  - name: a\n    footprint: {type: box, dims: [2, 2]}\n"
          "  - name: b\n    footprint: {type: box, dims: [2, 2]}\n"
          "    pose: {position: {x: 4.0, y: 0.0}}\n")


@pytest.mark.parametrize(("text", "message"), [
    ("rooms: []\n", "not a pyrobosim world"),
    ("- a list\n", "not a pyrobosim world"),
    ("rooms:\n  - name: a\n    footprint: {type: mesh, model_path: m}\n", "mesh footprint"),
    ("rooms:\n  - name: a\n    footprint: {type: box, dims: [2, 2]}\nhallways:\n"
     "  - {room_start: a, room_end: b}\n", "unknown room 'b'"),
    ("rooms:\n  - name: a\n    footprint: {type: box, dims: [2, 2]}\nlocations:\n"
     "  - {name: t, category: table, parent: garage}\n", "parent room 'garage'"),
    ("rooms:\n  - name: a\n    footprint: {type: box, dims: [2, 2]}\nobjects:\n"
     "  - {category: apple, parent: shelf}\n", "parent 'shelf'"),
    ("rooms: [\n", r"line \d+, column \d+: YAML syntax error"),
    (_ROOMS + "hallways:\n  - {room_start: a, room_end: b, width: 0.8, conn_method: points,"
              " conn_points: [[0, 0], [2.5, 0]]}\n",
     r"line 8: hallways\[0\] \(a to b\).room_end: the hallway's corridor ends 0.50 m short "
     "of room 'b'"),
    (_ROOMS.replace("y: 0.0", "y: 1.3") + "hallways:\n  - {room_start: a, room_end: b, "
     "width: 0.8, conn_method: points, conn_points: [[0, 0], [3.2, 0]]}\n",
     "meets room 'b' over only 0.30 m, too little for a door"),
    (_ROOMS + "hallways:\n  - {room_start: a, room_end: b, width: 0.6, conn_method: angle, "
              "conn_angle: 1.57}\n",  # leaves a northwards: b, east, is never reached
     r"hallways\[0\] \(a to b\).room_end: the hallway's corridor ends 2.\d\d m short of room "
     "'b'"),
    (_ROOMS + "hallways:\n  - {room_start: b, room_end: b, width: 1}\n",
     "a hallway joins two different rooms; it starts and ends in 'b'"),
    (_ROOMS + "locations:\n  - {name: 9t, category: table, parent: a}\n",
     r"line 8: locations\[0\].name: '9t' is no name homebot can say"),
    (_ROOMS + "hallways:\n  - {room_start: a, room_end: b, conn_method: auto}\n",
     r"hallways\[0\] \(a to b\).width: a hallway needs a width above 0"),
    (_ROOMS + "hallways:\n  - {room_start: a, room_end: b, width: 1, conn_method: curve}\n",
     "conn_method 'curve' is not one of auto, angle, points"),
    (_ROOMS + "locations:\n  - {name: t, category: table, parent: a, pose: {position: {x: 0},"
              " relative_to: sofa}}\n", "'sofa' is no room, location or object given above"),
    (_ROOMS + "locations:\n  - {name: t, category: table, parent: a, pose: [1, 2, 3, 4, 5]}\n",
     r"locations\[0\] \(t\).pose: a pose list is \[x, y\]"),
    ("metadata: {locations: $PWD/broken.yaml}\n" + _ROOMS, r"broken.yaml: line 2: table."
                                                           "footprint: a box footprint needs"),
])
def test_what_cannot_be_imported_is_a_world_error(tmp_path: Path, text: str,
                                                  message: str) -> None:
    path = tmp_path / "world.yaml"
    path.write_text(text, encoding="utf-8")
    (tmp_path / "broken.yaml").write_text("table:\n  footprint: {type: box, dims: [1]}\n",
                                          encoding="utf-8")
    with pytest.raises(WorldError, match=message):
        import_pyrobosim(path)
