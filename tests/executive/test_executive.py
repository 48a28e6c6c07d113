"""The executive: outcomes per step, recovery protocols, telling the operator why."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from homebot.app import Run, RunSettings, build_run
from homebot.bench.robustness import compare_modes
from homebot.cancel import CancelToken
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.robot import Blocker, MoveReport, PersonPercept
from homebot.sim import PERSON_PREFIX
from homebot.skills import ErrorCode
from homebot.task import Step, Task
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import DisturbanceModel, DoorState, World


def _bring(obj: str, placement: str, person: str = "operator") -> Task:
    return Task((Step("navigate", {"to": placement}),
                 Step("find_object", {"object": obj, "placement": placement}),
                 Step("pick", {"object": obj}), Step("navigate", {"to": person}),
                 Step("give", {"person": person})))


def _run(world: World, navigator: Navigator, **kwargs: object) -> Run:
    return build_run(RunSettings(
        world=world, navigator=navigator, **kwargs))  # type: ignore[arg-type]


def test_undisturbed_fetch_is_verified_step_by_step(apartment: World,
                                                    apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    report = run.run(_bring("cola", "fridge"))
    assert report.success
    assert [step.status for step in report.steps] == ["verified"] * 5
    assert run.simulation.object_location["cola"] == PERSON_PREFIX + "Alex"
    assert report.sim_time > 0
    statuses = [e.data["status"] for e in run.simulation.events.of_kind("skill.status")]
    assert statuses.count("finished") == 5 and statuses.count("verified") == 5


def test_closed_doors_are_opened(apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    for door in ("kitchen arch", "kitchen door"):
        run.simulation.door_state[door] = DoorState.CLOSED
    report = run.run(_bring("apple", "kitchen table"))
    assert report.success
    assert "door_closed" in report.steps[0].recoveries


def test_locked_door_gets_someone_to_open_it(apartment: World,
                                             apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.door_state["bedroom door"] = DoorState.LOCKED
    run.simulation.people["Sophie"].position = (3.0, 5.0)
    run.simulation.people["Sophie"].room = "corridor"
    report = run.run(Task((Step("navigate", {"to": "bed"}),)))
    assert report.success
    assert any("open the bedroom door" in text for text in report.speech)


def test_with_nobody_by_a_locked_door_the_robot_goes_to_ask_someone(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Nobody outside the bedroom is near its door (John is inside, behind it), and there
    # is no other way in: the robot goes to someone it can reach (Alex, in the living
    # room) and asks there.
    run = _run(apartment, apartment_navigator)
    run.simulation.door_state["bedroom door"] = DoorState.LOCKED
    door = apartment.doors["bedroom door"].position
    assert all(math.dist(state.position, door) > 3.0
               for state in run.simulation.people.values() if state.room != "bedroom")
    report = run.run(Task((Step("navigate", {"to": "bed"}),)))
    assert report.success, report.reason
    assert any(text.startswith("Alex, could you please open the bedroom door")
               for text in report.speech)
    assert run.simulation.door_state["bedroom door"] is DoorState.OPEN


def test_person_in_the_way_is_asked_to_step_aside(apartment: World,
                                                  apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.place_person_in_doorway("office door", "Maria")
    report = run.run(Task((Step("navigate", {"to": "desk"}),)))
    assert report.success
    assert report.steps[0].recoveries == ("path_blocked",)
    assert any("let me through" in text for text in report.speech)


def test_moved_object_is_searched_for_in_likely_places(apartment: World,
                                                       apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.object_location["cola"] = "coffee table"
    report = run.run(_bring("cola", "fridge"))
    assert report.success
    assert run.context.beliefs.object_at["cola"] == f"person:{apartment.model.operator}"
    assert "not_found" in report.steps[1].recoveries


def test_missing_object_fails_and_the_operator_is_told_why(apartment: World,
                                                           apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.object_location["red wine"] = None
    report = run.run(_bring("red wine", "kitchen counter"))
    assert not report.success
    assert report.steps[-1].skill == "find_object"
    assert report.steps[-1].error == ErrorCode.NOT_FOUND.value
    assert report.speech[-1].startswith("I am sorry") and "red wine" in report.speech[-1]
    # it went back to the operator to say so
    operator = apartment.person("Alex").position
    x, y = run.robot.pose().xy()
    assert abs(x - operator[0]) < 1.5 and abs(y - operator[1]) < 1.5


def test_slipped_grasp_is_retried(apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator, seed=5,
               disturbances=DisturbanceModel(grasp_slip=0.5))
    report = run.run(_bring("biscuits", "pantry"))
    assert report.success
    statuses = [e.data["status"] for e in run.simulation.events.of_kind("skill.status")
                if e.data["skill"] == "pick"]
    assert "retrying" in statuses and statuses[-1] == "verified"


def test_a_grasp_the_robot_will_not_try_again_is_not_retried_by_recovery(
        apartment: World, apartment_navigator: Navigator,
        monkeypatch: pytest.MonkeyPatch) -> None:
    # The robot's own word: every grasp it found failed. Neither the skill's retries nor
    # the slipped-grasp protocol send it back to the same refusal.
    run = _run(apartment, apartment_navigator)
    tries: list[str] = []

    def grasp(detection: object, hand: str) -> str:
        tries.append(hand)
        return "I tried every grasp of the cola I could find, and it kept slipping"

    monkeypatch.setattr(run.robot, "grasp", grasp)
    report = run.run(_bring("cola", "fridge"))
    assert not report.success and len(tries) == 1
    assert report.steps[-1].skill == "pick" and report.steps[-1].error == "not_grasped"
    assert not any("slipping. Let me try again" in line for line in report.speech)


def test_without_monitoring_a_slip_goes_unnoticed(apartment: World,
                                                  apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator, disturbances=DisturbanceModel(grasp_slip=1.0),
               monitoring=False)
    report = run.run(_bring("cola", "fridge"))
    assert [step.status for step in report.steps] == ["finished"] * 5
    assert run.simulation.object_location["cola"] == "fridge"


def test_same_seed_same_event_log(apartment: World, apartment_navigator: Navigator) -> None:
    from homebot.app import disturbed

    logs = []
    for _ in range(2):
        run = _run(apartment, apartment_navigator, seed=11, disturbances=disturbed())
        run.run(_bring("milk", "fridge", "Sophie"))
        logs.append(run.simulation.events.to_json_lines())
    assert logs[0] == logs[1]


@pytest.mark.parametrize("seed", [1])
def test_two_hundred_disturbed_fetches(apartment: World, seed: int) -> None:
    """The issue's robustness test: ≥ 95 % verified with recovery, measurably worse without."""
    monitored, plain = compare_modes(apartment, 200, seed, mix="fetch")
    assert monitored.verified / monitored.tasks >= 0.95
    assert plain.delivered / plain.tasks <= monitored.verified / monitored.tasks - 0.2
    assert monitored.told_why == monitored.failed


