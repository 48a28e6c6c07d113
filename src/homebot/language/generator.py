"""Our own GPSR command generator: commands with their expected steps, for any world.

Written from the rulebook's description of the command types (the official
generator has no licence and is not used). Every command comes with the steps
the parser must produce, built here directly from the chosen entities.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from homebot.errors import LanguageError
from homebot.task import Step

__all__ = ["COMMAND_TYPES", "generate_commands"]

Command = tuple[str, list[Step]]

_VERBS = {
    "go": ("go to", "navigate to", "head to", "move to"),
    "take": ("take", "get", "grasp", "fetch", "grab", "pick up"),
    "find": ("find", "locate", "look for", "search for"),
    "meet": ("meet",),
    "bring": ("bring", "give", "deliver"),
    "bring_me": ("bring me", "give me", "fetch me"),
    "place": ("put", "place"),
    "greet": ("greet", "salute", "say hello to", "introduce yourself to"),
    "follow": ("follow",),
    "guide": ("guide", "escort", "take", "lead"),
    "tell": ("tell", "say"),
    "answer": ("answer a question", "answer a quiz"),
}
_TOPICS = (("the time", "the time"), ("what day is today", "what day is today"),
           ("what day is tomorrow", "what day is tomorrow"),
           ("your teams name", "your team's name"), ("your teams country", "your team's country"),
           ("your teams affiliation", "your team's affiliation"),
           ("the day of the week", "the day of the week"),
           ("the day of the month", "the day of the month"),
           ("something about yourself", "something about yourself"), ("a joke", "a joke"))
_GESTURES = (("waving", "waving", True), ("raising their left arm", "raising_left_arm", False),
             ("raising their right arm", "raising_right_arm", False),
             ("pointing to the left", "pointing_left", False),
             ("pointing to the right", "pointing_right", False))
_POSTURES = ("sitting", "standing", "lying")
_COLOURS = ("blue", "yellow", "black", "white", "red", "orange", "gray")
_GARMENTS = (("t shirt", "t-shirt"), ("shirt", "shirt"), ("blouse", "blouse"),
             ("sweater", "sweater"), ("coat", "coat"), ("jacket", "jacket"))
_PROPERTIES = (("biggest", "biggest"), ("largest", "biggest"), ("smallest", "smallest"),
               ("heaviest", "heaviest"), ("lightest", "lightest"), ("thinnest", "thinnest"))
_INFO = ("name", "pose", "gesture")


@dataclass
class _Names:
    rooms: list[str]
    placements: list[str]
    objects: list[str]
    categories: list[str]
    plurals: dict[str, str]
    people: list[str]

    @property
    def locations(self) -> list[str]:
        return self.rooms + self.placements

    def where(self, name: str) -> dict[str, str]:
        return {"room": name} if name in self.rooms else {"placement": name}


class _Generator:
    """One seeded run of the generator over one world's names."""

    def __init__(self, names: _Names, rng: random.Random) -> None:
        self.names = names
        self.rng = rng

    def pick(self, options: Any) -> Any:
        return self.rng.choice(list(options))

    def verb(self, action: str) -> str:
        return str(self.pick(_VERBS[action]))

    def thing(self) -> tuple[str, str]:
        """(words, value): an object by name or a category, with its article."""
        if self.rng.random() < 0.5:
            name = self.pick(self.names.objects)
        else:
            name = self.pick(self.names.categories)
        article = "an" if name[0] in "aeiou" else "a"
        return f"{article} {name}", name

    def person(self, kind: str) -> tuple[str, dict[str, str]]:
        """(words after "the", description) for gesture, posture or clothes."""
        if kind == "gesture":
            words, value, before = self.pick(_GESTURES)
            return (f"{words} person" if before else f"person {words}"), {"gesture": value}
        if kind == "posture":
            posture = self.pick(_POSTURES)
            return f"{posture} person", {"posture": posture}
        colour, (garment, canonical) = self.pick(_COLOURS), self.pick(_GARMENTS)
        article = "an" if colour[0] in "aeiou" else "a"
        return f"person wearing {article} {colour} {garment}", {
            "clothes": f"{colour} {canonical}"}

    def any_person(self) -> tuple[str, dict[str, str]]:
        return self.person(self.pick(("gesture", "posture", "clothes")))

    # ------------------------------------------------------------------ main types

    def go_to_loc(self) -> Command:
        place = self.pick(self.names.locations)
        steps = [Step("navigate", {"to": place})]
        text = f"{self.verb('go')} the {place}"
        follow = self.pick(("find_obj", "find_prs", "meet"))
        where = self.names.where(place)
        if follow == "find_obj":
            words, value = self.thing()
            steps.append(Step("find_object", {"object": value, **where}))
            tail, more = self.object_followups(value, allow_place=True)
            return f"{text} then {self.verb('find')} {words} and {tail}", steps + more
        if follow == "find_prs":
            words, description = self.any_person()
            steps.append(Step("find_person", {"person": description, **where}))
            tail, more = self.person_followup()
            return f"{text} then {self.verb('find')} the {words} and {tail}", steps + more
        name = self.pick(self.names.people)
        steps.append(Step("find_person", {"person": {"name": name}, **where}))
        tail, more = self.person_followup()
        return f"{text} then meet {name} and {tail}", steps + more

    def take_obj(self) -> Command:
        words, value = self.thing()
        place = self.pick(self.names.placements)
        steps = [Step("navigate", {"to": place}),
                 Step("find_object", {"object": value, "placement": place}),
                 Step("pick", {"object": value})]
        tail, more = self.deliver(value)
        return f"{self.verb('take')} {words} from the {place} and {tail}", steps + more

    def find_obj_in_room(self) -> Command:
        words, value = self.thing()
        room = self.pick(self.names.rooms)
        steps = [Step("navigate", {"to": room}),
                 Step("find_object", {"object": value, "room": room})]
        tail, more = self.object_followups(value, allow_place=False)
        return f"{self.verb('find')} {words} in the {room} then {tail}", steps + more

    def find_prs_in_room(self) -> Command:
        words, description = self.person(self.pick(("gesture", "posture")))
        room = self.pick(self.names.rooms)
        article = "an" if words[0] in "aeiou" else "a"
        steps = [Step("navigate", {"to": room}),
                 Step("find_person", {"person": description, "room": room})]
        tail, more = self.person_followup()
        return f"{self.verb('find')} {article} {words} in the {room} and {tail}", steps + more

    def meet_or_greet(self) -> Command:
        room = self.pick(self.names.rooms)
        greet = self.rng.random() < 0.6
        if self.rng.random() < 0.5:
            name = self.pick(self.names.people)
            who, description = name, {"name": name}
        else:
            words, description = self.person("clothes")
            who = f"the {words}"
            greet = True
        steps = [Step("navigate", {"to": room}),
                 Step("find_person", {"person": description, "room": room})]
        if greet:
            steps.append(Step("greet", {}))
        verb = self.verb("greet") if greet else "meet"
        tail, more = self.person_followup()
        return f"{verb} {who} in the {room} and {tail}", steps + more

    def count(self) -> Command:
        if self.rng.random() < 0.5:
            category = self.pick(self.names.categories)
            place = self.pick(self.names.placements)
            text = (f"tell me how many {self.names.plurals[category]} there are on the {place}")
            counted: dict[str, Any] = {"object": category, "placement": place}
        else:
            room = self.pick(self.names.rooms)
            if self.rng.random() < 0.5:
                colour, (garment, canonical) = self.pick(_COLOURS), self.pick(_GARMENTS)
                plural = garment + "s"
                text = f"tell me how many people in the {room} are wearing {colour} {plural}"
                counted = {"person": {"clothes": f"{colour} {canonical}"}, "room": room}
            else:
                posture = self.pick(_POSTURES)
                text = f"tell me how many {posture} persons are in the {room}"
                counted = {"person": {"posture": posture}, "room": room}
        place = counted.get("placement") or counted["room"]
        return text, [Step("navigate", {"to": place}), Step("count", counted),
                      Step("navigate", {"to": "operator"}), Step("say", {"text": "$result"})]

    def tell_property(self) -> Command:
        words, value = self.pick(_PROPERTIES)
        place = self.pick(self.names.placements)
        category = self.pick([*self.names.categories, "object"])
        return (f"tell me what is the {words} {category} on the {place}",
                [Step("navigate", {"to": place}),
                 Step("describe", {"property": value, "object": category, "placement": place}),
                 Step("navigate", {"to": "operator"}), Step("say", {"text": "$result"})])

    def tell_person_info(self) -> Command:
        info = self.pick(_INFO)
        first = self.pick(self.names.locations)
        prep = "in" if first in self.names.rooms else "at"
        steps = [Step("navigate", {"to": first}),
                 Step("find_person", {"person": {}, **self.names.where(first)}),
                 Step("describe", {"info": info})]
        if self.rng.random() < 0.5:
            return (f"tell me the {info} of the person {prep} the {first}",
                    [*steps, Step("navigate", {"to": "operator"}),
                     Step("say", {"text": "$result"})])
        second = self.pick(self.names.placements)
        return (f"tell the {info} of the person {prep} the {first} to the person at the {second}",
                [*steps, Step("navigate", {"to": second}),
                 Step("find_person", {"person": {}, "placement": second}),
                 Step("say", {"text": "$result"})])

    def talk_or_answer(self) -> Command:
        words, description = self.person("gesture")
        room = self.pick(self.names.rooms)
        steps = [Step("navigate", {"to": room}),
                 Step("find_person", {"person": description, "room": room})]
        if self.rng.random() < 0.5:
            topic, value = self.pick(_TOPICS)
            return (f"{self.verb('tell')} {topic} to the {words} in the {room}",
                    [*steps, Step("say", {"info": value})])
        noun = self.pick(("question", "quiz"))
        return (f"answer the {noun} of the {words} in the {room}",
                [*steps, Step("answer_question", {})])

    def follow_or_guide(self) -> Command:
        if self.rng.random() < 0.5:
            name = self.pick(self.names.people)
            who, description = name, {"name": name}
        else:
            words, description = self.any_person()
            who = f"the {words}"
        source = self.pick(self.names.locations)
        target = self.pick(self.names.locations)
        guide = self.rng.random() < 0.6
        skill = "guide" if guide else "follow"
        verb = self.verb("guide") if guide else "follow"
        return (f"{verb} {who} from the {source} to the {target}",
                [Step("navigate", {"to": source}),
                 Step("find_person", {"person": description, **self.names.where(source)}),
                 Step(skill, {"to": target})])

    def bring_me(self) -> Command:
        words, value = self.thing()
        place = self.pick(self.names.placements)
        return (f"{self.verb('bring_me')} {words} from the {place}",
                [Step("navigate", {"to": place}),
                 Step("find_object", {"object": value, "placement": place}),
                 Step("pick", {"object": value}), Step("navigate", {"to": "operator"}),
                 Step("give", {"person": "operator"})])

    def meet_then_find(self) -> Command:
        name = self.pick(self.names.people)
        first = self.pick(self.names.placements)
        room = self.pick(self.names.rooms)
        description = {"name": name}
        return (f"meet {name} at the {first} then {self.verb('find')} them in the {room}",
                [Step("navigate", {"to": first}),
                 Step("find_person", {"person": description, "placement": first}),
                 Step("navigate", {"to": room}),
                 Step("find_person", {"person": description, "room": room})])

    # ------------------------------------------------------------------ follow-ups

    def object_followups(self, value: str, *, allow_place: bool) -> tuple[str, list[Step]]:
        """"take it and deliver it to ..." after an object was found."""
        tail, more = self.deliver(value)
        return (f"{self.verb('take')} it and {tail}",
                [Step("pick", {"object": value}), *more])

    def deliver(self, value: str) -> tuple[str, list[Step]]:
        choice = self.pick(("me", "name", "person", "place"))
        if choice == "place":
            place = self.pick(self.names.placements)
            return (f"{self.verb('place')} it on the {place}",
                    [Step("navigate", {"to": place}), Step("place", {"placement": place})])
        verb = self.verb("bring")
        if choice == "me":
            return (f"{verb} it to me", [Step("navigate", {"to": "operator"}),
                                         Step("give", {"person": "operator"})])
        room = self.pick(self.names.rooms)
        if choice == "name":
            name = self.pick(self.names.people)
            return (f"{verb} it to {name} in the {room}",
                    [Step("navigate", {"to": room}),
                     Step("find_person", {"person": {"name": name}, "room": room}),
                     Step("give", {"person": name})])
        words, description = self.person(self.pick(("gesture", "posture")))
        return (f"{verb} it to the {words} in the {room}",
                [Step("navigate", {"to": room}),
                 Step("find_person", {"person": description, "room": room}), Step("give", {})])

    def person_followup(self) -> tuple[str, list[Step]]:
        choice = self.pick(("talk", "answer", "follow", "follow_to", "guide"))
        if choice == "talk":
            topic, value = self.pick(_TOPICS)
            return f"{self.verb('tell')} {topic}", [Step("say", {"info": value})]
        if choice == "answer":
            return self.verb("answer"), [Step("answer_question", {})]
        if choice == "follow":
            return "follow them", [Step("follow", {})]
        place = self.pick(self.names.locations)
        if choice == "follow_to":
            return f"follow them to the {place}", [Step("follow", {"to": place})]
        return f"{self.verb('guide')} them to the {place}", [Step("guide", {"to": place})]


