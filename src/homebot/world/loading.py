"""Validating world files: YAML documents to pydantic models, every error with file, line
and field (the YAML itself is read by ``homebot.yamlfile``)."""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

from pydantic import BaseModel, ValidationError

from homebot.errors import WorldError
from homebot.yamlfile import LocatedDocument, field_error, short_repr

__all__ = ["Origin", "locate", "validate_document"]

ModelT = TypeVar("ModelT", bound=BaseModel)

#: where a field of a generated world came from (``"maps/location_names.md: line 7"``), for
#: a world an importer wrote from other files; None where no input line says it
Origin = Callable[[Sequence[str | int]], str | None]


def locate(document: LocatedDocument, location: Sequence[str | int], message: str,
           origin: Origin | None = None) -> str:
    """``message`` about the field at ``location``, with file and line: the input file's
    line by ``origin`` when the world was generated from one, else the document's own."""
    if origin is None:
        return field_error(document, location, message)
    field = ".".join(str(step) for step in location) or "(document)"
    return f"{origin(location) or document.source}: {field}: {message}"


def validate_document(document: LocatedDocument, model: type[ModelT],
                      origin: Origin | None = None) -> ModelT:
    """Validate a document against a pydantic model, translating every error (located by
    ``origin`` for a generated world)."""
    if not isinstance(document.data, dict):
        raise WorldError(
            f"{document.source}: line 1: the file must be a YAML mapping of fields "
            f"({', '.join(model.model_fields)})"
        )
    try:
        return model.model_validate(document.data)
    except ValidationError as error:
        messages = [_describe(document, model, detail, origin)
                    for detail in error.errors()[:5]]
        more = len(error.errors()) - len(messages)
        if more > 0:
            messages.append(f"... and {more} more")
        raise WorldError("\n".join(messages)) from None


def _describe(document: LocatedDocument, model: type[BaseModel], detail: Any,
              origin: Origin | None) -> str:
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
    return locate(document, location, message, origin)


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
