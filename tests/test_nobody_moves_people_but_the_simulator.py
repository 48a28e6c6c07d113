"""Nobody moves a simulated person but the simulator (issue: people as agents).

Statically, the only code that calls ``Simulation.move_person`` outside ``homebot.sim`` sets
an arena up before an episode starts (a referee placing people, as a judge places them at
a competition). Dynamically, during an embodied Follow Me episode every move of a person is
made by the simulator's own people (``homebot.sim``), one walking step at a time.
"""

from __future__ import annotations

import ast
import inspect
import math
from pathlib import Path

import pytest

from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.world import World

SRC = Path(__file__).resolve().parents[1] / "src" / "homebot"

#: modules outside ``homebot.sim`` allowed to place people, and why: each only sets its
#: arena up before the robot starts
ARENA_SET_UP = {
    "trials/following.py": "places the operator and the passers-by before Follow Me starts",
    "trials/looks.py": "places the people of each look before the robot looks",
    "trials/guiding.py": "places the person to guide before the robot asks them along",
    "scenarios/library/butler.py": "Luis's scripted day in the Golem-III butler story",
    "bench/console.py": "puts the person to follow beside the robot before a stop trial",
}


def _callers_of_move_person() -> set[str]:
    callers = set()
    for path in SRC.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
                    node.func.attr == "move_person":
                callers.add(path.relative_to(SRC).as_posix())
    return callers


def test_only_the_simulator_and_arena_set_ups_call_move_person() -> None:
    outside = {module for module in _callers_of_move_person() if not module.startswith("sim/")}
    assert outside <= set(ARENA_SET_UP), (
        f"{sorted(outside - set(ARENA_SET_UP))} move people: only the simulator may, "
        f"or an arena set-up before an episode (add it to ARENA_SET_UP saying why)")
    for robot_side in ("embodied/", "skills/", "executive/", "navigation/", "perception/",
                       "app/"):
        assert not any(module.startswith(robot_side) for module in outside)


def test_during_follow_me_people_only_walk_and_only_the_simulator_walks_them(
        apartment: World, apartment_navigator: Navigator, monkeypatch: pytest.MonkeyPatch
) -> None:
    pytest.importorskip("cv2")
    pytest.importorskip("pocketsphinx")
    from homebot.app.embodied import follow_me_episode

    moves: list[tuple[str, str, float]] = []  # (module, person, step length)
    original = Simulation.move_person
    started: list[bool] = []

    def watched(self: Simulation, name: str, position: tuple[float, float]) -> None:
        caller = inspect.stack()[1].frame.f_globals["__name__"]
        if started:
            moves.append((caller, name, math.dist(self.people[name].position, position)))
        elif caller == "homebot.sim.routes":
            started.append(True)  # the arena is set: from the first step on, watch
            moves.append((caller, name, math.dist(self.people[name].position, position)))
        original(self, name, position)

    monkeypatch.setattr(Simulation, "move_person", watched)
    episode = follow_me_episode(apartment, 7, apartment_navigator)
    assert episode.skipped is None and moves
    assert {module for module, _, _ in moves} <= {"homebot.sim.routes", "homebot.sim.walkers"}
    # a step of one tick (1/20 s) at under 1 m/s: nobody jumps
    assert max(step for _, _, step in moves) < 0.05
