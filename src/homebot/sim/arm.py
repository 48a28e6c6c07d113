"""``ArmSimulation``: the robot's arm, gripper and the objects in front of it, in MuJoCo.

The scene is built from the robot's MJCF model (``homebot/sim/mjcf/arm.xml`` unless a world
file names another with ``robot.arm``) with ``mujoco.MjSpec``: the surfaces near the robot
become static boxes and the objects on them free bodies with their catalogue's mass and
friction. The base is a mocap body, placed at the robot's true pose (map frame), so the
objects stay where the world says they are. Physics runs in simulated time only
(``step``); what the arm's drivers would measure (joint states, gripper width, the wrist's
force-torque) is read here and offered to the robot through the ``Body`` port.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any, Literal

import numpy as np

from homebot.errors import WorldError
from homebot.geometry import quaternion_from_yaw

__all__ = [
    "ARM_JOINTS",
    "ArmSimulation",
    "Contact",
    "DoorLeaf",
    "ObjectBody",
    "SurfaceBox",
    "default_arm_model",
    "drive_base",
    "load_arm_spec",
]

#: the arm's seven joints, shoulder to wrist, as the MJCF model names them
ARM_JOINTS = ("shoulder_pan", "shoulder_lift", "upper_arm_roll", "elbow_flex", "forearm_roll",
              "wrist_flex", "wrist_roll")
#: a tucked arm: upper arm up, forearm folded back over the base, hand down behind the
#: shoulder; clear of anything in front of the robot below 1.2 m
HOME = (0.0, -1.4, 0.0, -1.8, 0.0, -1.3, 0.0)
MAX_GRIPPER_WIDTH = 0.2  #: metres between the finger pads, fully open
_SETTLE = 0.05  #: seconds of physics after building a scene (objects come to rest)
_WORLD_CONTYPE, _WORLD_CONAFFINITY = 1, 3

Shape = Literal["box", "cylinder", "sphere"]


def default_arm_model() -> Path:
    """The MJCF file homebot ships for its arm."""
    return Path(str(resources.files("homebot") / "sim" / "mjcf" / "arm.xml"))


def load_arm_spec(path: Path) -> Any:
    """The arm's ``mujoco.MjSpec`` from ``path``.

    Raises:
        WorldError: the file is missing or not a valid MJCF model (naming file and line).
    """
    import mujoco

    if not path.is_file():
        raise WorldError(f"{path}: no such MJCF file; 'robot.arm' in the world file must name "
                         "an arm model (or leave it out for homebot's own)")
    try:
        spec = mujoco.MjSpec.from_file(str(path))
        spec.compile()
    except ValueError as problem:
        text = " ".join(str(problem).split())
        line = re.search(r"line (\d+)", text)
        where = f"{path}:{line.group(1)}" if line else str(path)
        raise WorldError(f"{where}: not a usable MJCF arm model ({text}); fix the file or "
                         "leave 'robot.arm' out") from None
    missing = [name for name in (*ARM_JOINTS, "torso_lift", "left_finger", "right_finger")
               if spec.joint(name) is None]
    if missing or spec.site("grasp") is None or spec.site("wrist_ft") is None:
        raise WorldError(f"{path}: the arm model lacks {', '.join(missing) or 'a site'}; it "
                         "needs the joints of homebot's arm and the sites 'grasp', 'wrist_ft'")
    return spec


@dataclass(frozen=True, slots=True)
class SurfaceBox:
    """A surface the arm works on: a footprint (map frame, metres) with its top's height."""

    name: str
    center: tuple[float, float]
    size: tuple[float, float]
    height: float


@dataclass(frozen=True, slots=True)
class ObjectBody:
    """An object as a rigid body: catalogue shape and its full extents (x, y, z), metres.

    A cylinder's extents are (diameter, diameter, height), a sphere's (d, d, d). ``position``
    is where it stands (map frame); ``base`` the height of the surface under it, ``yaw``
    its heading.
    """

    name: str
    shape: Shape
    extents: tuple[float, float, float]
    mass: float
    friction: float = 0.8
    rgba: tuple[float, float, float, float] = (0.8, 0.3, 0.2, 1.0)
    position: tuple[float, float] = (0.0, 0.0)
    base: float = 0.75
    yaw: float = 0.0

    def geom_size(self) -> list[float]:
        """MuJoCo's size for the shape (half-extents, radius and half-height, radius)."""
        x, y, z = self.extents
        if self.shape == "box":
            return [x / 2, y / 2, z / 2]
        if self.shape == "cylinder":
            return [x / 2, z / 2, 0.0]
        return [x / 2, 0.0, 0.0]


