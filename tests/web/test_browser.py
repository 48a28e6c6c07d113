"""The console in a real headless Chromium: a fetch typed in the page, the map live, e-stop;
control given back when its page is reloaded or closed."""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import threading
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")
playwright_api = pytest.importorskip("playwright.sync_api")

from homebot.app import Fidelity  # noqa
from homebot.web import Console, ConsoleSettings  # noqa: E402
from homebot.web.app import create_app  # noqa: E402
from homebot.world import World  # noqa: E402

pytestmark = pytest.mark.browser

TOKEN = "browser-test-token"
_TIMEOUT_MS = 90_000  # the longest wait for anything in the page


def _chromium() -> str | None:
    named = os.environ.get("HOMEBOT_CHROMIUM")
    candidates = [named] if named else []
    candidates += [shutil.which(name) for name in ("chromium", "chromium-browser",
                                                   "google-chrome")]
    return next((path for path in candidates if path and Path(path).exists()), None)


@contextlib.contextmanager
def _serving(settings: ConsoleSettings) -> Iterator[tuple[str, Console]]:
    """The console app served on a free local port: its address and its home."""
    import uvicorn

    app = create_app(settings)
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port,
                                           log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    for _ in range(400):  # at most 20 s for the server to listen
        if server.started:
            break
        thread.join(0.05)
    try:
        yield f"http://127.0.0.1:{port}", app.state.console
    finally:
        server.should_exit = True
        thread.join(timeout=10.0)


@pytest.fixture(scope="module")
def served() -> Iterator[tuple[str, Console]]:
    with _serving(ConsoleSettings(world=World.load("apartment"), token=TOKEN,
                                  speed=10.0)) as serving:
        yield serving


@pytest.fixture(scope="module")
def browser() -> Iterator[object]:
    executable = _chromium()
    if executable is None:
        pytest.skip("no Chromium installed (apt-get install chromium)")
    with playwright_api.sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=executable, headless=True,
                                              args=["--no-sandbox"])
        yield launched
        launched.close()


def _robot_xy(page: object) -> tuple[float, float]:
    robot = page.locator("#robot")  # type: ignore[attr-defined]
    return float(robot.get_attribute("data-x")), float(robot.get_attribute("data-y"))


