"""The robot's English: articles, agreement and prepositions for every sentence it says.

Pure functions of names and numbers, so one test can render every sentence with
singular and plural objects and people. Object names are as the world file spells
them; a name that is an English plural ("biscuits", "crisps", "noodles") takes
"are", and a container ("fridge", "pantry", "drawer") takes "in" where a surface
("table", "shelf") takes "on".
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from homebot.world import World

__all__ = [
    "a",
    "arrived",
    "be",
    "count_objects",
    "count_people",
    "described_people",
    "here_is",
    "is_plural",
    "listing",
    "number",
    "object_is_at",
    "person_fact",
    "place",
    "place_in",
    "plural",
    "preposition",
    "the",
]

# Nouns ending in s that are singular ("glass", "bus", "hummus", "lettuce" needs no rule).
_SINGULAR_S = ("ss", "us", "is", "os", "ics")
_SINGULAR_WORDS = frozenset({"news", "chess", "lens", "gas", "series", "species"})
# Names that are plural without an s ("people"); mass nouns stay singular ("water").
_PLURAL_WORDS = frozenset({"people", "children", "men", "women", "feet", "teeth", "mice",
                           "dice", "trousers", "jeans", "glasses", "scissors", "pants",
                           "shorts", "clothes"})
# Places one puts things into rather than onto.
_CONTAINERS = frozenset({
    "fridge", "refrigerator", "freezer", "pantry", "cabinet", "cupboard", "drawer", "drawers",
    "dishwasher", "wardrobe", "closet", "bin", "trashbin", "basket", "box", "oven", "microwave",
    "sink", "bag", "container", "crate", "bucket", "bowl", "tray", "washing machine"})
_VOWEL_SOUND_EXCEPTIONS = {"one": False, "uni": False, "use": False, "eu": False, "hour": True,
                           "honest": True, "heir": True}
_NUMBERS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine",
            "ten", "eleven", "twelve")
_GESTURES = {"waving": "waving", "raising_left_arm": "raising the left arm",
             "raising_right_arm": "raising the right arm", "pointing_left": "pointing to the left",
             "pointing_right": "pointing to the right", "none": ""}


def is_plural(noun: str) -> bool:
    """Whether a name is an English plural ("biscuits", "crisps", "toy cars", "dice")."""
    last = noun.strip().lower().split()[-1] if noun.strip() else ""
    if last in _PLURAL_WORDS:
        return True
    if last in _SINGULAR_WORDS or not last.endswith("s") or last.endswith(_SINGULAR_S):
        return False
    return len(last) > 2


def plural(noun: str) -> str:
    """The plural of a singular English noun ("glass" -> "glasses", "candy" -> "candies")."""
    if is_plural(noun):
        return noun
    head, _, last = noun.rpartition(" ")
    prefix = f"{head} " if head else ""
    irregular = {"person": "people", "child": "children", "man": "men", "woman": "women",
                 "knife": "knives", "leaf": "leaves", "shelf": "shelves", "mouse": "mice"}
    if last in irregular:
        return prefix + irregular[last]
    if last.endswith(("s", "x", "z", "ch", "sh")):
        return f"{prefix}{last}es"
    if last.endswith("y") and len(last) > 1 and last[-2] not in "aeiou":
        return f"{prefix}{last[:-1]}ies"
    return f"{prefix}{last}s"


def be(noun: str | int) -> str:
    """ "is" or "are" for a noun phrase or a count."""
    if isinstance(noun, int):
        return "is" if noun == 1 else "are"
    return "are" if is_plural(noun) else "is"


def the(noun: str) -> str:
    """The noun with "the"; a person's name stays bare ("Maria")."""
    return noun if noun[:1].isupper() else f"the {noun}"


def a(noun: str) -> str:
    """The noun with "a"/"an" ("an apple", "a uniform", "an hour"); plurals take none."""
    if is_plural(noun):
        return noun
    word = noun.lower()
    vowel = next((sound for start, sound in _VOWEL_SOUND_EXCEPTIONS.items()
                  if word.startswith(start)), word[:1] in set("aeiou"))
    return f"{'an' if vowel else 'a'} {noun}"


def number(count: int) -> str:
    """A count in words up to twelve ("no", "one", "two"), in digits beyond."""
    return _NUMBERS[count] if 0 <= count < len(_NUMBERS) else str(count)


def listing(items: Sequence[str]) -> str:
    """ "a", "a and b", "a, b and c"."""
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " and " + items[-1]


