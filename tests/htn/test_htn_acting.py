"""Plans carried out through the monitored skills: retry, abort, replan and give up, by seed."""

from __future__ import annotations

import pytest

from homebot.app import RunSettings, build_run, disturbed
from homebot.errors import PlanningError
from homebot.events import EventLog
from homebot.executive import RunReport
from homebot.htn import Goal, HtnTrace, Names, PlanActor, home_domain, read_domain_text
from homebot.navigation import Navigator
from homebot.world import DisturbanceModel, World


def _carry_out(world: World, navigator: Navigator, task: str, args: list[str], *, seed: int = 0,
               disturbances: DisturbanceModel | None = None, keep: int | None = None,
               **actor: object) -> tuple[RunReport[HtnTrace], EventLog]:
    run = build_run(RunSettings(
        world=world, seed=seed, disturbances=disturbances, navigator=navigator))
    run.simulation.events.keep = keep
    names = Names()
    domain = home_domain()
    done = PlanActor(run.executive, domain, **actor).run(Goal.of(task, args, world, names, domain),
                                                       names)
    return done, run.simulation.events


def _statuses(events: EventLog, skill: str) -> list[str]:
    return [event.data["status"] for event in events.of_kind("skill.status")
            if event.data["skill"] == skill]


def test_bring_object_verified_operator_by_operator(apartment: World,
                                                    apartment_navigator: Navigator) -> None:
    done, events = _carry_out(apartment, apartment_navigator, "bring_object", ["pringles", "Alex"])
    assert done and done.detail.replans == 0 and len(done.detail.plans) == 1
    assert [r.status for r in done.detail.operators] == ["verified"] * 8
    assert [r.skill for r in done.detail.operators] == ["say", "navigate", "find_object", "pick",
                                                 "navigate", "find_person", "give", "say"]
    # Each operator's state machine: executed (finished), then monitored (verified).
    assert _statuses(events, "pick") == ["finished", "verified"]
    assert done.speech[-1] == "I have brought the pringles to Alex."
    kinds = [event.kind for event in events.events]
    assert kinds.count("htn.operator") == 8 and kinds[-1] == "htn.end"


def test_guide_person(apartment: World, apartment_navigator: Navigator) -> None:
    done, _ = _carry_out(apartment, apartment_navigator, "guide_person", ["Alex", "bedroom"])
    assert done and [r.operator for r in done.detail.operators][3] == "!guide"


def test_a_slipping_grasp_is_retried(apartment: World, apartment_navigator: Navigator) -> None:
    done, events = _carry_out(apartment, apartment_navigator, "bring_object",
                              ["pringles", "Alex"], seed=2,
                              disturbances=DisturbanceModel(grasp_slip=0.5))
    grasp = next(r for r in done.detail.operators if r.operator == "!grasp")
    assert done and done.detail.replans == 0 and grasp.attempts == 3 and grasp.status == "verified"
    assert _statuses(events, "pick") == ["finished", "aborted", "retrying", "finished",
                                         "aborted", "retrying", "finished", "verified"]


def test_attempts_are_counted_when_the_log_keeps_only_its_latest_events(
        apartment: World, apartment_navigator: Navigator) -> None:
    # a long-running robot's log lets old events go while a step runs
    done, events = _carry_out(apartment, apartment_navigator, "bring_object",
                              ["pringles", "Alex"], seed=2, keep=5,
                              disturbances=DisturbanceModel(grasp_slip=0.5))
    grasp = next(r for r in done.detail.operators if r.operator == "!grasp")
    assert events.dropped > 0 and (grasp.status, grasp.attempts) == ("verified", 3)


def test_an_aborted_grasp_leads_to_a_new_plan(apartment: World,
                                              apartment_navigator: Navigator) -> None:
    done, events = _carry_out(apartment, apartment_navigator, "bring_object",
                              ["pringles", "Alex"], seed=4,
                              disturbances=DisturbanceModel(grasp_slip=0.5))
    assert done and done.detail.replans == 1 and len(done.detail.plans) == 2
    aborted = [r for r in done.detail.operators if r.status == "aborted"]
    assert [(r.operator, r.error, r.attempts) for r in aborted] == [
        ("!grasp", "not_grasped", 3)]
    # The new plan starts from what the robot believes: at the pantry, not yet announced again.
    assert [step.operator for step in done.detail.plans[1]][:2] == ["!find_object", "!grasp"]
    assert [event.data["reason"] for event in events.of_kind("htn.replan")] == [
        "the pringles slipped from my hand"]


def test_per_operator_retries_are_the_users(apartment: World,
                                            apartment_navigator: Navigator) -> None:
    done, _ = _carry_out(apartment, apartment_navigator, "bring_object", ["pringles", "Alex"],
                         seed=2, disturbances=DisturbanceModel(grasp_slip=0.5),
                         retries={"!grasp": 0})
    grasps = [r for r in done.detail.operators if r.operator == "!grasp"]
    assert grasps[0].attempts == 1 and grasps[0].status == "aborted" and done.detail.replans >= 1


