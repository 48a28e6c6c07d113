"""The console reads well: the map names its furniture, the command box's example fits the
served home, and the event log reads as ``homebot do`` narrates (raw JSON kept)."""

from __future__ import annotations

import io

import numpy as np
import pytest

pytest.importorskip("fastapi")
pytest.importorskip("httpx")

from fastapi.testclient import TestClient

from homebot.app import Fidelity
from homebot.web import Console, ConsoleSettings
from homebot.web.app import create_app
from homebot.web.console import VIEW_PERIOD, example_command
from homebot.world import World

TOKEN = "test-token-readable"
_WAIT = 120.0


@pytest.mark.parametrize("name", ["apartment", "family_home", "supermarket"])
def test_the_example_command_names_an_object_and_placement_of_the_served_home(
        name: str) -> None:
    world = World.load(name)
    settings = ConsoleSettings(world=world, token=TOKEN, speed=0.0)
    with TestClient(create_app(settings)) as client:
        served = client.get("/api/map", headers={"X-Homebot-Token": TOKEN}).json()
    first = world.model.objects[0]
    assert served["example"] == example_command(world)
    assert first.name.replace("_", " ") in served["example"]
    assert first.placement.replace("_", " ") in served["example"]
    assert set(served["placements"]) == set(world.placements)  # each one drawn and named


def test_the_examples_differ_between_homes_and_a_home_without_objects_gets_a_trip() -> None:
    apartment, family = World.load("apartment"), World.load("family_home")
    assert example_command(apartment) != example_command(family)
    empty = World(apartment.model.model_copy(update={"objects": []}))
    assert example_command(empty).startswith("go to the ")


def test_the_served_log_carries_a_narrated_line_beside_each_raw_event() -> None:
    settings = ConsoleSettings(world=World.load("apartment"), token=TOKEN, speed=0.0)
    with TestClient(create_app(settings)) as client:
        headers = {"X-Homebot-Token": TOKEN}
        session = client.post("/api/session", headers=headers).json()["session"]
        page = {**headers, "X-Homebot-Session": session}
        client.post("/api/control", json={"action": "take"}, headers=page)
        client.post("/api/command", json={"text": "bring me the cola from the fridge"},
                    headers=page)
        assert client.app.state.console.wait_idle(_WAIT)  # type: ignore[attr-defined]
        events = client.get("/api/events", headers=headers).json()
    lines = [event["line"] for event in events]
    assert "▶ navigate(to=fridge)" in lines
    assert "verified pick(object=cola) — I have the cola" in lines
    assert lines[-1] == "task done"
    # each thing the robot said, once, though the skill and the speaker both logged it
    said = [event["text"] for event in events if event["kind"] == "speech"]
    assert said and said[-1] == "I have done what you asked."
    assert [line for line in lines if line and line.startswith("robot: ")] == \
        [f"robot: {text}" for text in said]
    sounds = [event["text"] for event in events if event["kind"] == "sim.speech"]
    assert sounds == said  # the raw records kept: one of each pair folded into the other
    assert sum(event["line"] is None for event in events) == len(said)


def test_the_symbolic_home_says_it_has_no_camera() -> None:
    settings = ConsoleSettings(world=World.load("apartment"), token=TOKEN, speed=0.0)
    with TestClient(create_app(settings)) as client:
        answer = client.get("/api/camera.jpg", headers={"X-Homebot-Token": TOKEN})
        state = client.get("/api/state", headers={"X-Homebot-Token": TOKEN}).json()
    assert answer.status_code == 404
    assert "no camera" in answer.json()["error"] and "--fidelity embodied" in \
        answer.json()["error"]
    assert "camera" not in state  # the page says so from the fidelity


def _jpeg(answer: object) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(answer.content)).convert("RGB"),  # type: ignore[attr-defined]
                      dtype=float)


def test_the_embodied_home_serves_what_its_head_camera_sees_now() -> None:
    pytest.importorskip("cv2")
    settings = ConsoleSettings(world=World.load("apartment"), token=TOKEN, speed=0.0,
                               fidelity=Fidelity.EMBODIED)
    with TestClient(create_app(settings)) as client:
        headers = {"X-Homebot-Token": TOKEN}
        home = client.app.state.console  # type: ignore[attr-defined]
        # before the robot has looked at all, the page sees what it would see
        first = client.get(f"/api/camera.jpg?token={TOKEN}")
        assert first.status_code == 200 and first.headers["content-type"] == "image/jpeg"
        assert client.get("/api/state", headers=headers).json()["camera"] is None
        assert home.body.last_camera() is None  # watching took no image for the robot
        again = client.get(f"/api/camera.jpg?token={TOKEN}")  # no time passed: the same one
        assert again.content == first.content
        session = client.post("/api/session", headers=headers).json()["session"]
        page = {**headers, "X-Homebot-Session": session}
        client.post("/api/control", json={"action": "take"}, headers=page)
        looked = client.post("/api/steps", headers=page, json={"steps": [
            {"skill": "look", "placement": "coat rack"}]})  # by the robot, in the entrance
        assert looked.status_code == 200
        assert home.wait_idle(_WAIT)
        stamp = client.get("/api/state", headers=headers).json()["camera"]
        after = client.get(f"/api/camera.jpg?token={TOKEN}")
        frame = home.body.last_camera()
    assert stamp is not None and stamp == pytest.approx(frame.stamp, abs=1e-3)
    # the view is stamped now, later than the first; the robot turned to the rack
    assert float(after.headers["X-Homebot-Stamp"]) > float(first.headers["X-Homebot-Stamp"])
    assert float(after.headers["X-Homebot-Stamp"]) >= stamp - 1e-3
    assert np.abs(_jpeg(after) - _jpeg(first)).mean() > 10.0


def test_a_watched_console_runs_as_an_unwatched_one() -> None:
    """A page watching the camera all along changes nothing the robot senses or does."""
    pytest.importorskip("cv2")

    def events(watched: bool) -> list[dict[str, object]]:
        settings = ConsoleSettings(world=World.load("apartment"), token=TOKEN, speed=0.0,
                                   fidelity=Fidelity.EMBODIED, seed=5)
        home = Console(settings)
        views: list[float] = []
        if watched:
            home.tick_hooks.append(lambda tick: views.append(home.camera_jpeg()[0]))
        home.start()
        try:
            home.take_control("operator")
            home.run_steps("operator", [{"skill": "look", "placement": "coat rack"}])
            assert home.wait_idle(_WAIT)
        finally:
            home.close()
        if watched:  # drawn as the robot acted, at most four times a simulated second
            drawn = sorted(set(views))
            assert len(drawn) >= 4 and min(np.diff(drawn)) >= VIEW_PERIOD - 1e-9
        return [data for _, data in home.events]

    assert events(watched=True) == events(watched=False)
