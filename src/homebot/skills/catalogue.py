"""The skill library by name, and checks that a step names a real skill with sane arguments."""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from typing import Any

from homebot.errors import TaskError
from homebot.skills.interaction import AnswerQuestion, Ask, Greet, Say, WhereIs
from homebot.skills.manipulation import Give, Pick, Place, Receive
from homebot.skills.motion import Follow, Guide, Navigate, OpenDoor
from homebot.skills.perception import Count, Describe, FindObject, FindPerson, Look
from homebot.skills.places import OPERATOR, point_goal
from homebot.skills.skill import Skill
from homebot.task import Step
from homebot.text import closest_names, find_name
from homebot.world import World
from homebot.yamlfile import short_repr

__all__ = ["SKILLS", "check_step", "skill_named", "spelled_as_world"]

SKILLS: Mapping[str, type[Skill]] = {
    skill.name: skill
    for skill in (Navigate, Look, FindObject, Pick, Place, Give, Receive, FindPerson, Follow,
                  Guide, Greet, Say, Ask, Count, Describe, OpenDoor, AnswerQuestion, WhereIs)
}

# Which kind of name each argument holds, for checking steps against the world.
_ARGUMENT_KINDS = {"to": "target", "placement": "placement", "room": "room",
                   "object": "object", "door": "door"}
_PERSON_FIELDS = {"name", "posture", "gesture", "clothes"}
# Skills whose ``to`` may be a point goal, [x, y] or {x: X, y: Y}, besides a name.
_POINT_GOAL_SKILLS = frozenset({"navigate"})


def skill_named(name: str) -> Skill:
    """A fresh instance of the named skill; an unknown name raises ``TaskError``."""
    if name not in SKILLS:
        guess = difflib.get_close_matches(name, list(SKILLS), n=1)
        hint = f"did you mean '{guess[0]}'?" if guess else f"skills: {', '.join(SKILLS)}"
        raise TaskError(f"unknown skill '{name}'; {hint}")
    return SKILLS[name]()


def check_step(step: Step, world: World, where: str) -> None:
    """Raise ``TaskError`` (prefixed by ``where``) if the step cannot make sense in ``world``."""
    try:
        skill = skill_named(step.skill)
    except TaskError as error:
        raise TaskError(f"{where}: {error}") from None
    missing = [name for name in skill.required if name not in step.args]
    if missing:
        raise TaskError(f"{where}: {step.skill} needs argument '{missing[0]}'; add it "
                        f"(arguments: {', '.join(skill.required + skill.optional)})")
    allowed = set(skill.required) | set(skill.optional)
    for name, value in step.args.items():
        if name not in allowed:
            guess = difflib.get_close_matches(name, sorted(allowed), n=1)
            hint = f"did you mean '{guess[0]}'?" if guess else (
                f"arguments: {', '.join(sorted(allowed)) or 'none'}")
            raise TaskError(f"{where}: {step.skill} has no argument '{name}'; {hint}")
        _check_value(step.skill, name, value, world, where)


def spelled_as_world(step: Step, world: World) -> Step:
    """The step with each name written as the world writes it: a task file may say
    "patricia" or "creme brulee" for "Patrícia" and "crème brûlée" (``homebot.text.fold``).
    Names the world does not know are left as they are, for ``check_step`` to report."""
    args: dict[str, Any] = {}
    for name, value in step.args.items():
        kind = "person" if name == "person" else _ARGUMENT_KINDS.get(name)
        if name == "person" and isinstance(value, Mapping):
            if isinstance(value.get("name"), str):
                value = {**value, "name": _spelled(value["name"], world, "person", step.skill)}
        elif name == "exclude" and isinstance(value, list):
            value = [_spelled(v, world, "placement", step.skill) if isinstance(v, str) else v
                     for v in value]
        elif kind is not None and isinstance(value, str):
            value = _spelled(value, world, kind, step.skill)
        args[name] = value
    return Step(step.skill, args)


def _spelled(text: str, world: World, kind: str, skill: str) -> str:
    known = _names(world, kind, skill)
    return text if text in known else (find_name(text, known) or text)


def _check_value(skill: str, name: str, value: Any, world: World, where: str) -> None:
    if name == "person" and isinstance(value, Mapping):
        unknown = sorted(map(str, set(value) - _PERSON_FIELDS))
        if unknown:
            raise TaskError(f"{where}: a person is described by {', '.join(sorted(_PERSON_FIELDS))}"
                            f", not '{unknown[0]}'")
        for field, text in value.items():
            if isinstance(text, (list, dict)) or not str(text).strip():
                raise TaskError(f"{where}: {skill}.person.{field} is a word such as 'waving', "
                                f"not {short_repr(text)}")
        return
    if name == "hand":
        if str(value) not in world.robot.hands:
            raise TaskError(f"{where}: {skill}.hand is one of the robot's hands "
                            f"({', '.join(world.robot.hands)}), not {short_repr(value)}")
        return
    if name == "to" and skill in _POINT_GOAL_SKILLS and isinstance(value, (list, Mapping)):
        _check_point_goal(skill, value, world, where)
        return
    if name == "exclude" and isinstance(value, list):
        value = tuple(value)
    elif isinstance(value, (list, dict)):
        raise TaskError(f"{where}: {skill}.{name} is a name or text, not {short_repr(value)}; "
                        "write it as one word or a quoted string")
    if name == "exclude":
        for placement in value if isinstance(value, tuple) else (value,):
            _check_value(skill, "placement", placement, world, where)
        return
    kind = _ARGUMENT_KINDS.get(name)
    if name == "person":
        kind = "person"
    if kind is None:
        return
    text = str(value)
    known = _names(world, kind, skill)
    if text not in known:
        guess = closest_names(text, sorted(known))
        hint = f"did you mean '{guess[0]}'?" if guess else "check the world's names"
        raise TaskError(f"{where}: unknown {kind} '{text}' for {skill}.{name}; {hint}")


def _check_point_goal(skill: str, value: Any, world: World, where: str) -> None:
    """A point goal is two finite numbers where the robot fits: on a room's free floor."""
    try:
        point = point_goal(value)
    except ValueError as error:
        raise TaskError(f"{where}: {skill}.to is a name or a point [x, y] / {{x: X, y: Y}}, "
                        f"not {short_repr(value)}: {error}") from None
    problem = world.footprint_problem(*point) if point is not None else None
    if point is not None and problem is not None:
        raise TaskError(f"{where}: {skill}.to ({point[0]:g}, {point[1]:g}) {problem}; give a "
                        "point on free floor inside a room, at least the robot's radius from "
                        "walls and furniture")


def _names(world: World, kind: str, skill: str) -> set[str]:
    people = {*world.people, OPERATOR}
    categories = {*world.categories, *(c.plural for c in world.categories.values())}
    return {
        "placement": set(world.placements),
        "room": set(world.rooms),
        "door": set(world.doors),
        "person": people,
        "object": {*world.objects, *categories, "object"},
        "target": {*world.placements, *world.rooms, *people, *world.doors},
    }[kind]