def test_a_fetch_typed_in_the_page_runs_live_and_the_stop_button_stops(
        served: tuple[str, Console], browser: object, tmp_path: Path) -> None:
    url, home = served
    page = browser.new_page(viewport={"width": 1280, "height": 800})  # type: ignore[attr-defined]
    page.set_default_timeout(_TIMEOUT_MS)
    page.goto(f"{url}/?token={TOKEN}")
    page.wait_for_selector("#robot", state="attached")
    page.wait_for_function("document.getElementById('camera-note').textContent"
                           ".includes('no camera')")  # served symbolic: the panel says so
    assert not page.locator("#camera").is_visible()
    page.click("#take")
    page.wait_for_function("document.getElementById('control').textContent"
                           ".includes('you have control')")
    start = _robot_xy(page)
    page.fill("#command", "bring me the cola from the fridge")
    page.press("#command", "Enter")
    page.wait_for_selector("#plan", state="attached")  # the planned path, drawn dashed
    page.wait_for_function(
        f"(() => {{ const r = document.getElementById('robot'); return r && "
        f"Math.hypot(r.dataset.x - {start[0]}, r.dataset.y - {start[1]}) > 0.5; }})()")
    page.screenshot(path=str(tmp_path / "moving.png"))
    page.wait_for_function("document.getElementById('task').textContent.includes('— done')")
    page.screenshot(path=str(tmp_path / "done.png"))
    assert page.locator(".step[data-status=verified]").count() >= 4
    assert "I have done what you asked." in page.inner_text("#speech")
    assert "task done" in page.inner_text("#log")  # narrated
    with home.lock:  # ground truth: the operator holds the cola
        assert home.sim.object_location["cola"] == f"person:{home.world.model.operator}"
    # skill level: a click on an object picks it
    page.check("input[name=click][value=pick]")
    # at the milk's dot: the page redraws its dots with each state, so a click on the element
    # itself may meet one just replaced; the map picks the object nearest the click
    x, y = page.evaluate("(() => { const box = document.querySelector("
                         "\"circle[data-object='milk']\").getBoundingClientRect(); "
                         "return [box.x + box.width / 2, box.y + box.height / 2]; })()")
    page.mouse.click(x, y)
    page.wait_for_function("document.getElementById('task').textContent.includes('pick milk')")
    page.wait_for_function("document.getElementById('task').textContent.includes('— done')")
    with home.lock:  # ground truth: the milk is in the robot's hand
        assert "milk" in home.sim.hands.values()
    # a long drive, stopped from the page
    page.fill("#command", "go to the bedroom")
    page.press("#command", "Enter")
    page.wait_for_function("document.querySelector('.step.running') !== null")
    page.click("#estop")
    page.wait_for_function("document.getElementById('estop').className === 'engaged'")
    page.wait_for_function("document.getElementById('status').textContent.includes('idle')")
    page.screenshot(path=str(tmp_path / "stopped.png"))
    with home.lock:
        assert home.estop
        assert home.world.room_at(*home.sim.robot_pose[:2]) != "bedroom"
    # the step view says what is true: stopped, nothing left running; then it goes on
    page.wait_for_function("document.getElementById('task-head').dataset.outcome === 'stopped'")
    assert page.locator(".step.running").count() == 0
    assert page.locator(".step[data-status=stopped]").count() == 1
    assert "Release the stop" in page.inner_text("#help")
    page.click("#release-estop")
    page.wait_for_function("document.getElementById('estop').className === ''")
    page.click("#resume")
    page.wait_for_function("document.getElementById('task-head').dataset.outcome === 'done'")
    page.screenshot(path=str(tmp_path / "resumed.png"))
    with home.lock:  # ground truth: it went on to the bedroom
        assert home.world.room_at(*home.sim.robot_pose[:2]) == "bedroom"
    for name in ("moving.png", "done.png", "stopped.png", "resumed.png"):
        assert (tmp_path / name).stat().st_size > 10_000  # a real picture of the page
    page.close()


_CONTROL = "document.getElementById('control').textContent.includes('{}')"


def test_control_goes_back_when_its_page_is_reloaded_or_closed(
        served: tuple[str, Console], browser: object, tmp_path: Path) -> None:
    url, home = served
    first = browser.new_page(viewport={"width": 1280, "height": 800})  # type: ignore[attr-defined]
    first.set_default_timeout(_TIMEOUT_MS)
    first.goto(f"{url}/?token={TOKEN}")
    first.wait_for_selector("#robot", state="attached")
    first.click("#take")
    first.wait_for_function(_CONTROL.format("you have control"))
    held_by = home.controller
    assert held_by is not None and held_by in first.inner_text("#whoami")
    # a reload: the old page's beacon gives control back at once (well within the lease)
    first.reload()
    first.wait_for_selector("#robot", state="attached")
    first.wait_for_function(_CONTROL.format("nobody has control"))
    assert home.controller is None
    assert held_by not in first.inner_text("#whoami")  # the reloaded page is a new session
    first.click("#take")
    first.wait_for_function(_CONTROL.format("you have control"))
    # a second page cannot take it, and sees who has it
    second = browser.new_page(viewport={"width": 1280, "height": 800})  # type: ignore[attr-defined]
    second.set_default_timeout(_TIMEOUT_MS)
    second.goto(f"{url}/?token={TOKEN}")
    second.wait_for_selector("#robot", state="attached")
    second.wait_for_function(_CONTROL.format("someone else has control"))
    second.click("#take")
    second.wait_for_function("document.getElementById('error').textContent"
                             ".includes('another operator')")
    second.screenshot(path=str(tmp_path / "refused.png"))
    # closing the tab gives it back: the second page takes it without waiting out the lease
    first.close(run_before_unload=True)
    second.wait_for_function(_CONTROL.format("nobody has control"))
    second.click("#take")
    second.wait_for_function(_CONTROL.format("you have control"))
    second.screenshot(path=str(tmp_path / "taken_over.png"))
    assert home.controller is not None and home.controller != held_by
    for name in ("refused.png", "taken_over.png"):
        assert (tmp_path / name).stat().st_size > 10_000
    second.close(run_before_unload=True)


