"""Skills that move the robot: navigate, follow, guide, open_door."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from homebot.geometry import Pose
from homebot.robot import Blocker, MoveReport
from homebot.skills.places import (
    HANDING_REACH,
    OPERATOR,
    near,
    person_name,
    resolve_target,
    sees_person_nearby,
    target_label,
)
from homebot.skills.skill import ErrorCode, Outcome, Skill, SkillContext, Status, speak
from homebot.skills.wording import arrived, the

__all__ = ["Follow", "Guide", "Navigate", "OpenDoor", "drive", "drive_to_target"]


def drive(context: SkillContext, goal: Pose, escort: str | None = None) -> Outcome:
    """Drive to ``goal``, around doors believed shut when there is a way round.

    When every route crosses a door believed shut, drive through one anyway: the
    robot port stops at the first shut door and reports ``DOOR_CLOSED``, so the
    door protocol (open it, ask someone, go round) runs there. This lives here,
    in the skill layer, so every Robot implementation gets it from the same
    ``move_to(goal, avoid_doors)`` contract.
    """
    closed = frozenset(context.beliefs.closed_doors)
    report = context.robot.move_to(goal, closed, escort, cancel=context.cancel)
    if not report.reached and report.blocker is Blocker.NO_PATH and closed:
        context.events.record("motion.through_closed_doors", doors=sorted(closed))
        report = context.robot.move_to(goal, frozenset(), escort, cancel=context.cancel)
    return _motion_outcome(context, report)


def drive_to_target(context: SkillContext, target: str) -> Outcome | None:
    """Drive to the named ``target`` (a place or person); the motion's outcome when it
    did not get there, else None (also when the target has no pose to drive to)."""
    goal = resolve_target(context, target)
    moved = drive(context, goal) if goal else None
    if moved is not None and moved.status is not Status.FINISHED:
        return moved
    return None


def _motion_outcome(context: SkillContext, report: MoveReport) -> Outcome:
    if report.reached:
        return Outcome.finished(f"moved {report.distance:.1f} m", distance=report.distance)
    if report.blocker is Blocker.CANCELLED:
        return Outcome.cancelled(context.cancel)
    if report.blocker is Blocker.STOPPED:
        return Outcome.failed(ErrorCode.STOPPED, f"{report.person or 'someone'} showed me to "
                              "stop", person=report.person)
    if report.blocker is Blocker.DOOR_CLOSED and report.door:
        context.beliefs.door_closed(report.door)
        return Outcome.failed(ErrorCode.DOOR_CLOSED, f"the {report.door} is closed",
                              door=report.door)
    if report.blocker is Blocker.PERSON and report.door:
        return Outcome.failed(ErrorCode.PATH_BLOCKED,
                              f"{report.person or 'someone'} is standing in the {report.door}",
                              door=report.door, person=report.person, someone=True)
    if report.blocker is Blocker.PERSON:
        return Outcome.failed(ErrorCode.PATH_BLOCKED,
                              f"{report.person or 'someone'} is standing in my way",
                              person=report.person, someone=True)
    if report.blocker is Blocker.OBSTRUCTED:
        return Outcome.failed(ErrorCode.PATH_BLOCKED, "something I cannot get past is in my way")
    return Outcome.failed(ErrorCode.NO_PATH, "there is no way there with the doors I know of")


class Navigate(Skill):
    """Drive to a placement, room, person, ``operator`` or door, or to a point goal
    ``[x, y]`` / ``{x: X, y: Y}`` (metres, map frame).

    Preconditions: the target is known. Effects: the robot stands at the target's
    pose. Monitor: localisation says the robot is within 0.3 m of the goal.
    """

    name = "navigate"
    required = ("to",)
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        goal = resolve_target(context, args["to"])
        if goal is None:
            return Outcome.failed(ErrorCode.UNKNOWN_TARGET,
                                  f"I do not know where {target_label(args['to'])} is")
        outcome = drive(context, goal)
        person = person_name(context, args["to"]) if isinstance(args["to"], str) else None
        if outcome.error is ErrorCode.PATH_BLOCKED and person is not None and \
                outcome.data.get("person") == person and \
                sees_person_nearby(context, person, HANDING_REACH):
            # the one in the way is the one the robot came to: it is with them
            return Outcome.finished(f"I am with {person}", goal=context.robot.pose())
        if outcome.status is not Status.FINISHED:
            return outcome
        return Outcome.finished(outcome.message, goal=goal)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        goal = finished.data["goal"]
        if near(context, goal):
            target = args["to"]
            said = arrived(context.world, target, operator=target == OPERATOR) if isinstance(
                target, str) else f"I am at {target_label(target)}"
            return Outcome.verified(said)
        return Outcome.aborted(ErrorCode.NOT_REACHED,
                               f"I did not get to {target_label(args['to'])}")


class Follow(Skill):
    """Follow the person last found (to a room, when told where they go).

    Monitor: the person is seen within reach when they stop.
    """

    name = "follow"
    optional = ("to", "person")
    retries = 1  # a person missed by one look is usually seen by the next

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        person = person_name(context, args.get("person"))
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I have nobody to follow")
        goal = resolve_target(context, str(args["to"])) if args.get("to") else None
        report = context.robot.follow(person, goal, cancel=context.cancel)
        if report.blocker is Blocker.CANCELLED:
            return Outcome.cancelled(context.cancel)
        if report.blocker is Blocker.STOPPED:  # the person showed stop: following ends here
            return Outcome.finished(f"followed {person} until they showed stop", person=person)
        if not report.reached:
            return Outcome.failed(ErrorCode.LOST_PERSON, f"I could not follow {person}")
        return Outcome.finished(f"followed {person}", person=person)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        return _person_nearby(context, finished.data["person"], "followed")


class Guide(Skill):
    """Lead the person last found to a place.

    Monitor: at the goal, the person is seen close behind the robot.
    """

    name = "guide"
    required = ("to",)
    optional = ("person",)
    retries = 1
    retry_on = frozenset({ErrorCode.LOST_PERSON})

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        person = person_name(context, args.get("person"))
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I have nobody to guide")
        goal = resolve_target(context, str(args["to"]))
        if goal is None:
            return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not know where {args['to']} is")
        speak(context, f"{person}, please follow me to {_destination(context, args['to'])}.")
        outcome = drive(context, goal, escort=person)
        if outcome.status is not Status.FINISHED:
            return outcome
        return Outcome.finished(outcome.message, person=person)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        return _person_nearby(context, finished.data["person"], "guided")


def _destination(context: SkillContext, target: Any) -> str:
    """How a guide names where it goes: "the kitchen", "Alex", "the point (2, 3)"."""
    if not isinstance(target, str):
        return target_label(target)
    operator = context.world.operator
    if target == OPERATOR and operator is not None:
        return operator.name
    return the(target)


def _person_nearby(context: SkillContext, person: str, verb: str) -> Outcome:
    if sees_person_nearby(context, person):
        return Outcome.verified(f"{verb} {person}", person=person)
    return Outcome.aborted(ErrorCode.LOST_PERSON, f"I lost {person} on the way")


class OpenDoor(Skill):
    """Open a door the robot stands at (driving to it first if needed).

    Monitor: the door is seen open.
    """

    name = "open_door"
    required = ("door",)
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        door = str(args["door"])
        if door not in context.world.doors:
            return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not know the door {door}")
        if context.robot.door_is_open(door) is None:
            goal = resolve_target(context, door)
            if goal is not None:
                context.robot.move_to(goal, frozenset(context.beliefs.closed_doors),
                                      cancel=context.cancel)
        context.robot.open_door(door)
        return Outcome.finished(f"pushed the {door}")

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        door = str(args["door"])
        if context.robot.door_is_open(door):
            context.beliefs.door_open(door)
            return Outcome.verified(f"the {door} is open")
        return Outcome.aborted(ErrorCode.DOOR_LOCKED, f"the {door} did not open")
