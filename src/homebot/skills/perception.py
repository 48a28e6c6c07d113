"""Skills that look: look, find_object, find_person, count, describe."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

from homebot.robot import Detection, PersonPercept
from homebot.skills.motion import drive, drive_to_target
from homebot.skills.places import (
    OPERATOR,
    near,
    people_in_view,
    pose_near_point,
    resolve_target,
    sees_person_nearby,
)
from homebot.skills.skill import ErrorCode, Outcome, Skill, SkillContext, Status, time_left
from homebot.skills.wording import (
    a,
    be,
    count_objects,
    count_people,
    described_people,
    listing,
    person_fact,
    place_in,
    plural,
    the,
)
from homebot.space.referring import Scene, modifiers_from, resolve
from homebot.text import fold
from homebot.world import LEG_GARMENTS

__all__ = [
    "Count",
    "Describe",
    "FindObject",
    "FindPerson",
    "Look",
    "candidate_placements",
    "go_and_look",
    "go_into_room",
    "looked_everywhere",
    "matches_object",
    "matches_person",
]

# Seconds allowed per look at a placement (turning to it, looking, looking again).
_LOOK_ALLOWANCE = 15.0


def matches_object(context: SkillContext, wanted: str, detection: Detection) -> bool:
    """Whether a detection is the wanted object, or belongs to the wanted category."""
    return detection.label == wanted or detection.category == wanted or (
        context.world.plural_of(detection.category) == wanted)


def go_and_look(context: SkillContext, placement: str) -> tuple[Outcome, list[Detection]]:
    """Drive to a placement unless already there, then look at it; beliefs follow."""
    if placement not in context.world.placements:
        return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not know the {placement}"), []
    goal = context.world.placements[placement].approach
    if not near(context, goal):
        moved = drive(context, goal)
        if moved.status is not Status.FINISHED:
            return moved, []
    detections = context.robot.perceive_objects(placement)
    seen = {d.label for d in detections}
    for detection in detections:
        context.beliefs.saw_object(detection.label, placement)
    for name, where in list(context.beliefs.object_at.items()):
        if where == placement and name not in seen:
            context.beliefs.missed_object(name, placement)
    return Outcome.finished(), detections


def go_into_room(context: SkillContext, room: str, target: str) -> Outcome | None:
    """Drive to ``target`` unless already in ``room``; a blocked way is returned, else None."""
    if context.world.room_at(*context.robot.pose().xy()) == room:
        return None
    return drive_to_target(context, target)


def candidate_placements(context: SkillContext, wanted: str, room: str | None = None,
                         exclude: Sequence[str] = ()) -> list[str]:
    """Where ``wanted`` (an object or category) most likely is, most likely first.

    Order: where the robot believes it is; placements meant to hold its category;
    the rest; each group nearest first. Placements already known not to hold it
    are left out, and ``room`` restricts the search to one room.
    """
    world, beliefs = context.world, context.beliefs
    category = world.objects[wanted].category if wanted in world.objects else _category(
        context, wanted)
    names = [wanted] if wanted in world.objects else [
        name for name, obj in world.objects.items() if obj.category == category]
    believed = [beliefs.object_at.get(name) for name in names]
    believed_places = [p for p in believed if p in world.placements]
    holding = [p.name for p in world.placements_holding(category)] if category else []
    here = context.robot.pose().xy()
    rest = sorted(world.placements, key=lambda p: math.dist(world.placements[p].approach.xy(),
                                                             here))
    ordered = list(dict.fromkeys([*believed_places, *holding, *rest]))
    excluded = set(exclude)
    if wanted in beliefs.not_at:
        excluded |= beliefs.not_at[wanted]
    return [p for p in ordered if p not in excluded and (
        room is None or world.placements[p].room == room)]


def _category(context: SkillContext, wanted: str) -> str | None:
    for name, category in context.world.categories.items():
        if wanted in (name, category.plural):
            return name
    return None


class Look(Skill):
    """Look at what is on a placement (driving there first). Data: the labels seen."""

    name = "look"
    required = ("placement",)

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        outcome, detections = go_and_look(context, str(args["placement"]))
        if outcome.status is not Status.FINISHED:
            return outcome
        return Outcome.finished(objects=[d.label for d in detections])

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        labels = finished.data["objects"]
        listed = listing([f"the {label}" for label in labels]) if labels else "nothing"
        text = (f"{place_in(context.world, str(args['placement'])).capitalize()} I saw "
                f"{listed} when I looked just now.")
        context.bindings["result"] = text  # what a following say reports
        return Outcome.verified(text, objects=labels, result=text)


class FindObject(Skill):
    """Search candidate placements in order until the object (or one of the category) is seen.

    Monitor: another look at that placement sees it again (a confused detection
    rarely repeats; one more look when that look misses it). Data: ``object``
    (what was found) and ``placement``.
    """

    name = "find_object"
    required = ("object",)
    optional = ("placement", "room", "exclude", "spatial", "property")
    retries = 1
    retry_on = frozenset({ErrorCode.NOT_FOUND})  # a missed detection rarely repeats

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        wanted = str(args["object"])
        if wanted not in context.world.objects and _category(context, wanted) is None:
            return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not know what {wanted} is")
        if args.get("placement"):
            if args["placement"] not in context.world.placements:
                return Outcome.failed(ErrorCode.UNKNOWN_TARGET,
                                      f"I do not know the {args['placement']}")
            candidates = [str(args["placement"])]
        else:
            candidates = candidate_placements(context, wanted, args.get("room"),
                                              args.get("exclude", ()))
            if not candidates and not args.get("exclude"):
                # Every place was searched and missed it; a detection may have failed,
                # so a retry searches them all again rather than nothing.
                context.beliefs.not_at.pop(wanted, None)
                candidates = candidate_placements(context, wanted, args.get("room"))
        # Every placement looked at for ``wanted``, in order, for the message that says
        # where the robot looked when it gives up. The bindings outlive a task, so each
        # placement is listed once: a home searched 50 000 times holds 19 names, not a
        # million.
        looked: list[str] = context.bindings.setdefault(f"searched:{wanted}", [])
        for placement in candidates:
            if context.cancel.cancelled:
                return Outcome.cancelled(context.cancel)
            if not _affordable(context, placement):
                return Outcome.failed(
                    ErrorCode.OUT_OF_TIME, f"I ran out of time looking for the {wanted}; "
                    f"{looked_everywhere(wanted, list(dict.fromkeys(looked)))}",
                    searched=list(dict.fromkeys(looked)))
            outcome, detections = go_and_look(context, placement)
            if outcome.status is not Status.FINISHED:
                return outcome
            if placement not in looked:
                looked.append(placement)
            found = [d for d in detections if matches_object(context, wanted, d)]
            if found and args.get("spatial"):  # "the left cup": the one the words fit best
                return _referent(context, wanted, placement, found, detections, args["spatial"])
            if found and args.get("property"):  # "the lightest fruit on the shelf"
                found = [_superlative(context, found, str(args["property"]))]
            if found:
                return Outcome.finished(f"I see the {found[0].label} "
                                        f"{place_in(context.world, placement)}",
                                        object=found[0].label, placement=placement)
            context.beliefs.not_at.setdefault(wanted, set()).add(placement)
        if not candidates:
            return Outcome.failed(ErrorCode.NOT_FOUND,
                                  f"I did not find the {wanted} anywhere I looked", searched=[])
        message = f"I did not find the {wanted} {place_in(context.world, candidates[0])}" if len(
            candidates) == 1 else looked_everywhere(wanted, candidates)
        return Outcome.failed(ErrorCode.NOT_FOUND, message, searched=candidates)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        name, placement = finished.data["object"], finished.data["placement"]
        # Two looks at most: one miss is likelier a missed detection than a moved object.
        for _ in range(2):
            if any(d.label == name for d in context.robot.perceive_objects(placement)):
                return Outcome.verified(finished.message, object=name, placement=placement)
        context.beliefs.missed_object(name, placement)
        return Outcome.aborted(ErrorCode.NOT_FOUND, f"the {name} {be(name)} not "
                               f"{place_in(context.world, placement)}")


def _referent(context: SkillContext, wanted: str, placement: str, found: Sequence[Detection],
              detections: Sequence[Detection], spatial: Any) -> Outcome:
    """The one of ``found`` the spatial modifiers fit best, read in the placement's frame
    as seen from where the robot stands at it; when two fit about equally, or none, the
    robot asks which one is meant (``homebot.space.referring``)."""
    where = context.world.placements[placement]
    centre = (float(where.model.center[0]), float(where.model.center[1]))
    scene = Scene({d.label: d.position or centre for d in detections},
                  {d.label: d.category for d in detections}, math.hypot(*where.model.size),
                  where.approach.xy(), where.approach.theta)
    try:
        modifiers = modifiers_from(spatial)
    except ValueError as error:
        return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not understand which {wanted}: "
                              f"{error}")
    resolution = resolve([d.label for d in found], modifiers, scene, noun=wanted)
    if resolution.referent is None:
        question = resolution.question or f"Which {wanted} do you mean?"
        context.robot.say(question)
        return Outcome.failed(ErrorCode.UNKNOWN_TARGET, question,
                              candidates=[name for name, _ in resolution.degrees])
    return Outcome.finished(f"I see the {resolution.referent} "
                            f"{place_in(context.world, placement)}",
                            object=resolution.referent, placement=placement)


def _superlative(context: SkillContext, found: Sequence[Detection], prop: str) -> Detection:
    """The detection with the property ("lightest", "biggest") among those of known objects:
    by perception's estimates where it made them, else by the world file."""
    measure = "weight" if prop in {"heaviest", "lightest"} else "size"
    choose = max if prop in {"biggest", "largest", "heaviest", "thickest"} else min
    if all(_estimated(d, measure) is not None for d in found):
        return choose(found, key=lambda d: float(_estimated(d, measure) or 0.0))
    known = [d for d in found if d.label in context.world.objects] or list(found)
    if not all(d.label in context.world.objects for d in known):
        return known[0]
    return choose(known, key=lambda d: float(getattr(context.world.objects[d.label], measure)))


