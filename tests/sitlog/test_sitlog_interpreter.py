"""The interpreter's semantics: first match, repetition and recovery, scopes, pipe, stack."""

from __future__ import annotations

import textwrap

import pytest

from homebot.errors import DialogueError
from homebot.sitlog import (
    Arc,
    DialogueModel,
    Environment,
    Interpreter,
    Program,
    RecordingBody,
    ScriptedPerception,
    Situation,
    Term,
    UserFunction,
    format_term,
    load_program_text,
    parse_term,
)


def _program(text: str, functions: dict[str, UserFunction] | None = None) -> Program:
    return load_program_text(textwrap.dedent(text), "test.yaml", functions=functions)


def _run(program: Program, inputs: list[str], call: str | None = None) -> tuple:
    body = RecordingBody()
    result = Interpreter(program, ScriptedPerception(inputs), body=body).run(call)
    return result, body.said


CHOICE = """
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        arcs:
          - "colour(red) : say(first) => fs"
          - "colour(X) : say(X) => fs"
          - "X : say(any) => fs"
      - {id: fs, type: final}
"""


def test_the_first_matching_arc_wins_in_declaration_order() -> None:
    assert _run(_program(CHOICE), ["colour(red)"])[1] == ["first"]
    assert _run(_program(CHOICE), ["colour(blue)"])[1] == ["blue"]
    assert _run(_program(CHOICE), ["hello"])[1] == ["any"]


REPEAT = """
recovery: help
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        repeat: 2
        arcs:
          - "yes : say(good) => fs"
          - "gave_up : say('I give up') => fs"
      - {id: fs, type: final}
  - id: help
    situations:
      - id: is
        type: neutral
        arcs: ["empty : say('Please say yes or no') => gave_up"]
      - {id: gave_up, type: final}
"""


def test_an_unmet_situation_repeats_then_runs_the_recovery_model() -> None:
    result, said = _run(_program(REPEAT), ["maybe", "perhaps"])
    assert said == ["Please say yes or no", "I give up"]
    assert format_term(result.detail.final) == "fs"


def test_the_situation_is_met_again_before_the_recovery() -> None:
    _, said = _run(_program(REPEAT), ["maybe", "yes"])
    assert said == ["good"]


def test_without_recovery_a_run_stops_with_the_place() -> None:
    program = _program(REPEAT.replace("recovery: help\n", ""))
    with pytest.raises(DialogueError, match=r"test.yaml, line 5.*no expectation .* met 2 times"):
        _run(program, ["maybe", "perhaps"])


SCOPES = """
globals: {total: 0}
dialogue_models:
  - id: main
    locals: {mine: 5}
    situations:
      - id: is
        type: recursive
        embedded_dm: "add(3, Sum)"
        out_arg: Sum
        arcs: ["done(_) : say(get(total)) => fs"]
      - {id: fs, type: final}
  - id: add(N, Sum)
    situations:
      - id: is
        type: neutral
        arcs: ["empty : set(total, N + 4) => done(N)"]
      - {id: done(M), type: final, diag_mod: "add(_, M)"}
"""


def test_models_pass_results_by_reference_and_share_globals() -> None:
    result, said = _run(_program(SCOPES), [])
    assert said == ["7"]
    assert result.detail.out_arg == 3
    assert result.detail.globals == {"total": 7}


def test_locals_of_an_embedding_model_are_not_visible_in_the_embedded_one() -> None:
    text = SCOPES.replace("set(total, N + 4)", "set(mine, N)")
    with pytest.raises(DialogueError, match="no variable 'mine'"):
        _program(text)


PIPE = """
dialogue_models:
  - id: main
    situations:
      - id: is
        type: neutral
        in_arg: In
        out_arg: "apply(twice, [In])"
        arcs: ["empty : empty => middle"]
      - id: middle
        type: neutral
        arcs: ["empty : empty => fs"]
      - {id: fs, type: final}
"""


def test_the_pipe_runs_from_in_arg_to_out_arg_and_propagates_when_unset() -> None:
    def twice(env: Environment, value: Term) -> Term:
        return value * 2 if isinstance(value, int) else 1

    program = _program(PIPE, {"twice": twice})
    result = Interpreter(program, ScriptedPerception([])).run(pipe=21)
    assert result.detail.out_arg == 42


HISTORY = """
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        arcs:
          - "again : say(apply(count_heard, [])) => is"
          - "stop : empty => fs"
      - {id: fs, type: final}
"""


def test_user_functions_read_the_history_of_the_task() -> None:
    def count_heard(env: Environment) -> Term:
        return len([t for t in env.history if getattr(t, "expectation", None) == "again"])

    program = _program(HISTORY, {"count_heard": count_heard})
    assert _run(program, ["again", "again", "again", "stop"])[1] == ["0", "1", "2"]


def test_a_model_built_in_python_runs_like_a_loaded_one() -> None:
    hello = Situation(parse_term("is"), "speech", (Arc.from_text("hi(Name) : say(Name) => fs"),))
    model = DialogueModel("main", (hello, Situation("fs", "final")))
    program = Program.build([model])
    result, said = _run(program, ["hi(ada)"])
    assert said == ["ada"] and format_term(result.detail.final) == "fs"
    with pytest.raises(DialogueError, match="no final situation"):
        Program.build([DialogueModel("main", (hello,))])


