"""The qualitative-space commands refuse bad arguments in one line (exit 2), and run."""

from __future__ import annotations

import json

import pytest

from homebot.cli import main

BAD = [
    (["bench", "referring", "--scenes", "0"], "--scenes '0'"),
    (["bench", "referring", "--noise", "2"], "--noise '2'"),
    (["bench", "referring", "--noise", "nan"], "--noise 'nan'"),
    (["bench", "referring", "--margin", "abc"], "--margin 'abc'"),
    (["scenario", "fetch_carry", "--object", "unicorn"], "--object 'unicorn'"),
    (["scenario", "fetch_carry", "--object", "apple", "--to", "moon"], "'moon'"),
    (["scenario", "order_cups_pointing", "--goal", "red,red,blue"], "--goal"),
]


@pytest.mark.parametrize(("argv", "named"), BAD, ids=[" ".join(argv[:4]) for argv, _ in BAD])
def test_a_bad_argument_is_exit_2_with_one_line(argv: list[str], named: str,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert named in lines[0] and "Traceback" not in captured.err


def test_bench_referring_prints_its_figures_as_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "referring", "--scenes", "20", "--repeats", "2", "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)
    assert figures["scenes"] == 20 and figures["clear"] + figures["close"] == 20
    assert figures["relations_pairs"] == 50 * 49
