"""pyrobosim's location metadata: each furniture category's footprint, height and spawns.

A pyrobosim world names its metadata files under ``metadata: locations:`` with the
tokens ``$PWD`` (the world file's folder), ``$DATA`` (pyrobosim's data folder, where its
own worlds sit beside their metadata) and ``$HOME``. A file that is not there is
replaced by ``EXAMPLE_CATEGORIES``, the categories of pyrobosim's
``example_location_data.yaml``, with a warning.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from shapely.geometry import Polygon, box

from homebot.errors import WorldError
from homebot.world.pyrobosim_geometry import PoseFormatError, simple_footprint
from homebot.yamlfile import field_error, load_yaml_document

__all__ = ["EXAMPLE_CATEGORIES", "LocationCategory", "metadata_paths",
           "read_location_metadata"]


@dataclass(frozen=True)
class LocationCategory:
    """A furniture category: its footprint in its own frame, height and object spawns."""

    footprint: Polygon
    height: float | None = None
    #: the names of its object spawns ("left" makes "counter0_left")
    spawns: tuple[str, ...] = ()
    #: why the footprint is a stand-in (a mesh pyrobosim reads and homebot does not)
    approximated: str | None = None


def _box(width: float, depth: float) -> Polygon:
    return box(-width / 2, -depth / 2, width / 2, depth / 2)


#: pyrobosim's example categories (``pyrobosim/data/example_location_data*.yaml``); the
#: trash can's mesh is stood in for by a 0.4 m square
EXAMPLE_CATEGORIES: Mapping[str, LocationCategory] = {
    "table": LocationCategory(_box(0.9, 1.2), 0.5, ("tabletop",)),
    "desk": LocationCategory(_box(0.6, 0.6), 0.3, ("desktop",)),
    "counter": LocationCategory(_box(1.2, 0.6), 0.75, ("left", "right")),
    "trash_can": LocationCategory(_box(0.4, 0.4), None, ("top",),
                                  "its mesh footprint is taken as a 0.4 m square"),
    "charger": LocationCategory(_box(0.6, 0.3), 0.1, ("dock",)),
}

Warn = Callable[[str], None]


def metadata_paths(entry: Any, world_file: Path) -> list[tuple[str, Path]]:
    """The files a ``metadata: locations:`` entry names (one or a list), tokens replaced;
    ``$DATA`` is looked for beside the world file, where pyrobosim's own worlds keep it."""
    texts = entry if isinstance(entry, list) else [entry]
    folder = world_file.resolve().parent
    paths: list[tuple[str, Path]] = []
    for text in texts:
        written = str(text)
        replaced = (written.replace("$HOME", str(Path.home())).replace("$PWD", str(folder))
                    .replace("$DATA", str(folder)))
        path = Path(replaced)
        paths.append((written, path if path.is_absolute() else folder / path))
    return paths


def read_location_metadata(entry: Any, world_file: Path,
                           warn: Warn) -> dict[str, LocationCategory]:
    """The categories of every location metadata file ``entry`` names.

    A file that is missing is replaced by ``EXAMPLE_CATEGORIES`` (``warn`` says so); a
    file that is there but malformed raises ``WorldError`` naming its line.
    """
    categories: dict[str, LocationCategory] = {}
    missing: list[str] = []
    for written, path in metadata_paths(entry, world_file) if entry is not None else []:
        if not path.is_file():
            missing.append(written)
            continue
        categories.update(_read_file(path))
    if missing or entry is None:
        for name, category in EXAMPLE_CATEGORIES.items():
            categories.setdefault(name, category)
        what = (f"{', '.join(missing)} is not beside the world file" if missing
                else "no location metadata is named")
        warn(f"{what}; furniture sizes come from pyrobosim's example categories (table, "
             "desk, counter, trash_can, charger); put the metadata files beside the world "
             "to use yours")
    return categories


def _read_file(path: Path) -> dict[str, LocationCategory]:
    document = load_yaml_document(path, WorldError)
    if not isinstance(document.data, Mapping):
        raise WorldError(f"{path}: line 1: location metadata is a mapping of categories "
                         "(pyrobosim docs: yaml/location_schema.rst)")
    categories: dict[str, LocationCategory] = {}
    for name, entry in document.data.items():
        footprint = entry.get("footprint") if isinstance(entry, Mapping) else None
        kind = footprint.get("type") if isinstance(footprint, Mapping) else None
        spawns = tuple(str(spawn.get("name")) for spawn in entry.get("locations") or []
                       if isinstance(spawn, Mapping) and spawn.get("name")) if isinstance(
            entry, Mapping) else ()
        if kind == "mesh":
            stand_in = EXAMPLE_CATEGORIES.get(str(name), EXAMPLE_CATEGORIES["trash_can"])
            categories[str(name)] = LocationCategory(
                stand_in.footprint, stand_in.height, spawns,
                f"its mesh footprint is not read; it is taken as the "
                f"{_size(stand_in.footprint)} box of pyrobosim's example '{name}'"
                if str(name) in EXAMPLE_CATEGORIES else
                f"its mesh footprint is not read; it is taken as a {_size(stand_in.footprint)}"
                " box")
            continue
        try:
            polygon, height = simple_footprint(footprint)
        except PoseFormatError as error:
            raise WorldError(field_error(document, [name, "footprint"], str(error))) from None
        categories[str(name)] = LocationCategory(polygon, height, spawns)
    return categories


def _size(polygon: Polygon) -> str:
    min_x, min_y, max_x, max_y = polygon.bounds
    return f"{max_x - min_x:g} × {max_y - min_y:g} m"
