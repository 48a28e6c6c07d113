"""Watering a plant with a can (Cosero §6.4.3): approach the pot, pour over it, tip back.

The robot holds a watering can by its handle, a tool adapter in Cosero's manner whose
lips close round the fingers (Cosero grasps a known can at a predefined reference pose;
here the can starts in the hand). It stands where navigation left it, at a seeded pose
6–15 cm short of the pouring pose, up to 6 cm to the side and 2.6° turned; it sees the
pot with its torso laser (``homebot.perception.plant_pot``: the rim's height and a circle
fitted to the wall below it), drives the rest of the way to where the level can's spout
is above the pot (the can itself beside it; a sweep twice a second, odometry between),
looks once more, and runs
the pouring primitive (``homebot.manipulation.tools.WateringMotion``): the spout held
15 cm above the pot's rim while the wrist rolls the can about it. The water is a model over the
physics' truth: it runs from the spout while the can is tipped more than 20° (up to
0.25 L/s) and lands below the spout's true tip; it waters the plant when that is inside
the pot. Success: at least 0.3 L in the pot, at most 0.03 L spilled, the can still in the
hand.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np
from rich.console import Console

from homebot.errors import SceneError
from homebot.geometry import quaternion_from_yaw
from homebot.scenarios.running import RunBuilder
from homebot.scenarios.summary import scenario_summary

__all__ = ["add_arguments", "pour", "run"]

_CAN = (0.0, 0.21, -0.015)  #: the spout's tip in the hand frame (the can's model and grasp)
_HAND = np.array([0.6, 0.0, 0.95])  #: where the hand carries the can, base frame
_WATER = 1.0  #: litres in the can
_POT_RADIUS = 0.09  #: inside the rim
_FLOWING = math.radians(20.0)
_FULL_FLOW = 0.25  #: litres per second
_STREAM = 1864
_SWEEP_EVERY = 50  #: control ticks between the laser's sweeps while driving (0.5 s)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    del parser  # --seed and --json only


def pour(seed: int) -> dict[str, Any]:
    """One watering, judged on the physics' truth; the figures the scenario prints."""
    from homebot.manipulation.compliance import Compliance, ComplianceController
    from homebot.manipulation.interaction import Command, to_base, to_odometry
    from homebot.manipulation.tools import PourPhase, Tool, WateringMotion, approach_offset
    from homebot.perception.plant_pot import PotScan
    from homebot.robot import Twist
    from homebot.sim.hri import InteractionScene
    from homebot.trials.interaction import BaseDrive, apply, reach, reading

    rng = np.random.default_rng([seed, _STREAM])
    scene = InteractionScene("watering", sensor_seed=seed)
    q = reach(scene, _HAND, np.eye(3), np.array([0.0, 1.2, 0.0, -1.9, 0.0, 0.7, 0.0]))
    scene.set_arm(q, torso=0.0, gripper=0.07)
    tool = Tool("watering can", _CAN, axis=(-1.0, 0.0, 0.0))  # the wrist rolls
    pot_world = np.asarray(scene.data.site("pot_rim").xpos, dtype=float).copy()
    offset = approach_offset(tool, _HAND)
    back, side = rng.uniform(0.06, 0.15), rng.uniform(-0.06, 0.06)
    turn = rng.uniform(-0.045, 0.045)
    start = (float(pot_world[0] - offset[0] - back), float(pot_world[1] + side), float(turn))
    scene.move_base(*start)
    scene.step()
    scene.set_arm(q, gripper=0.03)  # the fingers on the handle's sides
    scene.place_body("can", scene.hand_world(), quaternion_from_yaw(start[2]))
    scene.grip(True)
    held = reading(scene)
    controller = ComplianceController(Compliance(), held.hand_position, held.hand_rotation,
                                      rest=q)
    hold = Command(held.hand_position, held.hand_rotation, Compliance(), gripper_closed=True)
    for _ in range(50):
        apply(scene, controller, hold)
        scene.step()

    sweep = PotScan()

    def look() -> np.ndarray:
        """The pot's rim in the odometry frame, from a sweep of the torso laser."""
        torso = scene.torso_height()
        seen = sweep.find(torso, scene.laser(sweep.mount(torso), sweep.directions()))
        if seen is None:
            raise SceneError(f"{scene.path}: the torso laser sees no pot within "
                             f"{sweep.reach} m in front of the robot; put the pot in front "
                             "of it")
        return to_odometry(scene.base_pose(), seen.rim)

    def seen_pot() -> np.ndarray:
        return to_base(scene.base_pose(), rim)

    rim = look()
    # Drive to where the pot is at the offset (facing it), steering on what it sees: a
    # sweep twice a second, odometry in between.
    base = BaseDrive(scene, speed=0.25, turn=0.3, acceleration=0.3, angular_acceleration=0.5)
    driven, ticks = 0.0, 0
    while driven < 20.0:
        if ticks % _SWEEP_EVERY == 0 and ticks:
            rim = look()
        ticks += 1
        pot = seen_pot()
        error = pot[:2] - offset
        heading = math.atan2(pot[1], pot[0]) - math.atan2(offset[1], offset[0])
        if math.hypot(*error) < 0.01 and abs(heading) < 0.02:
            break
        base.drive(Twist(1.5 * float(error[0]), 1.5 * float(error[1]), 1.5 * heading),
                   scene.control_period)
        apply(scene, controller, hold)
        scene.step()
        driven += scene.control_period
    while math.hypot(base.velocity.vx, base.velocity.vy) > 1e-3 or abs(base.velocity.wz) > 1e-3:
        base.drive(Twist(), scene.control_period)
        apply(scene, controller, hold)
        scene.step()
    rim = look()  # standing: one more look before pouring
    motion = WateringMotion(tool, held.hand_position, held.hand_rotation, seen_pot(),
                            clearance=0.15)
    watered = spilled = 0.0
    left = _WATER
    worst_tilt = 0.0
    while motion.phase is not PourPhase.DONE and scene.time < 60.0:
        target, rotation = motion.update(scene.control_period)
        apply(scene, controller, Command(target, rotation, Compliance(), gripper_closed=True))
        scene.step()
        can = scene.body_rotation("can")
        tilt = math.asin(max(-1.0, min(1.0, -float(can[2, 1]))))  # spout down: positive
        worst_tilt = max(worst_tilt, tilt)
        if tilt > _FLOWING and left > 0:
            flow = min(left, _FULL_FLOW * min(1.0, (tilt - _FLOWING) / _FLOWING)
                       * scene.control_period)
            left -= flow
            tip = np.asarray(scene.data.site("spout_tip").xpos)
            if math.dist(tip[:2], pot_world[:2]) <= _POT_RADIUS:
                watered += flow
            else:
                spilled += flow
    # Truth: the handle still sits between the fingers (its centre within the pads' reach).
    slipped = scene.to_base(scene.body_position("can")) - scene.to_base(scene.hand_world())
    in_hand = abs(float(slipped[1])) < 0.03 and abs(float(slipped[2])) < 0.03 and \
        -0.045 < float(slipped[0]) < 0.03
    success = watered >= 0.3 and spilled <= 0.03 and in_hand and \
        motion.phase is PourPhase.DONE
    return {"success": success, "watered_l": round(watered, 3), "spilled_l": round(spilled, 3),
            "can_in_hand": in_hand,
            "handle_slip_m": [round(float(v), 3) for v in slipped],
            "tipped_deg": round(math.degrees(worst_tilt), 1),
            "drove_s": round(driven, 2), "start": [round(v, 3) for v in start],
            "seconds": round(scene.time, 2)}


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Water the plant; print what happened."""
    figures = pour(args.seed)
    success = figures.pop("success")
    speech = ["I will water the plant.",
              "The plant is watered." if success else "I could not water the plant properly."]
    if console is not None:
        console.print(f"drove {figures['drove_s']} s to the pot, tipped the can to "
                      f"{figures['tipped_deg']}°: {figures['watered_l']} L in the pot, "
                      f"{figures['spilled_l']} L spilled"
                      f"{'' if figures['can_in_hand'] else '; the can slipped from the hand'}")
        console.print(speech[-1])
    actions = [{"skill": "approach", "args": {"to": "pot"}, "status": "finished"},
               {"skill": "pour", "args": {"tool": "watering can"},
                "status": "verified" if success else "aborted"}]
    return scenario_summary("water_plant", success, actions, speech, **figures)
