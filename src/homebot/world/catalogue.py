"""The object catalogue: every object's shape, dimensions, colour and mass, with defaults.

An object's entry comes from the world file where it says so (the object's own
``shape``, ``dimensions``, ``colour``, ``size``, ``weight``), else from its
category's fields there, else from ``CATEGORY_DEFAULTS`` (a drink is a bottle, a
fruit a sphere...; an unknown category a small box). Where neither the object nor
its category gives a colour or dimensions, the default varies a little by the
object's name (stable across runs: a CRC of the name), so that the objects of one
category do not all look alike. Furniture surfaces get their height the same way
(``surface_height``).
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass

from homebot.world.model import (
    COLOUR_PALETTE,
    ObjectModel,
    PlacementKind,
    PlacementModel,
    Shape,
)
from homebot.world.world import World

__all__ = [
    "CATEGORY_DEFAULTS",
    "CatalogueEntry",
    "CategoryDefaults",
    "catalogue_entry",
    "defaults_for",
    "object_catalogue",
    "surface_height",
]


@dataclass(frozen=True, slots=True)
class CategoryDefaults:
    """What an object of a category is like when the world file does not say."""

    shape: Shape
    dimensions: tuple[float, ...]  #: as the shape takes them (see ``Shape``)
    mass: float  #: kg
    colours: tuple[str, ...]  #: palette names; an object takes one by its name


#: defaults per category (singular, lower case; ``_`` and ``-`` read as spaces)
CATEGORY_DEFAULTS: dict[str, CategoryDefaults] = {
    "drink": CategoryDefaults(Shape.CYLINDER, (0.07, 0.2), 0.5,
                              ("red", "orange", "white", "blue", "brown", "green", "yellow")),
    "food": CategoryDefaults(Shape.BOX, (0.07, 0.14, 0.19), 0.4,
                             ("yellow", "red", "orange", "beige", "green", "blue")),
    "snack": CategoryDefaults(Shape.BOX, (0.05, 0.15, 0.11), 0.15,
                              ("purple", "yellow", "red", "orange", "brown", "cyan")),
    "fruit": CategoryDefaults(Shape.SPHERE, (0.08,), 0.17,
                              ("red", "green", "yellow", "orange", "purple")),
    "dish": CategoryDefaults(Shape.CYLINDER, (0.16, 0.05), 0.35,
                             ("white", "blue", "grey", "beige", "green")),
    "cleaning supply": CategoryDefaults(Shape.CYLINDER, (0.075, 0.27), 0.7,
                                        ("blue", "green", "yellow", "white", "pink")),
    "toy": CategoryDefaults(Shape.BOX, (0.1, 0.1, 0.1), 0.2,
                            ("red", "blue", "yellow", "green", "pink", "orange")),
    "decoration": CategoryDefaults(Shape.CYLINDER, (0.11, 0.24), 0.6,
                                   ("white", "gold", "blue", "purple", "silver")),
    "gadget": CategoryDefaults(Shape.BOX, (0.08, 0.15, 0.04), 0.25,
                               ("black", "silver", "grey", "white")),
    "bread": CategoryDefaults(Shape.BOX, (0.1, 0.24, 0.09), 0.4, ("beige", "brown", "orange")),
}
#: a category nobody described: a small box of some colour
_GENERIC = CategoryDefaults(Shape.BOX, (0.08, 0.08, 0.12), 0.3,
                            ("red", "green", "blue", "yellow", "orange", "purple", "white"))
#: how much a defaulted object's dimensions vary by its name (fraction, either way)
_SPREAD = 0.1

#: the top surface's height (metres) by furniture category, when the file gives none
_SURFACE_HEIGHTS = {"table": 0.75, "desk": 0.75, "counter": 0.9, "storage": 0.8,
                    "shelf": 0.8, "appliance": 0.85, "seating": 0.45, "bin": 0.4}
_DEFAULT_SURFACE = 0.75


@dataclass(frozen=True, slots=True)
class CatalogueEntry:
    """One object as perception and manipulation know it.

    ``extent`` is the axis-aligned size in the object's own frame (x, y, z), metres:
    a cylinder's and a sphere's first two are the diameter.
    """

    name: str
    category: str
    shape: Shape
    dimensions: tuple[float, ...]
    colour: str  #: a palette name, or ``rgb(r, g, b)`` when the file gave numbers
    rgb: tuple[int, int, int]
    mass: float  #: kg

    @property
    def extent(self) -> tuple[float, float, float]:
        return _extent(self.shape, self.dimensions)

    @property
    def size(self) -> float:
        """The largest dimension, metres."""
        return max(self.extent)

    @property
    def volume(self) -> float:
        """Cubic metres."""
        return _volume(self.shape, self.dimensions)


def defaults_for(category: str) -> CategoryDefaults:
    """The built-in defaults of a category (a generic small box for unknown ones)."""
    key = category.strip().lower().replace("_", " ").replace("-", " ")
    found = CATEGORY_DEFAULTS.get(key)
    if found is None and key.endswith("s"):
        found = CATEGORY_DEFAULTS.get(key[:-1])
    return found or _GENERIC


def catalogue_entry(world: World, name: str) -> CatalogueEntry:
    """The catalogue entry of the object ``name`` of ``world``."""
    obj = world.objects[name]
    return _entry(world, obj)


def object_catalogue(world: World) -> dict[str, CatalogueEntry]:
    """Every object's catalogue entry, by object name."""
    return {name: _entry(world, obj) for name, obj in world.objects.items()}


