"""Reading YAML files people write: safely, with the line of every node for error messages.

Every YAML file homebot reads (worlds, task files, maps, maintenance, dialogue models,
knowledge bases, imported pyrobosim and RoboCup files, robot profiles) goes through
here, so a syntax error always names the file, the line and the column, a key written
twice is an error (YAML would silently keep the last), and ``field_error`` names file,
line and field for the checks that follow; a file is read within its size limit
(``homebot.files``). This module imports nothing of homebot but its errors and that
reader, so every layer may use it.
"""

from __future__ import annotations

import reprlib
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import yaml

from homebot.errors import HomebotError
from homebot.files import read_text_file

__all__ = [
    "LocatedDocument",
    "compose_yaml_text",
    "field_error",
    "load_yaml_document",
    "parse_yaml_text",
    "read_yaml_text",
    "short_repr",
]

_LIBYAML: Any = getattr(yaml, "CSafeLoader", None)

# Values quoted in messages are cut short: a file may nest aliases into millions of items.
_SHORT = reprlib.Repr()
_SHORT.maxlevel, _SHORT.maxlist, _SHORT.maxdict, _SHORT.maxstring = 2, 4, 4, 60


def short_repr(value: Any) -> str:
    """``repr(value)``, cut short enough to quote in a one-line message."""
    return _SHORT.repr(value)


class LocatedDocument:
    """A YAML document together with the line of every node, for error messages."""

    def __init__(self, data: Any, root: yaml.Node | None, source: str) -> None:
        self.data = data
        self.root = root
        self.source = source

    def line_of(self, location: Sequence[str | int]) -> int | None:
        """The 1-based line of the node at ``location`` (keys and list indices), if known.

        When the location does not exist (a missing field) the line of its closest
        existing parent is returned.
        """
        node = self.root
        line = node.start_mark.line + 1 if node is not None else None
        for step in location:
            child = _child_node(node, step)
            if child is None:
                break
            if isinstance(child, tuple):
                line = _key_line(child)
                node = child[1]
            else:
                line = child.start_mark.line + 1
                node = child
        return line


def _key_line(pair: tuple[yaml.Node, yaml.Node]) -> int:
    line: int = pair[0].start_mark.line
    return line + 1


def _child_node(
    node: yaml.Node | None, step: str | int
) -> yaml.Node | tuple[yaml.Node, yaml.Node] | None:
    if isinstance(node, yaml.MappingNode) and isinstance(step, str):
        for key, value in node.value:
            if isinstance(key, yaml.ScalarNode) and key.value == step:
                return (key, value)
    if isinstance(node, yaml.SequenceNode) and isinstance(step, int) and 0 <= step < len(
        node.value
    ):
        child: yaml.Node = node.value[step]
        return child
    return None


def read_yaml_text(path: Path | str, error_type: type[HomebotError]) -> str:
    """The text of a YAML file; a missing, unreadable or oversized file (past
    ``SIZE_LIMITS["yaml"]``) raises ``error_type``."""
    return read_text_file(path, error_type, "yaml", "YAML file")


def load_yaml_document(path: Path | str, error_type: type[HomebotError]) -> LocatedDocument:
    """Read a YAML file safely, keeping node positions. Raises ``error_type``."""
    return parse_yaml_text(read_yaml_text(path, error_type), str(path), error_type)


def parse_yaml_text(text: str, source: str, error_type: type[HomebotError]) -> LocatedDocument:
    """Parse YAML text named ``source`` into data and nodes; a syntax error names its line
    and column, a key written twice its line."""
    root = compose_yaml_text(text, source, error_type)
    try:
        # Built from the nodes already composed: the text is parsed once.
        data = None if root is None else yaml.SafeLoader("").construct_document(root)
    except yaml.YAMLError as error:  # composed, so only a value's constructor can fail
        raise _syntax_error(error, source, error_type, "fix the indentation or quoting"
                            ) from None
    except RecursionError:
        raise error_type(f"{source}: YAML nested too deeply; flatten the lists and mappings"
                         ) from None
    except ValueError:  # Python refuses to read an integer of over 4300 digits
        raise error_type(f"{source}: {_too_long_number_place(root)}: a number too long "
                         f"to read (over {sys.get_int_max_str_digits()} digits); write a "
                         "smaller one") from None
    return LocatedDocument(data, root, source)