@dataclass(frozen=True, slots=True)
class DoorLeaf:
    """A shut door's leaf on its hinge, with a lever handle on each face (map frame).

    ``hinge`` is the hinge axis's foot; ``yaw`` the direction from the hinge to the latch
    edge while shut; the leaf turns about the hinge by positive angles when ``swing`` is
    +1 (counter-clockwise seen from above), negative ones when -1. ``handles`` are the
    levers' centres (x, y, z); each lever turns down about the leaf's normal from its
    latch-side end. While latched the leaf cannot turn; pressing a lever down past
    ``DOOR_UNLATCH`` releases the latch unless the door is ``locked``.
    """

    name: str
    hinge: tuple[float, float]
    yaw: float
    length: float  #: metres from the hinge to the latch edge
    thickness: float
    height: float
    handles: tuple[tuple[float, float, float], ...]
    handle_size: tuple[float, float, float]  #: the lever's length, depth and height
    swing: float = 1.0
    locked: bool = False
    friction: float = 1.0  #: the hinge's dry friction (N·m)
    damping: float = 2.0  #: the hinge's damping (N·m·s/rad)


DOOR_UNLATCH = 0.3  #: radians a lever is pressed down to draw the latch
_DOOR_RANGE = 1.9  #: radians a leaf turns at most
_LATCH_PLAY = 0.003  #: radians a latched leaf rattles in its frame
_LEVER_TRAVEL = 0.6  #: radians a lever goes down at most
_LEVER_SPRING = 1.5  #: N·m/rad: the spring that brings a lever back up
_LEVER_PIVOT_IN = 0.01  #: metres in from the lever's latch-side end to its pivot
_UNDER_DOOR = 0.01  #: metres between a leaf and the floor
_LATCH_EVERY = 3  #: physics steps between checks of the latches
_BASE_JOINTS = ("base_x", "base_y", "base_yaw")


@dataclass(frozen=True, slots=True)
class Contact:
    """Two bodies touching, and the normal force between them (newtons)."""

    body1: str
    body2: str
    position: tuple[float, float, float]
    force: float


