"""The narration of a run as it happens: the console's log and ``homebot demo`` read alike,
as ``homebot do`` reports, and each thing the robot says is told once."""

from __future__ import annotations

from homebot.executive.narration import Narrator


def test_each_event_reads_as_the_narration_do_prints() -> None:
    narrator = Narrator()
    assert narrator.line("skill.start", {"skill": "navigate", "args": {"to": "kitchen"}}) == \
        "▶ navigate(to=kitchen)"
    # a status event does not repeat the arguments: the narrator remembers them
    assert narrator.line("skill.status", {"skill": "navigate", "status": "verified",
                                          "error": None, "message": "I am in the kitchen"}) \
        == "verified navigate(to=kitchen) — I am in the kitchen"
    assert narrator.line("skill.status", {"skill": "navigate", "status": "failed",
                                          "error": "blocked", "message": ""}) \
        == "failed navigate(to=kitchen) (blocked)"
    assert narrator.line("speech", {"text": "I have found the cola"}) == \
        "robot: I have found the cola"
    assert narrator.line("task.end", {"success": False, "reason": "no cola"}) == \
        "task failed: no cola"
    unknown = narrator.line("door.opened", {"door": "kitchen_door", "by": "x" * 400})
    assert unknown is not None
    assert unknown.startswith("door.opened: door=kitchen_door, by=xxx") and len(unknown) <= 160


def test_words_logged_by_the_skill_and_by_the_speaker_are_told_once() -> None:
    narrator = Narrator()
    # say: the speaker's sound first, then the skill's speech act
    assert narrator.line("sim.speech", {"text": "Here is the cola."}) == \
        "robot: Here is the cola."
    assert narrator.line("speech", {"text": "Here is the cola."}) is None
    # ask: the speech act first, then the sound
    assert narrator.line("speech", {"text": "Which one?"}) == "robot: Which one?"
    assert narrator.line("sim.speech", {"text": "Which one?"}) is None
    # the same words said twice are two utterances; other words are never folded
    assert narrator.line("sim.speech", {"text": "Sorry?"}) == "robot: Sorry?"
    assert narrator.line("sim.speech", {"text": "Sorry?"}) == "robot: Sorry?"
    assert narrator.line("speech", {"text": "Thank you"}) == "robot: Thank you"
    assert narrator.line("sim.speech", {"text": "Bye"}) == "robot: Bye"


def test_the_demo_reads_the_same_lines_coloured() -> None:
    narrator = Narrator()
    narrator.markup("skill.start", {"skill": "pick", "args": {"object": "cola"}})
    marked = narrator.markup("skill.status", {"skill": "pick", "status": "verified",
                                              "message": "I have the [cola]"})
    assert marked is not None and marked.startswith("[green]verified")
    # what an event names is escaped: a bracket in it is text, not markup
    assert Narrator().line("speech", {"text": "[bold]hi"}) == "robot: [bold]hi"
    assert "I have the [cola]" in (Narrator().line("skill.status", {
        "skill": "pick", "status": "verified", "message": "I have the [cola]"}) or "")
