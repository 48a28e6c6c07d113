"""The cycle in the simulated supermarket: the Fig. 1 story, a declined failure, the bench."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import pytest

from homebot.app import RunSettings, build_run
from homebot.bench import inference as bench
from homebot.cli import scenario
from homebot.cli.scenario import run_builder
from homebot.inference import InferenceCycle, Inventory, fetch_task
from homebot.knowledge.store import KnowledgeStore
from homebot.navigation import Navigator
from homebot.scenarios.library import supermarket as story
from homebot.sim import ScriptedResponder
from homebot.skills import ErrorCode, Outcome, skill_named
from homebot.task import Step, Task
from homebot.world import World


@pytest.fixture(scope="module")
def supermarket_navigator(supermarket: World) -> Navigator:
    return Navigator(supermarket)


def _story(seed: int = 0, *options: str) -> dict:
    parser = argparse.ArgumentParser()
    story.add_arguments(parser)
    args = parser.parse_args(list(options))
    args.seed = seed
    return story.run(args, None, run_builder())


def test_the_fig1_story_ends_with_malz_and_a_message_to_the_manager() -> None:
    summary = _story()
    assert summary["success"]
    assert summary["delivered"] == ["malz"]
    speech = summary["speech"]
    assert "Beer contains alcohol. How old are you?" in speech
    assert "I see coke, malz and noodles, but I do not see the heineken." in speech
    assert "The heineken must have been placed on the shelf of food." in speech
    assert any("we ran out of heineken" in text for text in speech)
    assert "We ran out of heineken. Would you like malz instead?" in speech
    assert any("heineken is out of stock" in m for m in summary["messages"])
    assert summary["put_back"] == ["noodles", "baguette"]
    first, second = summary["cycles"][:2]
    assert first["assumed"]["heineken"] == "shelf_food"
    assert first["decision"] == ["heineken", "noodles"]
    assert second["ended"] == "ran_out"


def test_with_little_to_spare_nothing_is_put_back_and_the_manager_hears_of_it() -> None:
    summary = _story(0, "--r-max", "30")
    assert summary["success"] and summary["delivered"] == ["malz"]
    assert summary["put_back"] == []
    assert "still misplaced: baguette, noodles" in summary["messages"][-1]


def test_the_story_is_the_same_for_the_same_seed() -> None:
    assert _story(3) == _story(3)


def test_homebot_scenario_supermarket_json(capsys: pytest.CaptureFixture[str]) -> None:
    parser = argparse.ArgumentParser(prog="homebot")
    scenario.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["scenario", "supermarket", "--json"])
    assert args.handler(args) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["scenario"] == "supermarket" and summary["success"]


@pytest.mark.parametrize("budget", ["-5", "nan", "lots"])
def test_a_budget_that_is_no_number_of_seconds_is_refused(
    budget: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as caught:
        _story(0, "--r-max", budget)
    assert caught.value.code == 2
    assert f"r_max is a number of seconds from 0 up, not '{budget}'" in capsys.readouterr().err


def test_a_product_on_its_shelf_needs_no_inference(
        supermarket: World, supermarket_navigator: Navigator) -> None:
    inventory = Inventory.load("supermarket")
    cycle = InferenceCycle(inventory)
    run = build_run(RunSettings(
        world=supermarket, navigator=supermarket_navigator, inference=cycle))
    report = run.run(fetch_task(inventory, "coke"))
    assert report.success
    assert cycle.records == []
    assert run.simulation.object_location["coke"] == "person:customer"


def test_a_misplaced_product_is_found_where_the_diagnosis_sends_the_robot(
        supermarket: World, supermarket_navigator: Navigator) -> None:
    inventory = Inventory.load("supermarket")
    cycle = InferenceCycle(inventory)
    run = build_run(RunSettings(
        world=supermarket, navigator=supermarket_navigator, inference=cycle))
    run.simulation.object_location["coke"] = "shelf food"
    report = run.run(fetch_task(inventory, "coke"))
    assert report.success
    assert run.simulation.object_location["coke"] == "person:customer"
    assert cycle.records[0].diagnosis.location["coke"] == "shelf_food"
    assert inventory.believed_at("coke") == "robot"  # until the client has it
    cycle.handed_over("coke")
    assert inventory.believed_at("coke") == "customer"


def test_other_failures_are_left_to_the_protocols(supermarket: World,
                                                  supermarket_navigator: Navigator) -> None:
    cycle = InferenceCycle(Inventory.load("supermarket"))
    run = build_run(RunSettings(world=supermarket, navigator=supermarket_navigator))
    failed = Outcome.failed(ErrorCode.DOOR_CLOSED, "shut")
    assert cycle(run.context, "navigate", {"to": "shelf food"}, failed, lambda *a: failed) is False
    missing = Outcome.failed(ErrorCode.NOT_FOUND, "gone")
    assert cycle(run.context, "pick", {"object": "bicycle"}, missing, lambda *a: missing) is False


def test_the_bench_serves_every_request_and_keeps_the_kb_consistent() -> None:
    parser = argparse.ArgumentParser()
    bench.add_arguments(parser)
    figures = bench.run(parser.parse_args(["--worlds", "12"]), None)
    assert figures["right_outcomes"] == figures["requests"] == 36
    assert figures["kb_consistent_worlds"] == 12
    assert figures["baseline_right_outcomes"] == 36
    assert figures["shelf_visits_until_in_hand"] < figures["baseline_shelf_visits_until_in_hand"]


def test_a_declined_alternative_is_put_back_and_the_request_fails(
        supermarket: World, supermarket_navigator: Navigator) -> None:
    inventory = Inventory.load("supermarket")
    cycle = InferenceCycle(inventory)
    run = build_run(RunSettings(
        world=supermarket, navigator=supermarket_navigator, inference=cycle,
        responder=ScriptedResponder({"customer": {
            "We ran out of heineken. Would you like malz instead?": "No, thanks."}})))
    run.simulation.object_location["heineken"] = None
    report = run.run(fetch_task(inventory, "heineken"))
    assert not report.success
    assert "ran out of heineken" in report.reason
    assert inventory.out_of_stock("heineken")
    assert run.simulation.object_location["malz"] == "shelf drinks"
    assert [r.ended for r in cycle.records][-1] == "taken"


def test_a_failed_find_ends_when_the_product_is_seen(
        supermarket: World, supermarket_navigator: Navigator) -> None:
    inventory = Inventory.load("supermarket")
    cycle = InferenceCycle(inventory)
    run = build_run(RunSettings(
        world=supermarket, navigator=supermarket_navigator, inference=cycle))
    run.simulation.object_location["noodles"] = "shelf bread"
    task = Task((Step("find_object", {"object": "noodles", "placement": "shelf food"}),
                 Step("pick", {"object": "noodles"}), Step("navigate", {"to": "operator"}),
                 Step("give", {"person": "operator", "object": "noodles"})))
    report = run.run(task)
    assert report.success
    assert report.steps[0].status == "verified"
    assert run.simulation.object_location["noodles"] == "person:customer"


def test_placing_a_named_product_never_puts_down_another(
        supermarket: World, supermarket_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=supermarket, navigator=supermarket_navigator))
    run.simulation.hands["left"] = "malz"
    run.simulation.object_location["malz"] = "hand:left"
    run.context.beliefs.took("malz", "left")
    placed = skill_named("place").run(run.context, {"placement": "shelf food",
                                                    "object": "noodles"})
    assert placed.error is ErrorCode.NOT_HOLDING
    assert run.simulation.hands["left"] == "malz"


def test_what_ran_out_is_remembered_in_the_kb_store(tmp_path: Path) -> None:
    store = tmp_path / "supermarket.db"
    first = _story(0, "--kb-store", str(store))
    second = _story(0, "--kb-store", str(store))
    assert first["success"] and second["success"]
    assert second["cycles"][0]["ran_out"] == ["heineken"]
    assert "We ran out of heineken." in second["speech"]
    with KnowledgeStore.open(store) as kept:
        assert kept.kb.value("heineken", "out_of_stock") == "yes"
        assert any("ran out of heineken" in entry.why for entry in kept.history())