def _estimated(detection: Detection, measure: str) -> float | None:
    """Perception's own estimate of ``measure`` ("size" or "weight"), if it made one."""
    return detection.mass if measure == "weight" else detection.size


def _measured(context: SkillContext, detection: Detection, measure: str) -> float:
    """A detection's ``measure`` ("size" or "weight"): perception's estimate where it made
    one, else the world file's."""
    estimate = _estimated(detection, measure)
    if estimate is not None:
        return estimate
    return float(getattr(context.world.objects[detection.label], measure))


def looked_everywhere(wanted: str, searched: Sequence[str]) -> str:
    """"I did not find the X anywhere I looked: the A, the B and the C" (or "nowhere yet")."""
    if not searched:
        return f"I did not get to look anywhere for the {wanted}"
    return f"I did not find the {wanted} anywhere I looked: " + listing(
        [f"the {place}" for place in searched])


def _affordable(context: SkillContext, placement: str) -> bool:
    """Whether a look at ``placement`` and the way back to the operator fit the time left."""
    return _affordable_at(context, context.world.placements[placement].approach.xy())


def _affordable_at(context: SkillContext, there: tuple[float, float]) -> bool:
    """Whether going to ``there``, a look, and the way back to the operator fit the time left."""
    left = time_left(context)
    if math.isinf(left):
        return True
    here = context.robot.pose().xy()
    operator = resolve_target(context, OPERATOR)
    back = operator.xy() if operator is not None else here
    metres = _metres(context, here, there) + _metres(context, there, back)
    speed: float = context.world.robot.speed
    return metres / speed + _LOOK_ALLOWANCE <= left


