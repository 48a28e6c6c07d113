"""GPSR trials: the commands a home can satisfy, and a referee that judges a run by the truth.

``feasible`` keeps the generated commands the world file can satisfy (the others are
commands to refuse or report on). ``judge`` judges a run by the simulator's ground truth,
never by the robot's own report.

After a command ran, ``judge`` looks at the simulation (where every object truly is, where
each person truly stands) and at what the robot said, and checks the command's effects:

- ``give``: the object taken ends with a person who fits the description searched for
  (the operator for "me");
- ``place``: the object taken truly lies on that placement;
- a ``pick`` that ends the command: the object is truly in the robot's hand;
- ``count`` then ``say``: the number said is the true number (objects of that kind on the
  placement; people fitting the description in the room);
- ``describe(property)`` then ``say``: the object named is truly the lightest / biggest...
  of those on the placement;
- ``guide(to=X)``: the person found truly stands in X;
- ``greet``: the person greeted fits the description;
- ``say(text)`` after ``find_person``: the robot said it next to a person who fits.

Anything else (going somewhere, talking about the time) counts as done when the robot
reported it done; those have no effect to check in the home.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from typing import Any

from homebot.executive import RunReport
from homebot.robot import PersonPercept
from homebot.sim import Simulation
from homebot.skills.perception import matches_person
from homebot.skills.wording import number
from homebot.task import Step
from homebot.world import World

__all__ = ["feasible", "judge"]

_NUMBER_WORDS = {number(count): count for count in range(0, 13)}


def _person_fits(truth: Simulation, name: str, description: Mapping[str, Any],
                 room: str | None) -> bool:
    world, sim = truth.world, truth
    person = world.people.get(name)
    state = sim.people.get(name)
    if person is None or state is None:
        return name == "operator" and not description
    where = world.room_at(*state.position)
    if room is not None and where != room:
        return False
    percept = PersonPercept(name, person.posture.value, person.gesture.value,
                            tuple(person.clothes), state.position, where or person.room)
    return matches_person(percept, description)


def _room_of(truth: Simulation, args: Mapping[str, Any]) -> str | None:
    if args.get("room"):
        return str(args["room"])
    if args.get("placement"):
        return truth.world.placements[str(args["placement"])].room
    return None


def _said_number(text: str) -> int | None:
    for word in re.findall(r"[a-z]+|\d+", text.lower()):
        if word.isdigit():
            return int(word)
        if word in _NUMBER_WORDS:
            return _NUMBER_WORDS[word]
        if word in {"nobody", "a"}:
            return 0 if word == "nobody" else 1
    return None


def _true_count(truth: Simulation, args: Mapping[str, Any]) -> int:
    world, sim = truth.world, truth
    if "person" in args:
        room = str(args.get("room") or _room_of(truth, args))
        return sum(_person_fits(truth, name, dict(args["person"] or {}), room)
                   for name in world.people)
    wanted = str(args.get("object", "object"))
    return sum(1 for name, where in sim.object_location.items()
               if where == args.get("placement") and _is(truth, name, wanted))


def _is(truth: Simulation, name: str, wanted: str) -> bool:
    world = truth.world
    obj = world.objects.get(name)
    if obj is None:
        return False
    return wanted in (name, obj.category, world.plural_of(obj.category), "object")


def _true_superlatives(truth: Simulation, args: Mapping[str, Any]) -> list[str]:
    """The objects truly on the placement with the property (several when they tie)."""
    world, sim = truth.world, truth
    there = [name for name, where in sim.object_location.items()
             if where == args.get("placement") and _is(truth, name, str(args.get("object")))]
    if not there:
        return []
    prop = str(args["property"])
    measure = "weight" if prop in {"heaviest", "lightest"} else "size"
    choose = max if prop in {"biggest", "largest", "heaviest", "thickest"} else min
    value = choose(float(getattr(world.objects[name], measure)) for name in there)
    return [name for name in there if float(getattr(world.objects[name], measure)) == value]


def judge(truth: Simulation, steps: Sequence[Step],
          report: RunReport[Any]) -> tuple[bool, str]:
    """Whether the home shows the command done (and if not, the first effect missing).

    ``truth`` is the simulation the command ran in: where every object and person truly
    is. ``report`` is what the robot did and said."""
    if len(report.steps) != len(steps):
        return False, "not every step ran"
    sim = truth
    model = truth.world.operator
    operator = model.name if model is not None else "operator"
    taken: str | None = None
    searched: tuple[dict[str, Any], str | None] | None = None
    found_name: str | None = None
    pending: Step | None = None  # a count or description whose result a say reports
    for planned, done in zip(steps, report.steps, strict=True):
        args = done.args
        if planned.skill == "pick":
            taken = str(args.get("object"))
        elif planned.skill == "find_person":
            searched = (dict(planned.args.get("person") or {}), _room_of(truth, planned.args))
            match = re.search(r"(?:I found|I am with) (.+)$", done.message or "")
            found_name = match.group(1) if match else None
        elif planned.skill == "give":
            where = sim.object_location.get(taken or "") or ""
            if not where.startswith("person:"):
                return False, f"the {taken} is not with a person but at {where or 'nowhere'}"
            person = where.removeprefix("person:")
            wanted = str(planned.args.get("person", ""))
            if wanted == "operator" and person not in {operator, "operator"}:
                return False, f"the {taken} went to {person}, not the operator"
            if wanted != "operator" and searched is not None and not _person_fits(
                    truth, person, searched[0], None):
                return False, f"the {taken} went to {person}, who does not fit"
            if wanted not in {"", "operator"} and person != wanted:
                return False, f"the {taken} went to {person}, not {wanted}"
        elif planned.skill == "place":
            placement = str(planned.args.get("placement"))
            if sim.object_location.get(taken or "") != placement:
                return False, f"the {taken} is not on the {placement}"
        elif planned.skill in {"count", "describe"}:
            pending = planned
        elif planned.skill == "say" and planned.args.get("text") == "$result" and pending:
            said = done.message or ""
            if pending.skill == "count":
                true_number = _true_count(truth, pending.args)
                if _said_number(said) != true_number:
                    return False, f"said '{said}' but there are {true_number}"
            elif pending.args.get("property"):
                best = _true_superlatives(truth, pending.args)
                if not any(f"the {name}." in said for name in best):
                    return False, f"said '{said}' but it is the {' or the '.join(best)}"
            pending = None
        elif planned.skill == "guide" and searched is not None:
            destination = str(planned.args.get("to"))
            if found_name is None or found_name not in sim.people:
                return False, "nobody known was guided"
            room = truth.world.room_at(*sim.people[found_name].position)
            target_room = truth.world.placements[destination].room if (
                destination in truth.world.placements) else destination
            if room != target_room:
                return False, f"{found_name} is in the {room}, not the {destination}"
        elif planned.skill in {"greet", "say"} and searched is not None and found_name:
            moved = any(step.skill in {"follow", "guide"} for step in steps)  # room changes
            if not _person_fits(truth, found_name, searched[0], None if moved else searched[1]):
                return False, f"{found_name} does not fit the person asked for"
    if steps and steps[-1].skill == "pick" and not any(
            held == taken for held in sim.hands.values()):
        return False, f"the {taken} is not in the robot's hand"
    return report.success, "" if report.success else report.reason


def _someone_fits(world: World, description: Mapping[str, Any], room: str | None) -> bool:
    """Whether someone in ``room`` fits the description, as find_person would match them."""
    return any(
        matches_person(PersonPercept(person.name, person.posture.value, person.gesture.value,
                                     tuple(person.clothes), person.position, person.room),
                       description)
        for person in world.people.values() if room is None or person.room == room)


def _something_fits(world: World, wanted: str, placement: str | None, room: str | None) -> bool:
    for obj in world.objects.values():
        if wanted not in (obj.name, obj.category, world.plural_of(obj.category), "object"):
            continue
        where = world.placements[obj.placement]
        if placement is not None and where.name != placement:
            continue
        if room is not None and where.room != room:
            continue
        return True
    return False


def feasible(world: World, steps: list[Step]) -> bool:
    """Whether the home as the world file describes it can satisfy every step.

    A generated command may ask for the waving person in a room where nobody
    waves, or the biggest fruit on a shelf that holds none; those are commands
    to refuse or report on, not to carry out, and are left out here.
    """
    for step in steps:
        args = step.args
        room = args.get("room")
        if "placement" in args and step.skill in {"find_person"}:
            room = world.placements[args["placement"]].room
        if step.skill == "find_person" and not _someone_fits(world, args.get("person") or {},
                                                            room):
            return False
        if step.skill == "find_object" and not _something_fits(
                world, str(args["object"]), args.get("placement"), room):
            return False
        if step.skill == "describe" and "property" in args and not _something_fits(
                world, str(args.get("object", "object")), args.get("placement"), None):
            return False
    return True
