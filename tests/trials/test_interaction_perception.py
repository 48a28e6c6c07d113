"""The physical HRI scenes perceive: the carried table's pitch and the pot, judged by truth."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

pytest.importorskip("mujoco")

from homebot.perception.plant_pot import PotScan
from homebot.scenarios.library.water_plant import pour
from homebot.sim.hri import InteractionScene
from homebot.trials.interaction import carry_table_episode


def test_the_perceived_pitch_tracks_the_true_pitch_through_a_carry() -> None:
    result = carry_table_episode(0, 3)  # walks towards the robot, which is pushed back
    assert result.success
    assert 0.0 < result.pitch_error_deg <= 0.6  # the referee's worst gap while carried


@pytest.mark.parametrize("pot", [(1.0, 0.0), (0.8, 0.35), (1.1, -0.3)])
def test_the_torso_laser_finds_the_pot_where_it_stands(pot: tuple[float, float]) -> None:
    def moved(spec: Any) -> None:
        spec.body("pot").pos = [pot[0], pot[1], 0.0]

    scene = InteractionScene("watering", edit=moved, sensor_seed=7)
    scene.move_base(0.1, 0.05, 0.2)
    sweep = PotScan()
    seen = sweep.find(scene.torso_height(),
                      scene.laser(sweep.mount(scene.torso_height()), sweep.directions()))
    assert seen is not None
    truth = scene.to_base(np.asarray(scene.data.site("pot_rim").xpos))
    assert math.dist(seen.rim[:2], truth[:2]) < 0.01
    assert abs(float(seen.rim[2] - truth[2])) < 0.015
    assert seen.radius == pytest.approx(0.1, abs=0.01)


@pytest.mark.parametrize("seed", [0, 7])
def test_the_plant_is_watered_from_what_the_laser_sees(seed: int) -> None:
    figures = pour(seed)
    assert figures["success"] and figures["watered_l"] >= 0.3 and figures["spilled_l"] <= 0.03


def test_the_head_camera_sees_the_door_leaf_where_it_stands() -> None:
    from homebot.robot import HeadState
    from homebot.trials.interaction import DoorVariant, door_scene

    door = DoorVariant("left", 0.8, 1.0, 1.0)
    scene = door_scene(door)
    scene.set_arm(np.array([0.0, -1.4, 0.0, -1.8, 0.0, -1.3, 0.0]))
    scene.move_base(-0.4, 0.0, 0.0)
    points = scene.camera(HeadState(0.0, 0.2)).points()[0]
    leaf = points[(points[:, 2] > 0.3) & (points[:, 2] < 1.8) & (np.abs(points[:, 1]) < 0.3)]
    # the leaf's near face stands 2 cm before the hinge axis, 1.2 m - 2 cm before the robot
    assert len(leaf) > 1000
    assert float(np.median(leaf[:, 0])) == pytest.approx(1.18, abs=0.005)
