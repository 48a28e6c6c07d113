"""Golem-III's supermarket assistant (Fig. 1): a beer is asked for, it ran out, Malz is offered."""

from __future__ import annotations

import argparse
import math
from typing import Any

from rich.console import Console

from homebot.inference import (
    InferenceCycle,
    Inventory,
    age_in_words,
    fetch_task,
    requested_product,
)
from homebot.scenarios.running import OptionKind, RunBuilder, ScenarioRun, SharedOption
from homebot.scenarios.summary import report_actions, scenario_summary
from homebot.sim import ScriptedResponder
from homebot.skills import speak
from homebot.world import World

__all__ = ["SHARED_OPTIONS", "STORY_TRUTH", "add_arguments", "run"]

SHARED_OPTIONS = (SharedOption(OptionKind.FIDELITY),)

GREETING = "Hello, I am the supermarket assistant. How can I help you?"

#: Where the assistant really left things (None: the supermarket ran out of it).
STORY_TRUTH: dict[str, str | None] = {
    "heineken": None, "noodles": "shelf drinks", "baguette": "shelf food"}

_CUSTOMER_SAYS = {
    GREETING: "Could you bring me a beer?",
    "Beer contains alcohol. How old are you?": "I am twenty five.",
    "We ran out of heineken. Would you like malz instead?": "Yes, please.",
}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--r-max", type=_budget, default=240.0,
                        help="the most (expected) seconds a decision may cost (r_max)")
    parser.add_argument("--kb-store", metavar="FILE", default=None,
                        help="keep the robot's KB in this SQLite store across runs")


def _budget(text: str) -> float:
    """An argparse type: r_max, in seconds from 0 up (inf: no limit)."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not value >= 0:  # also false for nan
        raise argparse.ArgumentTypeError(f"r_max is a number of seconds from 0 up, not '{text}'")
    return value


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """The Fig. 1 story; success is the Malz in the customer's hands and the KB up to date."""
    world = World.load("supermarket")
    inventory = Inventory.load("supermarket") if not args.kb_store else Inventory.kept_in(
        args.kb_store)
    cycle = InferenceCycle(inventory, r_max=args.r_max, seed=args.seed)
    simulated = build(world, seed=args.seed, inference=cycle,
                      responder=ScriptedResponder({"customer": _CUSTOMER_SAYS}))
    inventory.clock = simulated.robot.now
    simulated.simulation.object_location.update(STORY_TRUTH)
    context = simulated.context
    run_step = simulated.executive.run_step

    cycle.inspect(context, "shelf_bread", run=run_step)  # the robot's round by the entrance
    run_step("navigate", {"to": "operator"}, recover=False)
    heard = run_step("ask", {"question": GREETING, "person": "operator"}, recover=False)
    request = str(heard.data.get("answer", ""))
    product = requested_product(inventory, request)
    report = None
    if product is None:
        speak(context, "I am sorry, we do not sell that.")
    elif not _old_enough(simulated, inventory, product):
        speak(context, f"I am sorry, I cannot serve you {product}.")
    else:
        speak(context, f"Thank you. I will bring you a {product}.")
        report = simulated.run(fetch_task(inventory, product))
        for step in report.steps:
            if step.skill == "give" and step.status == "verified":
                cycle.handed_over(str(step.args["object"]))
    cycle.tidy_up(context, run=run_step)
    put_back = list(cycle.objects_placed)
    cycle.report_to_manager(context)

    truth = simulated.simulation.object_location
    delivered = sorted(name for name, where in truth.items() if where == "person:customer")
    kb_ok = inventory.out_of_stock("heineken") and all(
        inventory.believed_at(name) == inventory.home(name) for name in put_back)
    success = bool(report and report.success) and delivered == ["malz"] and kb_ok
    dialogue = _dialogue(simulated)
    if console is not None:
        for who, text in dialogue:
            console.print(f"  {who}: {text}", highlight=False)
        for number, record in enumerate(cycle.records, 1):
            facts = record.to_dict()
            assumed = ", ".join(f"{p} on {s}" for p, s in facts["assumed"].items()) or "-"
            console.print(f"  [inference {number}] goal {facts['goal']}; assumed: {assumed}; "
                          f"ran out: {', '.join(facts['ran_out']) or '-'}; plan: "
                          f"{' '.join(facts['plan']) or '-'} ({facts['ended']})",
                          highlight=False, markup=False)
        for message in cycle.messages:
            console.print(f"  [text to the manager] {message}", highlight=False, markup=False)
        console.print(f"delivered: {', '.join(delivered) or 'nothing'}; put back: "
                      f"{', '.join(put_back) or 'nothing'}; "
                      f"{simulated.robot.now():.0f} s simulated")
    summary = scenario_summary(
        "supermarket", success, report_actions(report) if report else [],
        [text for who, text in dialogue if who == "robot"],
        dialogue=[{"who": who, "text": text} for who, text in dialogue],
        delivered=delivered, put_back=put_back, messages=list(cycle.messages),
        cycles=[record.to_dict() for record in cycle.records],
        kb_changes=[change.text for change in inventory.changes if change.text],
        sim_time=round(simulated.robot.now(), 2))
    if inventory.store is not None:
        inventory.store.close()
    return summary


def _old_enough(simulated: ScenarioRun, inventory: Inventory, product: str) -> bool:
    """Alcohol only for adults: the KB's ``min_age`` prompts the question (Fig. 1, box 1)."""
    minimum = inventory.minimum_age(product)
    if minimum is None:
        return True
    kind = next((c for c in inventory.kb.classes_of_individual(product)), product)
    answer = simulated.executive.run_step("ask", {
        "question": f"{kind.capitalize()} contains alcohol. How old are you?",
        "person": "operator"}, recover=False)
    age = age_in_words(str(answer.data.get("answer", "")))
    return age is not None and age >= minimum


def _dialogue(simulated: ScenarioRun) -> list[tuple[str, str]]:
    """Who said what, in order: the robot's speech acts and what people answered."""
    lines: list[tuple[str, str]] = []
    for event in simulated.simulation.events.events:
        if event.kind == "speech":
            lines.append(("robot", str(event.data["text"])))
        elif event.kind == "heard":
            lines.append((str(event.data["person"]), str(event.data["text"])))
    return lines
