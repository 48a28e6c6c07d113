"""JSHOP2's features on fixtures of our own, its ten example domains, and repeatable plans.

The expected plans of the fixtures are those JSHOP2 1.0.3 (built from its distribution)
finds for the same files. The distribution's own examples are not shipped (its licence is
not stated in the copy we read): point ``HOMEBOT_JSHOP2_EXAMPLES`` at its ``examples``
directory to plan all ten.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from homebot.beliefs import Beliefs
from homebot.cli import main
from homebot.errors import PlanningError
from homebot.htn import Goal, Planner, State, home_domain, read_domain_text, state_from_beliefs
from homebot.world import World

DATA = Path(__file__).parent / "data" / "jshop2"


def _plan(capsys: pytest.CaptureFixture[str], *argv: str) -> list[str]:
    assert main(["plan", *argv, "--json"]) == 0
    plans = json.loads(capsys.readouterr().out)["plans"]
    return [" ".join(str(item) for item in (step["operator"], *step["args"]))
            for step in plans[0]]


def test_forall_effects_protection_sort_by_assert_and_case(
        capsys: pytest.CaptureFixture[str]) -> None:
    steps = _plan(capsys, "--domain", str(DATA / "carts.jshop"),
                  "--problem", str(DATA / "carts.problem"))
    # the locked cart cannot roll, so the first method fails; the boxes go heaviest first
    assert steps == ["!lock cart1 dock", "!unlock cart1 dock", "!load barrel cart1 dock",
                     "!load chest cart1 dock", "!load crate cart1 dock",
                     "!roll cart1 dock shed", "!!assert ['sent', 'cart1', 'shed']"]


def test_unordered_immediate_open_variables_and_own_functions(
        capsys: pytest.CaptureFixture[str]) -> None:
    steps = _plan(capsys, "--domain", str(DATA / "relay.jshop"),
                  "--problem", str(DATA / "relay.problem"),
                  "--functions", str(DATA / "relay_functions.py"))
    assert steps == ["!walk ann kitchen", "!hand ann p1 41", "!log ?ticket#1",
                     "!walk ann hall", "!hand ann p2 71", "!log ?ticket#2",
                     "!walk ann garden"]


def test_a_missing_function_names_the_option(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "--domain", str(DATA / "relay.jshop"),
                 "--problem", str(DATA / "relay.problem")]) == 2
    assert "unknown function 'ticket'" in capsys.readouterr().err


def test_forall_effects_act_on_the_state_when_applied() -> None:
    domain = read_domain_text("""(defdomain d ((:operator (!clear)
        () ((forall (?x) ((dirty ?x)) ((dirty ?x)))) ((forall (?x) ((cup ?x)) ((clean ?x)))))))""")
    result = Planner(domain).search(State([("cup", "a"), ("dirty", "a"), ("cup", "b")]),
                                    [("!clear",)])
    assert result.plan is not None
    step = result.plan.steps[0]
    assert step.deletes == (("dirty", "a"),)
    assert step.adds == (("clean", "a"), ("clean", "b"))


def test_an_undeclared_primitive_task_is_noted_and_never_applies() -> None:
    domain = read_domain_text("(defdomain d ((:method (t) () ((!missing)))))", "d.jshop")
    assert domain.notes and "!missing" in domain.notes[0]
    assert not Planner(domain).search(State(), [("t",)])


def test_undo_restores_the_order_of_atoms() -> None:
    state = State([("at", "a", "x"), ("at", "b", "x"), ("at", "c", "y")])
    mark = state.mark()
    state.remove(("at", "a", "x"))
    state.add(("at", "d", "x"))
    state.add(("at", "a", "x"))  # made true again: it goes last, as in JSHOP2
    assert state.atoms("at")[-1] == ("at", "a", "x")
    state.undo(mark)
    assert state.atoms("at") == [("at", "a", "x"), ("at", "b", "x"), ("at", "c", "y")]
    assert list(state.candidates("at", 2, [(2, "x")])) == [("at", "a", "x"), ("at", "b", "x")]


def test_protected_atoms_cannot_be_deleted_and_undo_lifts_protections() -> None:
    with pytest.raises(PlanningError):
        read_domain_text("(defdomain d ((:operator (!p) () () ((:protection)))))")
    state = State([("door", "open")])
    mark = state.mark()
    state.protect(("door", "open"))
    assert state.is_protected(("door", "open"))
    state.undo(mark)
    assert not state.is_protected(("door", "open"))


def _tidy_plans(size: int, repeats: int) -> list[list[tuple[object, ...]]]:
    from homebot.bench.htn import _tidy_world

    world = _tidy_world(World.load("apartment"), size)
    domain = home_domain()
    state, names = state_from_beliefs(world, Beliefs.from_world(world), world.robot.pose.xy())
    goal = Goal.of("tidy", [], world, names, domain)
    planner = Planner(domain)
    plans = []
    for _ in range(repeats):
        result = planner.search(state, [goal.task])
        assert result.plan is not None
        plans.append(result.plan.actions())
    fresh, _ = state_from_beliefs(world, Beliefs.from_world(world), world.robot.pose.xy())
    again = planner.search(fresh, [goal.task]).plan
    assert again is not None
    plans.append(again.actions())
    return plans


@pytest.mark.parametrize("size", [100, 200, 400])
def test_tidy_up_plans_are_identical_when_repeated(size: int) -> None:
    plans = _tidy_plans(size, repeats=3)
    assert all(plan == plans[0] for plan in plans)
    assert sum(1 for action in plans[0] if action[0] == "!put_down") == size


EXAMPLES = os.environ.get("HOMEBOT_JSHOP2_EXAMPLES")
#: Plan lengths JSHOP2 1.0.3 finds for its own examples (first plan).
JSHOP2_LENGTHS = {"basic": 2, "blocks": 2249, "forall": 3, "freecell": 35, "logistics": 124,
                  "madrts": 3, "oldblocks": 27, "propagation": 5, "rover": 571, "test": 3}


@pytest.mark.skipif(not EXAMPLES, reason="set HOMEBOT_JSHOP2_EXAMPLES to JSHOP2's examples/")
@pytest.mark.parametrize("name", sorted(JSHOP2_LENGTHS))
def test_jshop2s_own_examples_plan(name: str, capsys: pytest.CaptureFixture[str]) -> None:
    folder = Path(str(EXAMPLES)) / name
    steps = _plan(capsys, "--domain", str(folder / name), "--problem", str(folder / "problem"),
                  "--functions", str(DATA / "examples_functions.py"))
    assert len(steps) == JSHOP2_LENGTHS[name]
