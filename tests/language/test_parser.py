"""Behaviour of the parser: pronouns, operator, category level, chaining, robustness."""

from __future__ import annotations

import string

from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.errors import LanguageError
from homebot.language import ParseStatus, Vocabulary, parse_command


def steps(text: str, vocabulary: Vocabulary) -> list[dict]:
    result = parse_command(text, vocabulary)
    assert result, result
    return result.to_dict()["steps"]


def test_pronoun_it_is_replaced_by_its_referent(vocabulary: Vocabulary) -> None:
    parsed = steps("Find a fruit in the kitchen then get it and deliver it to Maria in the "
                   "kitchen", vocabulary)
    assert {"skill": "pick", "object": "fruit"} in parsed
    assert all("it" not in step.values() for step in parsed)
    assert parsed[-1] == {"skill": "give", "person": "Maria"}


def test_them_refers_to_the_person_last_found(vocabulary: Vocabulary) -> None:
    parsed = steps("Meet John in the bedroom then find them in the bathroom", vocabulary)
    assert parsed[-1] == {"skill": "find_person", "person": {"name": "John"}, "room": "bathroom"}


def test_me_is_the_operator(vocabulary: Vocabulary) -> None:
    assert steps("Bring it to me after taking the cup from the kitchen table",
                 vocabulary)[-2:] == [{"skill": "navigate", "to": "operator"},
                                      {"skill": "give", "person": "operator"}]


def test_take_is_guide_for_people_and_pick_for_objects(vocabulary: Vocabulary) -> None:
    assert steps("Take Maria from the kitchen to the office", vocabulary)[-1] == {
        "skill": "guide", "to": "office"}
    assert steps("Take the cup from the kitchen table", vocabulary)[-1] == {
        "skill": "pick", "object": "cup"}


def test_synonyms_and_misspellings_map_to_world_names(vocabulary: Vocabulary) -> None:
    assert steps("Go to the refrigerator", vocabulary) == [{"skill": "navigate", "to": "fridge"}]
    assert steps("Go to the bedrom", vocabulary) == [{"skill": "navigate", "to": "bedroom"}]


def test_the_table_in_a_room_is_narrowed_to_that_room(vocabulary: Vocabulary) -> None:
    assert steps("Look at the table in the kitchen", vocabulary)[0] == {
        "skill": "navigate", "to": "kitchen table"}
    result = parse_command("Look at the table in the living room", vocabulary)
    assert result.status is ParseStatus.CLARIFY
    assert "coffee table" in str(result.question) and "side table" in str(result.question)


def test_open_a_door(vocabulary: Vocabulary) -> None:
    assert steps("Open the office door", vocabulary) == [
        {"skill": "open_door", "door": "office door"}]


def test_parse_result_makes_a_task(vocabulary: Vocabulary) -> None:
    result = parse_command("Go to the kitchen", vocabulary)
    task = result.to_task()
    assert task.description == "Go to the kitchen" and len(task.steps) == 1


def test_parsing_is_deterministic(vocabulary: Vocabulary) -> None:
    text = "Grab a snack from the pantry and give it to the waving person in the office"
    assert parse_command(text, vocabulary).to_dict() == parse_command(text, vocabulary).to_dict()


@settings(max_examples=150, deadline=None)
@given(text=st.text(alphabet=string.printable + "éü’“”", max_size=120))
def test_nothing_a_person_types_crashes_the_parser(text: str, vocabulary: Vocabulary) -> None:
    try:
        result = parse_command(text, vocabulary)
    except LanguageError:
        return
    assert result.status in set(ParseStatus)


def test_full_width_letters_and_ligatures_read_as_plain(vocabulary: Vocabulary) -> None:
    assert steps("Ｇｏ ｔｏ ｔｈｅ ｋｉｔｃｈｅｎ", vocabulary) == [
        {"skill": "navigate", "to": "kitchen"}]
    assert steps("ﬁnd a fruit in the kitchen", vocabulary)[1]["object"] == "fruit"