def _metres(context: SkillContext, start: tuple[float, float],
            goal: tuple[float, float]) -> float:
    """The route's length on the robot's map (a detour's guess through doors believed shut)."""
    length = context.navigator.distance(start, goal, frozenset(context.beliefs.closed_doors))
    return 1.5 * math.dist(start, goal) if math.isinf(length) else length


def matches_person(percept: PersonPercept, description: Mapping[str, Any]) -> bool:
    """Whether a seen person fits every field of a description (name, posture...)."""
    for key, value in description.items():
        wanted = str(value).lower().replace(" ", "_") if key != "clothes" else str(value).lower()
        if key == "name" and fold(percept.name or "") != fold(str(value)):
            return False
        if key == "posture" and percept.posture != wanted:
            return False
        if key == "gesture" and not percept.gesture.startswith(wanted):
            return False
        if key == "clothes" and not any(_wears(wanted, item.lower()) for item in percept.clothes):
            return False
    return True


def _wears(wanted: str, item: str) -> bool:
    """Whether a worn ``item`` fits a description of clothes: "red" fits "red sweater";
    a camera's "red top" fits "red sweater" too (it sees the colour on the upper body,
    not the cut), but not "red trousers"."""
    if wanted in item:
        return True
    words = item.split()
    if len(words) < 2 or words[-1] not in ("top", "trousers"):
        return False
    legs = any(word in LEG_GARMENTS for word in wanted.split())
    return (words[-1] == "trousers") == legs and all(word in wanted.split()
                                                     for word in words[:-1])