def test_fetch_tasks_are_seeded(apartment: World) -> None:
    first = [(t.obj, t.person) for t in fetch_tasks(apartment, 20, 4)]
    assert first == [(t.obj, t.person) for t in fetch_tasks(apartment, 20, 4)]
    assert first != [(t.obj, t.person) for t in fetch_tasks(apartment, 20, 5)]


def test_delivered_reads_ground_truth(apartment: World, apartment_navigator: Navigator) -> None:
    fetch = fetch_tasks(apartment, 1, 0)[0]
    run = _run(apartment, apartment_navigator)
    assert not delivered(run.simulation, fetch)


def test_inference_is_asked_when_an_object_is_not_where_expected(
        apartment: World, apartment_navigator: Navigator) -> None:
    asked = []

    def inference(context, skill, args, outcome, run):
        asked.append((skill, outcome.error))
        found = run("find_object", {"object": args["object"], "placement": "coffee table"})
        return found if skill == "find_object" else True

    run = build_run(RunSettings(
        world=apartment, navigator=apartment_navigator, inference=inference))
    run.simulation.object_location["cola"] = "coffee table"
    report = run.run(_bring("cola", "fridge"))
    assert report.success
    assert asked == [("find_object", ErrorCode.NOT_FOUND)]
    assert not any("look elsewhere" in text for text in report.speech)


