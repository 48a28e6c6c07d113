"""RIPS (CAESAR Alg. 2): a Golog program registers the robot, through the skills, in the home."""

from __future__ import annotations

import argparse
from typing import Any

from rich.console import Console

from homebot.golog import Interpreter, State
from homebot.golog.build import do
from homebot.golog.domains import rips_theory
from homebot.golog.skill_executor import SkillExecutor
from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.scenarios.summary import scenario_summary
from homebot.skills import speak
from homebot.task import Step
from homebot.world import World

__all__ = ["PLACES", "SHARED_OPTIONS", "add_arguments", "rips_world", "run"]

SHARED_OPTIONS = (SharedOption(OptionKind.FIDELITY),
                  SharedOption(OptionKind.DISTURBANCE_LEVEL, "--disturb", 0.0,
                               "disturbance level (0: a perfect world)"))

#: the test's names for things, and what they are in the apartment
PLACES = {"Registration Desk": "desk", "Door B": "office door", "Door C": "entrance door",
          "Out C": "entrance"}
SHEET = "registration sheet"
COMMITTEE = "Sophie"  #: the Technical Committee member, at the registration desk


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """No options of its own."""


def rips_world() -> World:
    """The apartment with a registration sheet on the coat rack by the entrance."""
    data = World.load("apartment").to_dict()
    data["categories"].append({"name": "document", "plural": "documents"})
    data["objects"].append({"name": SHEET, "category": "document", "placement": "coat rack"})
    return World.from_dict(data, "apartment + registration sheet")


def _bindings() -> dict[str, Any]:
    def name(value: Any) -> str:
        text = str(value)
        return SHEET if text.lower() == SHEET else PLACES.get(text, text)

    return {
        "grasp": lambda action: [Step("pick", {"object": name(action[1])})],
        "park_arm": lambda action: [],
        "extend_arm": lambda action: [],
        "goto_place": lambda action: [Step("navigate", {"to": name(action[1])})],
        "introduce_yourself_and_the_team": lambda action: [
            Step("say", {"info": "yourself"}), Step("say", {"info": "team"})],
        "give": lambda action: [Step("give", {"person": COMMITTEE,
                                              "object": name(action[1])})],
        "say": lambda action: [Step("say", {"text": str(action[1])})],
    }


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Run ``rips`` from ``rips.golog``; success is the sheet with the committee, robot out."""
    world = rips_world()
    level = getattr(args, "disturb", 0.0)
    simulation_run = build(world, seed=args.seed, level=level if level else None)
    context = simulation_run.context
    waits: list[int] = []

    def waiting(state: State) -> list[tuple[Any, ...]] | None:
        # The robot waits for its start button; the committee presses it on the second look.
        waits.append(len(waits))
        if len(waits) == 1:
            speak(context, "I am ready. Please press my start button.")
            return []
        return [("press_start_button",)] if len(waits) <= 3 else None

    theory = rips_theory()
    executor = SkillExecutor(simulation_run.executive, _bindings(), waiting=waiting)
    def record(entry: dict[str, Any]) -> None:
        # Golog's own steps go into the run's event log beside the skills' events.
        context.events.record(f"golog.{entry['kind']}",
                              **{key: value for key, value in entry.items() if key != "kind"})

    outcome = Interpreter(theory, executor, seed=args.seed, listener=record).run(do("rips"))
    if not outcome.success:
        speak(context, f"I am sorry, I could not finish the registration: {outcome.reason}.")
    simulation = simulation_run.simulation
    with_committee = simulation.object_location.get(SHEET) == f"person:{COMMITTEE}"
    out = world.room_at(*simulation.robot_pose[:2]) == "entrance"
    speech = [event.data["text"] for event in context.events.of_kind("speech")]
    success = outcome.success and out and with_committee
    if console is not None:
        for entry in outcome.detail.log:
            if entry["kind"] in ("action", "exogenous", "wait"):
                console.print(f"  {entry['kind']}: {entry.get('action', '')}", highlight=False)
        for text in speech:
            console.print(f"  robot: {text}", highlight=False)
        console.print(f"RIPS {'done' if success else 'failed'}"
                      f"{': ' + outcome.reason if outcome.reason else ''}")
    return scenario_summary("rips", success, executor.steps, speech,
                            golog_actions=outcome.detail.actions, reason=outcome.reason,
                            handed_over=with_committee,
                            sim_time=round(context.robot.now(), 2))