class FindPerson(Skill):
    """Find a person fitting a description, in a room or at a placement, and face them.

    Monitor: the person is seen again within reach. Binds ``person``.
    """

    name = "find_person"
    optional = ("person", "room", "placement")
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        description = _description(args.get("person"))
        where = args.get("room") or args.get("placement")
        rooms = [str(args["room"])] if args.get("room") else (
            [context.world.placements[str(args["placement"])].room] if args.get("placement")
            else self._likely_rooms(context, description))
        searched: list[str] = []
        for room in rooms:
            if context.cancel.cancelled:
                return Outcome.cancelled(context.cancel)
            if room not in context.world.rooms:
                return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not know the {where}")
            entrance = resolve_target(context, room)
            if entrance is not None and not _affordable_at(context, entrance.xy()):
                looked = listing([the(place) for place in searched]) or "nowhere yet"
                return Outcome.failed(ErrorCode.OUT_OF_TIME, f"I ran out of time looking for "
                                      f"{_describe(description)}; I looked in {looked}")
            searched.append(room)
            moved = go_into_room(context, room,
                                 str(where) if where and len(rooms) == 1 else room)
            if moved is not None:
                return moved
            for seen in _people_met(context, description):
                if seen.name and matches_person(seen, description):
                    context.beliefs.saw_person(seen.name, seen.position)
                    moved = drive(context, resolve_target(context, seen.name) or
                                  context.robot.pose())
                    if moved.status is not Status.FINISHED:
                        return moved
                    return Outcome.finished(f"I found {seen.name}", person=seen.name)
        return Outcome.failed(ErrorCode.NOT_FOUND,
                              f"I did not find {_describe(description)} in "
                              f"{listing([the(room) for room in rooms])}")

    @staticmethod
    def _likely_rooms(context: SkillContext, description: Mapping[str, Any]) -> list[str]:
        name = description.get("name")
        known = context.beliefs.person_at.get(str(name)) if name else None
        first = [context.world.room_at(*known)] if known else []
        return list(dict.fromkeys([*[r for r in first if r], *context.world.rooms]))

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        person = finished.data["person"]
        if sees_person_nearby(context, person):
            context.bindings["person"] = person
            return Outcome.verified(f"I am with {person}", person=person)
        return Outcome.aborted(ErrorCode.NOT_FOUND, f"{person} is no longer here")


_SAME_PERSON = 1.0  #: metres a person seen again may have moved and still be the one gone to
_NAMELESS_VISITED = 3  #: nameless people the robot goes up to, per room, to see their faces


def _people_met(context: SkillContext, description: Mapping[str, Any]
                ) -> Iterator[PersonPercept]:
    """The people seen in the room; then, for each seen without a name (too far to see
    their face) who may fit the description, nearest first, the people seen after going
    up to them. A robot knows people by their faces, and sees a face only from near."""
    first = people_in_view(context)
    yield from first
    unnamed = {key: value for key, value in description.items() if key != "name"}
    nameless = [seen for seen in first if seen.name is None and
                matches_person(seen, unnamed)]
    for seen in nameless[:_NAMELESS_VISITED]:
        moved = drive(context, pose_near_point(context, seen.position))
        if moved.status is not Status.FINISHED:
            continue
        yield from (again for again in people_in_view(context)
                    if math.dist(again.position, seen.position) <= _SAME_PERSON)