def test_inference_gets_a_turn_when_the_protocols_give_up(
        apartment: World, apartment_navigator: Navigator) -> None:
    asked = []

    def inference(context, skill, args, outcome, run):
        asked.append(outcome.error)
        return False

    # nobody will open the locked door, however the robot asks
    data = apartment.to_dict()
    for person in data["people"]:
        person["cooperative"] = False
    run = build_run(RunSettings(
        world=World.from_dict(data), navigator=apartment_navigator, inference=inference))
    run.simulation.door_state["bedroom door"] = DoorState.LOCKED
    report = run.run(Task((Step("navigate", {"to": "bed"}),)))
    assert not report.success
    assert asked == [ErrorCode.DOOR_CLOSED]


def test_run_step_recovers_like_a_task_step(apartment: World,
                                            apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.door_state["bedroom door"] = DoorState.CLOSED
    outcome = run.executive.run_step("navigate", {"to": "bed"})
    assert outcome
    assert not any(e.kind == "task.end" for e in run.simulation.events.events)


def test_the_report_names_the_object_a_recovery_really_picked(
        apartment: World, apartment_navigator: Navigator) -> None:
    def offer_another(context, skill, args, outcome, run):
        found = run("find_object", {"object": "orange juice", "placement": "fridge"})
        taken = run("pick", {"object": "orange juice"})
        return taken if found and taken else False

    run = build_run(RunSettings(
        world=apartment, navigator=apartment_navigator, inference=offer_another))
    run.simulation.object_location["cola"] = None
    report = run.run(Task((Step("navigate", {"to": "fridge"}), Step("pick", {"object": "cola"}))))
    assert report.success
    assert report.steps[1].args == {"object": "orange juice"}


def _obstructed(run: Run, times: int) -> list[object]:
    """Make the robot's first ``times`` motions stop at something nobody is known to be."""
    robot = run.executive.context.robot
    real, calls = robot.move_to, []

    def move_to(goal: Pose, avoid_doors: frozenset[str] = frozenset(),
                escort: str | None = None, *, cancel: CancelToken | None = None) -> MoveReport:
        calls.append(goal)
        if len(calls) <= times:
            return MoveReport(False, robot.pose(), 0.0, Blocker.OBSTRUCTED)
        return real(goal, avoid_doors, escort, cancel=cancel)

    robot.move_to = move_to  # type: ignore[method-assign]
    return calls


def test_an_unknown_obstruction_is_tried_again(apartment: World,
                                               apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    calls = _obstructed(run, times=1)
    report = run.run(Task((Step("navigate", {"to": "desk"}),)))
    assert report.success
    assert report.steps[0].recoveries == ("path_blocked",) and len(calls) == 2


def test_an_obstruction_that_stays_ends_the_trying_and_says_so(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    _obstructed(run, times=1000)
    report = run.run(Task((Step("navigate", {"to": "desk"}),)))
    assert not report.success
    assert 1 <= len(report.steps[0].recoveries) <= 4
    assert any("something I cannot get past" in text for text in report.speech)


def test_someone_taken_for_the_person_who_does_not_take_it_is_not_them(
        apartment: World, apartment_navigator: Navigator,
        monkeypatch: pytest.MonkeyPatch) -> None:
    # A visitor in the kitchen whose face reads as Maria's; Maria is in the office.
    run = _run(apartment, apartment_navigator)
    visitor = run.simulation.place_person_in_doorway("kitchen arch")
    run.simulation.move_person(visitor, (10.5, 2.5))
    run.simulation.move_person("Maria", (9.0, 7.0))
    perceive = run.robot.perceive_people

    def misreading() -> list[PersonPercept]:
        return [replace(seen, name="Maria") if seen.name == visitor else seen
                for seen in perceive()]

    monkeypatch.setattr(run.robot, "perceive_people", misreading)
    report = run.run(_bring("cola", "fridge", "Maria"))
    assert report.success
    assert run.simulation.object_location["cola"] == PERSON_PREFIX + "Maria"
    assert "not_delivered" in report.steps[-1].recoveries
    assert run.context.beliefs.is_mistaken("Maria", (10.5, 2.5))
    assert any("took you for Maria" in text for text in report.speech)