def test_arrow_keys_drive_the_embodied_base_capped_and_slowed(browser: object,
                                                             tmp_path: Path) -> None:
    pytest.importorskip("cv2")
    settings = ConsoleSettings(world=World.load("apartment"), token=TOKEN, speed=2.0,
                               fidelity=Fidelity.EMBODIED)
    speeds: list[tuple[float, float]] = []  # (nearest return ahead, forward speed)
    with _serving(settings) as (url, home):
        home.tick_hooks.append(lambda tick: speeds.append(
            (home.nearest_ahead(), home.body.odometry().twist.vx)))
        page = browser.new_page(viewport={"width": 1280, "height": 800})  # type: ignore[attr-defined]
        page.set_default_timeout(_TIMEOUT_MS)
        page.goto(f"{url}/?token={TOKEN}")
        page.wait_for_selector("#robot", state="attached")
        page.click("#take")
        page.wait_for_function("document.getElementById('control').textContent"
                               ".includes('you have control')")
        start = _robot_xy(page)
        page.keyboard.down("ArrowUp")  # north: out of the entrance, through its door
        page.wait_for_function(
            f"(() => {{ const r = document.getElementById('robot'); return r && "
            f"Math.hypot(r.dataset.x - {start[0]}, r.dataset.y - {start[1]}) > 1.5; }})()")
        page.keyboard.up("ArrowUp")
        page.screenshot(path=str(tmp_path / "driven.png"))
        page.close()
    cap = settings.max_linear
    moving = [(ahead, speed) for ahead, speed in speeds if speed > 0.01]
    assert moving and max(speed for _, speed in moving) <= cap + 1e-9
    assert any(speed > 0.9 * cap for _, speed in moving)  # free floor: the cap
    assert any(ahead < 1.0 and speed < 0.75 * cap for ahead, speed in moving)  # slowed near
    assert home.sim.collisions == []
    assert (tmp_path / "driven.png").stat().st_size > 10_000


_CAMERA_STAMP = "(() => {{ const i = document.getElementById('camera'); return i.complete && " \
    "i.naturalWidth === 320 && +i.dataset.stamp > {}; }})()"


def _camera_shot(page: object, path: Path) -> tuple[float, np.ndarray]:
    """The camera panel's image as the page shows it (saved at ``path``), and its stamp."""
    stamp = float(page.get_attribute("#camera", "data-stamp"))  # type: ignore[attr-defined]
    page.locator("#camera").screenshot(path=str(path))  # type: ignore[attr-defined]
    return stamp, np.asarray(Image.open(path).convert("RGB"), dtype=float)


