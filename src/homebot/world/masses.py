"""Typical masses of household objects, each with its source (``data/robocup/masses.yaml``).

The shipped file gives each object a mass in kg and where the figure comes from:
Table 1 of the YCB object set paper (Calli et al. 2015) for YCB objects, a typical
retail pack with its stated content for the others. Names are compared as people
say them (case, underscores and a plural ``s`` aside); ``also`` lists other names
teams use for the same object ("coke" for "cola").
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from importlib import resources
from types import MappingProxyType
from typing import Any

from homebot.errors import WorldError
from homebot.yamlfile import LocatedDocument, field_error, parse_yaml_text

__all__ = ["KnownMass", "known_mass", "known_masses"]

_HEAVIEST = 30.0  # kg: the world model's bound on an object's weight


@dataclass(frozen=True, slots=True)
class KnownMass:
    """An object's typical mass and where the figure comes from."""

    name: str  #: the entry's name in the file
    mass: float  #: kg
    source: str


def known_mass(name: str) -> KnownMass | None:
    """The typical mass of the object called ``name``, or None when the file has none."""
    table = known_masses()
    key = _key(name)
    found = table.get(key)
    if found is None and key.endswith("s"):
        found = table.get(key[:-1])
    return found


@cache
def known_masses() -> Mapping[str, KnownMass]:
    """Every name the shipped file knows (entries and their ``also`` names) -> its mass.

    Raises ``WorldError`` naming the file, line and field of a malformed entry.
    """
    shipped = resources.files("homebot.data").joinpath("robocup", "masses.yaml")
    document = parse_yaml_text(shipped.read_text(encoding="utf-8"), "masses.yaml", WorldError)
    return MappingProxyType(_entries(document))


def _key(name: str) -> str:
    return " ".join(name.lower().replace("_", " ").replace("-", " ").split())


def _entries(document: LocatedDocument) -> dict[str, KnownMass]:
    if not isinstance(document.data, Mapping):
        raise WorldError(f"{document.source}: line 1: expected a mapping of object names "
                         "to {mass, source}")
    table: dict[str, KnownMass] = {}
    for name, entry in document.data.items():
        known = _entry(document, str(name), entry)
        also = entry.get("also", [])
        if not isinstance(also, list) or not all(isinstance(other, str) for other in also):
            raise WorldError(field_error(document, [str(name), "also"],
                                         "needs a list of names, e.g. [coke, soda]"))
        for key in (_key(str(name)), *(_key(other) for other in also)):
            if key in table:
                raise WorldError(field_error(document, [str(name)], f"'{key}' is also named "
                                             f"by '{table[key].name}'; keep one"))
            table[key] = known
    return table


def _entry(document: LocatedDocument, name: str, entry: Any) -> KnownMass:
    if not isinstance(entry, Mapping):
        raise WorldError(field_error(document, [name], "needs 'mass' (kg) and 'source'"))
    mass, source = entry.get("mass"), entry.get("source")
    if isinstance(mass, bool) or not isinstance(mass, int | float) or not math.isfinite(
            mass) or not 0 < mass <= _HEAVIEST:
        raise WorldError(field_error(document, [name, "mass"],
                                     f"needs a mass in kg, above 0 and at most {_HEAVIEST:g}"))
    if not isinstance(source, str) or not source.strip():
        raise WorldError(field_error(document, [name, "source"],
                                     "needs the figure's source; no mass without one"))
    return KnownMass(name, float(mass), source.strip())
