"""World YAML as people write it: mappings in block style, coordinates and short lists in flow."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml

from homebot.errors import WorldError

__all__ = ["world_yaml", "write_world_yaml"]


class _WorldDumper(yaml.SafeDumper):
    """A safe dumper that writes a list of scalars (a coordinate, a size, names) on one line."""


def _represent_list(dumper: yaml.SafeDumper, data: list[Any]) -> yaml.Node:
    flow = all(isinstance(item, (int, float, str, bool)) or item is None for item in data) or all(
        isinstance(item, list) and all(isinstance(value, (int, float)) for value in item)
        for item in data)
    return dumper.represent_sequence("tag:yaml.org,2002:seq", data, flow_style=flow and bool(data))


def _represent_tuple(dumper: yaml.SafeDumper, data: tuple[Any, ...]) -> yaml.Node:
    return _represent_list(dumper, list(data))


_WorldDumper.add_representer(list, _represent_list)
_WorldDumper.add_representer(tuple, _represent_tuple)


def world_yaml(data: Mapping[str, Any], header: str = "") -> str:
    """``data`` as readable YAML: ``position: [2.5, 4.0]``, a polygon on one line.

    ``header`` (lines of text) is written first as ``#`` comments.
    """
    comment = "".join(f"# {line}\n" if line else "#\n" for line in header.splitlines())
    body = yaml.dump(dict(data), Dumper=_WorldDumper, sort_keys=False, allow_unicode=True,
                     width=100)
    return comment + body


def write_world_yaml(path: Path, data: Mapping[str, Any], header: str = "") -> None:
    """Write ``world_yaml(data, header)`` to ``path``; a path that cannot be written is a
    ``WorldError`` naming it."""
    try:
        path.write_text(world_yaml(data, header), encoding="utf-8")
    except OSError as error:
        raise WorldError(f"{path}: cannot be written ({error})") from None
