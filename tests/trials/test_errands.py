"""Everyday errands: seeded, the arena set before the run, refereed by the truth."""

from __future__ import annotations

from homebot.app import RunSettings, build_run
from homebot.sim import PERSON_PREFIX
from homebot.task import Step, Task
from homebot.trials.errands import Errand, ErrandKind, errands
from homebot.world import World


def test_errands_are_seeded_and_mix_the_three_kinds(apartment: World) -> None:
    first = errands(apartment, 40, 3)
    assert [e.task for e in first] == [e.task for e in errands(apartment, 40, 3)]
    assert [e.task for e in first] != [e.task for e in errands(apartment, 40, 4)]
    assert {e.kind for e in first} == set(ErrandKind)


def test_a_take_errand_puts_the_object_in_the_persons_hand_before_the_run(
        apartment: World) -> None:
    take = next(e for e in errands(apartment, 40, 3) if e.kind is ErrandKind.TAKE)
    run = build_run(RunSettings(world=apartment, seed=1))
    take.arrange(run.simulation)
    assert run.simulation.object_location[str(take.obj)] == PERSON_PREFIX + take.person
    assert not take.done(run.simulation)
    report = run.run(take.task)
    assert report.success and take.done(run.simulation)
    assert run.simulation.object_location[str(take.obj)] == take.placement


def test_an_ask_errand_is_done_only_when_the_true_answer_reaches_the_operator(
        apartment: World) -> None:
    ask = Errand(ErrandKind.ASK, Task((
        Step("navigate", {"to": "Sophie"}),
        Step("ask", {"person": "Sophie", "question": "what is your name?"}),
        Step("navigate", {"to": "operator"}),
        Step("say", {"text": "$answer"}))), "Sophie", question="what is your name?")
    silent = Task((Step("navigate", {"to": "Sophie"}),
                   Step("ask", {"person": "Sophie", "question": "what is your name?"}),
                   Step("navigate", {"to": "operator"}),
                   Step("say", {"text": "I forgot what she said"})))
    told = build_run(RunSettings(world=apartment, seed=1))
    assert told.run(ask.task).success and ask.done(told.simulation)
    forgotten = build_run(RunSettings(world=apartment, seed=1))
    forgotten.run(silent)
    assert not ask.done(forgotten.simulation)
