"""The catalogue of typical object masses: every figure says where it came from."""

from __future__ import annotations

from homebot.world.masses import known_mass, known_masses


def test_every_entry_has_a_mass_and_a_source() -> None:
    entries = set(known_masses().values())
    assert len(entries) >= 40
    for entry in entries:
        assert 0 < entry.mass <= 30
        assert entry.source.startswith(("YCB ", "typical retail pack (stated content): "))


def test_ycb_objects_cite_the_paper_and_retail_packs_state_their_content() -> None:
    cracker = known_mass("cheezit")
    assert cracker is not None and cracker.mass == 0.411
    assert "YCB 003 cracker box" in cracker.source and "Calli et al. 2015" in cracker.source
    cola = known_mass("cola")
    assert cola is not None and "330 ml can" in cola.source


def test_names_are_compared_as_people_say_them() -> None:
    assert known_mass("coke") == known_mass("cola") == known_mass("Cola")
    assert known_mass("Cheez_It") == known_mass("cheezit")
    assert known_mass("apples") == known_mass("apple")
    assert known_mass("orange juice") != known_mass("orange")
    assert known_mass("flux capacitor") is None
