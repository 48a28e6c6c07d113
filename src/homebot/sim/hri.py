"""Physical interaction scenes: the arm in MuJoCo, with a person's forces on what it holds.

``InteractionScene`` loads one of homebot's interaction scenes (``homebot/sim/mjcf/*.xml``,
each ``<include>``-ing the robot's ``arm.xml``) and offers what the arm's drivers would
offer a torque-controlled arm: joint state, the hand's pose and Jacobian in the base
frame, joint torque commands, the gripper, the torso lift and the wrist force-torque
sensor; the base is kinematic and moves where it is told. In ``arm.xml`` the base is a
mocap body, which MuJoCo moves by jumps and takes to stand still: a hand driven along
by a moving base would seem at rest to what it holds, and friction would not carry a
held table along (the fingers slid along its handle by as much as the base drove). So
the scene gives the base three joints (x, y, yaw) and drives them: ``drive_base`` sets
a velocity the base keeps, integrated every physics step, and contacts see the hand's
true velocity. ``move_base`` puts it somewhere at rest. The seven arm
joints run on their torque motors: the scene turns their position servos off (gain 0)
in its copy of the model, so compliance (``homebot.manipulation.compliance``) is all
that holds the hand. The person's forces (``homebot.sim.forces``) are added to
``xfrc_applied`` before every physics step; the scene's ground truth (where bodies truly
are) is for benchmarks and tests, never for the robot.

The robot sees the scene through a laser range finder (``laser``): rays cast from a
mount on the robot against the scene's geometry, the robot's own links filtered out (as
a self-filter does with the robot's model), each range with seeded noise. Cosero's
torso laser is pitchable and its head carries a depth camera; a fan of rays in any
plane stands for either. ``camera`` gives the head camera's RGB-D frame of the scene
(the home's camera model: the same pinhole, mounting, range and depth noise), cast with
``mujoco.mj_multiRay``, so perception runs on the scene as it runs in the home.
"""

from __future__ import annotations

from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from homebot.errors import SceneError
from homebot.geometry import yaw_rotation
from homebot.robot import CameraIntrinsics, HeadState, RgbdFrame
from homebot.sim.arm import drive_base

__all__ = ["ARM_JOINTS", "LASER_NOISE", "LASER_RANGE", "InteractionScene", "scene_path"]

ARM_JOINTS = ("shoulder_pan", "shoulder_lift", "upper_arm_roll", "elbow_flex", "forearm_roll",
              "wrist_flex", "wrist_roll")
_FINGERS = ("left_finger", "right_finger")
_FINGER_OPEN = 0.07

#: A force that acts on the scene: called before each physics step with (scene, time).
Pusher = Callable[["InteractionScene", float], None]


_BASE_JOINTS = ("base_x", "base_y", "base_yaw")
_LASER_STREAM = 2077
_CAMERA_STREAM = 2078
_CAMERA_RANGE = (0.4, 6.0)  #: metres the head's depth sensor measures between
LASER_NOISE = 0.01  #: metres: the range noise of a laser scanner (1 sigma)
LASER_RANGE = 5.0  #: metres: no return beyond this


def scene_path(name: str) -> Path:
    """The shipped scene file ``homebot/sim/mjcf/NAME.xml``."""
    path = Path(str(resources.files("homebot.sim").joinpath("mjcf", f"{name}.xml")))
    if not path.is_file():
        known = sorted(p.stem for p in path.parent.glob("*.xml"))
        raise SceneError(f"no interaction scene '{name}' in {path.parent}; scenes: "
                         f"{', '.join(known)}")
    return path


def _mujoco() -> Any:
    try:
        import mujoco
    except ImportError:
        raise SceneError("the arm's physics needs the 'embodied' extra (MuJoCo): "
                         "pip install 'homebot[embodied]'") from None
    return mujoco


