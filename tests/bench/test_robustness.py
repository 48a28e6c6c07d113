"""``bench robustness`` on many workers: the same figures as one after another."""

from __future__ import annotations

import json
from typing import Any

import pytest

from homebot.bench.robustness import ErrandTask, errand_tasks
from homebot.cli import main


def _figures(capsys: pytest.CaptureFixture[str], *arguments: str) -> dict[str, Any]:
    assert main(["bench", "robustness", "--tasks", "3", "--seed", "5", "--json",
                 *arguments]) == 0
    figures: dict[str, Any] = json.loads(capsys.readouterr().out)
    for mode in figures["modes"]:
        del mode["median_wall_ms"]  # a timing
    return figures


def test_two_workers_give_the_figures_of_one(capsys: pytest.CaptureFixture[str]) -> None:
    one = _figures(capsys, "--workers", "1")
    assert one == _figures(capsys, "--workers", "2")
    assert [mode["tasks"] for mode in one["modes"]] == [3, 3]


def test_a_task_seed_comes_from_the_benchmark_seed_and_its_index() -> None:
    units = errand_tasks("apartment", 3, 5)
    assert [unit.monitoring for unit in units] == [True] * 3 + [False] * 3
    assert [unit.run_seed for unit in units] == [500_015, 500_016, 500_017] * 2
    assert ErrandTask("apartment", "everyday", 3, 5, 2).run_seed == units[2].run_seed
