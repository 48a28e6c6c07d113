"""Reading world files: YAML to validated models, every error with file, line and field."""

from __future__ import annotations

import difflib
import re
import reprlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any, TypeVar

import yaml
from pydantic import BaseModel, ValidationError

from homebot.errors import HomebotError, WorldError

__all__ = [
    "LocatedDocument",
    "field_error",
    "load_yaml_document",
    "parse_yaml_text",
    "short_repr",
    "validate_document",
]

ModelT = TypeVar("ModelT", bound=BaseModel)

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


def load_yaml_document(path: Path | str,
                       error_type: type[HomebotError] = WorldError) -> LocatedDocument:
    """Read a YAML file safely, keeping node positions. Raises ``error_type``."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise error_type(f"{path}: no such file; check the path") from None
    except (OSError, UnicodeDecodeError) as error:
        raise error_type(f"{path}: cannot be read ({error}); give a UTF-8 text file") from None
    return parse_yaml_text(text, str(path), error_type)


def parse_yaml_text(text: str, source: str,
                    error_type: type[HomebotError] = WorldError) -> LocatedDocument:
    """Parse YAML text named ``source``; a syntax error names its line and column."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
        data = yaml.safe_load(text)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "unknown line"
        raise error_type(
            f"{source}: {where}: YAML syntax error: {error.problem}; fix the indentation or quoting"
        ) from None
    except yaml.YAMLError as error:
        raise error_type(f"{source}: YAML syntax error: {error}") from None
    except RecursionError:
        raise error_type(f"{source}: YAML nested too deeply; flatten the lists and mappings"
                         ) from None
    _check_unique_keys(root, source, error_type)
    return LocatedDocument(data, root, source)


def _check_unique_keys(root: yaml.Node | None, source: str,
                       error_type: type[HomebotError]) -> None:
    """A key written twice in one mapping is an error: YAML would keep only the last."""
    stack, seen = [root], set()
    while stack:
        node = stack.pop()
        if node is None or id(node) in seen:
            continue
        seen.add(id(node))
        if isinstance(node, yaml.MappingNode):
            keys: set[str] = set()
            for key, value in node.value:
                if isinstance(key, yaml.ScalarNode) and key.value != "<<":
                    if key.value in keys:
                        raise error_type(f"{source}: line {key.start_mark.line + 1}: "
                                         f"'{key.value}' appears twice in one mapping; "
                                         "keep one (YAML would drop the first)")
                    keys.add(key.value)
                stack.extend((key, value))
        elif isinstance(node, yaml.SequenceNode):
            stack.extend(node.value)


def field_error(document: LocatedDocument, location: Sequence[str | int], message: str) -> str:
    """Format ``message`` about the field at ``location`` with file and line."""
    line = document.line_of(location)
    where = f"line {line}" if line is not None else "unknown line"
    field = ".".join(str(step) for step in location) or "(document)"
    return f"{document.source}: {where}: {field}: {message}"


def validate_document(document: LocatedDocument, model: type[ModelT]) -> ModelT:
    """Validate a document against a pydantic model, translating every error."""
    if not isinstance(document.data, dict):
        raise WorldError(
            f"{document.source}: line 1: the file must be a YAML mapping of fields "
            f"({', '.join(model.model_fields)})"
        )
    try:
        return model.model_validate(document.data)
    except ValidationError as error:
        messages = [_describe(document, model, detail) for detail in error.errors()[:5]]
        more = len(error.errors()) - len(messages)
        if more > 0:
            messages.append(f"... and {more} more")
        raise WorldError("\n".join(messages)) from None


def _describe(document: LocatedDocument, model: type[BaseModel], detail: Any) -> str:
    location = [step for step in detail["loc"] if not _is_union_tag(step)]
    kind = detail["type"]
    if kind == "extra_forbidden":
        known = _fields_at(model, location[:-1])
        guess = difflib.get_close_matches(str(location[-1]), known, n=1)
        hint = f"did you mean '{guess[0]}'?" if guess else f"known fields: {', '.join(known)}"
        message = f"unknown field; {hint}"
    elif kind == "missing":
        message = "required field is missing; add it"
    else:
        text = str(detail["msg"]).replace("Input should be", "must be", 1).replace(
            "Value error, ", "", 1)
        message = f"{text} (got {short_repr(detail.get('input'))})"
        meaning = _description_at(model, location)
        if meaning:
            message += f"; {location[-1]} is {meaning}"
    return field_error(document, location, message)


def _description_at(model: type[BaseModel], location: Sequence[str | int]) -> str | None:
    """The ``description`` of the field at ``location`` under ``model``, if it has one."""
    current: Any = model
    description = None
    for step in location:
        if isinstance(step, int):
            continue
        field = current.model_fields.get(step) if hasattr(current, "model_fields") else None
        if field is None:
            return None
        description = field.description
        current = _inner_model(field.annotation)
    return description


def _is_union_tag(step: Any) -> bool:
    """Pydantic's own steps (``tuple[float, float]``, ``function-after[...]``), not a key."""
    return isinstance(step, str) and (re.fullmatch(r"[A-Za-z_-]+\[.*\]", step) is not None
                                      or step in {"function-after", "tagged-union"})


def _fields_at(model: type[BaseModel], location: Sequence[str | int]) -> list[str]:
    """The field names of the sub-model found at ``location`` under ``model``."""
    current: Any = model
    for step in location:
        if isinstance(step, int):
            continue
        field = current.model_fields.get(step) if hasattr(current, "model_fields") else None
        if field is None:
            return []
        current = _inner_model(field.annotation)
    return list(current.model_fields) if hasattr(current, "model_fields") else []


def _inner_model(annotation: Any) -> Any:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for argument in getattr(annotation, "__args__", ()):
        inner = _inner_model(argument)
        if inner is not None:
            return inner
    return None