class ArmSimulation:
    """The arm in front of some surfaces, with objects on them, under physics.

    Args:
        base: the robot's true pose (x, y, heading) on the map.
        surfaces: static boxes the objects stand on.
        objects: free bodies.
        model_path: the arm's MJCF file (default: homebot's).
        arm: joint positions to start from (default: tucked).
        torso: the torso lift's start height.
        held: an object to start in the gripper with its pose relative to the grasp site
            (``relative_to_grasp``), e.g. when the scene is rebuilt at another placement.
        doors: shut doors' leaves on their hinges, latched.
        grip: the gripper's command (width, force) when it differs from ``gripper``, the
            fingers' start width: a hand closed on an object keeps squeezing it.
    """

    def __init__(self, *, base: tuple[float, float, float],
                 surfaces: Sequence[SurfaceBox] = (), objects: Sequence[ObjectBody] = (),
                 model_path: Path | None = None, arm: Sequence[float] = HOME,
                 torso: float = 0.2, gripper: float = MAX_GRIPPER_WIDTH,
                 held: tuple[ObjectBody, np.ndarray] | None = None,
                 grip: tuple[float, float | None] | None = None,
                 doors: Sequence[DoorLeaf] = ()) -> None:
        import mujoco

        self._mj = mujoco
        self.model_path = model_path or default_arm_model()
        spec = load_arm_spec(self.model_path)
        for surface in surfaces:
            body = spec.worldbody.add_body(name=f"surface:{surface.name}",
                                           pos=[*surface.center, surface.height / 2])
            body.add_geom(name=f"surface:{surface.name}", type=mujoco.mjtGeom.mjGEOM_BOX,
                          size=[surface.size[0] / 2, surface.size[1] / 2, surface.height / 2],
                          contype=_WORLD_CONTYPE, conaffinity=_WORLD_CONAFFINITY,
                          rgba=[0.55, 0.4, 0.25, 1.0], friction=[0.6, 0.005, 0.0001])
        self.objects = {obj.name: obj for obj in objects}
        if held is not None:
            self.objects[held[0].name] = held[0]
        for obj in self.objects.values():
            body = spec.worldbody.add_body(
                name=obj.name, pos=[*obj.position, obj.base + obj.extents[2] / 2 + 0.0005],
                quat=list(quaternion_from_yaw(obj.yaw)))
            body.add_freejoint(name=f"{obj.name}:free")
            geom_type = {"box": mujoco.mjtGeom.mjGEOM_BOX,
                         "cylinder": mujoco.mjtGeom.mjGEOM_CYLINDER,
                         "sphere": mujoco.mjtGeom.mjGEOM_SPHERE}[obj.shape]
            # round things roll, and rolling friction brings them to rest (condim 6)
            body.add_geom(name=obj.name, type=geom_type, size=obj.geom_size(), mass=obj.mass,
                          friction=[obj.friction, 0.01, 0.002],
                          condim=4 if obj.shape == "box" else 6, priority=1,
                          contype=_WORLD_CONTYPE, conaffinity=_WORLD_CONAFFINITY,
                          rgba=list(obj.rgba))
        self.doors = {door.name: door for door in doors}
        for door in doors:
            _add_door(mujoco, spec, door)
        if doors:
            drive_base(mujoco, spec)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        m = self.model
        #: per door: the hinge's qpos address, its levers' qpos addresses, latched or not
        self._door_hinge = {name: int(m.jnt_qposadr[m.joint(f"door:{name}").id])
                            for name in self.doors}
        self._levers = {name: [int(m.jnt_qposadr[m.joint(f"door:{name}:lever{k}").id])
                               for k in range(len(door.handles))]
                        for name, door in self.doors.items()}
        self.latched = {name: True for name in self.doors}
        for name in self.doors:
            self._latch(name, True)
        self._arm_qpos = np.array([m.jnt_qposadr[m.joint(n).id] for n in ARM_JOINTS])
        self._arm_dof = np.array([m.jnt_dofadr[m.joint(n).id] for n in ARM_JOINTS])
        self._arm_act = np.array([m.actuator(n).id for n in ARM_JOINTS])
        self._arm_torque = np.array([m.actuator(f"{n}_torque").id for n in ARM_JOINTS])
        self._torso_q = int(m.jnt_qposadr[m.joint("torso_lift").id])
        self._torso_act = m.actuator("torso_lift").id
        self._finger_q = [int(m.jnt_qposadr[m.joint(n).id]) for n in ("left_finger",
                                                                       "right_finger")]
        self._finger_act = [m.actuator(n).id for n in ("left_finger", "right_finger")]
        self._grasp_site = m.site("grasp").id
        self._ft_site = m.site("wrist_ft").id
        self._force_adr = int(m.sensor_adr[m.sensor("wrist_force").id])
        self._torque_adr = int(m.sensor_adr[m.sensor("wrist_torque").id])
        self._pads = {m.geom("left_pad").id, m.geom("right_pad").id}
        palm = m.geom("palm").id
        #: how far the grasp site lies out from the palm's face, along the approach
        self._grasp_to_palm = float(m.site_pos[self._grasp_site][0] - m.geom_pos[palm][0] -
                                    m.geom_size[palm][0])
        self._base_mocap = int(m.body_mocapid[m.body("base").id])
        #: the base's joints (x, y, yaw) where it is driven (a door in the scene), else None
        self._base_joints = None if self._base_mocap >= 0 else (
            np.array([m.jnt_qposadr[m.joint(n).id] for n in _BASE_JOINTS]),
            np.array([m.jnt_dofadr[m.joint(n).id] for n in _BASE_JOINTS]))
        self._base_velocity = np.zeros(3)
        self.set_base(base)
        self.data.qpos[self._arm_qpos] = arm
        self.data.qpos[self._torso_q] = torso
        self.data.qpos[self._finger_q] = gripper / 2
        self.command(arm, torso=torso)
        self.gripper_command: tuple[float, float | None] = (gripper, None)
        self.command_gripper(*(grip or (gripper, None)))
        mujoco.mj_forward(m, self.data)
        if held is not None:
            self._put_in_gripper(held[0], held[1])
        self.step(_SETTLE)

    # ------------------------------------------------------------ commands

    def set_base(self, pose: tuple[float, float, float]) -> None:
        """Put the (kinematic) base at ``pose`` (x, y, heading) on the map."""
        self.base = pose
        if self._base_joints is None:
            self.data.mocap_pos[self._base_mocap] = [pose[0], pose[1], 0.0]
            self.data.mocap_quat[self._base_mocap] = quaternion_from_yaw(pose[2])
            return
        self.data.qpos[self._base_joints[0]] = pose
        self.data.qvel[self._base_joints[1]] = self._base_velocity

    def command(self, arm: Sequence[float], *, torso: float | None = None,
                torques: Sequence[float] | None = None) -> None:
        """Joint position targets for the arm (and torso), and extra joint torques."""
        self.data.ctrl[self._arm_act] = arm
        if torso is not None:
            self.data.ctrl[self._torso_act] = torso
        self.data.ctrl[self._arm_torque] = torques if torques is not None else 0.0

    def command_gripper(self, width: float, force: float | None = None) -> None:
        """Move the fingers to ``width`` apart (metres); ``force`` caps each finger's push."""
        half = max(0.0, min(MAX_GRIPPER_WIDTH, width)) / 2
        # the force cap stays in the model until changed: the command keeps it too
        self.gripper_command = (width, force if force is not None else self.gripper_command[1])
        self.data.ctrl[self._finger_act] = half
        if force is not None:
            for act in self._finger_act:
                self.model.actuator_forcerange[act] = (-force, force)

    def push(self, body: str, force: Sequence[float]) -> None:
        """An external force (newtons, map frame) on ``body`` at its centre, until changed."""
        self.data.xfrc_applied[self.model.body(body).id, :3] = force

    def hold_at_grasp(self, name: str) -> None:
        """Put ``name`` upright (turned as the base) between the fingers, pushed in up to
        the palm, at rest: where a person holds it out into the robot's open hand."""
        joint = self.model.joint(f"{name}:free")
        position = int(self.model.jnt_qposadr[joint.id])
        velocity = int(self.model.jnt_dofadr[joint.id])
        approach = np.array(self.data.site_xmat[self._grasp_site]).reshape(3, 3)[:, 0]
        inward = max(self._grasp_to_palm - self.objects[name].extents[0] / 2 - 0.003, 0.0)
        self.data.qpos[position:position + 3] = self.grasp_point() - inward * approach
        self.data.qpos[position + 3:position + 7] = quaternion_from_yaw(self.base[2])
        self.data.qvel[velocity:velocity + 6] = 0.0
        self._mj.mj_forward(self.model, self.data)

    def step(self, seconds: float, *, base: tuple[float, float, float] | None = None) -> None:
        """Let ``seconds`` of simulated time pass; the base moves on to ``base`` meanwhile
        (driven at the velocity that takes it there), if given. A door's latch follows
        its levers."""
        if not self.doors and base is None:
            steps = max(1, round(seconds / self.model.opt.timestep))
            self._mj.mj_step(self.model, self.data, nstep=steps)
            return
        steps = max(1, round(seconds / self.model.opt.timestep))
        dt = self.model.opt.timestep
        start = np.array(self.base)
        velocity = np.zeros(3)
        if base is not None:
            turn = float(np.angle(np.exp(1j * (base[2] - start[2]))))
            velocity = np.array([base[0] - start[0], base[1] - start[1], turn]) / (steps * dt)
        # A driven base moves at its velocity, so what the hand holds feels it move (a
        # mocap base would jump, and friction would not carry a held handle along).
        self._base_velocity = velocity if self._base_joints is not None else np.zeros(3)
        for step in range(1, steps + 1):
            self._mj.mj_step(self.model, self.data)
            if base is not None:
                pose = start + velocity * step * dt
                self.set_base((float(pose[0]), float(pose[1]), float(pose[2])))
            elif self._base_joints is not None:
                self.set_base(self.base)  # at rest: held where it is
            if step % _LATCH_EVERY == 0 or step == steps:
                for name in self.doors:
                    self._follow_latch(name)
        self._base_velocity = np.zeros(3)
        if base is not None:
            self.set_base(base)

    # ------------------------------------------------------------ doors

    def door_angle(self, name: str) -> float:
        """Ground truth: how far the door's leaf has turned from shut (radians, ≥ 0)."""
        return abs(float(self.data.qpos[self._door_hinge[name]]))

    def lever_angle(self, name: str) -> float:
        """Ground truth: how far the door's most pressed lever is down (radians, ≥ 0)."""
        return max(-float(self.data.qpos[a]) for a in self._levers[name])

    def _follow_latch(self, name: str) -> None:
        """Pressed far enough, the lever draws the latch (not of a locked door); let go
        with the leaf shut, the latch snaps back in."""
        door = self.doors[name]
        if self.latched[name] and not door.locked and self.lever_angle(name) >= DOOR_UNLATCH:
            self._latch(name, False)
        elif not self.latched[name] and self.door_angle(name) < _LATCH_PLAY and \
                self.lever_angle(name) < DOOR_UNLATCH / 3:
            self._latch(name, True)

    def _latch(self, name: str, latched: bool) -> None:
        joint = self.model.joint(f"door:{name}").id
        reach = _LATCH_PLAY if latched else _DOOR_RANGE
        swing = self.doors[name].swing
        self.model.jnt_range[joint] = (0.0, reach) if swing > 0 else (-reach, 0.0)
        self.latched[name] = latched

    # ------------------------------------------------------------ measurements

    @property
    def time(self) -> float:
        """Simulated seconds since the scene was built."""
        return float(self.data.time)

    def arm_positions(self) -> np.ndarray:
        return np.array(self.data.qpos[self._arm_qpos])

    def arm_velocities(self) -> np.ndarray:
        return np.array(self.data.qvel[self._arm_dof])

    def arm_efforts(self) -> np.ndarray:
        """Joint torques the actuators apply (N·m)."""
        return np.array(self.data.qfrc_actuator[self._arm_dof])

    def torso_height(self) -> float:
        return float(self.data.qpos[self._torso_q])

    def gripper_width(self) -> float:
        """Metres between the finger pads."""
        return float(self.data.qpos[self._finger_q].sum())

    def gripper_effort(self) -> float:
        """The fingers' mean closing force (newtons; positive squeezes)."""
        return float(-np.mean(self.data.actuator_force[self._finger_act]))

    def wrist_wrench(self) -> tuple[np.ndarray, np.ndarray]:
        """Force (N) and torque (N·m) at the wrist sensor, in the sensor's frame."""
        data = self.data.sensordata
        return (np.array(data[self._force_adr:self._force_adr + 3]),
                np.array(data[self._torque_adr:self._torque_adr + 3]))

    def wrist_rotation(self) -> np.ndarray:
        """The sensor frame's orientation on the map (3×3)."""
        return np.array(self.data.site_xmat[self._ft_site]).reshape(3, 3)

    def grasp_point(self) -> np.ndarray:
        """Ground truth: where the point between the fingertips is (map frame)."""
        return np.array(self.data.site_xpos[self._grasp_site])

    def object_position(self, name: str) -> np.ndarray:
        """Ground truth: an object's centre (map frame)."""
        return np.array(self.data.xpos[self.model.body(name).id])

    def object_rotation(self, name: str) -> np.ndarray:
        return np.array(self.data.xmat[self.model.body(name).id]).reshape(3, 3)

    def door_touches(self, name: str) -> set[str]:
        """Ground truth: the robot's bodies (but the fingers) touching the door's leaf."""
        m, d = self.model, self.data
        door = {m.body(f"door:{name}").id, *(m.body(f"door:{name}:lever{k}").id
                                             for k in range(len(self.doors[name].handles)))}
        fingers = {m.body(n).id for n in ("left_finger", "right_finger", "gripper")}
        touching = set()
        for index in range(d.ncon):
            contact = d.contact[index]
            a, b = int(m.geom_bodyid[contact.geom1]), int(m.geom_bodyid[contact.geom2])
            other = b if a in door else a if b in door else -1
            if other >= 0 and other not in door and other not in fingers and \
                    int(m.body_rootid[other]) == int(m.body("base").id):
                touching.add(m.body(other).name)
        return touching

    def contacts(self) -> list[Contact]:
        """Every contact in the scene, by body, with its normal force."""
        found = []
        force = np.zeros(6)
        m, d = self.model, self.data
        for index in range(d.ncon):
            contact = d.contact[index]
            self._mj.mj_contactForce(m, d, index, force)
            found.append(Contact(m.body(m.geom_bodyid[contact.geom1]).name,
                                 m.body(m.geom_bodyid[contact.geom2]).name,
                                 (float(contact.pos[0]), float(contact.pos[1]),
                                  float(contact.pos[2])), float(force[0])))
        return found

    def touching_fingers(self, name: str) -> int:
        """Ground truth: how many finger pads touch object ``name`` (0, 1 or 2)."""
        geom = self.model.geom(name).id
        pads = set()
        for index in range(self.data.ncon):
            contact = self.data.contact[index]
            pair = {contact.geom1, contact.geom2}
            if geom in pair:
                pads |= pair & self._pads
        return len(pads)

    def held_object(self) -> str | None:
        """Ground truth: the object both fingers touch, if any."""
        for name in self.objects:
            if self.touching_fingers(name) == 2:
                return name
        return None

    def relative_to_grasp(self, name: str) -> np.ndarray:
        """An object's pose in the grasp site's frame, 4×4 (to carry it into another scene)."""
        site = np.array(self.data.site_xmat[self._grasp_site]).reshape(3, 3)
        relative = np.eye(4)
        relative[:3, :3] = site.T @ self.object_rotation(name)
        relative[:3, 3] = site.T @ (self.object_position(name) - self.grasp_point())
        return relative

    def _put_in_gripper(self, obj: ObjectBody, relative: np.ndarray) -> None:
        site = np.array(self.data.site_xmat[self._grasp_site]).reshape(3, 3)
        position = self.grasp_point() + site @ relative[:3, 3]
        joint = self.model.joint(f"{obj.name}:free")
        address = int(self.model.jnt_qposadr[joint.id])
        quat = np.zeros(4)
        self._mj.mju_mat2Quat(quat, (site @ relative[:3, :3]).flatten())
        self.data.qpos[address:address + 3] = position
        self.data.qpos[address + 3:address + 7] = quat
        self._mj.mj_forward(self.model, self.data)


