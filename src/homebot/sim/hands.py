"""The arm's drivers over ``ArmSimulation``: the ``Arm`` and ``Gripper`` parts of the Body port.

``ArmDriver`` ticks the physics in control periods and offers what real drivers would:
joint states, position targets (with optional torques), the gripper, the wrist's wrench.
``SimBody`` fits one for the placement the robot stands at; benchmarks use one alone.
``world_scene`` turns the world's placements and catalogue into the physics scene.
"""

from __future__ import annotations

import zlib
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from homebot.robot import Arm, ArmState, Gripper, GripperState, JointTarget, Wrench
from homebot.sim.arm import (
    ARM_JOINTS,
    HOME,
    MAX_GRIPPER_WIDTH,
    ArmSimulation,
    DoorLeaf,
    ObjectBody,
    SurfaceBox,
)
from homebot.sim.camera import door_solids, object_yaw
from homebot.sim.hearing import PeopleHearing
from homebot.sim.simulation import HAND_PREFIX, PERSON_PREFIX
from homebot.world import DoorState, World, catalogue_entry, surface_height

__all__ = ["DOOR_SWUNG_OPEN", "PAYLOAD", "ArmDriver", "SimHands", "door_leaf", "object_body",
           "world_scene"]

#: radians a leaf the arm swings must turn for the door to count as open (passable)
DOOR_SWUNG_OPEN = 1.2

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


def door_leaf(world: World, door: str, *, locked: bool = False) -> DoorLeaf:
    """The shut ``door``'s leaf as physics has it: where the camera draws it
    (``door_solids``), hinged on the world's jamb (``World.door_hinge_direction``),
    turning into the room the world file says it swings into (its first room unless
    ``swings_into`` says)."""
    leaf, *handles = door_solids(world, door)
    model = world.doors[door]
    hinge_x, hinge_y = world.door_hinge_direction(door)
    half = model.width / 2
    hinge = (model.position[0] + hinge_x * half, model.position[1] + hinge_y * half)
    into = world.point_before_door(door, model.swings_into or model.rooms[0], 1.0)
    normal = (into.x - model.position[0], into.y - model.position[1])
    # turning the hinge-to-latch direction counter-clockwise moves it along its left normal
    left = (hinge_y, -hinge_x)  # the left normal of (-hinge_x, -hinge_y)
    swing = 1.0 if left[0] * normal[0] + left[1] * normal[1] > 0 else -1.0
    return DoorLeaf(door, hinge, leaf.yaw, model.width - (model.width - leaf.extent[0]) / 2,
                    leaf.extent[1], leaf.extent[2],
                    tuple((h.x, h.y, h.z + h.extent[2] / 2) for h in handles),
                    (handles[0].extent[0], handles[0].extent[1], handles[0].extent[2]),
                    swing, locked)


def world_scene(world: World, placements: Iterable[str],
                positions: Mapping[str, tuple[str, tuple[float, float]]], seed: int = 0,
                headings: Mapping[str, float] | None = None
                ) -> tuple[list[SurfaceBox], list[ObjectBody]]:
    """The surfaces of ``placements`` and the objects on them.

    ``positions`` maps each object standing on one of them to (placement, (x, y)); objects
    stand turned as the camera draws them (``object_yaw`` with the run's ``seed``) unless
    ``headings`` says how physics left them.
    """
    headings = headings or {}
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
                objects.append(object_body(world, obj, xy, height,
                                           headings.get(obj, object_yaw(obj, seed))))
    return surfaces, objects



#: metres from the robot's centre within which a surface is part of the arm's scene
_SCENE_REACH = 1.4
_HELD_RISE = 0.02  #: metres above its resting height for a held object to count as lifted
_AT_REST = 0.02  #: m/s: an object slower than this has come to rest
_SETTLE_LIMIT = 3.0  #: seconds of physics for objects to come to rest when the robot leaves
_SETTLE_STEP = 0.1
_PERSON_REACH = 0.9  #: metres from where a person stands to a hand they reach into
_OPEN_ENOUGH = 0.05  #: metres between the fingers for a person to put something in
_STILL = 0.2  #: rad/s over the joints: the arm has stopped moving
_DOOR_REACH = 1.5  #: metres from the robot to a shut door's middle for its leaf to be in the scene
#: metres the base may drive, a door's leaf in the scene, before the scene is built anew
_DOOR_WORK = 1.2


