"""Recovery protocols (Golem-III §5): known failures and the standard ways to mend them.

Each protocol takes the failed outcome and returns True when the ground is
recovered and the step is worth running again, False when it cannot help, or an
``Outcome`` that stands for the step itself (a wider search that found the object
is the find step's result). Protocols talk to people and call
skills; they never touch the world except through the skills and the Robot port.
"""

from __future__ import annotations

import typing
from collections.abc import Callable, Collection, Mapping
from typing import Any

from homebot.robot import HelpRequest
from homebot.skills import ErrorCode, Outcome, SkillContext, Status, speak
from homebot.skills.perception import looked_everywhere
from homebot.skills.places import people_in_view, resolve_target
from homebot.skills.wording import be, is_plural

__all__ = ["PROTOCOLS", "WAY_BLOCKED", "Protocol", "Recover", "StepRunner"]

#: Which failures recovery may mend: True every one, False none, or these error codes.
Recover = bool | Collection[ErrorCode]
#: Failures of the way (a door shut, someone in it): mended on the spot for every engine,
#: while what to do about a thing not found or not grasped is the engine's to decide.
WAY_BLOCKED: frozenset[ErrorCode] = frozenset({ErrorCode.DOOR_CLOSED, ErrorCode.PATH_BLOCKED})


_HELPERS_SOUGHT = 2  #: people the robot goes to, one after another, to ask to open a door


class StepRunner(typing.Protocol):
    """Runs a skill step through the executive: ``run(skill, args)``, with recovery
    unless ``recover`` narrows it (False: the bare skill, as the inference cycle's own
    steps run)."""

    def __call__(self, skill: str, args: Mapping[str, Any], /, *,
                 recover: Recover = True) -> Outcome: ...


# A protocol gets the context, the failed skill, its arguments and outcome, and a
# runner that runs a skill step with recovery (so a search can open doors on its way).
Protocol = Callable[[SkillContext, str, Mapping[str, Any], Outcome, StepRunner], bool | Outcome]


def _door_closed(context: SkillContext, skill: str, args: Mapping[str, Any],
                 outcome: Outcome, run: StepRunner) -> bool:
    """Open the door; if it will not open, ask someone nearby; else go round it; with no
    way round, go and ask someone the robot can reach to open it."""
    door = str(outcome.data.get("door", ""))
    if not door:
        return False
    opened = run("open_door", {"door": door})
    if opened:
        return True
    seen = people_in_view(context)
    # people the robot cannot name are asked once, without a name: whoever is nearest hears
    asked = [person.name for person in seen if person.name] + (
        [""] if any(person.name is None for person in seen) else [])
    for name in asked:
        speak(context, f"{name}, could you please open the {door} for me?" if name else
              f"Excuse me, could you please open the {door} for me?")
        if context.robot.request(name, HelpRequest.OPEN_DOOR, door):
            context.beliefs.door_open(door)
            speak(context, "Thank you!")
            return True
    # The door stays in the believed-closed set, so the next attempt routes round it.
    if _has_other_way(context, skill, args):
        return True
    if _someone_elsewhere_opens(context, door, run):
        context.beliefs.door_open(door)
        return True
    return False


def _someone_elsewhere_opens(context: SkillContext, door: str, run: StepRunner) -> bool:
    """Nobody by the door opens it: go to the people the robot believes it can reach
    without passing a door it believes shut, nearest way first, and ask them."""
    here = context.robot.pose().xy()
    closed = frozenset(context.beliefs.closed_doors | {door})
    reachable = []
    for name, where in context.beliefs.person_at.items():
        plan = context.navigator.plan(here, where, closed)
        if plan is not None:
            reachable.append((plan.length, name))
    for _, name in sorted(reachable)[:_HELPERS_SOUGHT]:
        if not run("navigate", {"to": name}, recover=WAY_BLOCKED - {ErrorCode.DOOR_CLOSED}):
            continue
        speak(context, f"{name}, could you please open the {door} for me?")
        if context.robot.request(name, HelpRequest.OPEN_DOOR, door):
            speak(context, "Thank you!")
            return True
    return False


def _path_blocked(context: SkillContext, skill: str, args: Mapping[str, Any],
                  outcome: Outcome, run: StepRunner) -> bool:
    """Ask the person in the way to step aside; if they do not, go round them (past a
    door they stand in; one who blocks the way elsewhere leaves no way to go round).
    When nobody is known to be in the way, set off again: the robot has already waited,
    and what stood there (a passer-by, a chair pushed back) may be gone, or a way round
    open; the executive's limit on recoveries ends the trying."""
    person, door = outcome.data.get("person"), str(outcome.data.get("door", ""))
    someone = bool(person or outcome.data.get("someone"))
    if someone:
        # a person the robot cannot name (a visitor, or a face too far to see) is
        # asked all the same, without a name
        speak(context, f"Excuse me{f', {person}' if person else ''}, could you please "
                       "let me through?")
        if context.robot.request(str(person or ""), HelpRequest.STEP_ASIDE, door):
            speak(context, "Thank you!")
            return True
    if not door:
        return not someone
    context.beliefs.door_closed(door)
    return _has_other_way(context, skill, args)


