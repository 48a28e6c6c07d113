"""``homebot serve`` refuses what a person can get wrong in one line, exit status 2."""

from __future__ import annotations

import pytest

from homebot.cli import main


@pytest.mark.parametrize("arguments", [["--port", "http"], ["--port", "70000"],
                                       ["--speed", "-1"], ["--speed", "fast"],
                                       ["--token", "short"], ["--world", "no-such-home"]])
def test_serve_refuses_bad_options_in_one_line(arguments: list[str],
                                                capsys: pytest.CaptureFixture[str]) -> None:
    try:
        status = main(["serve", *arguments])
    except SystemExit as exit_:  # argparse refuses a bad value itself, with status 2
        status = exit_.code
    assert status == 2
    error = capsys.readouterr().err
    assert "Traceback" not in error and error.strip()
