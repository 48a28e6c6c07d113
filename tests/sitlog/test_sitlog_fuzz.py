"""Whatever a dialogue file holds, loading it succeeds or raises ``DialogueError``."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.cli.scenario import run_builder
from homebot.errors import DialogueError
from homebot.sitlog import load_program_text, shipped_dialogue_path

_TEXT = shipped_dialogue_path("appendix_a").read_text(encoding="utf-8")
_NOISE = st.text(alphabet=st.sampled_from(list("[](){}:,'\"=>-_ \nabcXYZ019|#&*!%")),
                 max_size=12)


@settings(max_examples=300, deadline=None)
@given(st.integers(0, len(_TEXT)), st.integers(0, 40), _NOISE)
def test_a_damaged_file_is_rejected_with_a_dialogue_error(start: int, cut: int,
                                                          noise: str) -> None:
    damaged = _TEXT[:start] + noise + _TEXT[start + cut:]
    try:
        load_program_text(damaged, "damaged.yaml")
    except DialogueError as error:
        assert "damaged.yaml" in str(error) or "no dialogue file" in str(error)


_INPUT = st.sampled_from(["finish", "loop", "tuesday", "monday", "[day(monday)]",
                          "[day(tuesday)]", "[day(X)]", "[monday,ok]", "[tuesday,'not ok']",
                          "_", "[]", "42", "day(", "'quoted atom'", "[day(1)]", "hello there"])


@settings(max_examples=200, deadline=None)
@given(st.lists(_INPUT, max_size=12))
def test_any_inputs_end_the_run_or_stop_it_with_a_dialogue_error(inputs: list[str]) -> None:
    from homebot.sitlog import Interpreter, ScriptedPerception, load_program

    try:
        result = Interpreter(load_program("appendix_a"), ScriptedPerception(inputs),
                             max_steps=200).run()
    except DialogueError:
        return
    assert result.detail.final == "fs"


_ANSWERS = ["Yes.", "No.", "I like coke.", "Noodles.", "I had a bad day!", "Great day.",
            "Bring me something to drink and biscuits.", "Bring me noodles and coke.", "hmm", "",
            "Yes please, bring the biscuits", "coke and malz and noodles and biscuits"]


@settings(max_examples=12, deadline=None)
@given(st.randoms(use_true_random=False))
def test_whatever_luis_says_the_butler_ends_or_says_why_it_cannot_go_on(rng: object) -> None:
    from homebot.scenarios.library.butler import run_butler

    choose = rng.choice  # type: ignore[attr-defined]
    try:
        summary = run_butler(run_builder(),
                             typed=lambda person, question: choose(_ANSWERS) or None)
    except DialogueError as error:
        assert "cannot go on" in str(error)
        return
    assert summary["speech"][-1] == "Goodbye."
