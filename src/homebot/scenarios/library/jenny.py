"""Care-O-bot "Jenny": bring an object, then guide a person, by HTN plans monitored per operator.

The paper shows a grasp that slips and is retried; "--seed 2" does that here.
"""

from __future__ import annotations

import argparse
from collections import Counter
from typing import Any

from rich.console import Console

from homebot.beliefs import Beliefs
from homebot.htn import Goal, Names, PlanActor, Planner, home_domain, state_from_beliefs
from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.scenarios.summary import scenario_summary
from homebot.world import DisturbanceModel, World

__all__ = ["SHARED_OPTIONS", "add_arguments", "run"]

SHARED_OPTIONS = (
    SharedOption(OptionKind.FIDELITY),
    SharedOption(OptionKind.PROBABILITY, "--slip", 0.5,
                 "probability that a grasp slips (the paper's retried grasp)"),
    SharedOption(OptionKind.PROBABILITY, "--door-closed", 0.0,
                 "probability that each door starts closed"))

# The paper's two scenarios: (task, arguments) in the apartment; the guest is Alex.
_SCENARIOS = (("bring_object", ["pringles", "Alex"]), ("guide_person", ["Alex", "bedroom"]))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """No options of its own."""


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Table 1 from the planner, then both scenarios run through the monitored skills."""
    world = World.load("apartment")
    domain = home_domain()
    state, names = state_from_beliefs(world, Beliefs.from_world(world), world.robot.pose.xy())
    planner = Planner(domain)
    table = {}
    for task, task_args in _SCENARIOS:
        plans = planner.search(state, [Goal.of(task, task_args, world, names, domain).task],
                               limit=None).plans
        table[task] = {"plans": len(plans), "shortest": min(len(plan) for plan in plans)}
    simulation_run = build(
        world, seed=args.seed,
        disturbances=DisturbanceModel(grasp_slip=args.slip, door_closed=args.door_closed))
    actor = PlanActor(simulation_run.executive, domain)
    actions: list[dict[str, Any]] = []
    speech: list[str] = []
    success = True
    for task, task_args in _SCENARIOS:
        names = Names()
        done = actor.run(Goal.of(task, task_args, world, names, domain), names)
        success = success and done.success
        actions += [report.to_dict() for report in done.detail.operators]
        speech += done.speech
        if console is not None:
            console.print(f"[bold]{task} {' '.join(task_args)}[/]: "
                          f"{'done' if done else 'not done'}, {len(done.detail.plans)} plan(s), "
                          f"{done.detail.replans} replan(s)", highlight=False)
            for report in done.detail.operators:
                tries = f" after {report.attempts} attempts" if report.attempts > 1 else ""
                console.print(f"  {report.status:9} ({report.operator} "
                              f"{' '.join(map(str, report.args))}){tries}",
                              highlight=False, markup=False)
    statuses = Counter(event.data["status"] for event in
                       simulation_run.simulation.events.of_kind("skill.status"))
    if console is not None:
        for task, row in table.items():
            console.print(f"Table 1, {task}: {row['plans']} solution plans, shortest "
                          f"{row['shortest']}", highlight=False)
        console.print(f"skill statuses: {dict(sorted(statuses.items()))}", highlight=False)
        for text in speech:
            console.print(f"  robot: {text}", highlight=False)
    return scenario_summary("jenny", success, actions, speech, table1=table,
                            statuses=dict(sorted(statuses.items())),
                            sim_time=round(simulation_run.robot.now(), 2))