def _too_long_number_place(root: yaml.Node | None) -> str:
    """``line N`` of the first integer too long for Python to read, for the message."""
    for node in _nodes(root):
        if isinstance(node, yaml.ScalarNode) and node.tag == "tag:yaml.org,2002:int" and \
                len(node.value) > sys.get_int_max_str_digits():
            return f"line {node.start_mark.line + 1}"
    return "unknown line"


def _nodes(root: yaml.Node | None) -> Iterator[yaml.Node]:
    """Every node of a tree once (aliases share nodes), in document order, without
    recursion (a deep tree)."""
    stack, seen = [root], set()
    while stack:
        node = stack.pop()
        if node is None or id(node) in seen:
            continue
        seen.add(id(node))
        yield node
        if isinstance(node, yaml.MappingNode):
            stack.extend(item for pair in reversed(node.value) for item in reversed(pair))
        elif isinstance(node, yaml.SequenceNode):
            stack.extend(reversed(node.value))


def compose_yaml_text(text: str, source: str, error_type: type[HomebotError],
                      hint: str = "fix the indentation or quoting") -> yaml.Node | None:
    """The node tree of YAML text (None when empty), for readers that walk nodes.

    A syntax error raises ``error_type`` naming line and column, with ``hint`` on how to
    fix it; so does a key written twice in one mapping."""
    try:
        root = _compose(text)
    except yaml.YAMLError as error:
        raise _syntax_error(error, source, error_type, hint) from None
    except RecursionError:
        raise error_type(f"{source}: YAML nested too deeply; flatten the lists and mappings"
                         ) from None
    _check_unique_keys(root, source, error_type)
    return root


def _compose(text: str) -> yaml.Node | None:
    """The node tree, composed by libyaml when PyYAML has it (some ten times faster: a
    2 MB world took over 30 s in PyYAML's own parser). A text libyaml refuses is composed
    again by PyYAML's parser, whose messages and places the errors keep."""
    if _LIBYAML is not None:
        try:
            root: yaml.Node | None = yaml.compose(text, Loader=_LIBYAML)
        except yaml.YAMLError:
            pass
        else:
            _plain_style_as_pyyaml(root)
            return root
    return yaml.compose(text, Loader=yaml.SafeLoader)


def _plain_style_as_pyyaml(root: yaml.Node | None) -> None:
    """libyaml marks a plain scalar with style ``''``, PyYAML with ``None``: readers test
    ``node.style is None``, so the nodes get PyYAML's."""
    for node in _nodes(root):
        if isinstance(node, yaml.ScalarNode) and node.style == "":
            node.style = None


def _syntax_error(error: yaml.YAMLError, source: str, error_type: type[HomebotError],
                  hint: str) -> HomebotError:
    """``error_type`` for a YAML error, naming line and column where PyYAML knows them."""
    mark = getattr(error, "problem_mark", None)
    where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "unknown line"
    problem = getattr(error, "problem", None) or str(error).splitlines()[0]
    return error_type(f"{source}: {where}: YAML syntax error: {problem}; {hint}")


def _check_unique_keys(root: yaml.Node | None, source: str,
                       error_type: type[HomebotError]) -> None:
    """A key written twice in one mapping is an error: YAML would keep only the last."""
    for node in _nodes(root):
        if isinstance(node, yaml.MappingNode):
            keys: set[str] = set()
            for key, _ in node.value:
                if isinstance(key, yaml.ScalarNode) and key.value != "<<":
                    if key.value in keys:
                        raise error_type(f"{source}: line {key.start_mark.line + 1}: "
                                         f"'{key.value}' appears twice in one mapping; "
                                         "keep one (YAML would drop the first)")
                    keys.add(key.value)


def field_error(document: LocatedDocument, location: Sequence[str | int], message: str) -> str:
    """Format ``message`` about the field at ``location`` with file and line."""
    line = document.line_of(location)
    where = f"line {line}" if line is not None else "unknown line"
    field = ".".join(str(step) for step in location) or "(document)"
    return f"{document.source}: {where}: {field}: {message}"
