"""Dialogue models in SitLog's own notation: the paper's listings run as printed."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from sitlog_listings import INPUTS, LISTING_A6

from homebot.errors import DialogueError
from homebot.sitlog import (
    Interpreter,
    ScriptedPerception,
    format_term,
    load_program,
    render_globals,
    render_history,
)

DM = """
% a comment
Global_Vars = [greeted ==> no].
diag_mod(hello(Name),
  [ [id ==> is, type ==> speech,
     arcs ==> [ hi : [say(Name), set(greeted, yes)] => fs,
                X : say(X) => is ]],
    [id ==> fs, type ==> final] ],
  [ ]).
"""


def test_a_dm_file_loads_and_runs(tmp_path: Path) -> None:
    path = tmp_path / "hello.dm"
    path.write_text(DM)
    program = load_program(path)
    result = Interpreter(program, ScriptedPerception(["what", "hi"])).run("hello(ada)")
    assert result.detail.globals == {"greeted": "yes"}
    assert [format_term(t.action) for t in result.detail.transitions()][:2] == ["say(what)",
                                                                         "[say(ada),yes]"]


@pytest.mark.parametrize("damage, place, message", [
    ("=> fs,", "line 6, column 17", "unknown next situation 'fz'"),
    ("type ==> final]", "line 8, column 5", "unknown situation attribute 'typo'"),
    ("[ ]).", "line 9, column 8", "expected '.' at the end of the clause"),
])
def test_errors_name_line_and_column(tmp_path: Path, damage: str, place: str,
                                     message: str) -> None:
    broken = {"=> fs,": DM.replace("] => fs,", "] => fz,"),
              "type ==> final]": DM.replace("type ==> final]", "typo ==> final]"),
              "[ ]).": DM.replace("[ ]).", "[ ]) x.")}[damage]
    path = tmp_path / "broken.dm"
    path.write_text(broken)
    with pytest.raises(DialogueError) as caught:
        load_program(path)
    assert place in str(caught.value) and message in str(caught.value)


def test_the_shipped_appendix_a_in_sitlog_notation_gives_listing_a6() -> None:
    result = Interpreter(load_program("appendix_a.dm"), ScriptedPerception(INPUTS)).run()
    trace = result.detail
    text = (render_history(trace.history) + f"\n\nOut Arg: {format_term(trace.out_arg)}\n"
            f"Out Global Vars: {render_globals(trace.globals)}\n")
    assert re.sub(r"\s+", "", text) == re.sub(r"\s+", "", LISTING_A6)


@pytest.mark.acceptance
def test_the_papers_listings_verbatim_are_checked_and_then_run(golem_paper: str,
                                                               tmp_path: Path) -> None:
    blocks = [golem_paper[golem_paper.index(name):].split("```")[1]
              for name in ("Listing A2:", "Listing A3:", "Listing A4:")]
    text = "functions(['homebot.sitlog.functions.appendix_a']).\n" + "".join(blocks)
    printed = tmp_path / "appendix_a.dm"
    printed.write_text(text)
    with pytest.raises(DialogueError, match=r"line \d+, column 1: embedded_dm 'sample_wait'"):
        load_program(printed)  # Listing A3 embeds sample_wait; Listing A4 defines wait
    printed.write_text(text.replace("sample_wait", "wait"))
    result = Interpreter(load_program(printed), ScriptedPerception(INPUTS)).run()
    assert format_term(result.detail.out_arg) == "monday"
    assert render_globals(result.detail.globals) == "[g_count_fs1==>1,g_count_fs2==>1]"
