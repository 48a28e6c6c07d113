"""The inventory's KB updates, the decision's budget, and the request helpers."""

from __future__ import annotations

import ast
from collections.abc import Callable
from pathlib import Path

import homebot.inference
from homebot.inference import (
    HAND,
    USER,
    Carry,
    Inventory,
    age_in_words,
    decide,
    fetch_task,
    requested_product,
)

Distance = Callable[[str, str], float]


def test_a_product_not_found_twice_carries_the_double_exception(
        three_shelves: Inventory) -> None:
    three_shelves.believe_at("coke", "s2", "seen on s2")
    three_shelves.believe_not_at("coke", "s2", "not on s2 after all")
    assert three_shelves.believed_at("coke") is None
    assert three_shelves.kb.value("coke", "loc=>s1") == "no"
    assert three_shelves.kb.value("coke", "loc=>s2") == "no"
    three_shelves.believe_home("coke", "back")
    assert three_shelves.believed_at("coke") == "s1"
    assert three_shelves.kb.taxonomy.individual("coke").relations == []


def test_running_out_is_a_property_that_a_sighting_withdraws(three_shelves: Inventory) -> None:
    three_shelves.believe_out_of_stock("coke", "ran out")
    assert three_shelves.out_of_stock("coke")
    three_shelves.believe_at("coke", "s3", "seen on s3")
    assert not three_shelves.out_of_stock("coke")
    assert [c.text for c in three_shelves.changes if c.text] == ["ran out", "seen on s3"]


def test_the_shipped_kb_knows_shelves_substitutes_and_the_age_limit() -> None:
    inventory = Inventory.load("supermarket")
    assert inventory.shelves == ("shelf_drinks", "shelf_food", "shelf_bread")
    assert inventory.place("shelf_food") == "shelf food"
    assert inventory.home("heineken") == "shelf_drinks"
    assert inventory.substitute("heineken") == "malz"
    assert inventory.minimum_age("heineken") == 18
    assert inventory.minimum_age("coke") is None
    assert inventory.behaviour("take", "time", 0.0) == 12.0


def test_products_in_hand_are_always_put_somewhere(distance: Distance) -> None:
    request = Carry("coke", "s2", USER)
    pending = [Carry("noodles", HAND, "s2")]
    decision = decide(request, pending, "s1", distance, r_max=0.0, holding=["noodles"])
    assert decision is not None
    assert [c.product for c in decision.chosen] == ["coke", "noodles"]
    assert not decision.within_budget


def test_only_the_cheapest_pending_obligations_are_weighed(distance: Distance) -> None:
    request = Carry("coke", "s2", USER)
    pending = [Carry(f"p{i}", "s3", "s1") for i in range(6)]
    decision = decide(request, pending, "s1", distance, r_max=1e9, consider=2)
    assert decision is not None
    assert len(decision.weighed) == 4


def test_requests_and_answers_in_words() -> None:
    inventory = Inventory.load("supermarket")
    assert requested_product(inventory, "Could you bring me a beer?") == "heineken"
    assert requested_product(inventory, "some noodles please") == "noodles"
    assert requested_product(inventory, "a bicycle") is None
    assert age_in_words("I am twenty five.") == 25
    assert age_in_words("42 years") == 42
    assert age_in_words("no idea") is None
    task = fetch_task(inventory, "coke")
    assert [s.skill for s in task.steps] == ["navigate", "pick", "navigate", "give"]


def test_the_engine_never_imports_the_simulator() -> None:
    package = Path(homebot.inference.__file__).parent
    for module in package.glob("*.py"):
        tree = ast.parse(module.read_text())
        for node in ast.walk(tree):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else (
                [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            assert not any(n.startswith("homebot.sim") for n in names), module.name


def test_exports_are_exactly_the_public_names() -> None:
    public = {name for name in dir(homebot.inference) if not name.startswith("_")}
    modules = {"cycle", "decision", "diagnosis", "inventory", "observation", "planning",
               "service"}
    assert set(homebot.inference.__all__) == public - modules
