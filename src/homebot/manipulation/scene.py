"""The robot's planning scene: its arm model with what it knows stands in front of it.

The scene is the robot's own, built from the arm's description (the MJCF file the body
names, as ROS's ``robot_description``) and the obstacles the robot perceived or was told
of: surfaces as boxes, objects as their shapes. It is a second MuJoCo model, never the
simulator's: collision checks run ``mj_kinematics`` + ``mj_collision`` on it and read the
contacts; forward kinematics and the grasp site's Jacobian (``mj_jacSite``) serve the IK.

A configuration is 8 numbers: the torso lift's height, then the arm's 7 joints.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np

from homebot.geometry import quaternion_from_yaw

__all__ = ["ARM_JOINTS", "Obstacle", "PlanningScene"]

ARM_JOINTS = ("shoulder_pan", "shoulder_lift", "upper_arm_roll", "elbow_flex", "forearm_roll",
              "wrist_flex", "wrist_roll")
_GRIPPER_BODIES = ("gripper", "left_finger", "right_finger")
_CLEARANCE = 0.01  #: metres the arm keeps from obstacles while planning


@dataclass(frozen=True, slots=True)
class Obstacle:
    """Something in front of the robot: a box, an upright cylinder or a sphere.

    ``extents`` are full sizes (x, y, z) in its own frame (a cylinder's first two its
    diameter); ``center`` is its middle on the map, ``yaw`` its heading.
    """

    name: str
    shape: Literal["box", "cylinder", "sphere"]
    extents: tuple[float, float, float]
    center: tuple[float, float, float]
    yaw: float = 0.0


class PlanningScene:
    """The arm's kinematics and collisions among known obstacles, for one base pose.

    Args:
        description: the arm's MJCF file.
        base: the robot's pose (x, y, heading) on the map (its estimate).
        obstacles: what stands around.
    """

    def __init__(self, description: Path, base: tuple[float, float, float],
                 obstacles: Iterable[Obstacle] = ()) -> None:
        import mujoco

        self._mj = mujoco
        spec = mujoco.MjSpec.from_file(str(description))
        kinds = {"box": mujoco.mjtGeom.mjGEOM_BOX, "cylinder": mujoco.mjtGeom.mjGEOM_CYLINDER,
                 "sphere": mujoco.mjtGeom.mjGEOM_SPHERE}
        self.obstacles = {o.name: o for o in obstacles}
        for obstacle in self.obstacles.values():
            x, y, z = obstacle.extents
            size = {"box": [x / 2, y / 2, z / 2], "cylinder": [x / 2, z / 2, 0.0],
                    "sphere": [x / 2, 0.0, 0.0]}[obstacle.shape]
            body = spec.worldbody.add_body(
                name=obstacle.name, pos=list(obstacle.center),
                quat=list(quaternion_from_yaw(obstacle.yaw)))
            body.add_geom(name=obstacle.name, type=kinds[obstacle.shape], size=size,
                          contype=1, conaffinity=3)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        m = self.model
        joints = ["torso_lift", *ARM_JOINTS]
        self._qpos = np.array([m.jnt_qposadr[m.joint(n).id] for n in joints])
        self._dof = np.array([m.jnt_dofadr[m.joint(n).id] for n in joints])
        self._fingers = [int(m.jnt_qposadr[m.joint(n).id]) for n in ("left_finger",
                                                                      "right_finger")]
        self.lower = np.array([m.jnt_range[m.joint(n).id][0] for n in joints])
        self.upper = np.array([m.jnt_range[m.joint(n).id][1] for n in joints])
        self._site = m.site("grasp").id
        self._gripper_bodies = {m.body(n).id for n in _GRIPPER_BODIES}
        self._robot_geoms = {g for g in range(m.ngeom) if m.geom_contype[g] == 2}
        m.geom_margin[:] = 0.0
        m.geom_margin[list(self._robot_geoms)] = _CLEARANCE  # a pair's margins add up
        self._obstacle_body = {m.body(n).id: n for n in self.obstacles}
        self.base = base
        mocap = int(m.body_mocapid[m.body("base").id])
        self.data.mocap_pos[mocap] = [base[0], base[1], 0.0]
        self.data.mocap_quat[mocap] = quaternion_from_yaw(base[2])
        self._jacp = np.zeros((3, m.nv))
        self._jacr = np.zeros((3, m.nv))
        self.checks = 0  #: collision checks made (for the benchmark)

    def set(self, q: Sequence[float] | np.ndarray, gripper: float = 0.2) -> None:
        """Put the robot in configuration ``q`` with the fingers ``gripper`` apart."""
        self.data.qpos[self._qpos] = q
        self.data.qpos[self._fingers] = gripper / 2
        self._mj.mj_kinematics(self.model, self.data)

    def grasp_frame(self, q: Sequence[float] | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Where the grasp site is for ``q``: position and 3×3 rotation (map frame)."""
        self.set(q)
        return (np.array(self.data.site_xpos[self._site]),
                np.array(self.data.site_xmat[self._site]).reshape(3, 3))

    def jacobian(self) -> np.ndarray:
        """The grasp site's 6×8 Jacobian (linear over angular) at the last ``set``."""
        self._mj.mj_comPos(self.model, self.data)
        self._mj.mj_jacSite(self.model, self.data, self._jacp, self._jacr, self._site)
        return np.vstack((self._jacp[:, self._dof], self._jacr[:, self._dof]))

    def site(self) -> tuple[np.ndarray, np.ndarray]:
        """The grasp site's position and rotation at the last ``set``."""
        return (np.array(self.data.site_xpos[self._site]),
                np.array(self.data.site_xmat[self._site]).reshape(3, 3))

    def collides(self, q: Sequence[float] | np.ndarray, *, gripper: float = 0.2,
                 allowed: frozenset[str] = frozenset()) -> bool:
        """Whether the arm in ``q`` comes within the clearance of an obstacle; contacts
        between the gripper and an ``allowed`` obstacle (the object to grasp) do not count."""
        self.set(q, gripper)
        self._mj.mj_collision(self.model, self.data)
        self.checks += 1
        m, d = self.model, self.data
        for index in range(d.ncon):
            contact = d.contact[index]
            g1, g2 = contact.geom1, contact.geom2
            robot = g1 if g1 in self._robot_geoms else g2 if g2 in self._robot_geoms else -1
            if robot < 0:
                continue  # two obstacles touching: not the arm's business
            other = g2 if robot == g1 else g1
            name = self._obstacle_body.get(int(m.geom_bodyid[other]))
            if name in allowed and int(m.geom_bodyid[robot]) in self._gripper_bodies:
                continue
            return True
        return False

    def without(self, names: Iterable[str]) -> frozenset[str]:
        """The obstacle names, for ``allowed`` (those that exist)."""
        return frozenset(n for n in names if n in self.obstacles)