class SimHands:
    """The arm of a ``SimBody``: a physics scene around where the robot stands, kept in
    step with the simulation's truth.

    The scene is built on first use at the robot's true pose, from the surfaces within
    reach and the objects the truth has on them, and the leaves of the shut doors near it
    (``door_leaf``). It steps with the body's ticks while the base stands still; when the
    base moves, physics pauses (the arm and what it holds ride along) and the next use
    rebuilds the scene where the robot then stands; but with a door's leaf in the scene and
    no object in the hand, physics goes on with the base driven, within ``_DOOR_WORK`` of
    where it was built (the hand may hold the door's handle). A leaf swung open past
    ``DOOR_SWUNG_OPEN`` opens the door in the truth. After every step the truth follows
    physics: an object lifted between both fingers is in a hand, an object that came to
    rest on a surface is on that placement, one on the floor is on the floor of its room.

    Args:
        simulation: the truth.
        tick_period: the body's control period.
        model_path: the arm's MJCF file (default: homebot's).
    """

    def __init__(self, simulation: Any, tick_period: float,
                 model_path: Path | None = None, hearing: PeopleHearing | None = None) -> None:
        self.simulation = simulation
        self.tick_period = tick_period
        self.model_path = model_path
        #: what people were asked: to take what the robot holds out, to put something in
        #: its hand (None: nobody hands anything over)
        self.hearing = hearing
        #: the person pulling at what the robot holds out, and what they pull at
        self._taker: tuple[str, str] | None = None
        #: seconds the hand has stood held out near the person who is to take from it
        self._held_out = 0.0
        self._driver: ArmDriver | None = None
        self._base: tuple[float, float, float] | None = None
        self._built_at: tuple[float, float, float] | None = None
        self._touching_doors: set[str] = set()  #: leaves the robot's body touches now
        self._arm: tuple[float, ...] = HOME
        self._torso = 0.2
        self._gripper = MAX_GRIPPER_WIDTH
        self._grip: tuple[float, float | None] = (MAX_GRIPPER_WIDTH, None)
        self._held: tuple[ObjectBody, np.ndarray] | None = None
        self._surfaces: dict[str, SurfaceBox] = {}
        self._gone: set[str] = set()
        #: what a person holds out into the open hand until both fingers touch it, and who
        self._handing: str | None = None
        self._giver: str | None = None
        #: how objects physics moved stand turned now (radians, map frame)
        self.headings: dict[str, float] = {}

    def driver(self) -> ArmDriver:
        """The arm's drivers where the robot stands now (built when it has moved)."""
        pose = tuple(self.simulation.robot_pose)
        if self._driver is not None and pose != self._base and self._at_the_door(pose):
            self._driver.sim.set_base((float(pose[0]), float(pose[1]), float(pose[2])))
            self._base = (float(pose[0]), float(pose[1]), float(pose[2]))
        if self._driver is None or pose != self._base:
            self._build((float(pose[0]), float(pose[1]), float(pose[2])))
        assert self._driver is not None
        return self._driver

    def _at_the_door(self, pose: tuple[float, ...]) -> bool:
        """Whether the scene has a door's leaf, the hand holds no object and the base is
        still by where the scene was built: physics goes on with the base driven (the hand
        may hold a handle). What a hand holds rides along with the base, as anywhere else:
        a robot that picked something by a shut door and drove off shook it out of its
        fingers."""
        return self._driver is not None and bool(self._driver.sim.doors) and \
            self._driver.sim.held_object() is None and self._built_at is not None and \
            float(np.hypot(pose[0] - self._built_at[0], pose[1] - self._built_at[1])) < \
            _DOOR_WORK

    def advance(self, seconds: float) -> None:
        """Physics for ``seconds`` while the base stands where the scene was built."""
        if self._driver is None:
            return
        pose = tuple(float(v) for v in self.simulation.robot_pose)
        moving_to: tuple[float, float, float] | None = None
        if pose != self._base:
            if not self._at_the_door(pose):
                self._leave()
                return
            moving_to = (pose[0], pose[1], pose[2])
        if self._handing is None and self._giving() is not None:
            where = moving_to or self._base
            assert where is not None
            self._build(where)  # the person's object comes into the scene, in their hand
            moving_to = None
        assert self._driver is not None
        sim = self._driver.sim
        handing = self._handing
        if handing is not None:
            # The person's hand keeps it there, bearing its weight, until the robot's
            # fingers both touch it; then it lets go.
            sim.hold_at_grasp(handing)
            sim.push(handing, -sim.objects[handing].mass * sim.model.opt.gravity)
        pulled = self._pull(seconds)
        sim.step(seconds, base=moving_to)
        if moving_to is not None:
            self._base = moving_to
        self._doors_follow_physics()
        if handing is not None and sim.touching_fingers(handing) == 2:
            sim.push(handing, (0.0, 0.0, 0.0))
            self._let_go_into_hand(handing)
        if pulled is not None and sim.touching_fingers(pulled) < 2:
            self._taken(pulled)  # out of the fingers (they opened, or it was pulled out)
        self._follow_physics()

    # ------------------------------------------------------------ building

    def _leave(self) -> None:
        """The robot drives off: what is falling or rolling behind it comes to rest (up to
        ``_SETTLE_LIMIT`` s more of physics); the truth takes every object as it then lies."""
        assert self._driver is not None
        sim = self._driver.sim
        if self._handing is not None:  # driven off before closing the hand: they keep it
            self._take_away(self._handing)
            self._handing = self._giver = None
        if self._taker is not None:  # driven off before letting go: they let go of it
            self._driver.sim.push(self._taker[1], (0.0, 0.0, 0.0))
            self._taker = None
        held = sim.held_object()
        for _ in range(round(_SETTLE_LIMIT / _SETTLE_STEP)):
            if all(self._resting(name) for name in sim.objects
                   if name != held and name not in self._gone):
                break
            sim.step(_SETTLE_STEP)
        self._follow_physics(final=True)
        self._remember()
        self._driver = None

    def _remember(self) -> None:
        """Keep the arm's state and what its fingers hold for the next scene."""
        if self._driver is None:
            return
        sim = self._driver.sim
        self._arm = tuple(float(v) for v in sim.arm_positions())
        self._torso = sim.torso_height()
        self._gripper = sim.gripper_width()
        self._grip = sim.gripper_command
        held = sim.held_object()
        self._held = (sim.objects[held], sim.relative_to_grasp(held)) if held else None

    def _build(self, pose: tuple[float, float, float]) -> None:
        self._remember()
        truth = self.simulation
        world = truth.world
        near = [name for name, placement in world.placements.items()
                if placement.footprint.distance(_point(pose[:2])) < _SCENE_REACH]
        positions = {obj: (where, truth.position_on(obj, where))
                     for obj, where in truth.object_location.items() if where in near}
        surfaces, objects = world_scene(world, near, positions, truth.seed, self.headings)
        self._surfaces = {s.name: s for s in surfaces}
        holding = {name for name in truth.hands.values() if name}
        held = self._held if self._held is not None and self._held[0].name in holding \
            else None
        # What a person was asked for and holds: they put it into the open hand.
        giving = self._giving()
        handed = [giving[1]] if giving is not None and held is None else []
        objects += [object_body(world, name, pose[:2], 0.0) for name in handed]
        # Shut doors near the robot: their leaves on their hinges, latched (a door the arm
        # left ajar short of open fell shut: the truth keeps it shut).
        doors = [door_leaf(world, name, locked=state is DoorState.LOCKED)
                 for name, state in sorted(truth.door_state.items())
                 if state is not DoorState.OPEN and
                 _point(pose[:2]).distance(_point(world.doors[name].position)) < _DOOR_REACH]
        sim = ArmSimulation(base=pose, surfaces=surfaces, objects=objects,
                            model_path=self.model_path, arm=self._arm, torso=self._torso,
                            gripper=self._gripper if held or handed else MAX_GRIPPER_WIDTH,
                            held=held, grip=self._grip if held or handed else None,
                            doors=doors)
        self._handing = handed[0] if handed else None
        self._giver = giving[0] if handed and giving is not None else None
        if self._handing is not None:
            sim.hold_at_grasp(self._handing)
            truth.events.record("sim.person", person=self._giver, did="holds out",
                                object=self._handing)
        self._driver = ArmDriver(sim, self.tick_period, start=truth.clock.now())
        self._base = pose
        self._built_at = pose
        self._gone = set()

    # ------------------------------------------------------------ people handing over

    def _giving(self) -> tuple[str, str] | None:
        """(person, object) when a person asked to put something in the robot's hand holds
        it, stands within reach of the hand and the hand is open and empty."""
        hearing = self.hearing
        if hearing is None or hearing.asked_to_give is None or self._driver is None:
            return None
        person, wanted = hearing.asked_to_give
        truth = self.simulation
        state = truth.people.get(person)
        owned = sorted(name for name, where in truth.object_location.items()
                       if where == PERSON_PREFIX + person)
        if state is None or not owned or any(truth.hands.values()):
            return None
        sim = self._driver.sim
        if sim.gripper_width() < _OPEN_ENOUGH or sim.held_object() is not None or \
                _reach(state.position, sim.grasp_point()) > _PERSON_REACH:
            return None
        return person, wanted if wanted in owned else owned[0]

    def _let_go_into_hand(self, name: str) -> None:
        """Both fingers touch what the person holds out: they let go; it is the robot's."""
        self._into_free_hand(name)
        self.simulation.events.record("sim.person", person=self._giver, did="let go",
                                      object=name)
        if self.hearing is not None:
            self.hearing.asked_to_give = None
        self._handing = self._giver = None

    def _into_free_hand(self, name: str) -> str | None:
        """The truth has ``name`` in the robot's first free hand; which (None: both full)."""
        truth = self.simulation
        free: list[str] = [hand for hand, held in truth.hands.items() if held is None]
        if not free:
            return None
        truth.hands[free[0]] = name
        truth.handled.add(name)
        truth.object_location[name] = HAND_PREFIX + free[0]
        return free[0]

    def _pull(self, seconds: float) -> str | None:
        """The person the robot hands something to pulls at it once the hand has stood
        held out within their reach a moment; the object pulled, if any."""
        assert self._driver is not None
        sim, truth, hearing = self._driver.sim, self.simulation, self.hearing
        # once they have hold of it, they keep it, whatever the fingers do
        held = self._taker[1] if self._taker is not None else sim.held_object()
        taker = hearing.asked_to_take if hearing is not None else None
        state = truth.people.get(taker or "")
        hand = sim.grasp_point()
        moving = self._taker is None and float(np.linalg.norm(sim.arm_velocities())) > _STILL
        if held is None or taker is None or state is None or moving or \
                _reach(state.position, hand) > _PERSON_REACH:
            self._held_out = 0.0
            if self._taker is not None:
                sim.push(self._taker[1], (0.0, 0.0, 0.0))
                self._taker = None
            return None
        self._held_out += seconds
        rng = np.random.default_rng([truth.seed, zlib.crc32(taker.encode()), 909])
        delay, strength = float(rng.uniform(0.3, 1.5)), float(rng.uniform(6.0, 14.0))
        if self._held_out < delay:
            return None
        towards = np.array([state.position[0] - hand[0], state.position[1] - hand[1], 0.0])
        towards /= max(float(np.linalg.norm(towards)), 1e-6)
        # they take its weight and pull it towards them, harder over half a second
        ramp = min(1.0, (self._held_out - delay) / 0.5)
        weight = -sim.objects[held].mass * sim.model.opt.gravity
        sim.push(held, weight + ramp * strength * towards)
        self._taker = (taker, held)
        return held

    def _taken(self, name: str) -> None:
        """The person the robot let go to has ``name``: it leaves the robot's scene."""
        assert self._taker is not None
        truth = self.simulation
        person = self._taker[0]
        for hand, held in truth.hands.items():
            if held == name:
                truth.hands[hand] = None
        truth.object_location[name] = PERSON_PREFIX + person
        truth.events.record("sim.person", person=person, did="took", object=name)
        self._taker = None
        self._held_out = 0.0
        if self.hearing is not None:
            self.hearing.asked_to_take = None
        self._take_away(name)

    # ------------------------------------------------------------ truth follows physics

    def _doors_follow_physics(self) -> None:
        """A leaf swung past ``DOOR_SWUNG_OPEN`` makes its door open in the truth (it then
        lets the robot through), its leaf no longer where the world file stands an open one
        but out of the doorway (``Simulation.open_wide``: the truth knows no leaf
        angles between); the robot's body (not its hand) touching a leaf is a collision."""
        assert self._driver is not None
        sim, truth = self._driver.sim, self.simulation
        for name in sim.doors:
            if truth.door_state.get(name) is DoorState.CLOSED and \
                    sim.door_angle(name) >= DOOR_SWUNG_OPEN:
                truth.open_wide(name)
                truth.events.record("sim.door", door=name, what="swung open",
                                    degrees=round(float(np.degrees(sim.door_angle(name))), 1))
            touching = sim.door_touches(name)
            touched_before = name in self._touching_doors
            self._touching_doors.discard(name)
            if touching:
                self._touching_doors.add(name)
            if touching and not touched_before:  # one touch is one collision
                x, y, _ = sim.base
                truth.collisions.append({"time": round(truth.clock.now(), 3),
                                         "with": f"door {name}", "by": sorted(touching),
                                         "at": [round(x, 3), round(y, 3)]})

    def _follow_physics(self, final: bool = False) -> None:
        assert self._driver is not None
        sim, truth = self._driver.sim, self.simulation
        in_hand = {name: hand for hand, name in truth.hands.items() if name}
        for name, body in sim.objects.items():
            if name == self._handing:
                continue  # still in the person's hand
            where = truth.object_location.get(name)
            if name in self._gone or not (where is None or where in truth.world.placements or
                                          where.startswith((HAND_PREFIX, "floor:"))):
                self._take_away(name)  # someone took it (a person): it leaves the scene
                continue
            position = sim.object_position(name)
            gripped = sim.touching_fingers(name) == 2
            rest = body.base + body.extents[2] / 2
            if gripped and position[2] > rest + _HELD_RISE and name not in in_hand:
                hand = self._into_free_hand(name)
                if hand is not None:
                    truth.events.record("sim.arm", what="lifted", object=name, hand=hand)
                continue
            if gripped or not (final or self._resting(name)):
                continue
            where = self._surface_under(position, body)
            xy = (round(float(position[0]), 4), round(float(position[1]), 4))
            if name in in_hand:
                truth.hands[in_hand[name]] = None
            location = where or f"floor:{truth.world.room_at(*xy)}"
            if truth.object_location.get(name) != location or \
                    truth.object_position.get(name) != xy:
                if truth.object_location.get(name) != location:
                    truth.events.record("sim.arm", what="put down", object=name, on=location)
                truth.object_location[name] = location
                truth.object_position[name] = xy
                turn = sim.object_rotation(name)
                self.headings[name] = float(np.arctan2(turn[1, 0], turn[0, 0]))

    def heading(self, name: str) -> float:
        """How the object stands turned (radians): as physics left it, else as it started."""
        return self.headings.get(name, object_yaw(name, self.simulation.seed))

    def _take_away(self, name: str) -> None:
        assert self._driver is not None
        if name in self._gone:
            return
        self._gone.add(name)
        sim = self._driver.sim
        joint = sim.model.joint(f"{name}:free")
        address = int(sim.model.jnt_qposadr[joint.id])
        far = 100.0 + 2.0 * len(self._gone)
        sim.data.qpos[address:address + 3] = (far, far, 0.5)
        sim.data.qvel[int(sim.model.jnt_dofadr[joint.id]):][:6] = 0.0

    def _resting(self, name: str) -> bool:
        assert self._driver is not None
        sim = self._driver.sim
        joint = sim.model.joint(f"{name}:free")
        address = int(sim.model.jnt_dofadr[joint.id])
        return float(np.linalg.norm(sim.data.qvel[address:address + 3])) < _AT_REST

    def _surface_under(self, position: np.ndarray, body: ObjectBody) -> str | None:
        for surface in self._surfaces.values():
            inside = abs(position[0] - surface.center[0]) <= surface.size[0] / 2 and \
                abs(position[1] - surface.center[1]) <= surface.size[1] / 2
            if inside and position[2] >= surface.height:
                return surface.name
        return None


def _point(xy: tuple[float, ...]) -> Any:
    from shapely.geometry import Point

    return Point(xy)


def _reach(person: tuple[float, float], hand: np.ndarray) -> float:
    """Metres from where a person stands to the hand, on the floor plan."""
    return float(np.hypot(hand[0] - person[0], hand[1] - person[1]))
