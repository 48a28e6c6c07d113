"""Malformed dialogue models are rejected on load, with the place of the error."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from homebot.errors import DialogueError, HomebotError
from homebot.sitlog import load_program, load_program_text

GOOD = """
globals: {count: 0}
dialogue_models:
  - id: main
    situations:
      - id: is
        type: speech
        arcs:
          - "hello : say('Hi') => fs"
          - "again : inc(count) => is"
      - {id: fs, type: final}
"""


def _load(text: str) -> None:
    load_program_text(textwrap.dedent(text), "test.yaml")


def _error(text: str) -> str:
    with pytest.raises(DialogueError) as caught:
        _load(text)
    return str(caught.value)


def test_the_good_program_loads() -> None:
    _load(GOOD)


def test_unknown_next_situation_names_line_and_column() -> None:
    message = _error(GOOD.replace("=> fs\"", "=> fz\""))
    assert "test.yaml, line 9, column 13" in message
    assert "unknown next situation 'fz'" in message
    assert "situations: fs, is" in message


def test_missing_final_situation() -> None:
    message = _error(GOOD.replace("      - {id: fs, type: final}\n", "").replace("=> fs", "=> is"))
    assert "test.yaml, line 4" in message
    assert "has no final situation" in message


def test_bad_expression_syntax_names_the_column() -> None:
    message = _error(GOOD.replace("say('Hi')", "say('Hi'"))
    assert "test.yaml, line 9, column" in message
    assert "expected" in message


def test_a_situation_defined_twice_is_rejected() -> None:
    message = _error(GOOD.replace("      - {id: fs, type: final}\n",
                                  "      - {id: fs, type: final}\n      - {id: fs, type: final}\n"))
    assert "test.yaml, line 12, column 9" in message
    assert "situation fs is defined twice" in message


def test_unknown_variable_in_an_expression() -> None:
    message = _error(GOOD.replace("inc(count)", "inc(cuont)"))
    assert "line 10" in message and "no variable 'cuont'" in message
    assert "did you mean 'count'" in message


def test_unknown_function_in_apply() -> None:
    message = _error(GOOD.replace("say('Hi')", "say(apply(greeting, []))"))
    assert "line 9" in message and "unknown function 'greeting'" in message


def test_wrong_arity_of_an_operator() -> None:
    message = _error(GOOD.replace("inc(count)", "set(count)"))
    assert "set takes 2 arguments" in message


def test_unknown_situation_type() -> None:
    message = _error(GOOD.replace("type: speech", "type: speach"))
    assert "line 6" in message and "did you mean 'speech'" in message


def test_unknown_embedded_model_and_bad_final_names() -> None:
    recursive = GOOD.replace("""        type: speech
        arcs:
          - "hello : say('Hi') => fs"
          - "again : inc(count) => is"
""", """        type: recursive
        embedded_dm: helper
        arcs:
          - "done : empty => fs"
""")
    assert "embedded_dm 'helper' is no dialogue model" in _error(recursive)
    helper = recursive + """
  - id: helper
    situations:
      - {id: finished, type: final}
"""
    assert "'done' is not a final situation of helper" in _error(helper)


def test_arcs_on_a_final_situation() -> None:
    message = _error(GOOD.replace("{id: fs, type: final}",
                                  "{id: fs, type: final, arcs: ['a : b => is']}"))
    assert "final situation fs has arcs" in message


def test_unknown_keys_are_named_with_a_suggestion() -> None:
    message = _error(GOOD.replace("type: speech", "type: speech\n        arc: []"))
    assert "unknown key 'arc'" in message and "did you mean 'arcs'" in message


def test_an_unquoted_arc_is_explained() -> None:
    message = _error(GOOD.replace('"hello : say(\'Hi\') => fs"', "hello: fs"))
    assert "Expectation : Action => Next" in message


def test_a_number_too_long_to_read_names_its_place() -> None:
    message = _error(GOOD.replace("{count: 0}", "{count: " + "9" * 5000 + "}"))
    assert message == "test.yaml, line 2, column 18: a number too long to read; write a smaller one"


def test_invalid_yaml_names_the_line() -> None:
    assert "line" in _error("dialogue_models: [\n  - id: x\n")


def test_missing_files_and_functions(tmp_path: Path) -> None:
    with pytest.raises(DialogueError, match="no dialogue file"):
        load_program(tmp_path / "nothing.yaml")
    message = _error(GOOD + "functions: [no_such_module_here]\n")
    assert "test.yaml, line 12" in message
    assert "functions 'no_such_module_here' is neither a .py file in the model's folder" in message
    message = _error(GOOD + "functions: [homebot.sitlog.functions.no_such_module]\n")
    assert "cannot import functions 'homebot.sitlog.functions.no_such_module'" in message


def test_dialogue_errors_are_homebot_errors() -> None:
    assert issubclass(DialogueError, HomebotError)


@pytest.mark.parametrize("name", ["appendix_a", "behaviours", "butler"])
def test_every_shipped_program_loads(name: str) -> None:
    assert load_program(name).models
