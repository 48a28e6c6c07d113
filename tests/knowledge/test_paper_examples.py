"""The paper's examples (Listings 2 and 3) and the injured-bird KB, as the issue asks."""

from __future__ import annotations

from homebot.knowledge import (
    AddStatement,
    ChangeValue,
    Kind,
    KnowledgeBase,
    parse_statement,
)


def _add(kb: KnowledgeBase, owner: str, text: str, weight: int = 0) -> None:
    kb.apply(AddStatement(owner=owner, kind=Kind.PROPERTY, statement=parse_statement(text, weight)))


# -- Listing 2 --------------------------------------------------------------------------------


def test_penguins_do_not_fly_but_birds_do(animals: KnowledgeBase) -> None:
    assert animals.value("birds", "fly") == "yes"
    assert animals.value("penguins", "fly") == "no"
    assert animals.value("arthur", "fly") == "no"


def test_arthur_swims_though_birds_do_not(animals: KnowledgeBase) -> None:
    assert animals.value("birds", "swim") == "no"
    assert animals.value("penguins", "swim") == "yes"
    assert animals.value("arthur", "swim") == "yes"


def test_fish_swimming_is_unknown_not_false(animals: KnowledgeBase) -> None:
    assert animals.value("fish", "swim") == "unknown"


def test_eagles_eat_animals_and_the_class_expands_to_its_individuals(
    animals: KnowledgeBase,
) -> None:
    assert animals.value("eagles", "eat=>animals") == "yes"
    assert animals.value("pete", "eat=>arthur") == "yes"
    assert animals.relation_extension("eat") == [("pete", ["pete", "arthur"])]


def test_pete_lives_in_mexico_because_work_beats_birth(animals: KnowledgeBase) -> None:
    # work (3) beats born (5): México, not Argentina.
    assert animals.value("pete", "live") == "mexico"
    assert animals.value("pete", "live=>argentina") == "no"
    assert animals.values("pete", "live") == ["mexico", "argentina"]


def test_why_does_pete_live_in_mexico(animals: KnowledgeBase) -> None:
    _add(animals, "pete", "live=>mexico")
    explanations = animals.explanation_of_individual("pete")
    assert [str(e) for e in explanations] == ["live=>mexico : work=>mexico"]
    assert explanations[0].weight == 3 and explanations[0].source == "birds"


def test_the_eight_services_on_listing_2(animals: KnowledgeBase) -> None:
    assert animals.class_extension("top") == ["pete", "arthur"]
    assert animals.class_extension("birds") == ["pete", "arthur"]
    assert animals.class_extension("fish") == []
    assert animals.property_extension("fly") == [("pete", "yes"), ("arthur", "no")]
    assert animals.classes_of_individual("arthur") == ["penguins", "birds", "animals", "top"]
    assert [str(p) for p in animals.properties_of_individual("pete")] == [
        "size=>large",
        "fly",
        "not(swim)",
        "live=>mexico",
    ]
    assert [str(r) for r in animals.relations_of_individual("pete")] == [
        "work=>mexico",
        "born=>argentina",
        "like=>mexico",
        "eat=>[pete,arthur]",
    ]
    assert [(i, str(e)) for i, e in animals.explanation_extension("live")] == [
        ("pete", "live=>mexico : work=>mexico")
    ]


# -- Listing 3 -----------------------------------------------------------------------------------


def test_user_is_found_in_the_living_room_after_a_bad_day_back_from_work(
    butler: KnowledgeBase,
) -> None:
    assert butler.value("user", "found_in") == "unknown"
    _add(butler, "user", "bad_day")
    _add(butler, "user", "back_from_work")
    assert butler.value("user", "tired") == "yes"  # chained: bad_day =>> tired
    assert butler.value("user", "found_in") == "living_room"


def test_living_room_wins_even_when_asked_comestible_holds(butler: KnowledgeBase) -> None:
    for fact in ("bad_day", "back_from_work", "asked_comestible"):
        _add(butler, "user", fact)
    assert butler.value("user", "found_in") == "living_room"
    assert butler.values("user", "found_in") == ["living_room", "dining_room"]


def test_without_the_bad_day_the_dining_room_wins(butler: KnowledgeBase) -> None:
    _add(butler, "user", "back_from_work")
    _add(butler, "user", "asked_comestible")
    assert butler.value("user", "found_in") == "dining_room"


def test_noodles_locations_in_preference_order(butler: KnowledgeBase) -> None:
    assert butler.values("noodles", "loc") == ["shelf_food", "shelf_snacks", "shelf_drinks"]
    assert butler.value("noodles", "loc") == "shelf_food"


def test_last_seen_puts_the_drinks_shelf_first(butler: KnowledgeBase) -> None:
    butler.apply(
        ChangeValue(
            owner="noodles",
            kind=Kind.PROPERTY,
            statement=parse_statement("last_seen=>shelf_drinks"),
        )
    )
    assert butler.values("noodles", "loc") == ["shelf_drinks", "shelf_food", "shelf_snacks"]
    assert butler.value("noodles", "loc") == "shelf_drinks"
    assert butler.values("bisquits", "loc")[0] == "shelf_food"  # only noodles were seen


def test_misplaced_coke_is_explained_by_the_child(butler: KnowledgeBase) -> None:
    _add(butler, "coke", "misplaced")
    explanations = {str(e.consequent): e for e in butler.explanation_of_individual("coke")}
    assert explanations["misplaced"].antecedent_text == "moved_by=>child"
    assert explanations["misplaced"].weight == 1  # the child (1) beats the partner (2)
    assert [(i, str(e)) for i, e in butler.explanation_extension("misplaced")] == [
        ("coke", "misplaced : moved_by=>child")
    ]


def test_objects_are_graspable_and_points_have_names(butler: KnowledgeBase) -> None:
    assert butler.value("malz", "graspable") == "yes"
    assert butler.value("living_room", "name") == "living room"
    assert butler.value("user", "graspable") == "unknown"


# -- Birds that do not fly are injured -------------------------------------------------------

INJURED_BIRDS = """
[class(top,none,[],[],[]),
 class(birds,top,[['-'=>>fly,2],[injured=>>not(fly),1],[not(fly)=>>injured,3]],[],[]),
 class(eagles,birds,[],[],[[id=>hurt_eagle,[[injured,0]],[]],[id=>eagle,[],[]]]),
 class(penguins,birds,[[not(fly),0]],[],[[id=>penguin,[],[]]])]
"""


def test_an_injured_eagle_does_not_fly() -> None:
    kb = KnowledgeBase.from_text(INJURED_BIRDS)
    assert kb.value("hurt_eagle", "fly") == "no"


def test_an_uninjured_eagle_flies() -> None:
    kb = KnowledgeBase.from_text(INJURED_BIRDS)
    assert kb.value("eagle", "fly") == "yes"
    assert kb.value("eagle", "injured") == "unknown"


def test_a_penguin_that_does_not_fly_is_explained_as_injured() -> None:
    kb = KnowledgeBase.from_text(INJURED_BIRDS)
    assert kb.value("penguin", "fly") == "no"
    explanations = {str(e.consequent): e for e in kb.explanation_of_individual("penguin")}
    assert explanations["not(fly)"].antecedent_text == "injured"


def test_answers_do_not_depend_on_the_order_of_questions() -> None:
    first = KnowledgeBase.from_text(INJURED_BIRDS)
    second = KnowledgeBase.from_text(INJURED_BIRDS)
    assert first.value("eagle", "injured") == "unknown"
    assert first.value("eagle", "fly") == "yes"
    assert second.value("eagle", "fly") == "yes"
    assert second.value("eagle", "injured") == "unknown"
