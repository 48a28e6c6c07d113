"""The paper's Appendix A program reproduces Listing A6: history, Out Arg and globals."""

from __future__ import annotations

import re

import pytest
from sitlog_listings import INPUTS, LISTING_A6

from homebot.sitlog import (
    Interpreter,
    RecordingBody,
    ScriptedPerception,
    format_term,
    load_program,
    render_globals,
    render_history,
)


def _session() -> tuple[str, list[str]]:
    body = RecordingBody()
    result = Interpreter(load_program("appendix_a"), ScriptedPerception(INPUTS), body=body).run()
    trace = result.detail
    text = (render_history(trace.history) + f"\n\nOut Arg: {format_term(trace.out_arg)}\n"
            f"Out Global Vars: {render_globals(trace.globals)}\n")
    return text, body.said


def _squeezed(text: str) -> str:
    return re.sub(r"\s+", "", text)


def test_the_session_reproduces_listing_a6_exactly() -> None:
    text, _ = _session()
    assert _squeezed(text) == _squeezed(LISTING_A6)


def test_out_arg_and_global_variables() -> None:
    text, _ = _session()
    assert "Out Arg: monday" in text
    assert text.rstrip().endswith("Out Global Vars: [g_count_fs1==>1,g_count_fs2==>1]")


def test_screen_actions_are_spoken_in_order() -> None:
    _, said = _session()
    assert said == ["Cont. recursive sit", "Back to initial sit", "Good Bye"]


def test_the_embedded_model_sees_the_pipe_and_leaves_it_unchanged() -> None:
    result = Interpreter(load_program("appendix_a"), ScriptedPerception(INPUTS)).run()
    waits = [t for t in result.detail.transitions() if t.model == "wait" and t.situation == "is"]
    assert [format_term(t.expectation) for t in waits] == ["loop", "tuesday"]


def test_the_history_is_nested_for_embedded_models() -> None:
    result = Interpreter(load_program("appendix_a"), ScriptedPerception(INPUTS)).run()
    nested = [item for item in result.detail.history if isinstance(item, list)]
    assert len(nested) == 2
    assert all(t.model == "wait" for part in nested for t in part)


@pytest.mark.acceptance
def test_the_paper_listing_matches_up_to_its_typesetting(golem_paper: str) -> None:
    start = golem_paper.index("Listing A6: History of a session.")
    block = golem_paper[start:].split("```")[1]
    text, _ = _session()

    def bare(value: str) -> str:
        return re.sub(r"[\s()]", "", value)

    assert bare(text) == bare(block)