COMMAND_TYPES: tuple[str, ...] = (
    "go_to_loc", "take_obj", "find_obj_in_room", "find_prs_in_room", "meet_or_greet", "count",
    "tell_property", "tell_person_info", "talk_or_answer", "follow_or_guide", "bring_me",
    "meet_then_find",
)


def generate_commands(world: Any, count: int, seed: int = 0) -> list[Command]:
    """``count`` commands (text, expected steps) over a ``World``'s names, by seed.

    Raises ``LanguageError`` when the world lacks rooms, placements, objects or
    people to talk about.
    """
    names = _Names(
        rooms=sorted(world.rooms), placements=sorted(world.placements),
        objects=sorted(world.objects),
        categories=sorted({obj.category for obj in world.objects.values()}),
        plurals={}, people=sorted(world.people))
    names.plurals = {category: world.plural_of(category) for category in names.categories}
    for label, entries in (("rooms", names.rooms), ("placements", names.placements),
                           ("objects", names.objects), ("people", names.people)):
        if not entries:
            raise LanguageError(f"world '{world.name}' has no {label}; the generator needs "
                                "rooms, placements, objects and people")
    generator = _Generator(names, random.Random(seed))
    builders: list[Callable[[], Command]] = [getattr(generator, kind) for kind in COMMAND_TYPES]
    commands = []
    for _ in range(count):
        text, steps = generator.pick(builders)()
        commands.append((text[0].upper() + text[1:], steps))
    return commands
