"""Physical HRI in MuJoCo, judged by the physics: handover, receiving, tool use, bad scenes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

from homebot.cli import main
from homebot.errors import SceneError
from homebot.sim.hri import InteractionScene
from homebot.trials.interaction import (
    DoorVariant,
    carry_table_episode,
    door_episode,
    handover_episode,
    receive_episode,
)


def test_handover_releases_on_a_pull_and_holds_through_bumps() -> None:
    pulled = handover_episode(5, 0, pull=True)
    assert pulled.pull_above is not None and pulled.correct
    assert pulled.left_hand_at is not None and pulled.left_hand_at >= pulled.pull_above
    unpulled = handover_episode(5, 1, pull=False)
    assert unpulled.pull_above is None and unpulled.left_hand_at is None
    assert unpulled.decided_at is None and unpulled.correct


def test_receive_takes_the_bottle_from_the_person() -> None:
    result = receive_episode(3)
    assert result.closed_at is not None and result.let_go_at is not None
    assert result.held and result.success


def test_the_watering_scenario_waters_the_plant(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["scenario", "water_plant", "--seed", "2", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["success"] and summary["watered_l"] >= 0.3 and summary["spilled_l"] <= 0.03


def test_a_bad_scene_is_an_error_that_names_the_file(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match="no interaction scene 'nowhere'"):
        InteractionScene("nowhere")
    broken = tmp_path / "broken.xml"
    broken.write_text("<mujoco><worldbody><body><geom type='sphere'/></body></mujoco>")
    with pytest.raises(SceneError, match=r"broken\.xml: not a usable MJCF scene"):
        InteractionScene(broken)


def test_the_bottle_rides_along_when_the_base_drives() -> None:
    # The base moves with a velocity, not by jumps: friction carries what the hand holds.
    import numpy as np

    from homebot.manipulation.compliance import Compliance
    from homebot.manipulation.interaction import Command
    from homebot.trials.interaction import _holding_scene, apply

    scene, controller = _holding_scene()
    hold = Command(controller.target_position, controller.target_rotation, Compliance(),
                   gripper_closed=True)
    for _ in range(30):
        apply(scene, controller, hold)
        scene.step()
    before = scene.to_base(scene.body_position("object")) - scene.to_base(scene.hand_world())
    scene.drive_base(0.5, 0.2, 0.3)
    for _ in range(100):
        apply(scene, controller, hold)
        scene.step()
    x, y, theta = scene.base_pose()
    assert x == pytest.approx(0.5, abs=0.01) and y == pytest.approx(0.2, abs=0.01)
    assert theta == pytest.approx(0.3, abs=0.01)
    after = scene.to_base(scene.body_position("object")) - scene.to_base(scene.hand_world())
    assert float(np.linalg.norm(after - before)) < 0.01


def test_the_table_is_carried_level_with_the_person() -> None:
    result = carry_table_episode(0, 19)  # walks 1.3 m away and 3 deg to the side
    assert not result.dropped and result.lowered
    assert result.max_tilt_deg <= 3.0 and result.max_height > 0.1 and result.travelled > 1.0
    assert result.success


def test_the_door_scenario_opens_and_shuts_the_door(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["scenario", "open_door", "--seed", "3", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["success"] and summary["opened_deg"] >= 60.0 and summary["closed_deg"] <= 2.0


def test_a_door_hinged_on_the_other_side_is_perceived_and_opened() -> None:
    # Hinged right (the scene file's door is hinged left) and stiff; the camera finds the
    # hinge on the right, within centimetres, and the handle it grasps.
    door = DoorVariant("right", 0.85, 2.5, 3.0)
    result = door_episode(0, variant=door)
    assert result.hinge_error is not None and result.hinge_error < 0.04
    assert result.handle_error is not None and result.handle_error < 0.02
    assert not result.lost_handle and not result.bumped
    assert result.opened_deg >= 60.0 and result.closed_deg <= 2.0 and result.success
