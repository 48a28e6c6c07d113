"""The arm's MuJoCo scene: objects stand where the world says, joints follow targets."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from homebot.errors import WorldError

pytest.importorskip("mujoco")

from homebot.sim.arm import ARM_JOINTS, ArmSimulation, ObjectBody, SurfaceBox

TABLE = SurfaceBox("table", (0.75, 0.0), (0.5, 0.8), 0.75)


def _scene(**kwargs: object) -> ArmSimulation:
    cup = ObjectBody("cup", "cylinder", (0.07, 0.07, 0.1), 0.3, position=(0.65, 0.1))
    return ArmSimulation(base=(0.0, 0.0, 0.0), surfaces=[TABLE], objects=[cup], **kwargs)  # type: ignore[arg-type]


def test_objects_rest_on_their_surface_where_the_world_puts_them() -> None:
    arm = _scene()
    arm.step(0.2)
    assert np.allclose(arm.object_position("cup"), (0.65, 0.1, 0.8), atol=2e-3)
    assert {c.body2 for c in arm.contacts() if c.body1 == "cup"} == {"surface:table"}


def test_the_base_is_placed_at_the_robots_pose() -> None:
    cup = ObjectBody("cup", "sphere", (0.06, 0.06, 0.06), 0.2, position=(3.0, 2.5))
    arm = ArmSimulation(base=(3.0, 2.0, np.pi / 2), objects=[cup],
                        surfaces=[SurfaceBox("t", (3.0, 2.7), (0.8, 0.5), 0.7)],
                        arm=(0.0, -0.3, 0.0, 0.3, 0.0, 0.0, 0.0))
    grasp = arm.grasp_point()
    assert grasp[1] > 2.9 and abs(grasp[0] - 3.0) < 0.05  # the arm reaches along +y


def test_joints_and_gripper_follow_their_targets() -> None:
    arm = _scene()
    target = (0.3, -0.5, 0.2, 1.2, 0.1, 0.4, -0.3)
    arm.command(target, torso=0.3)
    arm.command_gripper(0.05)
    arm.step(1.5)
    assert np.allclose(arm.arm_positions(), target, atol=0.02)
    assert arm.torso_height() == pytest.approx(0.3, abs=0.01)
    assert arm.gripper_width() == pytest.approx(0.05, abs=0.005)
    assert len(ARM_JOINTS) == 7


def test_the_wrist_sensor_feels_a_pull() -> None:
    arm = _scene()
    arm.step(0.2)
    rest = arm.wrist_rotation() @ arm.wrist_wrench()[0]
    arm.push("gripper", (0.0, 0.0, -20.0))
    arm.step(0.2)
    pulled = arm.wrist_rotation() @ arm.wrist_wrench()[0]
    assert abs(np.linalg.norm(pulled - rest) - 20.0) < 4.0


def test_a_malformed_model_names_its_file_and_line(tmp_path: Path) -> None:
    bad = tmp_path / "arm.xml"
    bad.write_text("<mujoco>\n  <worldbody>\n    <body name='a'><geom size='x'/></body>\n"
                   "  </worldbody>\n</mujoco>\n")
    with pytest.raises(WorldError, match=r"arm\.xml:3"):
        ArmSimulation(base=(0.0, 0.0, 0.0), model_path=bad)
    with pytest.raises(WorldError, match="no such MJCF file"):
        ArmSimulation(base=(0.0, 0.0, 0.0), model_path=tmp_path / "missing.xml")
