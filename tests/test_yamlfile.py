"""homebot.yamlfile: every YAML file is read one way, and its errors name file and line."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.errors import KnowledgeError, WorldError
from homebot.yamlfile import compose_yaml_text, field_error, load_yaml_document, parse_yaml_text


def test_a_syntax_error_names_file_line_and_column() -> None:
    with pytest.raises(WorldError, match=r"^home.yaml: line 3, column 12: YAML syntax error"):
        parse_yaml_text("rooms:\n  - name: a\n  - name: b: c\n", "home.yaml", WorldError)


def test_an_unknown_tag_names_its_line() -> None:
    with pytest.raises(WorldError, match=r"^home.yaml: line 2, column \d+: "):
        parse_yaml_text("name: a\nrobot: !!python/object:os.system {}\n", "home.yaml",
                        WorldError)


def test_a_key_written_twice_is_an_error_with_its_line() -> None:
    with pytest.raises(KnowledgeError, match=r"^kb.yaml: line 3: 'a' appears twice"):
        compose_yaml_text("a: 1\nb: 2\na: 3\n", "kb.yaml", KnowledgeError)


def test_a_field_is_found_by_its_path() -> None:
    document = parse_yaml_text("rooms:\n  - name: a\n  - name: b\n    polygon: []\n",
                               "home.yaml", WorldError)
    assert document.data["rooms"][1]["name"] == "b"
    assert document.line_of(["rooms", 1, "polygon"]) == 4
    # a field that is not there: the line of its nearest parent
    assert field_error(document, ["rooms", 0, "polygon"], "is missing") == (
        "home.yaml: line 2: rooms.0.polygon: is missing")


def test_an_empty_text_has_no_nodes() -> None:
    assert compose_yaml_text("", "empty.yaml", WorldError) is None
    assert parse_yaml_text("", "empty.yaml", WorldError).data is None


def test_a_missing_file_names_itself(tmp_path: Path) -> None:
    with pytest.raises(WorldError, match="no such file"):
        load_yaml_document(tmp_path / "nowhere.yaml", WorldError)


def test_an_integer_too_long_for_python_names_its_line() -> None:
    text = "name: a\nrooms:\n  - " + "9" * 5000 + "\n"
    with pytest.raises(WorldError, match=r"^home.yaml: line 3: a number too long to read "
                                         r"\(over \d+ digits\); write a smaller one$"):
        parse_yaml_text(text, "home.yaml", WorldError)
