"""The robot's English: every sentence template with singular and plural objects and people."""

from __future__ import annotations

import re
from collections.abc import Callable

import pytest

from homebot.app import Run, RunSettings, build_run
from homebot.navigation import Navigator
from homebot.skills import wording
from homebot.skills.perception import looked_everywhere
from homebot.task import Step, Task
from homebot.world import World

SINGULAR_OBJECTS = ("cola", "apple", "orange juice", "glass", "hummus", "rubik cube")
PLURAL_OBJECTS = ("biscuits", "crisps", "noodles", "pringles", "toy cars", "dice")
PEOPLE = ({}, {"posture": "lying"}, {"posture": "sitting", "gesture": "waving"},
          {"gesture": "raising_left_arm"}, {"clothes": "red sweater"},
          {"clothes": "black trousers"}, {"posture": "standing", "clothes": "orange jacket"})


def _check_sentence(text: str) -> None:
    """Checks every sentence of the robot must pass: form, articles, agreement."""
    assert text == text.strip() and "  " not in text, text
    assert text[0].isupper() or text[0].isdigit(), text
    assert not re.search(r"\ba [aeiou]", text, re.IGNORECASE), text  # "a apple"
    assert not re.search(r"\ban [bcdfgjklmnpqrstvwxyz]", text, re.IGNORECASE), text
    assert not re.search(r"\b(1|one|a) (people|persons)\b", text), text
    assert not re.search(r"\b([2-9]|two|three|four|five|no) person\b", text), text
    assert not re.search(r"\bthe the\b|\bthe [A-Z]", text), text  # "the Maria"
    assert not re.search(r"\bThere is (no|[2-9]|two|three)\b", text), text
    assert not re.search(r"\bThere are (1|one|a)\b", text), text
    assert not re.search(r"\bon the (fridge|pantry|dishwasher|cabinet|drawer)\b", text), text
    assert not re.search(r"\b(posture|gesture|clothes) ", text), text  # leaked field names


def _agrees(text: str, thing: str) -> None:
    verb = "are" if thing in PLURAL_OBJECTS else "is"
    wrong = "is" if verb == "are" else "are"
    assert f"the {thing} {wrong}" not in text.lower() and f"{wrong} the {thing}" not in (
        text.lower().replace("here is the", "here is the")), text
    if f"the {thing} " in text.lower() and re.search(rf"the {thing} (is|are)\b", text.lower()):
        assert f"the {thing} {verb}" in text.lower(), text


@pytest.mark.parametrize("thing", SINGULAR_OBJECTS + PLURAL_OBJECTS)
def test_object_sentences_agree_with_the_object(thing: str) -> None:
    plural = thing in PLURAL_OBJECTS
    assert wording.is_plural(thing) is plural
    sentences = [
        wording.here_is("Alex", thing),
        wording.object_is_at(thing, wording.place("fridge")),
        wording.object_is_at(thing, wording.place("kitchen table")),
        looked_everywhere(thing, ["fridge"]) + ".",
        looked_everywhere(thing, ["fridge", "pantry", "kitchen table"]) + ".",
        f"I know {wording.a(thing)}.",
    ]
    for text in sentences:
        _check_sentence(text)
        _agrees(text, thing)
    assert sentences[0] == f"Alex, here {'are' if plural else 'is'} the {thing}."
    assert "the fridge, the pantry and the kitchen table" in sentences[4]


@pytest.mark.parametrize("count", [0, 1, 2, 5, 13])
@pytest.mark.parametrize(("singular", "plural"), [("drink", "drinks"), ("dish", "dishes"),
                                                  ("apple", "apples"), ("object", "objects")])
def test_counting_objects(count: int, singular: str, plural: str) -> None:
    for where in (wording.place("fridge"), wording.place("kitchen table")):
        text = wording.count_objects(count, singular, plural, where)
        _check_sentence(text)
        noun = singular if count == 1 else plural
        assert f" {noun} " in text
    assert wording.count_objects(1, "apple", "apples", "on the table") == (
        "There is one apple on the table.")
    assert wording.count_objects(0, "drink", "drinks", "in the fridge") == (
        "There are no drinks in the fridge.")


@pytest.mark.parametrize("count", [0, 1, 2, 7])
@pytest.mark.parametrize("description", PEOPLE)
def test_counting_people(count: int, description: dict[str, str]) -> None:
    text = wording.count_people(count, description, "bedroom")
    _check_sentence(text)
    assert text.endswith(" in the bedroom.")
    if description:
        assert ("people" if count != 1 else "person") in text
    assert wording.count_people(1, {"posture": "lying"}, "bedroom") == (
        "There is a lying person in the bedroom.")
    assert wording.count_people(2, {"gesture": "waving"}, "office") == (
        "There are two people waving in the office.")


@pytest.mark.parametrize("info", ["name", "pose", "gesture", "clothes"])
@pytest.mark.parametrize("name", ["Maria", None])
@pytest.mark.parametrize("clothes", [("red sweater",), ("black trousers",),
                                     ("white shirt", "blue jeans", "orange jacket")])
