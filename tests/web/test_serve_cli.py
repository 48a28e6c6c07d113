"""``homebot serve`` refuses what a person can get wrong in one line, exit status 2."""

from __future__ import annotations

import socket

import pytest

from homebot.cli import main


@pytest.mark.parametrize("arguments", [["--port", "http"], ["--port", "70000"],
                                       ["--speed", "-1"], ["--speed", "fast"],
                                       ["--token", "short"], ["--world", "no-such-home"],
                                       ["--lease", "0"], ["--lease", "soon"],
                                       ["--host", "999.1.1.1"], ["--host", "\x00"]])
def test_serve_refuses_bad_options_in_one_line(arguments: list[str],
                                                capsys: pytest.CaptureFixture[str]) -> None:
    try:
        status = main(["serve", *arguments])
    except SystemExit as exit_:  # argparse refuses a bad value itself, with status 2
        status = exit_.code
    assert status == 2
    error = capsys.readouterr().err
    assert "Traceback" not in error and error.strip()


def test_a_port_already_in_use_is_named(capsys: pytest.CaptureFixture[str]) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        assert main(["serve", "--port", str(port), "--token", "long-enough-token"]) == 2
    error = capsys.readouterr().err
    assert f"--port {port}: cannot listen there" in error and "Traceback" not in error