def _describe(description: Mapping[str, Any]) -> str:
    if "name" in description:
        return str(description["name"])
    if not description:
        return "anyone"
    return a(described_people(description, 1))


class Count(Skill):
    """Count objects of a category on a placement, or people fitting a description in a room.

    Monitor: a second count agrees with the first. Binds ``result`` (a sentence).
    """

    name = "count"
    optional = ("object", "placement", "person", "room")
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        counted = self._count(context, args)
        if isinstance(counted, Outcome):
            return counted
        return Outcome.finished(count=counted)

    def _count(self, context: SkillContext, args: Mapping[str, Any]) -> int | Outcome:
        if args.get("placement"):
            outcome, detections = go_and_look(context, str(args["placement"]))
            if outcome.status is not Status.FINISHED:
                return outcome
            wanted = str(args.get("object", ""))
            return sum(1 for d in detections if not wanted or matches_object(context, wanted, d))
        room = str(args.get("room", ""))
        if room not in context.world.rooms:
            return Outcome.failed(ErrorCode.UNKNOWN_TARGET, f"I do not know the room {room}")
        moved = go_into_room(context, room, room)
        if moved is not None:
            return moved
        description = _description(args.get("person"))
        return sum(1 for seen in people_in_view(context)
                   if matches_person(seen, description))

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        again = self._count(context, args)
        if isinstance(again, Outcome):
            return Outcome.aborted(again.error or ErrorCode.NOT_FOUND, again.message)
        if again != finished.data["count"]:
            return Outcome.aborted(ErrorCode.NOT_FOUND, "my two counts disagree")
        text = _count_sentence(context, args, again)
        context.bindings["result"] = text
        return Outcome.verified(text, count=again, result=text)


def _count_sentence(context: SkillContext, args: Mapping[str, Any], count: int) -> str:
    if args.get("placement"):
        thing = str(args.get("object") or "object")
        many = context.world.plural_of(thing) if thing in context.world.categories else (
            plural(thing))
        return count_objects(count, thing, many,
                             place_in(context.world, str(args["placement"])))
    return count_people(count, _description(args.get("person")), str(args["room"]))


class Describe(Skill):
    """Tell something about the person last found, or the object with a property on a placement.

    Data and binding ``result``: the sentence to say.
    """

    name = "describe"
    optional = ("info", "property", "object", "placement", "person")

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        if args.get("property"):
            return self._object_property(context, args)
        person = context.bindings.get("person")
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I have nobody to describe")
        for seen in people_in_view(context):
            if seen.name == person:
                info = str(args.get("info", "name"))
                text = _person_fact(seen, info)
                return Outcome.finished(text, result=text)
        return Outcome.failed(ErrorCode.NOT_FOUND, f"I cannot see {person} any more")

    def _object_property(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        placement = str(args.get("placement", ""))
        outcome, detections = go_and_look(context, placement)
        if outcome.status is not Status.FINISHED:
            return outcome
        wanted = str(args.get("object") or "object")
        known = [d for d in detections if d.label in context.world.objects and (
            wanted == "object" or matches_object(context, wanted, d))]
        if not known:
            return Outcome.failed(ErrorCode.NOT_FOUND, f"I see no {wanted} "
                                  f"{place_in(context.world, placement)}")
        prop = str(args["property"])
        measure = {"biggest": "size", "largest": "size", "smallest": "size",
                   "heaviest": "weight", "lightest": "weight", "thinnest": "size"}
        field = measure.get(prop, "size")
        pick_max = prop in {"biggest", "largest", "heaviest"}
        choose = max if pick_max else min
        best = choose(known, key=lambda d: _measured(context, d, field))
        text = (f"The {prop} {wanted} {place_in(context.world, placement)} is the "
                f"{best.label}.")
        return Outcome.finished(text, result=text)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        context.bindings["result"] = finished.data["result"]
        return Outcome.verified(finished.message, result=finished.data["result"])


def _person_fact(seen: PersonPercept, info: str) -> str:
    return person_fact(seen.name, info, seen.posture, seen.gesture, seen.clothes)


def _description(person: Any) -> dict[str, Any]:
    """A person argument as a description: a mapping as it is, a bare name as ``{name}``."""
    if not person:
        return {}
    return dict(person) if isinstance(person, Mapping) else {"name": str(person)}