class InteractionScene:
    """One physics scene with the arm.

    Args:
        scene: a shipped scene's name or an MJCF file's path.
        control_rate: control ticks per simulated second (torques hold between ticks).
        edit: changes the scene's ``mujoco.MjSpec`` before it is compiled (a variant).
        sensor_seed: seeds the laser's range noise.
    """

    def __init__(self, scene: str | Path, *, control_rate: float = 100.0,
                 edit: Callable[[Any], None] | None = None, sensor_seed: int = 0) -> None:
        mujoco = _mujoco()
        self._mj = mujoco
        path = Path(scene) if isinstance(scene, Path) or str(scene).endswith(".xml") else (
            scene_path(str(scene)))
        try:
            spec = mujoco.MjSpec.from_file(str(path))
            if edit is not None:  # a variant of the scene (a door's side, width, friction)
                edit(spec)
            drive_base(mujoco, spec)
            self.model = spec.compile()
        except ValueError as error:  # MuJoCo's message names the file, line and problem
            first = str(error).strip().splitlines()[0] if str(error).strip() else "unreadable"
            raise SceneError(f"{path}: not a usable MJCF scene ({first}); fix the file or "
                             "give one of homebot's scenes") from None
        self.data = mujoco.MjData(self.model)
        model = self.model
        self.path = path
        self.substeps = max(1, round(1.0 / (control_rate * model.opt.timestep)))
        self.control_period = self.substeps * model.opt.timestep
        joint = model.joint
        self._qpos = np.array([joint(n).qposadr[0] for n in ARM_JOINTS])
        self._dof = np.array([joint(n).dofadr[0] for n in ARM_JOINTS])
        self._torque = np.array([model.actuator(f"{n}_torque").id for n in ARM_JOINTS])
        self._torque_range = model.actuator_ctrlrange[self._torque].copy()
        for name in ARM_JOINTS:  # the position servos off: the arm runs on torques
            servo = model.actuator(name).id
            model.actuator_gainprm[servo, :] = 0.0
            model.actuator_biasprm[servo, :] = 0.0
        self._fingers = [model.actuator(n).id for n in _FINGERS]
        self._lift = model.actuator("torso_lift").id
        self._lift_qpos = joint("torso_lift").qposadr[0]
        self._base = model.body("base").id
        self._base_qpos = np.array([joint(n).qposadr[0] for n in _BASE_JOINTS])
        self._base_dof = np.array([joint(n).dofadr[0] for n in _BASE_JOINTS])
        self._base_pose = np.zeros(3)  #: x, y, yaw: where the base is driven to
        self._base_velocity = np.zeros(3)  #: world frame: vx, vy, wz
        self._grasp = model.site("grasp").id
        self._force = model.sensor("wrist_force")
        self._torque_sensor = model.sensor("wrist_torque")
        self._jacp = np.zeros((3, model.nv))
        self._jacr = np.zeros((3, model.nv))
        self.pushers: list[Pusher] = []
        self._robot_bodies = {b for b in range(model.nbody)
                              if int(model.body_rootid[b]) == self._base}
        self._sensor_rng = np.random.default_rng([sensor_seed, _LASER_STREAM])
        self._camera_rng = np.random.default_rng([sensor_seed, _CAMERA_STREAM])
        mujoco.mj_forward(model, self.data)

    # ------------------------------------------------------------ set-up

    def set_arm(self, q: np.ndarray | list[float], *, torso: float | None = None,
                gripper: float | None = None) -> None:
        """Put the arm (and torso, fingers) in a configuration at rest; recompute."""
        data = self.data
        data.qpos[self._qpos] = q
        data.qvel[:] = 0.0
        if torso is not None:
            data.qpos[self._lift_qpos] = torso
            data.ctrl[self._lift] = torso
        if gripper is not None:
            for name, actuator in zip(_FINGERS, self._fingers, strict=True):
                data.qpos[self.model.joint(name).qposadr[0]] = gripper
                data.ctrl[actuator] = gripper
        self._mj.mj_forward(self.model, data)

    def place_body(self, body: str, position: np.ndarray | list[float],
                   quaternion: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)) -> None:
        """Put a free body at a world pose, at rest."""
        joint = self.model.body(body).jntadr[0]
        address = self.model.jnt_qposadr[joint]
        self.data.qpos[address:address + 3] = position
        self.data.qpos[address + 3:address + 7] = quaternion
        dof = self.model.jnt_dofadr[joint]
        self.data.qvel[dof:dof + 6] = 0.0
        self._mj.mj_forward(self.model, self.data)

    # ------------------------------------------------------------ what the drivers report

    @property
    def time(self) -> float:
        return float(self.data.time)

    def base_pose(self) -> tuple[float, float, float]:
        """The base's pose on the floor (x, y, yaw)."""
        x, y, theta = self._base_pose
        return float(x), float(y), float(theta)

    def _base_rotation(self) -> np.ndarray:
        return yaw_rotation(self.base_pose()[2])

    def to_base(self, point: np.ndarray) -> np.ndarray:
        """A world point in the base frame."""
        x, y, _ = self.base_pose()
        local: np.ndarray = self._base_rotation().T @ (np.asarray(point) - np.array([x, y, 0.0]))
        return local

    def to_world(self, point: np.ndarray) -> np.ndarray:
        x, y, _ = self.base_pose()
        world: np.ndarray = self._base_rotation() @ np.asarray(point) + np.array([x, y, 0.0])
        return world

    def arm_state(self) -> tuple[np.ndarray, ...]:
        """``(q, qd, hand position, hand rotation, jacobian, gravity)`` in the base frame:
        the fields of ``homebot.manipulation.compliance.ArmState``."""
        model, data = self.model, self.data
        rotation = self._base_rotation()
        self._mj.mj_jacSite(model, data, self._jacp, self._jacr, self._grasp)
        jacobian = np.vstack((rotation.T @ self._jacp[:, self._dof],
                              rotation.T @ self._jacr[:, self._dof]))
        hand = self.to_base(data.site_xpos[self._grasp])
        hand_rotation = rotation.T @ data.site_xmat[self._grasp].reshape(3, 3)
        gravity = data.qfrc_bias[self._dof] - data.qfrc_gravcomp[self._dof]
        return (data.qpos[self._qpos].copy(), data.qvel[self._dof].copy(), hand, hand_rotation,
                jacobian, gravity.copy())

    def wrist_wrench(self) -> np.ndarray:
        """The force-torque sensor's reading (sensor frame): fx, fy, fz, tx, ty, tz."""
        f, t = self._force, self._torque_sensor
        return np.concatenate((self.data.sensordata[f.adr[0]:f.adr[0] + 3],
                               self.data.sensordata[t.adr[0]:t.adr[0] + 3]))

    def gripper_opening(self) -> float:
        """How far apart the fingers are (m)."""
        return float(sum(self.data.qpos[self.model.joint(n).qposadr[0]] for n in _FINGERS))

    def torso_height(self) -> float:
        return float(self.data.qpos[self._lift_qpos])

    def laser(self, mount: np.ndarray, directions: np.ndarray, *,
              noise: float = LASER_NOISE) -> np.ndarray:
        """Ranges (m) along rays from ``mount`` (base frame) in ``directions`` (base frame,
        unit vectors, one a row) to the first surface that is not the robot's own; inf
        where nothing is within ``LASER_RANGE``. Each range has Gaussian noise."""
        mj, model, data = self._mj, self.model, self.data
        rotation = self._base_rotation()
        origin = self.to_world(np.asarray(mount, dtype=float))
        rays = np.atleast_2d(np.asarray(directions, dtype=float)) @ rotation.T
        ranges = np.full(len(rays), np.inf)
        hit = np.zeros(1, dtype=np.int32)
        for k, ray in enumerate(rays):
            travelled, start = 0.0, origin.copy()
            for _ in range(8):  # past the robot's own links
                distance = mj.mj_ray(model, data, start, ray, None, 1, -1, hit)
                if distance < 0:
                    break
                travelled += distance
                if int(model.geom_bodyid[hit[0]]) not in self._robot_bodies:
                    ranges[k] = travelled
                    break
                travelled += 1e-4
                start = origin + travelled * ray
        seen = np.isfinite(ranges)
        ranges[seen] += self._sensor_rng.normal(0.0, noise, int(seen.sum()))
        ranges[ranges > LASER_RANGE] = np.inf
        return ranges

    def camera(self, head: HeadState, intrinsics: CameraIntrinsics | None = None
               ) -> RgbdFrame:
        """The head camera's RGB-D frame (the home's camera: ``homebot.sim.camera``'s
        pinhole, height and depth noise) with the head at ``head``: the depth along the
        optical axis to the first surface that is not the robot's own, ``nan`` outside
        the sensor's range; the colour is the surface's."""
        from homebot.sim.camera import CAMERA_HEIGHT, DEFAULT_INTRINSICS, camera_pose

        mj, model, data = self._mj, self.model, self.data
        k = intrinsics or DEFAULT_INTRINSICS
        pose = camera_pose(head, CAMERA_HEIGHT)
        optical = k.rays().reshape(-1, 3)
        lengths = np.linalg.norm(optical, axis=1)
        rotation = self._base_rotation() @ pose[:3, :3]
        rays = (optical / lengths[:, None]) @ rotation.T
        origin = self.to_world(pose[:3, 3])
        hit = np.full(len(rays), -1, dtype=np.int32)
        distance = np.full(len(rays), -1.0)
        mj.mj_multiRay(model, data, origin, rays.ravel(), None, 1, -1, hit, distance, None,
                       len(rays), _CAMERA_RANGE[1] * 2)
        own = np.flatnonzero((hit >= 0) & np.isin(model.geom_bodyid[np.maximum(hit, 0)],
                                                  list(self._robot_bodies)))
        for index in own:  # past the robot's own links, as a self-filter does
            distance[index], hit[index] = self._past_own_links(origin, rays[index])
        depth = np.where(distance >= 0, distance / lengths, np.inf)
        depth += self._camera_rng.standard_normal(depth.shape) * (
            0.0012 + 0.0019 * np.square(np.nan_to_num(depth, posinf=0.0) - 0.4))
        depth = np.where((depth >= _CAMERA_RANGE[0]) & (depth <= _CAMERA_RANGE[1]), depth,
                         np.nan)
        colour = np.where(hit[:, None] >= 0, model.geom_rgba[np.maximum(hit, 0), :3], 0.0)
        return RgbdFrame(self.time, (255 * colour).astype(np.uint8).reshape(
            k.height, k.width, 3), depth.reshape(k.height, k.width).astype(np.float32), k,
            pose)

    def _past_own_links(self, origin: np.ndarray, ray: np.ndarray) -> tuple[float, int]:
        """The distance along ``ray`` to the first surface not the robot's, and its geom
        ((-1, -1): none)."""
        mj, model, data = self._mj, self.model, self.data
        hit = np.zeros(1, dtype=np.int32)
        travelled, start = 0.0, origin.copy()
        for _ in range(8):
            distance = mj.mj_ray(model, data, start, ray, None, 1, -1, hit)
            if distance < 0:
                return -1.0, -1
            travelled += distance
            if int(model.geom_bodyid[hit[0]]) not in self._robot_bodies:
                return travelled, int(hit[0])
            travelled += 1e-4
            start = origin + travelled * ray
        return -1.0, -1

    # ------------------------------------------------------------ commands

    def command_torques(self, tau: np.ndarray) -> None:
        """Joint torques for the seven arm joints (clipped to the motors' range)."""
        low, high = self._torque_range[:, 0], self._torque_range[:, 1]
        self.data.ctrl[self._torque] = np.clip(tau, low, high)

    def grip(self, closed: bool) -> None:
        """Close the fingers (as far as what is between them lets them) or open them."""
        for actuator in self._fingers:
            self.data.ctrl[actuator] = 0.0 if closed else _FINGER_OPEN

    def lift_torso(self, height: float) -> None:
        """Drive the torso lift towards ``height`` (m, within its range)."""
        low, high = self.model.actuator_ctrlrange[self._lift]
        self.data.ctrl[self._lift] = float(np.clip(height, low, high))

    def move_base(self, x: float, y: float, theta: float) -> None:
        """Put the kinematic base at a floor pose, at rest (the arm and what it holds come
        along)."""
        self._base_pose = np.array([x, y, theta], dtype=float)
        self._base_velocity = np.zeros(3)
        self._hold_base()
        self._mj.mj_forward(self.model, self.data)

    def drive_base(self, vx: float, vy: float, wz: float) -> None:
        """Drive the base at a velocity (world frame: m/s, m/s, rad/s) from the next step on;
        it keeps that velocity until told otherwise."""
        self._base_velocity = np.array([vx, vy, wz], dtype=float)

    def _hold_base(self) -> None:
        self.data.qpos[self._base_qpos] = self._base_pose
        self.data.qvel[self._base_dof] = self._base_velocity

    # ------------------------------------------------------------ time

    def step(self) -> None:
        """One control period of physics, the person's forces renewed every physics step."""
        mj, model, data = self._mj, self.model, self.data
        dt = model.opt.timestep
        for _ in range(self.substeps):
            if self.pushers:
                data.xfrc_applied[:] = 0.0
                for push in self.pushers:
                    push(self, float(data.time))
            self._hold_base()
            mj.mj_step(model, data)
            self._base_pose = self._base_pose + self._base_velocity * dt
        self._hold_base()

    # ------------------------------------------------------------ ground truth

    def body_position(self, body: str) -> np.ndarray:
        return np.asarray(self.data.body(body).xpos, dtype=float).copy()

    def body_rotation(self, body: str) -> np.ndarray:
        return np.asarray(self.data.body(body).xmat, dtype=float).reshape(3, 3).copy()

    def body_velocity(self, body: str, point: np.ndarray) -> np.ndarray:
        """The world velocity of a point fixed to ``body``."""
        b = self.model.body(body).id
        velocity: np.ndarray = np.zeros(6)
        self._mj.mj_objectVelocity(self.model, self.data, self._mj.mjtObj.mjOBJ_BODY, b,
                                   velocity, 0)
        angular, linear = velocity[:3], velocity[3:]
        result: np.ndarray = linear + np.cross(angular, np.asarray(point) - self.data.xipos[b])
        return result

    def body_id(self, body: str) -> int:
        return int(self.model.body(body).id)

    def hand_world(self) -> np.ndarray:
        return np.asarray(self.data.site_xpos[self._grasp], dtype=float).copy()

    def touching(self, geom_a: str, geom_b: str) -> bool:
        """Whether two named geoms are in contact."""
        a, b = self.model.geom(geom_a).id, self.model.geom(geom_b).id
        for k in range(self.data.ncon):
            contact = self.data.contact[k]
            if {int(contact.geom1), int(contact.geom2)} == {a, b}:
                return True
        return False
