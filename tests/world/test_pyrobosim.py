"""A homebot world from a pyrobosim world YAML (``homebot world from-pyrobosim``)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from homebot.app import RunSettings, build_run
from homebot.cli import main
from homebot.errors import WorldError
from homebot.language import Vocabulary, parse_command
from homebot.sim import PERSON_PREFIX
from homebot.world import DoorState, World
from homebot.world.pyrobosim import import_pyrobosim

FLAT = Path(__file__).resolve().parent / "data" / "pyrobosim_flat.yaml"


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
])
def test_what_cannot_be_imported_is_a_world_error(tmp_path: Path, text: str,
                                                  message: str) -> None:
    path = tmp_path / "world.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(WorldError, match=message):
        import_pyrobosim(path)
