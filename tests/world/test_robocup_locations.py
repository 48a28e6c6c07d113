"""Which room a RoboCup@Home location stands in and what it is, from the words of its name."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.world import World
from homebot.world.robocup import import_robocup
from homebot.world.robocup_locations import assign_rooms, furniture_kind, room_table

SHARED = Path(__file__).resolve().parents[3] / "shared" / "data" / "robocup" / "CompetitionTemplate"

# Another team's flat: its own room names and furniture names.
ROOMS = ["Living Room", "kitchen", "study", "hallway", "bathroom", "master bedroom",
         "dining room"]
EXPECTED = {
    "dishwasher": "kitchen", "fridge": "kitchen", "kitchen counter": "kitchen",
    "trashcan": "kitchen", "microwave": "kitchen", "sink": "kitchen",
    "bed": "master bedroom", "nightstand": "master bedroom", "wardrobe": "master bedroom",
    "shoe rack": "hallway", "coathanger": "hallway", "hallway cabinet": "hallway",
    "entrance": "hallway", "umbrella stand": "hallway",
    "couch": "Living Room", "lounge chair": "Living Room", "TV table": "Living Room",
    "tvstand": "Living Room", "armchair": "Living Room",
    "desk": "study", "desk lamp": "study", "wastebasket": "study",
    "dinner table": "dining room", "chairs": "dining room", "wine rack": "dining room",
    "bathtub": "bathroom", "washbasin": "bathroom", "toilet": "bathroom",
}


def assign(locations: list[str], rooms: list[str], warnings: list[str] | None = None,
           table: dict[str, list[str]] | None = None) -> dict[str, str]:
    lines = [f"location_names.md: line {index + 4}" for index in range(len(locations))]
    return assign_rooms(locations, lines, rooms, table or room_table(),
                        [] if warnings is None else warnings)


def test_well_known_furniture_lands_in_a_room_of_its_kind() -> None:
    warnings: list[str] = []
    assert assign(list(EXPECTED), ROOMS, warnings) == EXPECTED
    assert warnings == []


def test_a_location_no_word_of_which_says_a_room_goes_to_the_living_room_with_a_warning(
        ) -> None:
    warnings: list[str] = []
    rooms = assign(["bed", "flux capacitor"], ["bedroom", "kitchen", "lounge"], warnings)
    assert rooms == {"bed": "bedroom", "flux capacitor": "lounge"}
    assert warnings == ["location_names.md: line 5: no word of the location 'flux capacitor' "
                        "says which room it stands in; put it in the lounge (a --rooms file "
                        "line 'flux capacitor: ROOM' chooses)"]


def test_without_a_shared_room_the_fallback_is_the_emptiest_room() -> None:
    rooms = assign(["bed", "bedside table", "flux capacitor"], ["bedroom", "garage"])
    assert rooms["flux capacitor"] == "garage"


def test_a_room_the_data_lacks_is_skipped_for_the_next_likely_one() -> None:
    # sink: [kitchen, bathroom]; chairs: [dining room, kitchen]; desk: [office, study, bedroom]
    rooms = assign(["sink", "chairs", "desk"], ["bathroom", "kitchen", "bedroom"])
    assert rooms == {"sink": "kitchen", "chairs": "kitchen", "desk": "bedroom"}
    assert assign(["sink"], ["bathroom", "bedroom"]) == {"sink": "bathroom"}


@pytest.mark.parametrize(("name", "kind"), [
    ("desk lamp", "lamp"), ("bedside table", "table"), ("bookshelf", "storage"),
    ("coatrack", "storage"), ("trashbin", "bin"), ("cabinet", "storage"),
    ("refrigerator", "appliance"), ("kitchen counter", "counter"), ("side tables", "table"),
    ("entrance", "spot"), ("potted plant", "fixture"),
])
def test_the_furniture_kind_comes_from_the_head_noun(name: str, kind: str) -> None:
    assert furniture_kind(name, placeable=False) == kind


@pytest.mark.acceptance
def test_the_competition_templates_locations_land_in_plausible_rooms() -> None:
    if not SHARED.is_dir():
        pytest.skip("the shared acceptance data (../shared/data) is absent")
    imported = import_robocup(SHARED)
    world = World.from_dict(imported.data)
    expected = {"bed": "bedroom", "bedside table": "bedroom", "dishwasher": "kitchen",
                "refrigerator": "kitchen", "kitchen table": "kitchen", "pantry": "kitchen",
                "sink": "kitchen", "trashbin": "kitchen", "desk": "office",
                "desk lamp": "office", "sofa": "living room", "armchair": "living room",
                "tv stand": "living room", "side tables": "living room"}
    assert {name: world.placements[name].room for name in expected} == expected
    assert imported.warnings == []


def test_a_location_whose_rooms_the_data_lacks_says_so() -> None:
    warnings: list[str] = []
    assert assign(["bathtub"], ["kitchen", "living room"], warnings) == {
        "bathtub": "living room"}
    assert warnings == ["location_names.md: line 4: the location 'bathtub' belongs in a "
                        "bathroom, which the data does not have; put it in the living room "
                        "(a --rooms file line 'bathtub: ROOM' chooses)"]