def preposition(placement: str, kind: str = "furniture") -> str:
    """ "in" for a container or a room, "at" for a spot, else "on" ("on the kitchen table")."""
    if kind == "room":
        return "in"
    if kind == "spot":
        return "at"
    words = placement.lower().split()
    if words and (words[-1] in _CONTAINERS or " ".join(words[-2:]) in _CONTAINERS):
        return "in"
    return "on"


def place(placement: str, kind: str = "furniture") -> str:
    """ "in the fridge", "on the kitchen table", "in the kitchen", "at the entrance"."""
    return f"{preposition(placement, kind)} the {placement}"


def place_in(world: World, name: str) -> str:
    """ ``place`` for a name of ``world``: a placement (by its kind), a room, or a person."""
    if name in world.placements:
        return place(name, world.placements[name].model.kind.value)
    if name in world.rooms:
        return place(name, "room")
    return f"at {the(name)}"


def arrived(world: World, target: str, operator: bool = False) -> str:
    """ "I am back with you" (the operator), "I am with Maria", "I am in the kitchen",
    "I am at the kitchen table"."""
    if operator:
        return "I am back with you"
    if target in world.people:
        return f"I am with {target}"
    if target in world.rooms:
        return f"I am in the {target}"
    return f"I am at {the(target)}"


def here_is(person: str, thing: str) -> str:
    """What the robot says handing something over: "Alex, here are the biscuits." """
    return f"{person}, here {be(thing)} the {thing}."


def object_is_at(thing: str, where: str) -> str:
    """ "The cola is in the fridge." / "The biscuits are in the pantry." """
    return f"The {thing} {be(thing)} {where}."


def count_objects(count: int, singular: str, plural_form: str, where: str) -> str:
    """ "There is one apple on the kitchen table." / "There are no drinks in the fridge." """
    noun = singular if count == 1 else plural_form
    return f"There {be(count)} {number(count)} {noun} {where}."


def described_people(description: Mapping[str, Any], count: int) -> str:
    """ "lying person", "people waving", "person wearing a red sweater" (no article)."""
    noun = "person" if count == 1 else "people"
    posture = str(description.get("posture", "")).replace("_", " ")
    before = f"{posture} " if posture else ""
    after = []
    gesture = _GESTURES.get(str(description.get("gesture", "")).lower().replace(" ", "_"),
                            str(description.get("gesture", "")).replace("_", " "))
    if gesture:
        after.append(gesture)
    clothes = description.get("clothes")
    if clothes:
        after.append(f"wearing {a(str(clothes))}")
    return (before + noun + (" " + " and ".join(after) if after else "")).strip()


def count_people(count: int, description: Mapping[str, Any], room: str) -> str:
    """ "There is a lying person in the bedroom." / "There are two people waving in the office."

    A count of no one says "nobody" ("There is nobody in the kitchen.") when no
    description narrows it.
    """
    if count == 0 and not description:
        return f"There is nobody in the {room}."
    phrase = described_people(description, count)
    amount = "a" if count == 1 else number(count)
    if count == 1 and not phrase.startswith("person") and a(phrase).startswith("an "):
        amount = "an"
    return f"There {be(count)} {amount} {phrase} in the {room}."


def person_fact(name: str | None, info: str, posture: str, gesture: str,
                clothes: Sequence[str]) -> str:
    """ "Maria is sitting." / "Maria is raising the left arm." / "John is wearing a white shirt
    and black trousers." / "This is Sophie." """
    who = name or "The person"
    if info in {"pose", "posture"}:
        return f"{who} is {posture.replace('_', ' ')}."
    if info == "gesture":
        doing = _GESTURES.get(gesture, gesture.replace("_", " "))
        return f"{who} is {doing}." if doing else f"{who} is not making any gesture."
    if info == "clothes":
        worn = listing([a(item) for item in clothes]) or "nothing I can recognise"
        return f"{who} is wearing {worn}."
    if info == "description":
        parts = [posture.replace("_", " ")] if posture and posture != "unknown" else []
        doing = _GESTURES.get(gesture, gesture.replace("_", " ")) if gesture else ""
        if doing and gesture not in {"none", "unknown"}:
            parts.append(doing)
        worn = listing([a(item) for item in clothes])
        if worn:
            parts.append(f"wearing {worn}")
        said = listing(parts) if parts else "there, but I cannot tell more"
        return f"{name or 'The person'} is {said}."
    return f"This is {name}." if name else "I do not know this person's name."
