"""Expected skill steps for the shared GPSR commands, from the type columns and the text.

This checker is written independently of the parser: it knows the fixed sentence
shape of each command type of the competition template (the TSV's type and
follow-up columns say which), cuts the sentence with regular expressions over the
data directory's names, and builds the steps the issue's table prescribes.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from homebot.world.robocup import read_robocup_data

Steps = list[dict[str, Any]]

TOPICS = {
    "something about yourself": "something about yourself", "the time": "the time",
    "what day is today": "what day is today", "what day is tomorrow": "what day is tomorrow",
    "your teams name": "your team's name", "your teams country": "your team's country",
    "your teams affiliation": "your team's affiliation",
    "the day of the week": "the day of the week", "the day of the month": "the day of the month",
}
GESTURES = {
    "waving": "waving", "raising their left arm": "raising_left_arm",
    "raising their right arm": "raising_right_arm", "pointing to the left": "pointing_left",
    "pointing to the right": "pointing_right",
}
POSTURES = ("sitting", "standing", "lying")
PROPERTIES = {"biggest": "biggest", "largest": "biggest", "smallest": "smallest",
              "heaviest": "heaviest", "lightest": "lightest", "thinnest": "thinnest"}
GARMENTS = {"t shirt": "t-shirt", "t shirts": "t-shirt", "shirt": "shirt", "shirts": "shirt",
            "blouse": "blouse", "blouses": "blouse", "sweater": "sweater",
            "sweaters": "sweater", "coat": "coat", "coats": "coat", "jacket": "jacket",
            "jackets": "jacket"}


@dataclass
class Names:
    """The names of one RoboCup data directory, for matching and for kinds."""

    rooms: set[str]
    locations: set[str]
    people: set[str]
    objects: set[str]
    singular: dict[str, str]  # category plural or singular -> singular

    @classmethod
    def from_directory(cls, directory: str) -> Names:
        data = read_robocup_data(directory)
        clean = _clean
        singular: dict[str, str] = {}
        objects: set[str] = set()
        for entry in data["classes"]:
            singular[clean(entry["plural"])] = clean(entry["name"])
            singular[clean(entry["name"])] = clean(entry["name"])
            objects.update(clean(name) for name in entry["objects"])
        return cls(rooms={clean(r) for r in data["rooms"]},
                   locations={clean(loc["name"]) for loc in data["locations"]},
                   people={clean(n) for n in data["names"]}, objects=objects,
                   singular=singular)

    def place(self, name: str) -> dict[str, str]:
        return {"room": name} if name in self.rooms else {"placement": name}


def _clean(text: str) -> str:
    return " ".join(text.replace("_", " ").split())


def _alternation(names: set[str]) -> str:
    return "|".join(re.escape(name.lower()) for name in sorted(names, key=len, reverse=True))


class Expectations:
    """Builds expected steps for (type, follow-ups, text) rows of the shared TSV."""

    def __init__(self, names: Names) -> None:
        self.names = names
        self.name_of = {name.lower(): name for name in names.people}
        loc = _alternation(names.rooms | names.locations)
        self.loc = f"(?P<loc>{loc})"
        self.loc2 = f"(?P<loc2>{loc})"
        self.person = f"(?P<name>{_alternation(names.people)})"
        self.thing = f"(?P<obj>{_alternation(names.objects | set(names.singular))})"
        gesture = "|".join(GESTURES)
        self.desc = (rf"(?P<desc>(?:{'|'.join(POSTURES)}|{gesture}) person|person (?:{gesture})"
                     rf"|person wearing an? [a-z]+ [a-z ]+?)")
        self.topic = f"(?P<topic>{'|'.join(TOPICS)})"

    # ------------------------------------------------------------------ entities

    def description(self, text: str) -> dict[str, str]:
        text = text.strip()
        for posture in POSTURES:
            if text == f"{posture} person" or text == f"{posture} persons":
                return {"posture": posture}
        for phrase, gesture in GESTURES.items():
            if phrase in text:
                return {"gesture": gesture}
        match = re.search(r"wearing (?:an? )?([a-z]+) ([a-z ]+)$", text)
        if match:
            return {"clothes": f"{match.group(1)} {GARMENTS[match.group(2)]}"}
        return {}

    def object_value(self, text: str) -> str:
        return self.names.singular.get(text, text)

    # ------------------------------------------------------------------ main types

    def expected(self, kind: str, followups: str, text: str) -> Steps:
        """The expected steps of one command; raises ``ValueError`` if the text does not
        have the shape its type says."""
        sentence = text.lower().strip().rstrip(".")
        builder = getattr(self, f"_{kind}")
        steps, rest, state = builder(sentence)
        pieces = [piece for piece in re.split(r" (?:and|then) ", rest) if piece] if rest else []
        kinds = [] if followups.strip() == "-" else followups.strip().split(">")
        if len(pieces) != len(kinds):
            raise ValueError(f"{len(pieces)} follow-up pieces for {kinds}: {text}")
        for follow, piece in zip(kinds, pieces, strict=True):
            steps.extend(getattr(self, f"_fu_{follow}")(piece, state))
        return steps

    def _match(self, pattern: str, sentence: str) -> re.Match[str]:
        match = re.fullmatch(pattern, sentence)
        if match is None:
            raise ValueError(f"does not match {pattern!r}: {sentence}")
        return match

    def _goToLoc(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:go|navigate) to the {self.loc}(?: then (?P<rest>.*))?", s)
        where = self.names.place(m["loc"])
        return [{"skill": "navigate", "to": m["loc"]}], m["rest"] or "", {"where": where}

    def _takeObjFromPlcmt(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:take|get|grasp|fetch) an? {self.thing} from the {self.loc}"
                        rf"(?: and (?P<rest>.*))?", s)
        obj = self.object_value(m["obj"])
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_object", "object": obj, **self.names.place(m["loc"])},
                 {"skill": "pick", "object": obj}], m["rest"] or "", {"obj": obj})

    def _findPrsInRoom(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:find|locate|look for) an? {self.desc} in the {self.loc}"
                        rf"(?: and (?P<rest>.*))?", s)
        return self._person_at(m, self.description(m["desc"]))

    def _person_at(self, m: re.Match[str], desc: dict[str, str]) -> tuple[Steps, str, dict]:
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_person", "person": desc, **self.names.place(m["loc"])}],
                m.groupdict().get("rest") or "", {"person": desc})

    def _findObjInRoom(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:find|locate|look for) an? {self.thing} in the {self.loc}"
                        rf"(?: then (?P<rest>.*))?", s)
        obj = self.object_value(m["obj"])
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_object", "object": obj, **self.names.place(m["loc"])}],
                m["rest"] or "", {"obj": obj})

    def _meetPrsAtBeac(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"meet {self.person} in the {self.loc}(?: and (?P<rest>.*))?", s)
        return self._person_at(m, {"name": self.name_of[m["name"]]})

    def _report(self) -> Steps:
        return [{"skill": "navigate", "to": "operator"}, {"skill": "say", "text": "$result"}]

    def _countObjOnPlcmt(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"tell me how many {self.thing} there are on the {self.loc}", s)
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "count", "object": self.object_value(m["obj"]),
                  **self.names.place(m["loc"])}, *self._report()], "", {})

    def _countPrsInRoom(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"tell me how many (?P<desc>.+?) are in the {self.loc}", s)
        desc = self.description(m["desc"].replace("persons", "person"))
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "count", "person": desc, **self.names.place(m["loc"])},
                 *self._report()], "", {})

    def _countClothPrsInRoom(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"tell me how many people in the {self.loc} are wearing "
                        rf"(?P<colour>[a-z]+) (?P<garment>[a-z ]+)", s)
        desc = {"clothes": f"{m['colour']} {GARMENTS[m['garment']]}"}
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "count", "person": desc, **self.names.place(m["loc"])},
                 *self._report()], "", {})

    def _tellPrsInfoInLoc(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"tell me the (?P<info>name|pose|gesture) of the person (?:in|at) "
                        rf"the {self.loc}", s)
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_person", "person": {}, **self.names.place(m["loc"])},
                 {"skill": "describe", "info": m["info"]}, *self._report()], "", {})

    def _tellObjPropOnPlcmt(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"tell me what is the (?P<prop>[a-z]+) object on the {self.loc}", s)
        return self._describe(m, "object")

    def _tellCatPropOnPlcmt(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"tell me what is the (?P<prop>[a-z]+) {self.thing} on the {self.loc}",
                        s)
        return self._describe(m, self.object_value(m["obj"]))

    def _describe(self, m: re.Match[str], obj: str) -> tuple[Steps, str, dict[str, Any]]:
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "describe", "property": PROPERTIES[m["prop"]], "object": obj,
                  **self.names.place(m["loc"])}, *self._report()], "", {})

    def _talkInfoToGestPrsInRoom(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:say|tell) {self.topic} to the {self.desc} in the {self.loc}", s)
        steps, _, _ = self._person_at(m, self.description(m["desc"]))
        return [*steps, {"skill": "say", "info": TOPICS[m["topic"]]}], "", {}

    def _answerToGestPrsInRoom(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"answer the (?:question|quiz) of the {self.desc} in the {self.loc}", s)
        steps, _, _ = self._person_at(m, self.description(m["desc"]))
        return [*steps, {"skill": "answer_question"}], "", {}

    def _followNameFromBeacToRoom(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"follow {self.person} from the {self.loc} to the {self.loc2}", s)
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_person", "person": {"name": self.name_of[m["name"]]},
                  **self.names.place(m["loc"])}, {"skill": "follow", "to": m["loc2"]}], "", {})

    def _guide(self, s: str, who: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:guide|escort|take|lead) {who} from the {self.loc} to the "
                        rf"{self.loc2}", s)
        desc = ({"name": self.name_of[m["name"]]} if "name" in m.groupdict()
                else self.description(m["desc"]))
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_person", "person": desc, **self.names.place(m["loc"])},
                 {"skill": "guide", "to": m["loc2"]}], "", {})

    def _guideNameFromBeacToBeac(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        return self._guide(s, self.person)

    def _guidePrsFromBeacToBeac(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        return self._guide(s, f"the {self.desc}")

    _guideClothPrsFromBeacToBeac = _guidePrsFromBeacToBeac

    def _bringMeObjFromPlcmt(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:bring|give) me an? {self.thing} from the {self.loc}", s)
        obj = self.object_value(m["obj"])
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_object", "object": obj, **self.names.place(m["loc"])},
                 {"skill": "pick", "object": obj}, {"skill": "navigate", "to": "operator"},
                 {"skill": "give", "person": "operator"}], "", {})

    def _greet(self, s: str, who: str, desc_of: Any) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"(?:greet|salute|say hello to|introduce yourself to) {who} in the "
                        rf"{self.loc}(?: and (?P<rest>.*))?", s)
        steps, rest, state = self._person_at(m, desc_of(m))
        return [*steps, {"skill": "greet"}], rest, state

    def _greetClothDscInRm(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        return self._greet(s, f"the {self.desc}", lambda m: self.description(m["desc"]))

    def _greetNameInRm(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        return self._greet(s, self.person, lambda m: {"name": self.name_of[m["name"]]})

    def _meetNameAtLocThenFindInRm(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"meet {self.person} (?:at|in) the {self.loc} then "
                        rf"(?:find|locate|look for) them in the {self.loc2}", s)
        desc = {"name": self.name_of[m["name"]]}
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_person", "person": desc, **self.names.place(m["loc"])},
                 {"skill": "navigate", "to": m["loc2"]},
                 {"skill": "find_person", "person": desc, **self.names.place(m["loc2"])}],
                "", {})

    def _tellPrsInfoAtLocToPrsAtLoc(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"tell the (?P<info>name|pose|gesture) of the person (?:at|in) the "
                        rf"{self.loc} to the person (?:at|in) the {self.loc2}", s)
        return ([{"skill": "navigate", "to": m["loc"]},
                 {"skill": "find_person", "person": {}, **self.names.place(m["loc"])},
                 {"skill": "describe", "info": m["info"]},
                 {"skill": "navigate", "to": m["loc2"]},
                 {"skill": "find_person", "person": {}, **self.names.place(m["loc2"])},
                 {"skill": "say", "text": "$result"}], "", {})

    def _followPrsAtLoc(self, s: str) -> tuple[Steps, str, dict[str, Any]]:
        m = self._match(rf"follow the {self.desc} (?:in|at) the {self.loc}", s)
        steps, _, _ = self._person_at(m, self.description(m["desc"]))
        return [*steps, {"skill": "follow"}], "", {}

    # ------------------------------------------------------------------ follow-ups

    def _fu_findObj(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"(?:find|locate|look for) an? {self.thing}", piece)
        state["obj"] = self.object_value(m["obj"])
        return [{"skill": "find_object", "object": state["obj"], **state["where"]}]

    def _fu_findPrs(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"(?:find|locate|look for) the {self.desc}", piece)
        return [{"skill": "find_person", "person": self.description(m["desc"]),
                 **state["where"]}]

    def _fu_meetName(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"meet {self.person}", piece)
        return [{"skill": "find_person", "person": {"name": self.name_of[m["name"]]},
                 **state["where"]}]

    def _fu_takeObj(self, piece: str, state: dict[str, Any]) -> Steps:
        self._match(r"(?:take|get|grasp|fetch) it", piece)
        return [{"skill": "pick", "object": state["obj"]}]

    def _fu_placeObjOnPlcmt(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"(?:put|place) it on the {self.loc}", piece)
        return [{"skill": "navigate", "to": m["loc"]}, {"skill": "place", "placement": m["loc"]}]

    def _fu_deliverObjToMe(self, piece: str, state: dict[str, Any]) -> Steps:
        self._match(r"(?:bring|give|deliver) it to me", piece)
        return [{"skill": "navigate", "to": "operator"}, {"skill": "give", "person": "operator"}]

    def _fu_deliverObjToPrsInRoom(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"(?:bring|give|deliver) it to the {self.desc} in the {self.loc}", piece)
        return [{"skill": "navigate", "to": m["loc"]},
                {"skill": "find_person", "person": self.description(m["desc"]),
                 **self.names.place(m["loc"])}, {"skill": "give"}]

    def _fu_deliverObjToNameAtBeac(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"(?:bring|give|deliver) it to {self.person} in the {self.loc}", piece)
        name = self.name_of[m["name"]]
        return [{"skill": "navigate", "to": m["loc"]},
                {"skill": "find_person", "person": {"name": name}, **self.names.place(m["loc"])},
                {"skill": "give", "person": name}]

    def _fu_talkInfo(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"(?:say|tell) {self.topic}", piece)
        return [{"skill": "say", "info": TOPICS[m["topic"]]}]

    def _fu_answerQuestion(self, piece: str, state: dict[str, Any]) -> Steps:
        self._match(r"answer an? (?:question|quiz)", piece)
        return [{"skill": "answer_question"}]

    def _fu_followPrs(self, piece: str, state: dict[str, Any]) -> Steps:
        self._match(r"follow them", piece)
        return [{"skill": "follow"}]

    def _fu_followPrsToRoom(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"follow them to the {self.loc}", piece)
        return [{"skill": "follow", "to": m["loc"]}]

    def _fu_guidePrsToBeacon(self, piece: str, state: dict[str, Any]) -> Steps:
        m = self._match(rf"(?:guide|escort|take|lead) them to the {self.loc}", piece)
        return [{"skill": "guide", "to": m["loc"]}]
