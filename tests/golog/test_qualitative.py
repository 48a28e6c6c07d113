"""Qualitative fluents in Golog (dist, orient, is) and Fetch & Carry as Alg. 1 writes it."""

from __future__ import annotations

import argparse
import math

import pytest

from homebot.cli.scenario import run_builder
from homebot.errors import GologError
from homebot.golog import Interpreter, SimulatedExecutor, State
from homebot.golog.build import do
from homebot.golog.domains.fetch_carry import fetch_carry_theory
from homebot.golog.library import shipped_procedures
from homebot.golog.qualitative import add_qualitative
from homebot.golog.theory import Theory


def _ring(point: tuple[float, float]) -> tuple[tuple[float, float], ...]:
    return tuple((point[0] + r, point[1]) for r in (0.1, 0.5, 1.0, 3.0))


def _theory(scale: float = 6.0) -> Theory:
    return fetch_carry_theory({"cup": (1.0, 1.0)}, (5.0, 5.0), {"shelf": (4.0, 1.0)}, _ring,
                              lambda a, b: (scale, 0.0))


def test_is_dist_close_follows_the_frames_scale() -> None:
    theory = Theory("q")
    add_qualitative(theory, lambda a, b: (6.0, 0.0))
    state = State()
    dist = theory.functions["dist"]
    assert dist(state, (0.0, 0.0), (0.6, 0.0)).holds("close")
    assert not dist(state, (0.0, 0.0), (0.1, 0.0)).holds("close")
    small = Theory("small")
    add_qualitative(small, lambda a, b: (1.4, 0.0))
    assert small.functions["dist"](state, (0.0, 0.0), (0.6, 0.0)).holds("far")
    assert theory.functions["orient"](state, (0.0, 0.0), (0.0, 1.0)).holds("left")
    with pytest.raises(GologError, match="qualitative value"):
        theory.functions["is"](state, 3, "close")


def test_fetch_and_carry_approaches_until_close_then_delivers() -> None:
    theory = _theory()
    run = Interpreter(theory, SimulatedExecutor(theory, seed=0), seed=0).run(
        do("fetch_and_carry", "cup", "shelf"))
    assert run.success
    gotos = [action for action in run.detail.history if action[0] == "goto"]
    # the first standpoint 0.1 m off is "very close" in a 6 m frame; 0.5 m is "close"
    assert gotos == [("goto", (1.5, 1.0)), ("goto", (4.5, 1.0))]
    assert [a[0] for a in run.detail.history] == ["goto", "pickup", "goto", "putdown"]


def test_fetch_and_carry_fails_when_nothing_is_close_or_the_object_is_unknown() -> None:
    tiny = _theory(scale=100.0)  # every standpoint is "very close" by a 100 m measure
    assert not Interpreter(tiny, SimulatedExecutor(tiny, seed=0), seed=0).run(
        do("fetch_and_carry", "cup", "shelf")).success
    theory = _theory()
    assert not Interpreter(theory, SimulatedExecutor(theory, seed=0), seed=0).run(
        do("fetch_and_carry", "plate", "shelf")).success


def test_the_program_reads_like_alg_1() -> None:
    names = [procedure.name for procedure in shipped_procedures("fetch_carry")]
    assert names == ["fetch_and_carry", "approach"]


@pytest.mark.parametrize("seed", [0, 5])
def test_scenario_fetch_carry_delivers_by_the_truth(seed: int) -> None:
    from homebot.scenarios.library import fetch_carry

    summary = fetch_carry.run(argparse.Namespace(seed=seed), None, run_builder())
    assert summary["success"], summary
    assert summary["delivered"]
    assert all(record["category"] == "close" and math.isfinite(record["metres"])
               for record in summary["approached"])