def test_the_page_names_the_furniture_narrates_the_log_and_shows_the_head_camera_live(
        browser: object, tmp_path: Path) -> None:
    pytest.importorskip("cv2")
    world = World.load("apartment")
    settings = ConsoleSettings(world=world, token=TOKEN, speed=4.0, fidelity=Fidelity.EMBODIED)
    with _serving(settings) as (url, home):
        page = browser.new_page(viewport={"width": 1280, "height": 800})  # type: ignore[attr-defined]
        page.set_default_timeout(_TIMEOUT_MS)
        page.goto(f"{url}/?token={TOKEN}")
        page.wait_for_selector("#robot", state="attached")
        # every piece of furniture named on the map; the objects too
        labels = page.locator(".placement-label")
        assert sorted(labels.all_text_contents()) == sorted(
            name.replace("_", " ") for name in world.placements)
        assert page.locator(".object-label[data-object='cola']").text_content() == "cola"
        assert page.get_attribute("#command", "placeholder") == \
            "bring me the cola from the fridge"  # this home's own, from the served map
        # the head camera, live before the robot has looked at anything itself
        page.wait_for_function(_CAMERA_STAMP.format(-1))
        assert "seen at t=" in page.inner_text("#camera-note")
        assert "(simulated)" in page.inner_text("#camera-note")
        before, before_image = _camera_shot(page, tmp_path / "camera_before.png")
        page.click("#take")
        page.wait_for_function("document.getElementById('control').textContent"
                               ".includes('you have control')")
        page.evaluate("api('/api/steps', {steps: [{skill: 'navigate', to: 'fridge'}, "
                      "{skill: 'find_object', object: 'cola', placement: 'fridge'}]})")
        # while the robot drives, the camera keeps up: a later image, another scene
        start = _robot_xy(page)
        page.wait_for_function(
            f"(() => {{ const r = document.getElementById('robot'); return r && "
            f"Math.hypot(r.dataset.x - {start[0]}, r.dataset.y - {start[1]}) > 1.5; }})()")
        with home.lock:
            driven = home.sim.clock.now()
        page.wait_for_function(_CAMERA_STAMP.format(driven))
        moving, moving_image = _camera_shot(page, tmp_path / "camera_moving.png")
        page.screenshot(path=str(tmp_path / "driving.png"))
        page.wait_for_function("document.getElementById('log').textContent"
                               ".includes('verified find_object(object=cola, placement=fridge)')")
        with home.lock:
            now = home.sim.clock.now()
        page.wait_for_function(_CAMERA_STAMP.format(now - 1e-3))  # caught up with the robot
        at_fridge, fridge_image = _camera_shot(page, tmp_path / "camera_fridge.png")
        assert "the robot itself last looked at t=" in page.inner_text("#camera-note")
        page.screenshot(path=str(tmp_path / "labelled.png"))
        assert page.locator("#log details.event").count() >= 5
        raw = page.locator("#log details.event[data-kind='skill.start'] pre").first
        assert not raw.is_visible()  # the raw JSON is one click away
        page.locator("#log details.event[data-kind='skill.start'] summary").first.click()
        assert raw.is_visible() and '"kind": "skill.start"' in raw.inner_text()
        # reloaded, the page watches again (a new session, control given back)
        page.reload()
        page.wait_for_selector("#robot", state="attached")
        page.wait_for_function(_CAMERA_STAMP.format(-1))
        page.wait_for_function("document.getElementById('control').textContent"
                               ".includes('nobody has control')")
        page.locator("#camera").screenshot(path=str(tmp_path / "camera_reloaded.png"))
        page.click("#take")
        page.wait_for_function("document.getElementById('control').textContent"
                               ".includes('you have control')")
        assert home.controller is not None
        # the tab closed: control given back at once, not when the lease lapses
        page.close(run_before_unload=True)
        for _ in range(100):
            if home.controller is None:
                break
            threading.Event().wait(0.05)
        assert home.controller is None
        assert home.lease.seconds >= 10.0  # well within the lease
    assert before < moving < at_fridge
    assert np.abs(moving_image - before_image).mean() > 10.0
    assert np.abs(fridge_image - moving_image).mean() > 10.0
    # the robot's own look at the fridge is not the page's: watching took no image
    assert home.body.last_camera() is not None
    for name in ("labelled.png", "driving.png", "camera_before.png", "camera_fridge.png",
                 "camera_reloaded.png"):
        assert (tmp_path / name).stat().st_size > 5_000
