"""The map picture of an embodied run: driven trajectory, particle cloud and laser returns."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from homebot.cli import main
from homebot.viz import Canvas, EmbodiedRun, embodied_run, render_map
from homebot.viz.embodied import EMBODIED_COLOURS
from homebot.world import World

# A run in the apartment: the robot drove along the corridor (y = 5) from x = 1 to x = 6,
# its last scan saw the corridor's north wall at x 7..9 (y = 5.95), and its particles
# gather round (10.5, 2.5) in the kitchen. Two trajectory pieces, two clouds, two scans:
# the pieces are joined, the last cloud and scan are drawn.
EVENTS = [
    {"time": 0.0, "kind": "task.start", "description": "drive", "steps": []},
    {"time": 1.0, "kind": "robot.trajectory",
     "points": [[1.0 + 0.1 * i, 5.0] for i in range(21)]},
    {"time": 1.0, "kind": "robot.particles", "points": [[1.0, 8.0, 0.0]]},
    {"time": 1.0, "kind": "robot.laser", "points": [[1.0, 9.0]]},
    {"time": 2.0, "kind": "robot.trajectory",
     "points": [[3.0 + 0.1 * i, 5.0] for i in range(31)]},
    {"time": 2.0, "kind": "robot.particles",
     "points": [[10.5 + 0.02 * i, 2.5 - 0.01 * i, 0.3 * i] for i in range(50)]},
    {"time": 2.0, "kind": "robot.laser", "points": [[7.0 + 0.05 * i, 5.95] for i in range(41)]},
]


def _mask(image_array: np.ndarray, layer: str) -> np.ndarray:
    mask: np.ndarray = np.all(image_array == EMBODIED_COLOURS[layer], axis=-1)
    return mask


def test_the_log_gives_the_joined_trajectory_and_the_last_cloud_and_scan() -> None:
    run = embodied_run(EVENTS)
    assert len(run.trajectory) == 52
    assert run.trajectory[0] == (1.0, 5.0) and run.trajectory[-1] == pytest.approx((6.0, 5.0))
    assert len(run.particles) == 50 and run.particles[0] == (10.5, 2.5, 0.0)
    assert len(run.laser) == 41 and run.laser[0] == (7.0, 5.95)
    assert not embodied_run([{"kind": "robot.path", "points": [[0, 0], [1, 1]]}])


def test_events_of_another_world_are_left_out() -> None:
    events = [{**event, "world": "supermarket"} for event in EVENTS]
    assert not embodied_run(events, "apartment")
    assert embodied_run(events, "supermarket").laser == embodied_run(EVENTS).laser


@pytest.mark.parametrize("points", ["x", [[1.0]], [[1.0, "a"]], [[1.0, float("nan")]]])
def test_malformed_points_are_refused(points: object) -> None:
    with pytest.raises(ValueError):
        embodied_run([{"kind": "robot.laser", "points": points}])


def test_the_layers_are_drawn_where_the_run_was(apartment: World) -> None:
    # The map above the legend strip (the legend shows each layer's colour too).
    above_legend = Canvas.for_world(apartment).map_height
    plain = np.asarray(render_map(apartment))[:above_legend]
    drawn = np.asarray(render_map(apartment, run=embodied_run(EVENTS)))[:above_legend]
    assert plain.shape == drawn.shape
    centres = {}
    for layer in ("trajectory", "particles", "laser"):
        assert not _mask(plain, layer).any(), layer
        rows, columns = np.nonzero(_mask(drawn, layer))
        assert rows.size > 0, layer
        centres[layer] = (columns.mean(), rows.mean())
    # In the picture x grows to the right and y upwards (rows downwards):
    # trajectory x 1..6 left of the laser x 7..9 left of the particles x 10.5..11.5;
    # the laser (y 5.95) above the trajectory (y 5) above the particles (y 2.5).
    assert centres["trajectory"][0] < centres["laser"][0] < centres["particles"][0]
    assert centres["laser"][1] < centres["trajectory"][1] < centres["particles"][1]
    # The first cloud and scan (at y 8 and 9) are not drawn: nothing of theirs up there.
    laser_rows = np.nonzero(_mask(drawn, "laser"))[0]
    assert laser_rows.max() - laser_rows.min() <= 4


def test_an_empty_run_draws_nothing_extra(apartment: World) -> None:
    plain = np.asarray(render_map(apartment))
    assert np.array_equal(plain, np.asarray(render_map(apartment, run=EmbodiedRun())))


def test_world_show_png_draws_an_embodied_log(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    log = tmp_path / "events.jsonl"
    log.write_text("".join(json.dumps(event) + "\n" for event in EVENTS), encoding="utf-8")
    png = tmp_path / "map.png"
    assert main(["world", "show", "--png", str(png), "--events", str(log)]) == 0
    from PIL import Image

    with Image.open(png) as image:
        pixels = np.asarray(image.convert("RGB"))
    for layer in ("trajectory", "particles", "laser"):
        assert _mask(pixels, layer).any(), layer


def test_a_malformed_embodied_log_exits_2(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    log = tmp_path / "events.jsonl"
    log.write_text(json.dumps({"kind": "robot.laser", "points": [[1, 2, 3]]}) + "\n",
                   encoding="utf-8")
    status = main(["world", "show", "--png", str(tmp_path / "map.png"), "--events", str(log)])
    err = capsys.readouterr().err
    assert status == 2 and "not a homebot event log of an embodied run" in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