def _rank(world: World, obj: ObjectModel) -> int:
    """The object's place among its category's objects in the file (0 for the first)."""
    same = [other.name for other in world.model.objects if other.category == obj.category]
    return same.index(obj.name)


def _entry(world: World, obj: ObjectModel) -> CatalogueEntry:
    declared = world.categories.get(obj.category)
    builtin = defaults_for(obj.category)
    stamp = zlib.crc32(obj.name.encode("utf-8"))
    # shape and dimensions travel together: a category's box dimensions fit no sphere
    if obj.shape is not None:
        shape = obj.shape
        dims = tuple(obj.dimensions) if obj.dimensions else _dims_for(shape, declared, builtin)
        varied = obj.dimensions is None
    elif declared is not None and declared.shape is not None:
        shape = declared.shape
        dims = tuple(declared.dimensions) if declared.dimensions else _scaled(builtin, shape)
        varied = declared.dimensions is None
    else:
        shape, dims, varied = builtin.shape, builtin.dimensions, True
    if "size" in obj.model_fields_set:  # the file gave the largest dimension: scale to it
        factor = obj.size / max(_extent(shape, dims))
        dims = tuple(round(d * factor, 4) for d in dims)
    elif varied:
        factor = 1.0 + _SPREAD * ((stamp % 1000) / 500.0 - 1.0)
        dims = tuple(round(d * factor, 4) for d in dims)
    colour_value = obj.colour if obj.colour is not None else (
        declared.colour if declared is not None and declared.colour is not None
        else builtin.colours[_rank(world, obj) % len(builtin.colours)])
    if isinstance(colour_value, str):
        colour, rgb = colour_value, COLOUR_PALETTE[colour_value]
    else:
        rgb = (int(colour_value[0]), int(colour_value[1]), int(colour_value[2]))
        colour = f"rgb{rgb}"
    if "weight" in obj.model_fields_set:
        mass = obj.weight
    elif declared is not None and declared.mass is not None:
        mass = declared.mass
    else:  # the category's typical mass, for the object's volume
        mass = round(builtin.mass * _volume(shape, dims) / _volume(
            builtin.shape, builtin.dimensions), 3) if shape is builtin.shape else builtin.mass
    return CatalogueEntry(obj.name, obj.category, shape, tuple(float(d) for d in dims),
                          colour, rgb, float(mass))


def _dims_for(shape: Shape, declared: object, builtin: CategoryDefaults) -> tuple[float, ...]:
    category_shape = getattr(declared, "shape", None)
    category_dims = getattr(declared, "dimensions", None)
    if category_shape is shape and category_dims:
        return tuple(category_dims)
    return _scaled(builtin, shape)


def _scaled(builtin: CategoryDefaults, shape: Shape) -> tuple[float, ...]:
    """Dimensions for ``shape`` about as big as the category's default object."""
    if shape is builtin.shape:
        return builtin.dimensions
    size = max(_extent(builtin.shape, builtin.dimensions))
    return {Shape.BOX: (size * 0.6, size * 0.6, size), Shape.CYLINDER: (size * 0.5, size),
            Shape.SPHERE: (size * 0.8,)}[shape]


def _extent(shape: Shape, dims: tuple[float, ...]) -> tuple[float, float, float]:
    if shape is Shape.BOX:
        return (dims[0], dims[1], dims[2])
    if shape is Shape.CYLINDER:
        return (dims[0], dims[0], dims[1])
    return (dims[0], dims[0], dims[0])


def _volume(shape: Shape, dims: tuple[float, ...]) -> float:
    x, _, z = _extent(shape, dims)
    if shape is Shape.BOX:
        return dims[0] * dims[1] * dims[2]
    if shape is Shape.CYLINDER:
        return math.pi * x * x / 4 * z
    return math.pi * x ** 3 / 6


def surface_height(placement: PlacementModel) -> float:
    """The height of a placement's top surface, metres (0 for a spot on the floor)."""
    if placement.height is not None:
        return placement.height
    if placement.kind is PlacementKind.SPOT:
        return 0.0
    key = placement.category.strip().lower()
    return _SURFACE_HEIGHTS.get(key, _SURFACE_HEIGHTS.get(key.rstrip("s"), _DEFAULT_SURFACE))