def test_a_loop_without_end_is_stopped() -> None:
    program = _program("""
dialogue_models:
  - id: main
    situations:
      - id: is
        type: neutral
        arcs: ["empty : empty => is"]
      - {id: fs, type: final}
""")
    with pytest.raises(DialogueError, match="without an end"):
        Interpreter(program, ScriptedPerception([]), max_steps=50).run()


def test_running_out_of_input_is_an_error_not_a_hang() -> None:
    with pytest.raises(DialogueError, match="no more input"):
        _run(_program(CHOICE), [])


def test_a_situation_with_arguments_is_chosen_by_unification() -> None:
    program = _program("""
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        arcs: ["go(Where) : empty => at(Where)"]
      - id: at(kitchen)
        type: neutral
        arcs: ["empty : say(cooking) => fs"]
      - id: at(Place)
        type: neutral
        arcs: ["empty : say(Place) => fs"]
      - {id: fs, type: final}
""")
    assert _run(program, ["go(kitchen)"])[1] == ["cooking"]
    assert _run(program, ["go(garden)"])[1] == ["garden"]


def test_higher_order_functions_yield_functions_to_apply() -> None:
    def chooser(env: Environment, how: Term) -> Term:
        return parse_term("double(_)") if how == "twice" else parse_term("negate(_)")

    def double(env: Environment, value: Term) -> Term:
        return value * 2 if isinstance(value, int) else 0

    def negate(env: Environment, value: Term) -> Term:
        return -value if isinstance(value, int) else 0

    program = _program("""
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        arcs:
          - "how(H) : say(apply(apply(chooser, [H]), [21])) => fs"
      - {id: fs, type: final}
""", {"chooser": chooser, "double": double, "negate": negate})
    assert _run(program, ["how(twice)"])[1] == ["42"]
    assert _run(program, ["how(other)"])[1] == ["-21"]


def test_prog_runs_at_every_visit_of_a_situation_including_repeats() -> None:
    program = _program("""
globals: {visits: 0}
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        repeat: 5
        prog: "[inc(visits, V)]"
        arcs: ["yes : say(get(visits)) => fs"]
      - {id: fs, type: final}
""")
    result, said = _run(program, ["no", "maybe", "yes"])
    assert said == ["3"] and result.detail.globals["visits"] == 3


def test_speech_is_read_against_the_expectations() -> None:
    program = _program("""
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        arcs:
          - "yes : say(agreed) => fs"
          - "'no thanks' : say(declined) => fs"
          - "Other : say(Other) => fs"
      - {id: fs, type: final}
""")
    assert _run(program, ["Yes, Golem, please."])[1] == ["agreed"]
    assert _run(program, ["Oh no thanks, not now."])[1] == ["declined"]
    assert _run(program, ["Maybe later!"])[1] == ["maybe later"]


def test_an_arc_can_set_out_arg_through_its_shared_variable() -> None:
    program = _program("""
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        out_arg: Out
        arcs: ["said(X) : assign(Out, X) => fs"]
      - {id: fs, type: final}
""")
    assert _run(program, ["said(hello)"])[0].detail.out_arg == "hello"


def test_running_a_program_leaves_it_unchanged_for_the_next_run() -> None:
    program = _program("""
dialogue_models:
  - id: main(Heard)
    situations:
      - id: is
        type: speech
        arcs: ["X : assign(Heard, X) => fs"]
      - {id: fs, type: final}
""")
    _run(program, ["one"])
    second, _ = _run(program, ["two"])
    assert format_term(second.detail.transitions()[0].expectation) == "two"
    assert format_term(program.main_model.head) == "main(Heard)"


def test_arithmetic_errors_and_failing_user_functions_are_dialogue_errors() -> None:
    def boom(env: Environment, *args: Term) -> Term:
        raise ValueError("boom")

    text = """
    dialogue_models:
      - id: main
        situations:
          - {id: is, type: speech, arcs: ["X : %s => fs"]}
          - {id: fs, type: final}
    """
    with pytest.raises(DialogueError, match=r"line 5, column 9: cannot compute 1/0"):
        _run(_program(text % "assign(Y, 1/0)"), ["go"])
    with pytest.raises(DialogueError, match=r"user function boom failed: ValueError: boom"):
        _run(_program(text % "apply(boom, [X])", {"boom": boom}), ["go"])
    hearing = text.replace("type: speech,", "type: speech, interpreter: boom,") % "empty"
    with pytest.raises(DialogueError, match=r"line 5, column 9: the interpreter boom failed"):
        _run(_program(hearing, {"boom": boom}), ["go"])


def test_a_model_that_embeds_itself_without_end_is_stopped() -> None:
    text = """
    dialogue_models:
      - id: main
        situations:
          - {id: is, type: recursive, embedded_dm: main, arcs: ["fs : empty => fs"]}
          - {id: fs, type: final}
    """
    with pytest.raises(DialogueError, match=r"line 3, column 5: dialogue models embedded 50"):
        _run(_program(text), [])