def _has_other_way(context: SkillContext, skill: str, args: Mapping[str, Any]) -> bool:
    target = args.get("to") or args.get("placement") or args.get("room")
    if target is None:
        return True
    goal = resolve_target(context, target)
    if goal is None:
        return False
    plan = context.navigator.plan(context.robot.pose().xy(), goal.xy(),
                                  frozenset(context.beliefs.closed_doors))
    return plan is not None


def _object_not_found(context: SkillContext, skill: str, args: Mapping[str, Any],
                      outcome: Outcome, run: StepRunner) -> bool | Outcome:
    """Search the next most likely placements for the object, nearest first."""
    wanted = str(args.get("object", ""))
    if not wanted:
        return False
    searched = list(outcome.data.get("searched", ())) + (
        [str(outcome.data["placement"])] if outcome.data.get("placement") else [])
    speak(context, f"The {wanted} {be(wanted)} not where I expected. I will look elsewhere.")
    found = run("find_object", {"object": wanted, "exclude": searched})
    if not found and found.error is ErrorCode.NOT_FOUND:
        # The likely places were searched; a detection may have missed it where it
        # was expected, so forget the misses and search the whole home, once.
        context.beliefs.not_at.pop(wanted, None)
        speak(context, f"I will search the whole home once more for the {wanted}.")
        found = run("find_object", {"object": wanted})
    if not found:
        if found.error not in (ErrorCode.NOT_FOUND, ErrorCode.OUT_OF_TIME):
            return False
        # The search's word stands for the step: every place looked at, not the first.
        looked = list(dict.fromkeys([*context.bindings.get(f"searched:{wanted}", ()), *searched]))
        said = looked_everywhere(wanted, looked)
        if found.error is ErrorCode.OUT_OF_TIME:
            said = f"I ran out of time looking for the {wanted}; {said}"
        return Outcome.failed(found.error, said, searched=looked)
    context.bindings[f"object:{wanted}"] = found.data["object"]
    context.bindings[f"placement:{found.data['object']}"] = found.data["placement"]
    return found if skill == "find_object" else True


def _slipped(context: SkillContext, skill: str, args: Mapping[str, Any],
             outcome: Outcome, run: StepRunner) -> bool | Outcome:
    """A grasp that slipped is worth another round of attempts after a fresh look; one
    the robot would not even try (it said why: out of reach, every grasp it found
    failed) is not."""
    if outcome.status is Status.FAILED:
        return False
    thing = str(args.get("object", "object"))
    speak(context, f"The {thing} {'keep' if is_plural(thing) else 'keeps'} slipping. "
                   "Let me try again.")
    return True


def _person_not_found(context: SkillContext, skill: str, args: Mapping[str, Any],
                      outcome: Outcome, run: StepRunner) -> bool | Outcome:
    """Look for the person in the other rooms; a person to hand something to, or take
    it from, who is not where they were seen, is searched for and the step tried again."""
    if skill in ("give", "receive") and outcome.data.get("person"):
        person = str(outcome.data["person"])
        speak(context, f"I cannot see {person} here. I will look for them.")
        return bool(run("find_person", {"person": {"name": person}}))
    if skill != "find_person":
        return False
    speak(context, "I cannot see them here. I will look in the other rooms.")
    found = run("find_person", {"person": args.get("person") or {}})
    if found:
        context.bindings["person"] = found.data["person"]
        return found
    return False


def _not_taken(context: SkillContext, skill: str, args: Mapping[str, Any],
               outcome: Outcome, run: StepRunner) -> bool:
    """The person handed to did not take it: whoever stood there was not them (a face
    misread, or they had walked off). That spot is not believed to be them again; they
    are searched for, and the hand-over tried again where they are found."""
    person = str(outcome.data.get("person") or "")
    if skill != "give" or not person:
        return False
    where = context.beliefs.person_at.get(person)
    if where is not None:
        context.beliefs.mistook(person, where)
    speak(context, f"I am sorry, I took you for {person}. I will look for {person}.")
    return bool(run("find_person", {"person": {"name": person}}))


def _find_again(context: SkillContext, skill: str, args: Mapping[str, Any],
                outcome: Outcome, run: StepRunner) -> bool | Outcome:
    """Something was not where it should be: widen the search for it."""
    if skill in {"find_object", "pick"}:
        return _object_not_found(context, skill, args, outcome, run)
    return _person_not_found(context, skill, args, outcome, run)


PROTOCOLS: Mapping[ErrorCode, Protocol] = {
    ErrorCode.DOOR_CLOSED: _door_closed,
    ErrorCode.PATH_BLOCKED: _path_blocked,
    ErrorCode.NOT_FOUND: _find_again,
    ErrorCode.NOT_GRASPED: _slipped,
    ErrorCode.NOT_DELIVERED: _not_taken,
}
