"""Agreement with SitLog's own KB service (change_KB_extensions.pl) on hand-written KBs.

The expected answers are the ones the original gives under SWI-Prolog for the same KB
(``homebot bench kb_original`` compares whole generated KBs when it can run it).
"""

from __future__ import annotations

from homebot.knowledge import KnowledgeBase

KB = """[
class(top,none,[],[],[]),
class(shelfy,top,[[not(colour=>blue),0],['-'=>>loc=>shelf_a,2],['-'=>>loc=>shelf_b,2],
  ['-'=>>loc=>shelf_c,2],[b1=>>d1,1]],[],
  [[id=>x,[[colour=>red,0],[b1,0]],[]],[id=>y,[],[]]])
]"""


def _answer(kb: KnowledgeBase, individual: str) -> list[str]:
    return [str(literal) for literal in kb.properties_of_individual(individual)]


def test_of_three_equal_weight_defaults_the_last_listed_wins() -> None:
    kb = KnowledgeBase.from_text(KB)
    assert kb.value("y", "loc") == "shelf_c"
    assert _answer(kb, "y") == ["not(colour=>blue)", "loc=>shelf_c"]


def test_a_negation_is_kept_beside_a_value_it_does_not_contradict() -> None:
    kb = KnowledgeBase.from_text(KB)
    # the original: [colour=>red,b1,not(colour=>blue),d1,loc=>shelf_c]
    assert _answer(kb, "x") == ["colour=>red", "b1", "not(colour=>blue)", "d1", "loc=>shelf_c"]
    assert kb.value("x", "colour") == "red"


def test_a_negation_of_the_same_value_is_dropped_and_only_the_first_is_listed() -> None:
    kb = KnowledgeBase.from_text(
        "[class(top,none,[[not(a=>v3),0],[not(a=>v4),0]],[],[]),"
        " class(c,top,[[a=>v3,0]],[],[[id=>z,[[a=>v1,0]],[]]])]")
    # a=>v1 decides; not(a=>v3) is the first negation; not(a=>v4) comes after it
    assert _answer(kb, "z") == ["a=>v1", "not(a=>v3)"]


def test_derived_conclusions_are_listed_in_the_order_their_defaults_fire() -> None:
    kb = KnowledgeBase.from_text(
        "[class(top,none,[[p,0],['-'=>>late,5],[p=>>early,1]],[],[[id=>w,[],[]]])]")
    assert _answer(kb, "w") == ["p", "early", "late"]


def test_the_harness_counts_identical_reordered_and_different_answers() -> None:
    from homebot.bench.kb_original import compare_answers, split_prolog_list

    assert split_prolog_list("[a=>'x,y',not(b=>[c,d]),e]") == ["a=>'x,y'", "not(b=>[c,d])", "e"]
    kb = KnowledgeBase.from_text(KB)
    counts = compare_answers(kb, {
        "x": "[colour=>red,b1,not(colour=>blue),d1,loc=>shelf_c]",
        "y": "[loc=>shelf_c,not(colour=>blue)]",
    })
    assert (counts["identical"], counts["same_literals_other_order"], counts["different"]) == (
        1, 1, 0)
    counts = compare_answers(kb, {"y": "[loc=>shelf_a]", "x": "failed"})
    assert (counts["different"], counts["original_failed_or_timed_out"]) == (1, 1)
