"""The butler's dialogue (§9, lines 1-41): the paper's robot lines in content and order."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest

from homebot.cli import main
from homebot.cli.scenario import run_builder
from homebot.knowledge import KnowledgeBase
from homebot.knowledge.store import KnowledgeStore
from homebot.scenarios.library.butler import run_butler

#: The robot's lines of the paper's dialogue, by their number there.
PAPER_ROBOT_LINES = {
    1: "Hi, Luis.",
    2: "Please tell me what do you like best: malz or coke?",
    4: "Excellent! Malz is much healthier than the coke!",
    5: "What do you like best: noodles or biscuits?",
    7: "Great! I will recall your choice!",
    8: "Do you have any more preferences?",
    10: "Thank you, Luis.",
    11: "Hi, Luis, how was your day?",
    13: "Sorry to hear that; do you want me to do something for you?",
    15: "Ok. I will bring you malz, your favorite drink.",
    17: "But you like noodles better than biscuits! Shall I bring you the biscuits?",
    19: "Ok. I will bring you the malz and the noodles. I will get the malz.",
    20: "Attempting to grab the malz with my left arm.",
    21: "I took the malz.",
    22: "I will get the noodles.",
    23: "The noodles are not in the shelf of food.",
    24: "Attempting to grab the noodles with my right arm.",
    25: "I took the noodles.",
    26: "Here is the noodles.",
    27: "Here is the malz.",
    28: "I found the noodles on the shelf of snacks, but it should be on the shelf of food; do "
        "you want me to change the preferred location of noodles to the shelf of snacks?",
    30: "Ok. I updated my KB with your new preference.",
    31: "I also noticed that the coke is not in its right place.",
    32: "I think that the explanation for this is that the coke was misplaced there by your "
        "child.",
    33: "Do you want me to take it to its right shelf?",
    35: "Ok. I will take it to the shelf of drinks.",
    36: "Attempting to grab the coke with my right arm.",
    37: "I took the coke.",
    38: "I put the coke on its right shelf.",
    39: "All the objects are placed on their right shelves.",
    40: "The task is finished.",
    41: "Goodbye.",
}


def _words(text: str) -> str:
    return " ".join(re.findall(r"[a-z0-9]+", text.lower()))


def _same(said: str, paper: str) -> bool:
    """Equal in words; a hand-over may name whom it addresses first ("Luis, here is ..."),
    and says "here are" for a plural ("here are the noodles"; the paper has "here is")."""
    said_words, paper_words = _words(said).replace("here are", "here is"), _words(paper)
    return said_words in (paper_words, f"luis {paper_words}")


@pytest.fixture(scope="module")
def paper_run() -> dict[str, Any]:
    return run_butler(run_builder())


def test_the_robot_says_the_papers_lines_in_order(paper_run: dict[str, Any]) -> None:
    said = paper_run["speech"]
    expected = list(PAPER_ROBOT_LINES.values())
    assert len(said) == len(expected)
    for number, (line, paper) in enumerate(zip(said, expected, strict=True)):
        assert _same(line, paper), (number, line, paper)


def test_the_whole_conversation_has_the_papers_41_turns(paper_run: dict[str, Any]) -> None:
    transcript = paper_run["transcript"]
    assert len(transcript) == 41
    robot_turns = [n for n, line in enumerate(transcript, start=1) if line["who"] == "robot"]
    assert robot_turns == list(PAPER_ROBOT_LINES)


def test_luis_is_sought_in_the_living_room_because_he_is_tired(
        paper_run: dict[str, Any]) -> None:
    # In the order of SitLog's KB service: both defaults weigh 1 at the user's level, so
    # the one listed last comes first (explanation_of_individual under SWI-Prolog gives
    # [(found_in=>living_room):[back_from_work,tired],tired:bad_day]).
    assert paper_run["why_user"] == ["found_in=>living_room : [back_from_work,tired]",
                                     "tired : bad_day"]
    searched = [a["situation"] for a in paper_run["actions"]
                if a["model"] == "deliver" and a["situation"].startswith("find")]
    assert searched == ["find('living room')"]


def test_the_task_is_done_in_the_simulated_home(paper_run: dict[str, Any]) -> None:
    assert paper_run["success"]
    assert paper_run["order"] == ["malz", "noodles"]
    assert paper_run["objects"] == {"malz": "person:Luis", "noodles": "person:Luis",
                                    "coke": "shelf_drinks", "bisquits": "shelf_food"}


def test_every_kb_change_is_persisted(tmp_path: Path) -> None:
    store_path = tmp_path / "butler.db"
    summary = run_butler(run_builder(), kb_store=store_path)
    assert summary["kb_persisted"]
    whys = [update["why"] for update in summary["kb_updates"]]
    assert "Luis agreed that the noodles belong on shelf_snacks" in whys
    assert "the coke is on shelf_snacks, not on shelf_drinks" in whys
    with KnowledgeStore.open(store_path) as store:
        kb = store.kb
        assert kb.values("drink", "to_serve")[0] == "malz"
        assert kb.values("noodles", "loc")[0] == "shelf_snacks"
        assert kb.value("coke", "misplaced") != "yes"
        assert kb.value("coke", "last_seen") == "shelf_drinks"
        assert kb.value("user", "found_in") == "living_room"
        assert len(store.history()) == len(summary["kb_updates"]) + 1
    assert KnowledgeBase.load("butler").value("user", "bad_day") != "yes"


def test_luis_prefers_coke_and_refuses_the_update() -> None:
    summary = run_butler(run_builder(), prefers="coke", refuse_update=True)
    said = [_words(line) for line in summary["speech"]]
    assert _words("Ok. I will bring you coke, your favorite drink.") in said
    assert _words("The coke is not in the shelf of drinks.") in said
    assert not any("healthier than" in line and "excellent" in line for line in said)
    assert sum("do you want me to change the preferred location" in line for line in said) == 2
    assert not any("i updated my kb" in line for line in said)
    assert not any("misplaced there by" in line for line in said)
    assert summary["success"] and summary["order"] == ["coke", "noodles"]
    whys = [update["why"] for update in summary["kb_updates"]]
    assert not any("agreed" in why for why in whys)
    assert "Luis likes coke better than malz" in whys


def test_with_nothing_misplaced_the_dialogue_skips_the_repairs() -> None:
    summary = run_butler(run_builder(), tidy=True)
    said = [_words(line) for line in summary["speech"]]
    assert not any("not in the shelf" in line or "not in its right place" in line
                   for line in said)
    assert not any("preferred location" in line for line in said)
    assert said[-3:] == [_words(PAPER_ROBOT_LINES[n]) for n in (39, 40, 41)]
    assert summary["success"] and summary["objects"]["coke"] == "shelf_drinks"


def test_runs_are_deterministic() -> None:
    first, second = run_butler(run_builder(), seed=3), run_butler(run_builder(), seed=3)
    assert first["transcript"] == second["transcript"]
    assert first["actions"] == second["actions"]


def test_the_scenario_command(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    assert main(["scenario", "butler", "--json", "--kb-store", str(tmp_path / "kb.db")]) == 0
    assert '"scenario": "butler"' in capsys.readouterr().out
    assert main(["scenario", "butler", "--kb-store", str(tmp_path / "kb.db")]) == 0
    assert "Hi, Luis, how was your day?" in capsys.readouterr().out


def test_the_next_day_the_robot_remembers(tmp_path: Path) -> None:
    store = tmp_path / "luis.db"
    run_butler(run_builder(), kb_store=store)
    second = run_butler(run_builder(), kb_store=store)
    said = [_words(line) for line in second["speech"]]
    assert not any("what do you like best" in line for line in said)  # preferences known
    assert said[:2] == [_words("Hi, Luis."), _words("Hi, Luis, how was your day?")]
    assert not any("not in the shelf of food" in line for line in said)  # noodles: snacks
    assert not any("preferred location" in line for line in said)
    assert _words(PAPER_ROBOT_LINES[32]) in said  # the child again
    whys = [update["why"] for update in second["kb_updates"]]
    assert whys[:3] == ["a new day"] * 3
    assert second["success"]


@pytest.mark.acceptance
def test_the_robot_lines_match_the_seed_paper(golem_paper: str,
                                              paper_run: dict[str, Any]) -> None:
    dialogue = golem_paper[golem_paper.index("1. **Golem** : *Hi, Luis.*"):
                           golem_paper.index("This scenario could be implemented")]
    lines = re.findall(r"(\d+)\.\s+\*\*(Golem|Luis)(?::\*\*|\*\*\s*:)\s*\*(.+?)\*\s*$",
                       dialogue, re.M)
    assert [int(number) for number, _, _ in lines] == list(range(1, 42))
    robot = [text for _, who, text in lines if who == "Golem"]
    assert len(robot) == len(paper_run["speech"])
    for said, paper in zip(paper_run["speech"], robot, strict=True):
        assert _same(said, paper), (said, paper)


def test_an_answer_not_understood_is_recovered_and_the_question_asked_again(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from homebot.scenarios.library import butler

    original = butler.LuisScript._answer
    mumbled: list[str] = []

    def mumbling(self: butler.LuisScript, question: str) -> str | None:
        if "noodles or biscuits" in question and not mumbled:
            mumbled.append(question)
            return "Hmm, let me think."
        return original(self, question)

    monkeypatch.setattr(butler.LuisScript, "_answer", mumbling)
    said = [_words(line) for line in run_butler(run_builder())["speech"]]
    asked = _words(PAPER_ROBOT_LINES[5])
    at = said.index(asked)
    assert said[at + 1: at + 3] == [_words("Sorry, I did not understand you."), asked]
    assert said[at + 3] == _words(PAPER_ROBOT_LINES[7])


def test_after_a_good_day_luis_is_looked_for_in_the_dining_room_first(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from homebot.scenarios.library import butler

    original = butler.LuisScript._answer

    def cheerful(self: butler.LuisScript, question: str) -> str | None:
        return "I had a great day!" if "how was your day" in question else original(
            self, question)

    monkeypatch.setattr(butler.LuisScript, "_answer", cheerful)
    summary = run_butler(run_builder())
    said = [_words(line) for line in summary["speech"]]
    assert _words("Glad to hear that; do you want me to do something for you?") in said
    assert summary["success"]  # not in the dining room the KB prefers now: on the couch
    searched = [a["situation"] for a in summary["actions"]
                if a["model"] == "deliver" and a["situation"].startswith("find")]
    assert searched == ["find('dining room')", "find('living room')"]
    assert not any("bad_day" in str(update["what"]) for update in summary["kb_updates"])


def test_a_person_can_answer_for_luis() -> None:
    answers = iter(["I like coke.", "Noodles.", "No.", "Fine, thanks.", "Bring me a drink.",
                    "Yes.", "No.", "No, leave them there."])
    summary = run_butler(run_builder(), typed=lambda person, question: next(answers, None))
    said = [_words(line) for line in summary["speech"]]
    assert _words("Glad to hear that; do you want me to do something for you?") in said
    assert summary["order"] == ["coke"] and summary["success"]
    assert _words("Some objects are not on their right shelves.") in said  # the noodles


@pytest.mark.parametrize("seed", range(6))
def test_under_disturbances_the_dialogue_always_comes_to_an_end(seed: int) -> None:
    summary = run_butler(run_builder(), seed=seed, level=1.0)
    assert summary["speech"][-1] == "Goodbye."
    assert summary["kb_persisted"]


def test_an_object_off_every_shelf_is_sought_elsewhere(monkeypatch: pytest.MonkeyPatch) -> None:
    from homebot.scenarios.library import butler
    from homebot.world import World

    def moved_malz(tidy: bool = False) -> World:
        data = World.load("butler_home").to_dict()
        for item in data["objects"]:
            if item["name"] == "malz":
                item["placement"] = "dining table"
        return World.from_dict(data, source="malz on the dining table")

    monkeypatch.setattr(butler, "butler_world", moved_malz)
    summary = run_butler(run_builder())
    said = [_words(line) for line in summary["speech"]]
    assert _words("Let me look for the malz again.") in said
    assert _words("Let me look for the malz elsewhere.") in said
    assert summary["success"]
    assert any("change the preferred location of malz to the dining table" in line
               for line in said)
