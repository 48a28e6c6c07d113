"""A run's cancel token: the running skill ends ``cancelled``, the task stops, the robot says so."""

from __future__ import annotations

from homebot.app import Run, RunSettings, build_run
from homebot.cancel import CancelToken
from homebot.events import Event
from homebot.navigation import Navigator
from homebot.skills import ErrorCode, Status, skill_named
from homebot.task import Step, Task
from homebot.world import World

_TASK = Task((Step("navigate", {"to": "kitchen"}), Step("navigate", {"to": "bedroom"}),
              Step("navigate", {"to": "office"})), "a round of the flat")


def _pressed_during(run: Run, token: CancelToken, target: str, after: float
                    ) -> dict[str, float]:
    """Cancel ``token`` ``after`` simulated seconds into the drive to ``target``."""
    times: dict[str, float] = {}

    def heard(event: Event) -> None:
        if event.kind == "skill.start" and event.data["args"].get("to") == target:
            times["start"] = event.time

    def tick(before: float, now: float) -> None:
        if "start" in times and "press" not in times and now >= times["start"] + after:
            times["press"] = now
            token.cancel("stop pressed")

    run.simulation.events.listeners.append(heard)
    run.simulation.clock.observe(tick, step=0.1)
    return times


def test_a_run_cancelled_mid_drive_stops_there_and_the_robot_says_it_stopped(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    token = CancelToken()
    times = _pressed_during(run, token, "bedroom", after=3.0)
    report = run.run(_TASK, cancel=token)
    assert not report.success and report.reason == "stop pressed"
    assert [(s.skill, s.status, s.error) for s in report.steps] == [
        ("navigate", "verified", None), ("navigate", "failed", "cancelled")]
    assert report.speech[-1] == "All right, I stopped."
    assert not any("sorry" in line for line in report.speech)
    # the drive ended at the press: not in the bedroom, no recovery, no drive back
    assert apartment.room_at(*run.simulation.robot_pose[:2]) != "bedroom"
    after = [e for e in run.simulation.events.events if e.time >= times["press"]]
    assert [e.kind for e in after if e.kind in ("skill.start", "recovery")] == []
    ended = next(e for e in after if e.kind == "skill.status")
    assert ended.data["error"] == "cancelled" and ended.time == times["press"]
    assert next(e for e in after if e.kind == "task.end").data == {
        "success": False, "reason": "stop pressed"}


def test_a_run_cancelled_between_steps_does_not_start_the_next(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    token = CancelToken()

    def heard(event: Event) -> None:
        if event.kind == "skill.status" and event.data["status"] == "verified":
            token.cancel("the operator said stop")

    run.simulation.events.listeners.append(heard)
    report = run.run(_TASK, cancel=token)
    assert [s.status for s in report.steps] == ["verified"]
    assert report.reason == "the operator said stop"
    assert report.speech[-1] == "All right, I stopped."
    assert apartment.room_at(*run.simulation.robot_pose[:2]) == "kitchen"


def test_each_run_takes_its_own_token(apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    token = CancelToken()
    token.cancel("stop pressed")
    stopped = run.run(_TASK, cancel=token)
    assert stopped.steps == [] and stopped.reason == "stop pressed"
    assert run.run(Task((Step("navigate", {"to": "kitchen"}),))).success  # a fresh token


def test_a_skill_run_with_a_cancelled_token_does_not_act(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    run.context.cancel.cancel("emergency stop")
    where = run.simulation.robot_pose
    outcome = skill_named("navigate").run(run.context, {"to": "bedroom"})
    assert outcome.status is Status.FAILED and outcome.error is ErrorCode.CANCELLED
    assert outcome.message == "emergency stop"
    assert run.simulation.robot_pose == where


def test_an_engines_run_takes_its_token_at_its_beginning(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    executive = run.executive
    token = CancelToken()
    token.cancel("goal cancelled")
    assert not run.run(_TASK, cancel=token).success
    executive.begin()  # a new run: not the cancelled one's token
    assert executive.run_step("navigate", {"to": "kitchen"}).status is Status.VERIFIED
    executive.begin(cancel=token)
    outcome = executive.run_step("navigate", {"to": "bedroom"})
    assert outcome.error is ErrorCode.CANCELLED and outcome.message == "goal cancelled"
    assert apartment.room_at(*run.simulation.robot_pose[:2]) == "kitchen"
