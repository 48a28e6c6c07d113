"""``homebot.app.world_names``: a world's names from the cache while the file and the code
are unchanged, read afresh otherwise; a one-shot ``homebot parse`` then loads no world."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from homebot.app.cache import CACHE_DIRECTORY_VARIABLE
from homebot.app.world_names import world_names, world_vocabulary
from homebot.errors import WorldError
from homebot.world import World, shipped_world_path

SRC = Path(__file__).resolve().parents[2] / "src"


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv(CACHE_DIRECTORY_VARIABLE, str(folder))
    return folder


def _cached_files(cache: Path) -> list[Path]:
    return sorted((cache / "world_names").glob("*.json"))


def test_the_names_are_the_worlds_and_kept(cache: Path) -> None:
    names = world_names("apartment")
    world = World.load("apartment")
    assert names["rooms"] == list(world.rooms) and names["people"] == list(world.people)
    assert names["objects"] == {name: o.category for name, o in world.objects.items()}
    [kept] = _cached_files(cache)
    assert json.loads(kept.read_text(encoding="utf-8")) == names
    assert world_vocabulary("apartment").kind_of("kitchen") == "room"


def test_an_edited_world_is_read_afresh(cache: Path, tmp_path: Path) -> None:
    path = tmp_path / "home.yaml"
    text = shipped_world_path("apartment").read_text(encoding="utf-8")
    path.write_text(text, encoding="utf-8")
    assert "Alex" in world_names(path)["people"]
    path.write_text(text.replace("Alex", "Robin"), encoding="utf-8")
    people = world_names(path)["people"]
    assert "Robin" in people and "Alex" not in people
    assert len(_cached_files(cache)) == 2


def test_a_damaged_cache_file_is_read_afresh(cache: Path) -> None:
    names = world_names("apartment")
    [kept] = _cached_files(cache)
    kept.write_text("{not json", encoding="utf-8")
    assert world_names("apartment") == names
    assert json.loads(kept.read_text(encoding="utf-8")) == names


def test_a_broken_world_is_an_error_and_nothing_is_kept(cache: Path, tmp_path: Path) -> None:
    path = tmp_path / "broken.yaml"
    path.write_text("rooms: [\n", encoding="utf-8")
    with pytest.raises(WorldError, match=r"broken\.yaml"):
        world_names(path)
    with pytest.raises(WorldError, match="no world named 'atlantis'"):
        world_names("atlantis")
    assert _cached_files(cache) == []


def test_parse_in_a_fresh_process_loads_no_world_once_its_names_are_kept(cache: Path) -> None:
    script = ("import json, sys\nfrom homebot.cli import main\n"
              "status = main(['parse', 'bring me a coke', '--json'])\n"
              "heavy = [m for m in ('numpy', 'scipy', 'pydantic', 'shapely', 'yaml', 'rich')\n"
              "         if m in sys.modules]\n"
              "print(json.dumps([status, heavy]), file=sys.stderr)\n")
    environment = {**os.environ, "PYTHONPATH": str(SRC), CACHE_DIRECTORY_VARIABLE: str(cache)}

    def run() -> tuple[int, list[str]]:
        done = subprocess.run([sys.executable, "-c", script], env=environment, check=True,
                              capture_output=True, text=True)
        assert '"skill": "pick", "object": "cola"' in done.stdout
        status, heavy = json.loads(done.stderr)
        return status, heavy

    status, heavy = run()  # reads the world: pydantic, shapely and numpy come with it
    assert status == 0 and {"pydantic", "shapely", "numpy"} <= set(heavy)
    assert run() == (0, [])
