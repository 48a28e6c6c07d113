"""The htn benchmark runs and reports its figures (no timing is asserted)."""

from __future__ import annotations

import json

import pytest

from homebot.cli import main


def test_bench_htn_reports_table_1_and_the_comparison(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "htn", "--repeats", "3", "--sizes", "10", "20", "--runs", "2",
                 "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)["figures"]
    assert figures["table1"]["bring object"]["plans"] == 3
    assert figures["table1"]["bring object"]["shortest"] == 8
    assert figures["table1"]["bring object"]["identical_sequences"] is True
    assert (figures["table1"]["guide robot"]["plans"],
            figures["table1"]["guide robot"]["shortest"]) == (1, 5)
    comparison = figures["bring_object_first_plan"]
    if "gtpyhop_median_ms" in comparison:  # gtpyhop-core is a dev dependency
        assert comparison["same_plan"] is True
    assert [row["put_away"] for row in figures["tidy"]] == [10, 20]
    assert [row["tasks"] for row in figures["execution"]] == [2, 2]


@pytest.mark.parametrize("argv", [["--repeats", "0"], ["--sizes", "0"], ["--runs", "-1"]])
def test_bench_htn_refuses_counts_out_of_range(argv: list[str],
                                               capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "htn", *argv]) == 2  # one line, no argparse usage dump
    error = capsys.readouterr().err
    assert "give a whole number from" in error and len(error.strip().splitlines()) == 1
