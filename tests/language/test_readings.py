"""Issue 12 / CAESAR §3.3: an ambiguous command is carried out on its likeliest reading only
when that is worth more than asking, with the question's cost explicit."""

from __future__ import annotations

from homebot.language import ParseStatus, ReadingModel, Vocabulary, parse_command
from homebot.world import World


def _beliefs(world: World, question: float = 0.25) -> ReadingModel:
    return ReadingModel(object_at={name: obj.placement for name, obj in world.objects.items()},
                        categories={name: obj.category for name, obj in world.objects.items()},
                        question=question, places=len(world.placements))


def test_the_table_where_the_cup_is_believed_to_be(apartment: World,
                                                  vocabulary: Vocabulary) -> None:
    text = "Take the cup from the table"
    assert parse_command(text, vocabulary).status is ParseStatus.CLARIFY  # no beliefs: ask
    result = parse_command(text, vocabulary, readings=_beliefs(apartment))
    assert result.status is ParseStatus.OK
    assert result.steps[0].args == {"to": "kitchen table"}
    assert result.assumed is not None and "kitchen table" in result.assumed


def test_no_evidence_means_asking(apartment: World, vocabulary: Vocabulary) -> None:
    for text in ("Go to the table", "Bring me the drink"):
        assert parse_command(text, vocabulary,
                             readings=_beliefs(apartment)).status is ParseStatus.CLARIFY


def test_a_dear_question_makes_a_guess_worth_it(apartment: World,
                                                vocabulary: Vocabulary) -> None:
    cheap = parse_command("Go to the table", vocabulary, readings=_beliefs(apartment, 0.25))
    dear = parse_command("Go to the table", vocabulary, readings=_beliefs(apartment, 1.5))
    assert cheap.status is ParseStatus.CLARIFY and dear.status is ParseStatus.OK


def test_a_cup_believed_elsewhere_is_asked_about(apartment: World,
                                                 vocabulary: Vocabulary) -> None:
    model = _beliefs(apartment)
    moved = ReadingModel(object_at={**model.object_at, "cup": "bookshelf"},
                         categories=model.categories, places=model.places)
    assert parse_command("Take the cup from the table", vocabulary,
                         readings=moved).status is ParseStatus.CLARIFY


def test_fetch_the_kitchen_stays_refused(apartment: World, vocabulary: Vocabulary) -> None:
    result = parse_command("Fetch the kitchen", vocabulary, readings=_beliefs(apartment, 5.0))
    assert result.status is ParseStatus.REJECT
