"""``--plot FILE.png``: a picture of a tiny benchmark run, drawn from its own results.

Each test runs a benchmark through the real command line with ``--plot`` and checks the
file is a PNG of the figure's size; then draws the figure again from the figures the run
printed and counts what is on it (axes, lines, bars), as matplotlib's objects say.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

from homebot.bench import benchmark, missing_extras
from homebot.cli import main
from homebot.errors import BenchmarkError

pytest.importorskip("matplotlib")

from homebot.bench.plots import (  # after the skip: it draws with matplotlib
    htn_figure,
    localisation_figure,
    navigation_figure,
    require,
    robustness_figure,
    speech_figure,
)


def _needs(name: str) -> Any:
    missing = missing_extras(benchmark(name))
    return pytest.mark.skipif(bool(missing), reason=f"needs the {', '.join(missing)} extra")


def _plotted(capsys: pytest.CaptureFixture[str], png: Path, *arguments: str) -> dict[str, Any]:
    """Run ``homebot bench ARGUMENTS --plot png --json``; check the PNG; the figures."""
    assert main(["bench", *arguments, "--plot", str(png), "--json"]) == 0
    figures: dict[str, Any] = json.loads(capsys.readouterr().out)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with Image.open(png) as image:
        image.verify()
    with Image.open(png) as image:
        assert image.format == "PNG" and image.width >= 600 and image.height >= 400
    return figures


def _bars(axes: Any) -> int:
    return sum(len(container) for container in axes.containers)


def test_robustness_by_disturbance(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    figures = _plotted(capsys, tmp_path / "robustness.png", "robustness", "--tasks", "3")
    modes = figures["modes"]
    kinds = {kind for mode in modes for kind in mode["by_disturbance"]}
    # each task is counted under every disturbance in its run, or under "none"
    for mode in modes:
        assert sum(c["tasks"] for c in mode["by_disturbance"].values()) >= mode["tasks"]
    figure = robustness_figure(modes, 1.0)
    (axes,) = figure.axes
    assert _bars(axes) == len(modes) * len(kinds)
    assert [text.get_text() for text in axes.get_legend().get_texts()] == [
        "monitored + recovery", "plain sequence"]
    assert "(%)" in axes.get_ylabel()


def test_htn_timings_by_size(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    figures = _plotted(capsys, tmp_path / "htn.png", "htn", "--repeats", "1", "--runs", "0",
                       "--sizes", "1", "3")
    tidy = figures["figures"]["tidy"]
    (axes,) = htn_figure(tidy).axes
    compared = importlib.util.find_spec("gtpyhop") is not None
    assert len(axes.lines) == (2 if compared else 1)
    assert list(axes.lines[0].get_xdata()) == [1, 3]
    assert axes.get_ylabel() == "planning time, median (ms)"


@_needs("speech")
def test_speech_accuracy_by_voice(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    figures = _plotted(capsys, tmp_path / "speech.png", "speech", "--count", "2",
                       "--rejection", "0", "--babble-talkers", "0", "--worlds", "apartment")
    worlds = figures["worlds"]
    voices = set(worlds["apartment"]["clean"]["by_voice"])
    assert len(voices) == 2  # two commands, each spoken by the next voice
    (axes,) = speech_figure(worlds, ("clean", "noisy")).axes
    assert _bars(axes) == 2 * len(voices)


@_needs("localisation")
def test_localisation_error_over_time(capsys: pytest.CaptureFixture[str],
                                      tmp_path: Path) -> None:
    _plotted(capsys, tmp_path / "localisation.png", "localisation", "--runs", "1",
             "--only", "tracking", "--seconds", "3")
    figure = localisation_figure({"tracking": [[0.05, 0.04, 0.06]],
                                  "tracking, 50 % spurious": [[0.1, 0.2], [0.1, 0.3, 0.2]]},
                                 0.05)
    (axes,) = figure.axes
    # a median per experiment, and the 20 cm line; a band only where runs are several
    assert len(axes.lines) == 3 and len(axes.collections) == 1
    assert list(axes.lines[1].get_xdata()) == pytest.approx([0.05, 0.1])


def _refused(capsys: pytest.CaptureFixture[str], *arguments: str) -> str:
    """The one-line error of ``homebot bench ARGUMENTS`` (exit status 2)."""
    assert main(["bench", *arguments]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    return captured.err


@_needs("localisation")
def test_localisation_plot_needs_the_tracking_runs(capsys: pytest.CaptureFixture[str],
                                                   tmp_path: Path) -> None:
    assert "--plot draws the tracking runs, which --only timing leaves out" in _refused(
        capsys, "localisation", "--only", "timing", "--plot", str(tmp_path / "x.png"))


@_needs("navigation")
def test_navigation_paths_and_smoothness(capsys: pytest.CaptureFixture[str],
                                         tmp_path: Path) -> None:
    _plotted(capsys, tmp_path / "navigation.png", "navigation", "--repeat", "1", "--goals",
             "1", "--planner", "dwa", "--walkers", "0")
    assert "--plot draws the drives: give --goals N" in _refused(
        capsys, "navigation", "--plot", str(tmp_path / "out.png"))
    obstacles = np.zeros((40, 60), dtype=bool)
    obstacles[20, 10:50] = True
    figure = navigation_figure(
        obstacles, (0.0, 0.0, 3.0, 2.0), [(2.5, 1.5), (0.5, 0.5)],
        {"stage2": [[(0.5, 0.5), (1.5, 1.0), (2.5, 1.5)], [(2.5, 1.5), (0.5, 0.5)]],
         "dwa": [[(0.5, 0.5), (2.5, 1.5)], [(2.5, 1.5)]]},  # a goal it never left
        {"stage2": [0.1, 0.2, 0.0], "dwa": [0.5, 0.1]})
    paths, smoothness = figure.axes
    assert len(paths.lines) == 3 and len(paths.images) == 1  # one line per drive that moved
    assert [text.get_text() for text in paths.get_legend().get_texts()] == [
        "stage2", "dwa", "goals (numbered as the figures list them)"]
    assert [text.get_text() for text in paths.texts] == ["0", "1"]
    assert len(smoothness.lines) == 2 and smoothness.get_xlabel().endswith("(rad/s²)")


def test_a_plot_needs_a_png_in_a_folder_that_exists(capsys: pytest.CaptureFixture[str],
                                                     tmp_path: Path) -> None:
    assert f"--plot {tmp_path / 'out.jpg'}: give a file name ending in .png" in _refused(
        capsys, "htn", "--plot", str(tmp_path / "out.jpg"))
    assert f"the folder {tmp_path / 'nowhere'} does not exist" in _refused(
        capsys, "htn", "--plot", str(tmp_path / "nowhere" / "out.png"))


def test_without_matplotlib_the_plot_option_says_what_to_install(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
        tmp_path: Path) -> None:
    found = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *rest: None if name == "matplotlib" else found(name, *rest))
    with pytest.raises(BenchmarkError, match=r"pip install 'homebot\[plots\]'"):
        require()
    assert "error: --plot needs matplotlib, the 'plots' extra: pip install 'homebot[plots]'" \
        in _refused(capsys, "htn", "--plot", str(tmp_path / "out.png"))
    assert not (tmp_path / "out.png").exists()
