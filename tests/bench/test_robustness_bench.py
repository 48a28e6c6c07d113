"""The robustness benchmark's referee: an errand the disturbances made impossible is counted
apart, and refusing it is the right outcome."""

from __future__ import annotations

from homebot.app import RunSettings, build_run
from homebot.bench.robustness import ErrandRun, ModeResult, errand_set
from homebot.navigation import Navigator
from homebot.trials.errands import ErrandKind
from homebot.world import DisturbanceModel, World


def _fetch_run(world: World, navigator: Navigator, missing: float) -> ErrandRun:
    errand = next(e for e in errand_set(world, 20, 3) if e.kind is ErrandKind.FETCH)
    run = build_run(RunSettings(world=world, seed=5, navigator=navigator,
                                disturbances=DisturbanceModel(object_missing=missing)))
    errand.arrange(run.simulation)
    report = run.run(errand.task)
    return ErrandRun(errand, report, errand.done(run.simulation), 0.0,
                     run.simulation.events.events)


def test_a_fetch_whose_object_was_taken_out_of_the_home_is_impossible_and_refused(
        apartment: World, apartment_navigator: Navigator) -> None:
    gone = _fetch_run(apartment, apartment_navigator, missing=1.0)
    assert gone.impossible and not gone.done and not gone.report.success
    there = _fetch_run(apartment, apartment_navigator, missing=0.0)
    assert not there.impossible and there.verified
    result = ModeResult("monitored + recovery")
    result.add(gone.outcome())
    result.add(there.outcome())
    figures = result.to_dict()
    assert figures["verified_delivery_rate"] == 0.5
    assert figures["verified_of_possible_rate"] == 1.0
    assert (figures["impossible"], figures["impossible_refused"]) == (1, 1)
