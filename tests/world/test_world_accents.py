"""World files take names in any script, with accents (issue 22), and keep them as written."""

from __future__ import annotations

import unicodedata
from pathlib import Path
from typing import Any

import pytest
import yaml

from homebot.cli import main
from homebot.errors import WorldError
from homebot.world import World
from homebot.world.robocup import world_from_robocup

CASA = Path(__file__).resolve().parent / "data" / "casa.yaml"


def _casa_data() -> dict[str, Any]:
    data: dict[str, Any] = yaml.safe_load(CASA.read_text(encoding="utf-8"))
    return data


def test_the_accented_world_loads_with_its_spelling() -> None:
    world = World.load(CASA)
    assert set(world.people) == {"Patrícia", "José", "Antônia", "Zoë", "Søren"}
    assert "crème brûlée" in world.objects
    assert world.placements["étagère"].room == "salão"
    assert world.model.operator == "Zoë"


def test_names_may_be_written_in_other_scripts_and_decomposed() -> None:
    data = _casa_data()
    data["people"][0]["name"] = "Анна"
    data["people"][1]["name"] = unicodedata.normalize("NFD", "José")
    data["operator"] = "Анна"
    world = World.from_dict(data)
    assert "Анна" in world.people
    assert unicodedata.normalize("NFD", "José") in world.people


@pytest.mark.parametrize("bad", ["1st", "a.b", "tab\there", "-x"])
def test_a_name_still_starts_with_a_letter_and_holds_no_punctuation(bad: str) -> None:
    data = _casa_data()
    data["objects"][0]["name"] = bad
    with pytest.raises(WorldError, match=r"objects\.0\.name"):
        World.from_dict(data)


def test_names_that_differ_only_in_accents_or_case_are_one_name() -> None:
    data = _casa_data()
    data["people"][1]["name"] = "PATRICIA"
    with pytest.raises(WorldError, match="'PATRICIA' and 'Patrícia' in people differ only in "
                                         "accents or case"):
        World.from_dict(data)


def test_a_placement_named_like_a_room_but_for_accents_is_an_error() -> None:
    data = _casa_data()
    data["placements"][3]["name"] = "Salao"
    with pytest.raises(WorldError, match="'Salao' is also a room name \\('salão'"):
        World.from_dict(data)


def test_unknown_names_are_suggested_in_folded_form() -> None:
    world = World.load(CASA)
    with pytest.raises(WorldError, match="did you mean 'Patrícia'"):
        world.person("patrica")


def test_a_saved_world_keeps_its_letters(tmp_path: Path) -> None:
    world = World.load(CASA)
    path = tmp_path / "casa.yaml"
    world.save(path)
    text = path.read_text(encoding="utf-8")
    assert "crème brûlée" in text and "\\x" not in text and "\\u" not in text
    assert World.load(path).to_dict() == world.to_dict()


def test_robocup_data_keeps_accented_names(tmp_path: Path) -> None:
    tables = {
        "names/names.md": "| Names |\n| --- |\n| Patrícia |\n| Antônia |\n| Søren |\n",
        "maps/room_names.md": "| Name |\n| --- |\n| cozinha |\n| salão |\n",
        "maps/location_names.md": "| Number | Name | Object Category |\n| --- | --- | --- |\n"
                                  "| 1 | étagère (p) | desserts |\n| 2 | mesa (p) |\n",
        "objects/objects.md": "# Class desserts (dessert)\n| Objectname | Image |\n"
                              "| --- | --- |\n| crème_brûlée | ![](a.jpg) |\n",
    }
    for name, text in tables.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text, encoding="utf-8")
    world = World.from_dict(world_from_robocup(tmp_path))
    assert set(world.people) == {"Patrícia", "Antônia", "Søren"}
    assert "salão" in world.rooms
    assert world.objects["crème brûlée"].placement == "étagère"


def test_world_show_prints_names_as_written(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["world", "show", "--world", str(CASA), "--json"]) == 0
    out = capsys.readouterr().out
    assert "Søren" in out and "crème brûlée" in out and "\\u" not in out
    assert main(["world", "show", "--world", str(CASA)]) == 0
    out = capsys.readouterr().out
    assert "Antônia" in out and "étagère" in out