def test_an_object_moved_away_is_searched_for(apartment: World,
                                             apartment_navigator: Navigator) -> None:
    done, events = _carry_out(apartment, apartment_navigator, "bring_object",
                              ["pringles", "Alex"], seed=2,
                              disturbances=DisturbanceModel(object_moved=1.0))
    assert done and done.detail.replans == 1
    failed = [(r.operator, r.args[2], r.status, r.error) for r in done.detail.operators
              if r.status != "verified"]
    assert failed == [("!find_object", "pantry", "failed", "not_found")]
    assert ("!search_object", ("robot", "pringles")) in [(r.operator, r.args)
                                                          for r in done.detail.operators]
    assert "failed" in _statuses(events, "find_object")


def test_closed_doors_are_opened_on_the_way(apartment: World,
                                            apartment_navigator: Navigator) -> None:
    done, events = _carry_out(apartment, apartment_navigator, "guide_person",
                              ["Alex", "bedroom"], seed=2,
                              disturbances=DisturbanceModel(door_closed=1.0))
    assert done
    assert [e.data["error"] for e in events.of_kind("recovery")] == ["door_closed"] * 3
    assert "verified" in _statuses(events, "open_door")


def test_giving_up_after_the_replanning_bound(apartment: World,
                                              apartment_navigator: Navigator) -> None:
    done, events = _carry_out(apartment, apartment_navigator, "bring_object",
                              ["pringles", "Alex"], seed=1,
                              disturbances=DisturbanceModel(grasp_slip=1.0), max_replans=2)
    assert not done and done.detail.replans == 3 and len(done.detail.plans) == 3
    assert "2 new plans did not help" in done.reason
    assert done.speech[-1].startswith("I am sorry, I could not do it: the pringles slipped")
    assert next(iter(events.of_kind("htn.end"))).data["success"] is False


def test_same_seed_same_log(apartment: World, apartment_navigator: Navigator) -> None:
    logs = [_carry_out(apartment, apartment_navigator, "bring_object", ["pringles", "Alex"],
                       seed=4, disturbances=DisturbanceModel(grasp_slip=0.5))[1].to_json_lines()
            for _ in range(2)]
    assert logs[0] == logs[1]


def test_a_missed_second_look_keeps_the_found_placement(
        apartment: World, apartment_navigator: Navigator) -> None:
    done, _ = _carry_out(apartment, apartment_navigator, "place_object",
                              ["cup", "dishwasher"], seed=1, disturbances=disturbed(1.0))
    grasp = next(r for r in done.detail.operators if r.operator == "!grasp")
    assert done and done.detail.replans == 0 and (grasp.status, grasp.attempts) == ("verified", 2)


def test_an_object_moved_away_is_searched_for_and_found(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    run.simulation.object_location["cup"] = "desk"  # someone took it to the office
    names = Names()
    domain = home_domain()
    done = PlanActor(run.executive, domain).run(
        Goal.of("place_object", ["cup", "dishwasher"], apartment, names, domain), names)
    searches = [r.status for r in done.detail.operators if r.operator == "!search_object"]
    assert done and done.detail.replans >= 1 and searches and searches[-1] == "verified"
    assert run.simulation.object_location["cup"] == "dishwasher"


WRONG_MODEL = """\
(defdomain wrong
  ((:operator (!move_base ?r ?from ?to) ((at ?r ?from)) ((at ?r ?from))
              ((at ?r ?to) (object-at cola ?to)))
   (:method (go ?r ?to) there ((object-at cola ?to)) nil
                        drive ((at ?r ?from)) ((!move_base ?r ?from ?to)))))
"""


def test_declared_effects_are_checked_against_the_beliefs(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    domain = read_domain_text(WRONG_MODEL)
    done = PlanActor(run.executive, domain, max_replans=1).run(Goal(("go", "robot", "desk")))
    # The robot got there (navigate verified), but the model's promise is not believed.
    assert not done and [r.status for r in done.detail.operators] == ["verified", "verified"]
    missing = [e.data["missing"] for e in run.simulation.events.of_kind("htn.effects")]
    assert missing == [["object-at cola desk"]] * 2
    assert "after move_base I do not believe object-at cola desk" in done.reason


def test_operators_without_a_skill_are_refused_before_acting(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    domain = read_domain_text("(defdomain d ((:operator (!dance ?r) () () ((danced ?r)))))")
    with pytest.raises(PlanningError, match="no skill runs operator '!dance'"):
        PlanActor(run.executive, domain).run(Goal(("!dance", "robot")))
    assert not list(run.simulation.events.of_kind("skill.start"))


def test_with_monitoring_off_finished_operators_go_on(apartment: World,
                                                      apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator, monitoring=False))
    names = Names()
    domain = home_domain()
    done = PlanActor(run.executive, domain).run(
        Goal.of("bring_object", ["pringles", "Alex"], apartment, names, domain), names)
    assert done and done.detail.replans == 0
    assert [r.status for r in done.detail.operators] == ["finished"] * 8
