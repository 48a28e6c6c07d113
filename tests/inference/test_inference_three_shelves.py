"""The issue's unit cases: the robot seeks coke among three shelves (Golem-III §8)."""

from __future__ import annotations

import random
from collections.abc import Callable

from homebot.inference import (
    USER,
    Carry,
    Inventory,
    decide,
    diagnose,
    fulfil_cognitive_obligations,
    observe,
)

Distance = Callable[[str, str], float]


def _look(inventory: Inventory, shelf: str, labels: set[str],
          known: dict[str, set[str]]) -> list[Carry]:
    observation = observe(inventory, shelf, labels)
    notes = fulfil_cognitive_obligations(inventory, observation)
    known[shelf] = set(observation.seen)
    return [Carry(o.product, o.source, o.destination) for o in notes.obligations]


def _first_look(inventory: Inventory) -> tuple[dict[str, set[str]], list[Carry]]:
    known: dict[str, set[str]] = {}
    pending = _look(inventory, "s1", {"heineken", "noodles"}, known)
    return known, pending


def test_the_first_shelf_shows_what_is_seen_missing_and_misplaced(
        three_shelves: Inventory) -> None:
    observation = observe(three_shelves, "s1", {"heineken", "noodles"})
    assert observation.seen == {"heineken", "noodles"}
    assert observation.missing == {"coke"}
    assert observation.misplaced == {"noodles"}
    assert observation.unaccounted == {"coke"}


def test_cognitive_obligations_correct_the_kb_and_raise_a_put_back(
        three_shelves: Inventory) -> None:
    observation = observe(three_shelves, "s1", {"heineken", "noodles"})
    notes = fulfil_cognitive_obligations(three_shelves, observation)
    assert three_shelves.believed_at("coke") is None
    assert three_shelves.kb.value("coke", "loc=>s1") == "no"
    assert three_shelves.believed_at("noodles") == "s1"
    assert [(o.product, o.source, o.destination) for o in notes.obligations] == [
        ("noodles", "s1", "s2")]
    assert any("coke" in text and "do not know" in text for text in notes.said)
    assert any("noodles" in text and "should be on shelf 2" in text for text in notes.said)


def test_diagnosis_places_coke_and_kellogs_on_the_second_shelf_and_bisquits_on_the_third(
        three_shelves: Inventory, distance: Distance) -> None:
    known, _ = _first_look(three_shelves)
    diagnosis = diagnose(three_shelves, known, "s1", distance, sought="coke",
                         rng=random.Random(1))
    assert diagnosis.contents("s2") == {"coke", "kellogs"}
    assert diagnosis.contents("s3") == {"bisquits"}
    assert diagnosis.contents("s1") == {"heineken", "noodles"}
    assert diagnosis.assumed == {"coke", "kellogs", "bisquits"}
    assert diagnosis.misplaced == {"noodles", "coke"}
    assert diagnosis.actions[0] == ("move", "s1")
    assert ("place", "coke") in diagnosis.actions
    assert diagnosis.actions.index(("move", "s2")) < diagnosis.actions.index(("place", "coke"))


def test_the_decision_is_to_bring_the_coke_and_put_the_noodles_back(
        three_shelves: Inventory, distance: Distance) -> None:
    known, pending = _first_look(three_shelves)
    diagnosis = diagnose(three_shelves, known, "s1", distance, sought="coke")
    request = Carry("coke", diagnosis.location["coke"], USER, assumed=True)
    decision = decide(request, pending, "s1", distance, r_max=200.0)
    assert decision is not None
    assert [c.product for c in decision.chosen] == ["coke", "noodles"]
    kinds = [(a.kind, a.product or a.where) for a in decision.plan.actions
             if a.kind != "search"]
    assert kinds == [("take", "noodles"), ("move", "s2"), ("deliver", "noodles"),
                     ("take", "coke"), ("search_user", USER), ("deliver", "coke")]
    steps = [step.skill for step in decision.plan.steps(lambda shelf: f"shelf {shelf[1]}")]
    assert steps == ["pick", "navigate", "place", "look", "pick", "navigate", "give"]


def test_a_tight_budget_leaves_the_noodles_for_later(
        three_shelves: Inventory, distance: Distance) -> None:
    known, pending = _first_look(three_shelves)
    diagnosis = diagnose(three_shelves, known, "s1", distance, sought="coke")
    request = Carry("coke", diagnosis.location["coke"], USER, assumed=True)
    alone = decide(request, [], "s1", distance, r_max=1e9)
    assert alone is not None
    decision = decide(request, pending, "s1", distance, r_max=alone.plan.score + 1.0)
    assert decision is not None and [c.product for c in decision.chosen] == ["coke"]
    assert decision.within_budget


def test_seeing_only_kellogs_on_the_second_shelf_brings_the_coke_from_the_third(
        three_shelves: Inventory, distance: Distance) -> None:
    known, pending = _first_look(three_shelves)
    first = diagnose(three_shelves, known, "s1", distance, sought="coke")
    pending += _look(three_shelves, "s2", {"kellogs"}, known)
    second = diagnose(three_shelves, known, "s2", distance, sought="coke", previous=first)
    assert second.location["coke"] == "s3"
    assert second.revised == {"coke"}
    request = Carry("coke", "s3", USER, assumed=True)
    decision = decide(request, pending, "s2", distance, r_max=200.0)
    assert decision is not None
    takes = [(a.product, a.where) for a in decision.plan.actions if a.kind == "take"]
    assert ("coke", "s3") in takes


def test_with_every_shelf_seen_the_supermarket_ran_out(
        three_shelves: Inventory, distance: Distance) -> None:
    known, _ = _first_look(three_shelves)
    _look(three_shelves, "s2", {"kellogs"}, known)
    _look(three_shelves, "s3", {"bisquits"}, known)
    diagnosis = diagnose(three_shelves, known, "s3", distance, sought="coke")
    assert "coke" in diagnosis.ran_out
    assert not diagnosis.assumed


def test_other_missing_products_go_to_the_remaining_unseen_shelves_by_seed(
        three_shelves: Inventory, distance: Distance) -> None:
    known: dict[str, set[str]] = {}
    _look(three_shelves, "s1", set(), known)
    first = diagnose(three_shelves, known, "s1", distance, sought="coke", rng=random.Random(7))
    again = diagnose(three_shelves, known, "s1", distance, sought="coke", rng=random.Random(7))
    assert first == again
    assert first.location["coke"] == "s2"
    assert first.location["heineken"] == "s3"
    assert first.explain(three_shelves).startswith("The assistant moved to shelf 2, placed")


def test_a_hypothesis_stands_until_a_look_refutes_it(
        three_shelves: Inventory, distance: Distance) -> None:
    known: dict[str, set[str]] = {}
    _look(three_shelves, "s1", set(), known)
    first = diagnose(three_shelves, known, "s1", distance, sought="coke")
    _look(three_shelves, "s3", {"bisquits", "heineken"}, known)
    second = diagnose(three_shelves, known, "s3", distance, sought="coke", previous=first)
    assert second.location["heineken"] == "s3" and "heineken" not in second.assumed
    assert second.location["coke"] == "s2" and not second.revised
