"""Updates: each kind, atomic failure, coherence and cache invalidation under random sequences."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from kb_strategies import NAMES, literals, preferences, taxonomies

from homebot.errors import KnowledgeError
from homebot.knowledge import (
    AddClass,
    AddIndividual,
    AddStatement,
    ChangeValue,
    ChangeWeight,
    Kind,
    KnowledgeBase,
    Literal,
    MoveClass,
    MoveIndividual,
    RemoveClass,
    RemoveIndividual,
    RemoveStatement,
    Rename,
    Taxonomy,
    Update,
    parse_statement,
)
from homebot.knowledge.coherence import problems, warnings
from homebot.knowledge.tables import NAMESPACES


def test_removing_a_class_reattaches_its_children_and_members(animals: KnowledgeBase) -> None:
    animals.apply(RemoveClass(name="birds"))
    assert animals.taxonomy.classes["eagles"].mother == "animals"
    assert animals.taxonomy.classes["penguins"].mother == "animals"
    assert animals.value("pete", "fly") == "unknown"  # birds' defaults are gone
    assert animals.value("arthur", "swim") == "yes"
    assert problems(animals.taxonomy) == []


def test_removing_a_class_moves_its_individuals_up_and_drops_relations_to_it(
    animals: KnowledgeBase,
) -> None:
    animals.apply(RemoveClass(name="penguins"))
    assert animals.classes_of_individual("arthur") == ["birds", "animals", "top"]
    assert animals.value("arthur", "fly") == "yes"
    animals.apply(RemoveClass(name="animals"))
    assert animals.relations_of_individual("pete")[-1] != Literal("eat", "animals")
    assert all(r.name != "eat" for r in animals.relations_of_individual("pete"))


def test_top_cannot_be_removed_or_renamed(animals: KnowledgeBase) -> None:
    with pytest.raises(KnowledgeError, match="top"):
        animals.apply(RemoveClass(name="top"))
    with pytest.raises(KnowledgeError, match="top"):
        animals.apply(Rename(name="top", new_name="root"))


def test_a_new_statement_replaces_what_it_contradicts(animals: KnowledgeBase) -> None:
    animals.apply(AddStatement(owner="arthur", kind=Kind.PROPERTY, statement=Literal("fly")))
    assert animals.value("arthur", "fly") == "yes"
    animals.apply(
        AddStatement(owner="arthur", kind=Kind.PROPERTY, statement=Literal("fly", negated=True))
    )
    assert animals.taxonomy.individuals["arthur"].properties == [Literal("fly", negated=True)]
    assert warnings(animals.taxonomy) == []


def test_changing_a_weight_changes_the_preferred_conclusion(animals: KnowledgeBase) -> None:
    born = parse_statement("born=>'-'=>>live=>'-'", 5)
    animals.apply(ChangeWeight(owner="birds", kind=Kind.PROPERTY, statement=born, weight=1))
    assert animals.value("pete", "live") == "argentina"


def test_removing_a_preference_and_moving_an_individual(animals: KnowledgeBase) -> None:
    work = parse_statement("work=>'-'=>>live=>'-'", 3)
    animals.apply(RemoveStatement(owner="birds", kind=Kind.PROPERTY, statement=work))
    assert animals.value("pete", "live") == "argentina"
    animals.apply(MoveIndividual(name="pete", class_name="penguins"))
    assert animals.value("pete", "fly") == "no"
    assert animals.class_extension("penguins") == ["arthur", "pete"]


def test_rename_follows_mothers_members_and_relation_objects(animals: KnowledgeBase) -> None:
    animals.apply(Rename(name="animals", new_name="beasts"))
    assert animals.taxonomy.classes["birds"].mother == "beasts"
    assert animals.value("pete", "eat=>beasts") == "yes"
    animals.apply(Rename(name="pete", new_name="peter"))
    assert animals.class_extension("eagles") == ["peter"]
    assert animals.value("peter", "live") == "mexico"


def test_moving_a_class_below_itself_is_refused(animals: KnowledgeBase) -> None:
    with pytest.raises(KnowledgeError, match="cycle"):
        animals.apply(MoveClass(name="birds", mother="eagles"))
    animals.apply(MoveClass(name="penguins", mother="animals"))
    assert animals.value("arthur", "swim") == "yes"
    assert animals.value("arthur", "fly") == "no"


@pytest.mark.parametrize(
    ("update", "message"),
    [
        (AddClass(name="birds", mother="top"), "already names"),
        (AddClass(name="robots", mother="nowhere"), "unknown class 'nowhere'"),
        (AddIndividual(name="tweety", class_name="brids"), "did you mean 'birds'"),
        (RemoveIndividual(name="nobody"), "unknown individual"),
        (
            RemoveStatement(owner="pete", kind=Kind.PROPERTY, statement=Literal("fly")),
            "does not state fly",
        ),
        (
            AddStatement(owner="pete", kind=Kind.PROPERTY, statement=Literal("size", "large")),
            "already states",
        ),
        (
            ChangeValue(owner="pete", kind=Kind.PROPERTY, statement=parse_statement("a=>>b", 1)),
            "takes a literal",
        ),
        (
            AddStatement(
                owner="pete", kind=Kind.PROPERTY, statement=parse_statement("'-'=>>b", 1)
                .with_weight(0)
            ),
            "weight of 1 or more",
        ),
        (
            AddStatement(
                owner="pete", kind=Kind.PROPERTY, statement=parse_statement("'-'=>>b", 2**63)
            ),
            "at most 9223372036854775807",
        ),
    ],
)
def test_invalid_updates_raise_and_change_nothing(
    animals: KnowledgeBase, update: Update, message: str
) -> None:
    before = animals.taxonomy.copy()
    with pytest.raises(KnowledgeError, match=message):
        animals.apply(update)
    assert animals.taxonomy == before


def test_updates_round_trip_through_plain_data() -> None:
    updates = [
        AddClass(name="a", mother="top"),
        RemoveClass(name="a"),
        MoveClass(name="a", mother="b"),
        Rename(name="a", new_name="b"),
        AddIndividual(name="i", class_name="a"),
        RemoveIndividual(name="i"),
        MoveIndividual(name="i", class_name="b"),
        AddStatement(owner="i", kind=Kind.RELATION, statement=parse_statement("r=>[x,1]")),
        RemoveStatement(owner="i", kind=Kind.PROPERTY, statement=parse_statement("[p,q]=>>r", 2)),
        ChangeValue(owner="i", kind=Kind.PROPERTY, statement=parse_statement("last_seen=>s")),
        ChangeWeight(
            owner="i", kind=Kind.PROPERTY, statement=parse_statement("p=>'-'=>>q=>'-'", 2), weight=4
        ),
    ]
    for update in updates:
        data = update.to_dict()
        assert Update.from_dict(data).to_dict() == data
        if not isinstance(update, ChangeWeight):  # its rule's old weight does not matter
            assert Update.from_dict(data) == update


@pytest.mark.parametrize(
    "data",
    [
        {},
        {"type": "explode"},
        {"type": "add_class", "name": "a"},
        {"type": "add_class", "name": "a", "mother": "top", "colour": "red"},
        {"type": "add_statement", "owner": "a", "kind": "feeling", "statement": "p"},
        {"type": "add_statement", "owner": "a", "kind": "property", "statement": "p=>"},
        {"type": "add_statement", "owner": "a", "kind": "property", "statement": 3},
    ],
)
def test_malformed_update_data_raises_knowledge_errors(data: dict[str, object]) -> None:
    with pytest.raises(KnowledgeError):
        Update.from_dict(data)


def test_an_update_invalidates_only_what_it_touches(animals: KnowledgeBase) -> None:
    for name in animals.taxonomy.names():
        animals.holding(name, 0)
    dropped_before = animals.reasoner.cached()
    animals.apply(AddStatement(owner="pete", kind=Kind.PROPERTY, statement=Literal("tame")))
    assert animals.reasoner.statistics.last_dropped == 1  # pete's closure alone
    assert animals.reasoner.cached()[1] == dropped_before[1] - 1
    animals.apply(AddStatement(owner="penguins", kind=Kind.PROPERTY, statement=Literal("cold")))
    assert animals.reasoner.statistics.last_dropped == 3  # penguins' table, closure, arthur


# -- random update sequences ------------------------------------------------------------------


@st.composite
def updates(draw: st.DrawFn, taxonomy: Taxonomy) -> Update:
    """A plausible update: names mostly from the KB, sometimes unknown ones."""
    classes = [*taxonomy.classes, "ghost"]
    entities = [*taxonomy.names(), "ghost"]
    fresh = draw(st.sampled_from(["n1", "n2", "n3", *classes]))
    kind = draw(st.sampled_from(list(Kind)))
    statement = draw(st.one_of(literals(), preferences()))
    owner = draw(st.sampled_from(entities))
    choices = [
        AddClass(name=fresh, mother=draw(st.sampled_from(classes))),
        RemoveClass(name=draw(st.sampled_from(classes))),
        MoveClass(name=draw(st.sampled_from(classes)), mother=draw(st.sampled_from(classes))),
        Rename(name=draw(st.sampled_from(entities)), new_name=fresh),
        AddIndividual(name=fresh, class_name=draw(st.sampled_from(classes))),
        RemoveIndividual(name=draw(st.sampled_from(entities))),
        MoveIndividual(
            name=draw(st.sampled_from(entities)), class_name=draw(st.sampled_from(classes))
        ),
        AddStatement(owner=owner, kind=kind, statement=statement),
        RemoveStatement(owner=owner, kind=kind, statement=statement),
        ChangeValue(owner=owner, kind=kind, statement=draw(literals())),
        ChangeWeight(owner=owner, kind=kind, statement=statement, weight=draw(st.integers(0, 4))),
    ]
    return draw(st.sampled_from(choices))


def _everything(kb: KnowledgeBase) -> dict[str, object]:
    answers: dict[str, object] = {}
    for name in kb.taxonomy.names():
        answers[name] = (
            [tuple(kb.holding(name, ns)) for ns in NAMESPACES],
            [str(e) for e in kb.explanations(name)],
            [kb.values(name, n) for n in NAMES],
        )
    answers["extension"] = {c: kb.class_extension(c) for c in kb.taxonomy.classes}
    return answers


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(taxonomies(), st.data())
def test_random_update_sequences_keep_the_kb_coherent_and_caches_exact(
    taxonomy: Taxonomy, data: st.DataObject
) -> None:
    kb = KnowledgeBase(taxonomy)
    had_warnings = bool(warnings(taxonomy))
    for _ in range(data.draw(st.integers(1, 8))):
        _everything(kb)  # fill every cache, so stale entries would show
        update = data.draw(updates(kb.taxonomy))
        before = kb.taxonomy.copy()
        try:
            kb.apply(update)
        except KnowledgeError:
            assert kb.taxonomy == before  # a refused update changes nothing
            continue
        assert problems(kb.taxonomy) == []
        if not had_warnings:
            assert warnings(kb.taxonomy) == []
        assert _everything(kb) == _everything(KnowledgeBase(kb.taxonomy.copy()))
