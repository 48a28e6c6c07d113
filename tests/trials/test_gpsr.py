"""The GPSR referee reads the simulator's truth, not the robot's report."""

from __future__ import annotations

from homebot.app import Run, RunSettings, build_run
from homebot.executive import RunReport
from homebot.language import Vocabulary, parse_command
from homebot.task import Step
from homebot.trials.gpsr import judge
from homebot.world import World


def _carried_out(command: str) -> tuple[Run, list[Step], RunReport[None]]:
    world = World.load("apartment")
    parsed = parse_command(command, Vocabulary.from_world(world))
    run = build_run(RunSettings(world=world, seed=2))
    return run, parsed.steps, run.run(parsed.to_task())


def test_a_delivery_is_judged_where_the_object_truly_is() -> None:
    run, steps, report = _carried_out("bring me the cola from the fridge")
    assert judge(run.simulation, steps, report) == (True, "")
    run.simulation.object_location["cola"] = "fridge"  # the report says done; the home not
    done, why = judge(run.simulation, steps, report)
    assert report.success and not done and "cola" in why


def test_a_count_is_judged_against_the_true_number() -> None:
    run, steps, report = _carried_out("how many drinks are in the fridge")
    assert judge(run.simulation, steps, report)[0]
    run.simulation.object_location["water"] = "kitchen table"  # one fewer than was said
    done, why = judge(run.simulation, steps, report)
    assert not done and "there are 4" in why


def test_a_person_given_to_must_fit_the_description() -> None:
    run, steps, report = _carried_out(
        "take the apple from the kitchen table and give it to the waving person in the office")
    assert judge(run.simulation, steps, report)[0]
    run.simulation.object_location["apple"] = "person:John"
    assert not judge(run.simulation, steps, report)[0]
