"""The arm's drivers over ``ArmSimulation``: the ``Arm`` and ``Gripper`` parts of the Body port.

``ArmDriver`` ticks the physics in control periods and offers what real drivers would:
joint states, position targets (with optional torques), the gripper, the wrist's wrench.
``SimBody`` fits one for the placement the robot stands at; benchmarks use one alone.
``world_scene`` turns the world's placements and catalogue into the physics scene.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from pathlib import Path

from homebot.robot import Arm, ArmState, Gripper, GripperState, JointTarget, Wrench
from homebot.sim.arm import (
    ARM_JOINTS,
    MAX_GRIPPER_WIDTH,
    ArmSimulation,
    ObjectBody,
    SurfaceBox,
)
from homebot.world import World, catalogue_entry, surface_height

__all__ = ["PAYLOAD", "ArmDriver", "object_body", "world_scene"]

PAYLOAD = 1.5  #: kilograms the arm is rated to lift
#: friction of an object's surface, by catalogue shape (rounder things roll and slip more)
_FRICTION = {"box": 0.8, "cylinder": 0.7, "sphere": 0.6}


class _SimArm(Arm):
    def __init__(self, driver: ArmDriver) -> None:
        self._driver = driver
        model = driver.sim.model
        self.joint_names = ARM_JOINTS
        self.limits = tuple((float(model.joint(n).range[0]), float(model.joint(n).range[1]))
                            for n in ARM_JOINTS)
        torso = model.joint("torso_lift").range
        self.torso_limits = (float(torso[0]), float(torso[1]))
        self.payload = PAYLOAD

    def state(self) -> ArmState:
        sim = self._driver.sim
        return ArmState(self._driver.now(), ARM_JOINTS, sim.arm_positions(),
                        sim.arm_velocities(), sim.arm_efforts(), sim.torso_height())

    def command(self, target: JointTarget) -> None:
        self._driver.sim.command(target.positions, torso=target.torso, torques=target.torques)

    def description(self) -> Path:
        return self._driver.sim.model_path


class _SimGripper(Gripper):
    def __init__(self, driver: ArmDriver) -> None:
        self._driver = driver

    def state(self) -> GripperState:
        sim = self._driver.sim
        return GripperState(self._driver.now(), sim.gripper_width(), sim.gripper_effort(),
                            MAX_GRIPPER_WIDTH)

    def command(self, width: float, force: float | None = None) -> None:
        self._driver.sim.command_gripper(width, force)


class ArmDriver:
    """The arm, gripper and wrist sensor of a simulated robot, ticking its physics.

    Args:
        sim: the physics scene.
        tick_period: simulated seconds per control tick.
        start: the clock's reading when the scene was built.
    """

    def __init__(self, sim: ArmSimulation, tick_period: float = 0.05,
                 start: float = 0.0) -> None:
        self.sim = sim
        self.tick_period = tick_period
        self._start = start - sim.time
        self._arm = _SimArm(self)
        self._gripper = _SimGripper(self)

    def now(self) -> float:
        return self._start + self.sim.time

    def tick(self, ticks: int = 1) -> None:
        self.sim.step(ticks * self.tick_period)

    def arm(self) -> Arm:
        return self._arm

    def gripper(self) -> Gripper:
        return self._gripper

    def wrist_wrench(self) -> Wrench:
        force, torque = self.sim.wrist_wrench()
        return Wrench(self.now(), force, torque)


def object_body(world: World, name: str, position: tuple[float, float], base: float,
                yaw: float = 0.0) -> ObjectBody:
    """The rigid body of the world's object ``name``, from its catalogue entry."""
    entry = catalogue_entry(world, name)
    shape = entry.shape.value
    rgba = (entry.rgb[0] / 255, entry.rgb[1] / 255, entry.rgb[2] / 255, 1.0)
    return ObjectBody(name, shape, entry.extent, entry.mass,  # type: ignore[arg-type]
                      _FRICTION.get(shape, 0.7), rgba, position, base, yaw)


def object_yaw(name: str) -> float:
    """A stable heading for an object (its name's hash), so boxes do not all face alike."""
    return (sum(map(ord, name)) * 0.6180339887) % 1.0 * math.pi


def world_scene(world: World, placements: Iterable[str],
                positions: Mapping[str, tuple[str, tuple[float, float]]]
                ) -> tuple[list[SurfaceBox], list[ObjectBody]]:
    """The surfaces of ``placements`` and the objects on them.

    ``positions`` maps each object standing on one of them to (placement, (x, y)).
    """
    surfaces, objects = [], []
    for name in placements:
        model = world.placements[name].model
        height = surface_height(model)
        if height <= 0.0:
            continue
        surfaces.append(SurfaceBox(name, (float(model.center[0]), float(model.center[1])),
                                   (float(model.size[0]), float(model.size[1])), height))
        for obj, (where, xy) in positions.items():
            if where == name:
                objects.append(object_body(world, obj, xy, height, object_yaw(obj)))
    return surfaces, objects