def _add_door(mujoco: Any, spec: Any, door: DoorLeaf) -> None:
    """The leaf on its hinge and the levers on their pivots, into ``spec``."""
    body = spec.worldbody.add_body(name=f"door:{door.name}", pos=[*door.hinge, 0.0],
                                   quat=list(quaternion_from_yaw(door.yaw)))
    body.add_joint(name=f"door:{door.name}", type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1],
                   range=[0.0, _DOOR_RANGE] if door.swing > 0 else [-_DOOR_RANGE, 0.0],
                   frictionloss=door.friction, damping=door.damping, armature=0.1)
    body.add_geom(name=f"door:{door.name}", type=mujoco.mjtGeom.mjGEOM_BOX,
                  size=[door.length / 2, door.thickness / 2, (door.height - _UNDER_DOOR) / 2],
                  pos=[door.length / 2, 0.0, (door.height + _UNDER_DOOR) / 2], mass=12.0,
                  contype=_WORLD_CONTYPE, conaffinity=_WORLD_CONAFFINITY,
                  rgba=[0.75, 0.66, 0.52, 1.0])
    c, s = np.cos(door.yaw), np.sin(door.yaw)
    length, depth, height = door.handle_size
    for k, (x, y, z) in enumerate(door.handles):
        dx, dy = x - door.hinge[0], y - door.hinge[1]
        local = (c * dx + s * dy, -s * dx + c * dy)
        pivot = local[0] + length / 2 - _LEVER_PIVOT_IN
        lever = body.add_body(name=f"door:{door.name}:lever{k}", pos=[pivot, local[1], z],
                              gravcomp=1.0)  # its spring holds it level
        # about the leaf's normal; negative turns the lever's free end (towards the hinge) down
        lever.add_joint(name=f"door:{door.name}:lever{k}", type=mujoco.mjtJoint.mjJNT_HINGE,
                        axis=[0, 1, 0], range=[-_LEVER_TRAVEL, 0.0], stiffness=_LEVER_SPRING,
                        damping=0.05, armature=0.002)
        lever.add_geom(name=f"door:{door.name}:lever{k}", type=mujoco.mjtGeom.mjGEOM_BOX,
                       size=[length / 2, depth / 2, height / 2],
                       pos=[-(length / 2 - _LEVER_PIVOT_IN), 0.0, 0.0], mass=0.2,
                       friction=[1.5, 0.02, 0.002], condim=4,
                       contype=_WORLD_CONTYPE, conaffinity=_WORLD_CONAFFINITY,
                       rgba=[0.69, 0.69, 0.71, 1.0])


def drive_base(mujoco: Any, spec: Any) -> None:
    """Turn ``spec``'s mocap base into a body on three joints (x, y, yaw) that the scene
    drives kinematically; heavy (armature), so what the arm does within one physics step
    hardly moves it, and it never touches the floor it stands on."""
    base = spec.body("base")
    if base is None:
        raise ValueError("no body named 'base' (the robot's arm.xml is not included)")
    base.mocap = False
    heavy = 1.0e4
    base.add_joint(name="base_x", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[1, 0, 0],
                   armature=heavy)
    base.add_joint(name="base_y", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0, 1, 0],
                   armature=heavy)
    base.add_joint(name="base_yaw", type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1],
                   armature=heavy)
    spec.add_exclude(bodyname1="world", bodyname2="base")
