"""Names with accents (issue 22): typed with or without them, in any case, they bind to the
world's spelling; commands to Patrícia succeed when they say "patricia"."""

from __future__ import annotations

import json
import unicodedata
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from homebot.app import RunSettings, build_run
from homebot.cli import main
from homebot.language import Vocabulary, parse_command
from homebot.world import World
from homebot.world.robocup import world_from_robocup

CASA = Path(__file__).resolve().parents[1] / "world" / "data" / "casa.yaml"
ROBOCUP_DIRECTORY = (Path(__file__).resolve().parents[3] / "shared" / "data" / "robocup"
                     / "CompetitionTemplate")
# One command per kind of name; the person's command names a room as well.
TEMPLATES = {"person": "meet {} in the {} and follow them", "room": "go to the {}",
             "placement": "go to the {}", "object": "bring me the {}",
             "category": "bring me a {}"}
ACUTE = str.maketrans("aeiouAEIOU", "áéíóúÁÉÍÓÚ")


@pytest.fixture(scope="module")
def casa() -> World:
    return World.load(CASA)


def _without_accents(name: str) -> str:
    """How a keyboard without accents writes a name: marks dropped, ø as o, case kept."""
    decomposed = unicodedata.normalize("NFKD", name)
    plain = "".join(char for char in decomposed if not unicodedata.combining(char))
    return plain.replace("ø", "o").replace("Ø", "O")


def _spellings(name: str) -> list[str]:
    """The name as written, without accents, shouted, lower case, and with every vowel
    accented (for names that have none)."""
    return list(dict.fromkeys([name, _without_accents(name), name.upper(),
                               _without_accents(name).lower(), name.translate(ACUTE)]))


def _names(world: World) -> Iterator[tuple[str, str]]:
    for name in world.people:
        yield "person", name
    for name in world.rooms:
        yield "room", name
    for name in world.placements:
        yield "placement", name
    for name in world.objects:
        yield "object", name
    for category in sorted({obj.category for obj in world.objects.values()}):
        yield "category", category


def _strings(value: Any) -> Iterator[str]:
    if isinstance(value, dict):
        for item in value.values():
            yield from _strings(item)
    elif isinstance(value, list):
        for item in value:
            yield from _strings(item)
    elif isinstance(value, str):
        yield value


def _unbound(world: World) -> tuple[int, int, list[str]]:
    """How many names and commands were tried, and the commands whose steps lack the
    world's spelling of the name they say."""
    vocabulary = Vocabulary.from_world(world)
    room = next(iter(world.rooms))
    names = list(_names(world))
    parsed, wrong = 0, []
    for kind, name in names:
        for typed in _spellings(name):
            text = TEMPLATES[kind].format(typed, room)
            result = parse_command(text, vocabulary)
            parsed += 1
            if not result or name not in set(_strings(result.to_dict()["steps"])):
                wrong.append(f"{text!r} -> {result.to_dict()}")
    return len(names), parsed, wrong


def test_every_name_of_the_accented_world_binds_to_its_spelling(casa: World) -> None:
    names, parsed, wrong = _unbound(casa)
    assert names == 22  # 5 people, 3 rooms, 5 placements, 6 objects, 3 categories
    assert parsed == 87  # each name in up to five spellings
    assert wrong == []


@pytest.mark.acceptance
def test_every_robocup_name_binds_with_and_without_accents() -> None:
    if not ROBOCUP_DIRECTORY.is_dir():
        pytest.skip("the shared acceptance data (../shared/data) is absent")
    world = World.from_dict(world_from_robocup(ROBOCUP_DIRECTORY))
    names, parsed, wrong = _unbound(world)
    assert names == len(world.people) + len(world.rooms) + len(world.placements) + len(
        world.objects) + len({obj.category for obj in world.objects.values()})
    assert parsed >= 3 * names
    assert wrong == []


@pytest.mark.parametrize(("typed", "meant"), [
    ("patricia", "Patrícia"), ("PATRÍCIA", "Patrícia"), ("Soren", "Søren"), ("zoe", "Zoë"),
    ("Antonia", "Antônia"), ("jose", "José"),
])
def test_people_are_found_under_the_world_spelling(casa: World, typed: str, meant: str) -> None:
    result = parse_command(f"meet {typed} in the salao and follow them",
                           Vocabulary.from_world(casa))
    assert result.to_dict()["steps"][1] == {"skill": "find_person", "person": {"name": meant},
                                            "room": "salão"}


@pytest.mark.parametrize(("typed", "meant"), [
    ("creme brulee", "crème brûlée"), ("smorrebrod", "smørrebrød"), ("pina colada", "piña colada"),
    ("CAFÉ COM LEITE", "café com leite"),
])
def test_objects_are_found_under_the_world_spelling(casa: World, typed: str, meant: str) -> None:
    result = parse_command(f"bring me the {typed}", Vocabulary.from_world(casa))
    assert result.to_dict()["steps"][0] == {"skill": "find_object", "object": meant}


def test_misspelt_accented_names_are_corrected_in_folded_form(casa: World) -> None:
    vocabulary = Vocabulary.from_world(casa)
    meet = parse_command("meet Patrica in the salão", vocabulary).to_dict()["steps"]
    assert meet[1]["person"] == {"name": "Patrícia"}
    meet = parse_command("meet Sorenn in the quarto", vocabulary).to_dict()["steps"]
    assert meet[1]["person"] == {"name": "Søren"}
    bring = parse_command("bring me the creme brule from the etagere", vocabulary)
    assert bring.to_dict()["steps"][1] == {"skill": "find_object", "object": "crème brûlée",
                                           "placement": "étagère"}
    go = parse_command("go to the frigorifco", vocabulary).to_dict()["steps"]
    assert go == [{"skill": "navigate", "to": "frigorífico"}]


def test_a_delivery_to_patricia_succeeds_by_ground_truth(casa: World) -> None:
    result = parse_command("bring the creme brulee to patricia", Vocabulary.from_world(casa))
    run = build_run(RunSettings(world=casa, seed=0))
    report = run.run(result.to_task())
    assert report.success
    assert run.simulation.object_location["crème brûlée"] == "person:Patrícia"
    assert "Patrícia, here is the crème brûlée." in report.speech


def test_do_prints_and_logs_names_as_written(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    events = tmp_path / "events.jsonl"
    status = main(["do", "bring the CREME BRULEE to patricia", "--world", str(CASA),
                   "--events", str(events), "--json"])
    out = capsys.readouterr().out
    assert status == 0
    assert "Patrícia" in out and "\\u00ed" not in out
    report = json.loads(out)
    assert report["steps"][-1]["args"] == {"person": "Patrícia"}
    log = events.read_text(encoding="utf-8")
    assert "crème brûlée" in log and "\\u" not in log
