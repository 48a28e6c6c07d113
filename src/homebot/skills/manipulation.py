"""Skills that handle objects: pick, place, give, receive."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from homebot.skills.motion import drive, drive_to_target
from homebot.skills.perception import go_and_look, matches_object
from homebot.skills.places import HANDING_REACH, people_in_view, person_name, resolve_target
from homebot.skills.skill import ErrorCode, Outcome, Skill, SkillContext, Status, speak
from homebot.skills.wording import be, here_is, place_in

__all__ = ["Give", "Pick", "Place", "Receive"]

_LOOKS = 2  #: looks for a person before the robot says it cannot see them
_APPROACHES = 2  #: drives up to a person to hand to, or take from, before giving up


class Pick(Skill):
    """Grasp an object from where the robot believes it is.

    Preconditions: a free hand (``hand`` names one, else the first free); the
    object's placement is believed. Effects: the
    object is in a hand. Monitor: the hand camera sees the object in the hand
    (an empty hand or a different object is ``aborted``, and retried). A robot that
    does not even close its hand, and says why (``Robot.grasp``), has ``failed``.
    """

    name = "pick"
    required = ("object",)
    optional = ("hand",)
    retries = 2
    retry_on = frozenset({ErrorCode.NOT_FOUND})

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        wanted = str(args["object"])
        hand = str(args["hand"]) if args.get("hand") else context.beliefs.free_hand()
        if hand is None or context.beliefs.holding.get(hand, "") is not None:
            return Outcome.failed(ErrorCode.HANDS_FULL, "both my hands are full" if hand is None
                                  else f"my {hand} hand is not free")
        believed = context.beliefs.object_at.get(wanted)
        # Where the robot believes it is comes first; the binding only remembers where it
        # was last expected after a look that missed it (so a retry looks there again).
        placement = believed if believed in context.world.placements else context.bindings.get(
            f"placement:{wanted}")
        if placement not in context.world.placements:
            return Outcome.failed(ErrorCode.NOT_FOUND, f"I do not know where the {wanted} is")
        # A retry looks at the same place again, though this look may not see it.
        context.bindings[f"placement:{wanted}"] = placement
        outcome, detections = go_and_look(context, placement)
        if outcome.status is not Status.FINISHED:
            return outcome
        targets = [d for d in detections if d.label == wanted] or [
            d for d in detections if matches_object(context, wanted, d)]
        if not targets:
            return Outcome.failed(ErrorCode.NOT_FOUND, f"the {wanted} {be(wanted)} not "
                                  f"{place_in(context.world, placement)}", placement=placement)
        problem = context.robot.grasp(targets[0], hand)
        if problem:
            # The hand did not even close: nothing to sense, and the robot said why it would
            # not try (out of reach, too heavy, every grasp it found failed): trying the
            # same again would only repeat that.
            return Outcome.failed(ErrorCode.NOT_GRASPED, problem, placement=placement)
        return Outcome.finished(f"closed my {hand} hand on the {targets[0].label}", hand=hand,
                                object=targets[0].label, placement=placement)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        hand, expected = finished.data["hand"], finished.data["object"]
        held = context.robot.held(hand)
        if held is None:
            return Outcome.aborted(ErrorCode.NOT_GRASPED, f"the {expected} slipped from my hand")
        if held.label != expected and not matches_object(context, str(args["object"]), held):
            context.robot.release(hand, finished.data["placement"])
            context.beliefs.saw_object(held.label, finished.data["placement"])
            return Outcome.aborted(ErrorCode.WRONG_OBJECT,
                                   f"I picked the {held.label}, not the {expected}")
        context.beliefs.took(held.label, hand)
        context.bindings.pop(f"placement:{args['object']}", None)
        return Outcome.verified(f"I have the {held.label}", object=held.label, hand=hand)

    def assume(self, context: SkillContext, args: Mapping[str, Any], finished: Outcome) -> None:
        context.beliefs.took(finished.data["object"], finished.data["hand"])


class Place(Skill):
    """Put what the robot holds (or the named object) on a placement.

    Monitor: looking at the placement shows the object on it.
    """

    name = "place"
    required = ("placement",)
    optional = ("object",)
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        placement = str(args["placement"])
        if placement not in context.world.placements:
            return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not know the {placement}")
        wanted = args.get("object")
        hand = context.beliefs.hand_holding(str(wanted)) if wanted else None
        if hand is None and str(wanted) not in context.world.objects:
            hand = context.beliefs.hand_holding(context.beliefs.last_taken) or (
                context.beliefs.hand_holding())  # a category or pronoun: the last taken
        if hand is None:
            placed = context.bindings.get(f"placed:{placement}")
            if placed is not None and (wanted is None or placed == wanted):
                # A retry after a look that missed it: it is already down, look again.
                return Outcome.finished(f"the {placed} is already down", object=placed)
            return Outcome.failed(ErrorCode.NOT_HOLDING, "I am not holding anything to place")
        label = context.beliefs.holding[hand]
        stand = context.world.placements[placement].approach
        goal = resolve_target(context, placement)
        if goal is not None and math.dist(context.robot.pose().xy(), stand.xy()) > 0.3:
            moved = drive(context, goal)
            if moved.status is not Status.FINISHED:
                return moved
        context.robot.release(hand, placement)
        context.beliefs.let_go(hand, placement)
        context.bindings[f"placed:{placement}"] = label
        return Outcome.finished(f"put the {label} {place_in(context.world, placement)}",
                                object=label)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        name, placement = finished.data["object"], str(args["placement"])
        outcome, detections = go_and_look(context, placement)
        if outcome.status is Status.FINISHED and any(d.label == name for d in detections):
            return Outcome.verified(f"the {name} {be(name)} {place_in(context.world, placement)}",
                                    object=name)
        return Outcome.aborted(ErrorCode.NOT_PLACED,
                               f"I do not see the {name} {place_in(context.world, placement)}")


class Give(Skill):
    """Hand what the robot holds to a person (``operator``, a name, or the person last found).

    Monitor: the hand is empty afterwards, and the robot let go to the person (an empty
    hand it never opened for them dropped the object: not delivered).
    """

    name = "give"
    optional = ("person", "object")
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        person = person_name(context, args.get("person"))
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I do not know whom to give it to")
        wanted = args.get("object")
        hand = (context.beliefs.hand_holding(str(wanted)) if wanted else None) or (
            context.beliefs.hand_holding(context.beliefs.last_taken)) or (
            context.beliefs.hand_holding())
        if hand is None:
            return Outcome.failed(ErrorCode.NOT_HOLDING, "I have nothing to give")
        label = context.beliefs.holding[hand]
        moved = _come_to(context, person)
        if moved is not None:
            return moved
        speak(context, here_is(person, str(label)))
        given = context.robot.hand_over(hand, person)
        return Outcome.finished(f"offered it to {person}", hand=hand, person=person, object=label,
                                given=given)

    def assume(self, context: SkillContext, args: Mapping[str, Any], finished: Outcome) -> None:
        context.beliefs.let_go(finished.data["hand"], f"person:{finished.data['person']}")

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        hand = finished.data["hand"]
        empty = context.robot.held(hand) is None
        if empty and not finished.data["given"]:
            # the hand is empty, but the robot never let go to them: it fell (a retry has
            # nothing to give)
            context.beliefs.let_go(hand, None)
            return Outcome.failed(ErrorCode.NOT_DELIVERED,
                                   f"the {finished.data['object']} fell from my hand",
                                   person=finished.data["person"])
        if empty:
            context.beliefs.let_go(hand, f"person:{finished.data['person']}")
            return Outcome.verified(f"{finished.data['person']} has the {finished.data['object']}",
                                    person=finished.data["person"])
        return Outcome.aborted(ErrorCode.NOT_DELIVERED,
                               f"{finished.data['person']} did not take the object",
                               person=finished.data["person"])


class Receive(Skill):
    """Take an object from a person (``operator``, a name, or the person last found).

    The robot offers its open hand (Cosero §7.3.1); the person puts the object in, the
    fingers close on it. Preconditions: a free hand. Monitor: the hand's camera sees
    something in the hand (the named object, when one was named); an empty hand is
    ``aborted``.
    """

    name = "receive"
    optional = ("person", "object")
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        person = person_name(context, args.get("person"))
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I do not know whom to take it from")
        hand = context.beliefs.free_hand()
        if hand is None:
            return Outcome.failed(ErrorCode.HANDS_FULL, "both my hands are full")
        moved = _come_to(context, person)
        if moved is not None:
            return moved
        wanted = f"the {args['object']}" if args.get("object") else "it"
        speak(context, f"{person}, please put {wanted} in my hand")
        context.robot.receive(hand, person)
        return Outcome.finished(f"closed my {hand} hand", hand=hand, person=person)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        hand, person = finished.data["hand"], finished.data["person"]
        held = context.robot.held(hand)
        if held is None:
            return Outcome.aborted(ErrorCode.NOT_GRASPED, f"{person} gave me nothing")
        wanted = args.get("object")
        if wanted and held.label != wanted and not matches_object(context, str(wanted), held):
            context.beliefs.took(held.label, hand)
            return Outcome.aborted(ErrorCode.WRONG_OBJECT,
                                   f"{person} gave me the {held.label}, not the {wanted}")
        context.beliefs.took(held.label, hand)
        return Outcome.verified(f"I have the {held.label} from {person}", object=held.label,
                                hand=hand, person=person)

    def assume(self, context: SkillContext, args: Mapping[str, Any], finished: Outcome) -> None:
        if args.get("object"):
            context.beliefs.took(str(args["object"]), finished.data["hand"])


def _come_to(context: SkillContext, person: str) -> Outcome | None:
    """Look where ``person`` is, and drive up to them when they are more than arm's length
    away; the motion's outcome if it did not get there, ``not_found`` if they are not
    where the robot ends up, else None. The look comes first: where they were last seen
    may be stale (asked to let the robot by, they stepped aside). Seen again from nearer,
    they may be elsewhere (a look from afar can take someone else for them): the robot
    drives once more, and fails ``not_found`` if they are still out of arm's length."""
    def out_of_reach() -> bool:
        position = context.beliefs.person_at.get(person)
        return position is not None and \
            math.dist(context.robot.pose().xy(), position) > HANDING_REACH

    seen = _look_for(context, person)
    for _ in range(_APPROACHES):
        if not out_of_reach():
            break
        moved = drive_to_target(context, person)
        if moved is not None:
            return moved
        seen = _look_for(context, person)
    if not seen or out_of_reach():
        return Outcome.failed(ErrorCode.NOT_FOUND, f"I cannot see {person}", person=person)
    return None


def _look_for(context: SkillContext, person: str) -> bool:
    """Look round, twice if need be (a look can miss someone): is ``person`` seen? Where
    they are seen is believed."""
    for _ in range(_LOOKS):
        for seen in people_in_view(context):
            if seen.name == person:
                context.beliefs.saw_person(person, seen.position)
                return True
    return False