def test_facts_about_people(info: str, name: str | None, clothes: tuple[str, ...]) -> None:
    for gesture in ("waving", "raising_left_arm", "pointing_right", "none"):
        text = wording.person_fact(name, info, "sitting", gesture, clothes)
        _check_sentence(text)
        assert "_" not in text
    assert wording.person_fact("John", "clothes", "lying", "none",
                               ["white shirt", "black trousers"]) == (
        "John is wearing a white shirt and black trousers.")


def test_places_take_their_preposition(apartment: World) -> None:
    assert wording.place_in(apartment, "fridge") == "in the fridge"
    assert wording.place_in(apartment, "pantry") == "in the pantry"
    assert wording.place_in(apartment, "kitchen table") == "on the kitchen table"
    assert wording.place_in(apartment, "kitchen") == "in the kitchen"
    assert wording.place_in(apartment, "Maria") == "at Maria"
    assert wording.arrived(apartment, "Alex", operator=True) == "I am back with you"
    assert wording.arrived(apartment, "Maria") == "I am with Maria"
    assert wording.arrived(apartment, "kitchen") == "I am in the kitchen"
    assert wording.arrived(apartment, "couch") == "I am at the couch"


@pytest.mark.parametrize(("word", "article"), [("apple", "an apple"), ("banana", "a banana"),
                                               ("orange juice", "an orange juice"),
                                               ("uniform", "a uniform"), ("hour", "an hour"),
                                               ("biscuits", "biscuits")])
def test_articles(word: str, article: str) -> None:
    assert wording.a(word) == article


def test_every_sentence_template_is_rendered_by_these_tests() -> None:
    rendered: set[Callable[..., str]] = {
        wording.here_is, wording.object_is_at, wording.count_objects, wording.count_people,
        wording.person_fact, wording.arrived, wording.place_in, wording.place, wording.a,
        wording.the, wording.be, wording.is_plural, wording.plural, wording.listing,
        wording.number, wording.preposition, wording.described_people}
    assert {function.__name__ for function in rendered} == set(wording.__all__)


# ------------------------------------------------------------- what the running robot says


def _speech(run: Run, task: Task) -> list[str]:
    report = run.run(task)
    return report.speech


def test_the_robot_says_it_right_in_a_run(apartment: World,
                                          apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    said = _speech(run, Task((Step("navigate", {"to": "pantry"}),
                              Step("find_object", {"object": "biscuits", "placement": "pantry"}),
                              Step("pick", {"object": "biscuits"}),
                              Step("navigate", {"to": "operator"}),
                              Step("give", {"person": "operator"}))))
    assert "Alex, here are the biscuits." in said
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    said = _speech(run, Task((Step("count", {"person": {"posture": "lying"}, "room": "bedroom"}),
                              Step("say", {"text": "$result"}),
                              Step("count", {"object": "drink", "placement": "fridge"}),
                              Step("say", {"text": "$result"}))))
    assert "There is a lying person in the bedroom." in said
    assert "There are five drinks in the fridge." in said
    for text in said:
        _check_sentence(text)


def test_a_plural_object_that_is_gone_is_spoken_of_in_the_plural(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator, time_limit=200))
    run.simulation.object_location["biscuits"] = None
    report = run.run(Task((Step("find_object", {"object": "biscuits", "placement": "pantry"}),)))
    assert "The biscuits are not where I expected. I will look elsewhere." in report.speech
    for text in report.speech:
        _check_sentence(text)
    assert "the biscuits in the pantry" in report.steps[0].message or (
        "anywhere I looked: the pantry" in report.reason)


TASKS = [
    (Step("find_person", {"person": {"name": "Maria"}, "room": "kitchen"}),
     Step("describe", {"info": "gesture"}), Step("say", {"text": "$result"}),
     Step("describe", {"info": "clothes"}), Step("say", {"text": "$result"}),
     Step("greet", {}), Step("guide", {"to": "office"})),
    (Step("count", {"object": "fruit", "placement": "kitchen table"}),
     Step("say", {"text": "$result"}),
     Step("count", {"person": {"gesture": "waving"}, "room": "office"}),
     Step("say", {"text": "$result"}),
     Step("describe", {"property": "biggest", "object": "drink", "placement": "fridge"}),
     Step("say", {"text": "$result"})),
    (Step("find_person", {"person": {"posture": "lying"}, "room": "kitchen"}),),
    (Step("find_object", {"object": "noodles", "placement": "fridge"}),),
    (Step("navigate", {"to": "pantry"}), Step("pick", {"object": "pringles"}),
     Step("navigate", {"to": "operator"}), Step("give", {"person": "operator"})),
]


@pytest.mark.parametrize("steps", TASKS, ids=[steps[0].skill + str(i) for i, steps in
                                                enumerate(TASKS)])
def test_everything_said_in_a_run_passes_the_checks(
        apartment: World, apartment_navigator: Navigator, steps: tuple[Step, ...]) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator, time_limit=300))
    report = run.run(Task(steps))
    assert report.speech
    for text in report.speech:
        for sentence in re.split(r"(?<=[.?!]) ", text):
            _check_sentence(sentence)
