"""The home as data: pydantic models of everything a world file holds.

These models validate one world file; cross-references between entities (a door
naming a room, an object on a placement) are checked by ``homebot.world.world``.
"""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    GetCoreSchemaHandler,
    GetPydanticSchema,
    field_validator,
    model_validator,
)
from pydantic_core import core_schema

from homebot.geometry import Pose

__all__ = [
    "COLOUR_PALETTE",
    "Colour",
    "DisturbanceModel",
    "DoorModel",
    "DoorState",
    "Gesture",
    "LaserModel",
    "ObjectCategoryModel",
    "ObjectModel",
    "PersonModel",
    "PlacementKind",
    "PlacementModel",
    "Posture",
    "RobotModel",
    "RoomModel",
    "Shape",
    "WorldModel",
]

#: metres from the map's origin a home may reach: far beyond any house (the occupancy grid
#: allows about 1.5 km), near enough that distances stay finite (1e308 is a typo, not a place)
MAP_EXTENT = 100_000.0
Coordinate = Annotated[float, Field(ge=-MAP_EXTENT, le=MAP_EXTENT)]
Point = tuple[Coordinate, Coordinate]
Probability = Annotated[float, Field(ge=0.0, le=1.0)]
# A letter of any script first, then letters (with their accents), digits, space, _ ' -.
# The pattern runs in pydantic-core's regex engine, which knows Unicode classes.
Name = Annotated[str, Field(min_length=1, pattern=r"^\p{L}[\p{L}\p{M}\p{N}_ '\-]*$")]




def _pose_schema(_source: Any, handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
    """A pose is written ``[x, y, heading]`` and read into a ``Pose``; its errors name the
    list's items (``robot.pose.2``) as pydantic's own tuple check does."""
    return core_schema.no_info_before_validator_function(
        lambda value: (value.x, value.y, value.theta) if isinstance(value, Pose) else value,
        core_schema.no_info_after_validator_function(
            lambda xyt: Pose(*xyt), handler(tuple[Coordinate, Coordinate, float])),
        serialization=core_schema.plain_serializer_function_ser_schema(
            lambda pose: [pose.x, pose.y, pose.theta]))


#: a pose in a world file: ``[x, y, heading]`` in the map frame (metres, radians)
PoseField = Annotated[Pose, GetPydanticSchema(_pose_schema)]


#: the garments of a person's clothes ("black trousers") worn on the legs; anything else
#: a person wears ("red sweater") is worn above them
LEG_GARMENTS = ("trousers", "jeans", "skirt", "pants", "shorts", "leggings")

#: the colour names a world file may use, with their RGB values (0-255)
COLOUR_PALETTE: dict[str, tuple[int, int, int]] = {
    "red": (200, 30, 30), "green": (40, 160, 60), "blue": (40, 70, 200),
    "yellow": (230, 210, 40), "orange": (240, 130, 20), "purple": (120, 50, 150),
    "pink": (240, 140, 180), "brown": (120, 75, 35), "black": (25, 25, 25),
    "white": (235, 235, 235), "grey": (128, 128, 128), "gray": (128, 128, 128),
    "beige": (220, 200, 160), "cyan": (40, 200, 210), "silver": (190, 190, 200),
    "gold": (210, 170, 50),
}


def _colour(value: Any) -> Any:
    """A palette name (any case) or an RGB triple of integers 0-255."""
    if isinstance(value, str):
        if value.strip().lower() not in COLOUR_PALETTE:
            raise ValueError(f"'{value}' is no colour; use one of "
                             f"{', '.join(sorted(COLOUR_PALETTE))} or [r, g, b] (0-255)")
        return value.strip().lower()
    if isinstance(value, list | tuple):
        if len(value) != 3 or not all(isinstance(c, int) and not isinstance(c, bool)
                                      and 0 <= c <= 255 for c in value):
            raise ValueError(f"{value!r} is no colour; give [r, g, b] as three integers "
                             "0-255, or a colour name")
        return tuple(value)
    raise ValueError(f"{value!r} is no colour; give a colour name or [r, g, b]")


#: a colour: a name of ``COLOUR_PALETTE`` or ``(r, g, b)`` with 0-255 components
Colour = Annotated[str | tuple[int, int, int], BeforeValidator(_colour)]


class Shape(StrEnum):
    """The primitive an object's catalogue entry is drawn and grasped as."""

    BOX = "box"  #: dimensions [x, y, z] (width, depth, height)
    CYLINDER = "cylinder"  #: dimensions [diameter, height], standing upright
    SPHERE = "sphere"  #: dimensions [diameter]


#: how many dimensions each shape takes
SHAPE_DIMENSIONS = {Shape.BOX: 3, Shape.CYLINDER: 2, Shape.SPHERE: 1}

Dimension = Annotated[float, Field(gt=0.0, le=2.0)]
#: metres: the widest placement any home holds; beyond it a size is a typo (1e308)
_LARGEST_PLACEMENT = 100.0


class _Strict(BaseModel):
    """Base for world entities: unknown fields are errors (they are usually typos).

    Numbers are finite: ``.nan`` or ``.inf`` in a coordinate is an error, not geometry.
    """

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


def _check_dimensions(shape: Shape | None, dimensions: list[float] | None) -> None:
    """Dimensions need a shape, and as many numbers as the shape takes."""
    if dimensions is None:
        return
    if shape is None:
        raise ValueError("dimensions need a shape (box, cylinder or sphere) beside them")
    wanted = SHAPE_DIMENSIONS[shape]
    if len(dimensions) != wanted:
        raise ValueError(f"a {shape.value} takes {wanted} dimension(s), got {len(dimensions)} "
                         "(box: [x, y, z], cylinder: [diameter, height], sphere: [diameter])")


_DIMENSIONS_MEANING = ("metres: [x, y, z] for a box, [diameter, height] for a cylinder, "
                       "[diameter] for a sphere")


class DoorState(StrEnum):
    """Whether a door lets the robot through."""

    OPEN = "open"  #: passable
    CLOSED = "closed"  #: blocks the route; the robot may open it
    LOCKED = "locked"  #: blocks the route; only someone with the key opens it


class Posture(StrEnum):
    """How a person's body is placed."""

    STANDING = "standing"
    SITTING = "sitting"
    LYING = "lying"


class Gesture(StrEnum):
    """What a person is doing with their arms."""

    NONE = "none"
    WAVING = "waving"
    RAISING_LEFT_ARM = "raising_left_arm"
    RAISING_RIGHT_ARM = "raising_right_arm"
    POINTING_LEFT = "pointing_left"
    POINTING_RIGHT = "pointing_right"


class PlacementKind(StrEnum):
    """Furniture occupies floor; a spot is a place on the floor the robot can stand at."""

    FURNITURE = "furniture"
    SPOT = "spot"


class RoomModel(_Strict):
    """A room: a named polygon, corners in metres, counter-clockwise or not."""

    name: Name
    polygon: list[Point] = Field(min_length=3)


class DoorModel(_Strict):
    """A door in the wall between two rooms, centred at ``position``."""

    name: Name
    rooms: tuple[Name, Name]
    position: Point
    width: float = Field(default=0.9, gt=0.4, le=3.0)
    state: DoorState = DoorState.OPEN
    opening: float | None = Field(default=None, gt=0.0, le=180.0, description=(
        "degrees the leaf stands from the wall's line while the door is open (30: barely "
        "ajar, 90: square to the wall); unset: the leaf lies flat against the wall, out of "
        "the way"))
    hinge: Literal["north", "south", "east", "west"] | None = Field(default=None, description=(
        "the jamb the leaf turns on (an end of the doorway along the wall; default: the "
        "west end, or the south end of a wall running north-south); needs ``opening``"))
    swings_into: Name | None = Field(default=None, description=(
        "the room the leaf opens into (one of ``rooms``; default: the first); needs "
        "``opening``"))

    @model_validator(mode="after")
    def _leaf_needs_opening(self) -> DoorModel:
        if self.opening is None and (self.hinge is not None or self.swings_into is not None):
            raise ValueError("hinge and swings_into place an open door's leaf; give the "
                             "door an opening too (degrees from the wall, e.g. opening: 60)")
        return self


class PlacementModel(_Strict):
    """Furniture or a spot: where objects are put and people are met.

    ``center`` and ``size`` give the furniture footprint (axis-aligned); ``approach``
    is where the robot stands to use it (x, y, heading in radians); when left out
    it is computed as the nearest free place facing the footprint.
    ``holds`` lists the object categories the placement is meant to hold.
    ``front`` is the side it faces (``north`` is +y, ``east`` +x); when left out,
    the side its approach pose is on ("the left cup" is seen from there).
    """

    name: Name
    category: Name
    room: Name
    kind: PlacementKind = PlacementKind.FURNITURE
    center: Point
    size: tuple[float, float] = Field(default=(0.6, 0.6), description=(
        "its width (along x) and depth (along y) in metres, each above 0; the footprint "
        "must stand in its room"))
    approach: PoseField | None = None
    holds: list[Name] = Field(default_factory=list)
    front: Literal["north", "south", "east", "west"] | None = None
    height: float | None = Field(default=None, gt=0.0, le=2.5, description=(
        "the height of its top surface in metres (default: by category, a table 0.75)"))

    @field_validator("size")
    @classmethod
    def _positive_size(cls, size: tuple[float, float]) -> tuple[float, float]:
        if size[0] <= 0 or size[1] <= 0:
            raise ValueError("width and depth must both be greater than 0")
        if max(size) > _LARGEST_PLACEMENT:
            raise ValueError(f"width and depth are metres, at most {_LARGEST_PLACEMENT:g} "
                             "(furniture, not a house)")
        return size


class ObjectCategoryModel(_Strict):
    """An object category with its plural, as people say it, and its catalogue defaults.

    ``shape``, ``dimensions``, ``colour`` and ``mass`` (kg) hold for every object of
    the category that does not give its own; left out, ``homebot.world.catalogue``
    supplies a default for the category (a drink is a bottle, a fruit a sphere...).
    """

    name: Name
    plural: Name
    shape: Shape | None = None
    dimensions: list[Dimension] | None = Field(default=None, description=_DIMENSIONS_MEANING)
    colour: Colour | None = None
    mass: float | None = Field(default=None, gt=0.0, le=30.0)

    @model_validator(mode="after")
    def _dimensions_fit_shape(self) -> ObjectCategoryModel:
        _check_dimensions(self.shape, self.dimensions)
        return self


class ObjectModel(_Strict):
    """An object, the placement it lies on, and what perception can tell of it.

    ``size`` is its largest dimension in metres and ``weight`` its mass in kg
    (used to answer "the heaviest object on the desk"). ``position`` is where it
    stands on its placement's surface (x, y in the map frame, metres); when left out,
    ``homebot.world.object_positions`` samples one with the run's seed. ``shape``,
    ``dimensions`` and ``colour`` are its catalogue entry (defaults: its category's).
    """

    name: Name
    category: Name
    placement: Name
    size: float = Field(default=0.12, gt=0.0, le=2.0)
    weight: float = Field(default=0.3, gt=0.0, le=30.0)
    position: Point | None = None
    shape: Shape | None = None
    dimensions: list[Dimension] | None = Field(default=None, description=_DIMENSIONS_MEANING)
    colour: Colour | None = None

    @model_validator(mode="after")
    def _dimensions_fit_shape(self) -> ObjectModel:
        _check_dimensions(self.shape, self.dimensions)
        return self


class PersonModel(_Strict):
    """A person in the home and how the simulation plays them.

    ``answers`` maps a question (lower case, as asked) to the reply the person
    gives; ``cooperative`` people step aside and open doors when asked; ``height`` in
    metres is how tall the simulator draws them (unset: drawn from the name).
    """

    name: Name
    room: Name
    position: Point
    height: float | None = Field(default=None, ge=0.5, le=2.5)
    posture: Posture = Posture.STANDING
    gesture: Gesture = Gesture.NONE
    clothes: list[str] = Field(default_factory=list)
    answers: dict[str, str] = Field(default_factory=dict)
    cooperative: bool = True


class LaserModel(_Strict):
    """The 2-D laser of the embodied robot: beams over a field of view, noise, spurious returns.

    ``spurious`` is the share of beams that return a random short range instead
    of the true one (people's feet, reflections: CAESAR localised with up to 90 %).
    """

    beams: int = Field(default=271, ge=8, le=4000)
    field_of_view: float = Field(default=4.712389, gt=0.0, le=6.2832)
    range_max: float = Field(default=10.0, gt=0.5, le=60.0)
    noise: float = Field(default=0.01, ge=0.0, le=0.5)
    spurious: Probability = 0.0


class RobotModel(_Strict):
    """The robot's body: start pose (x, y, heading), size, speeds, hands, base and laser."""

    pose: PoseField
    radius: float = Field(default=0.25, gt=0.05, le=1.0)
    speed: float = Field(default=0.5, gt=0.0, le=3.0, description=(
        "the base's top linear speed, in m/s"))
    angular_speed: float = Field(default=1.2, gt=0.0, le=6.0, description=(
        "the base's top turning speed, in rad/s"))
    hands: list[Name] = Field(default_factory=lambda: ["left", "right"], min_length=1)
    #: how the base moves in the embodied fidelity (``homebot.robot.DriveKind``)
    drive: Literal["omnidirectional", "differential"] = "differential"
    laser: LaserModel = Field(default_factory=LaserModel)
    #: the arm's MJCF model, relative to the world file (default: homebot's own)
    arm: str | None = Field(default=None, min_length=1)


class DisturbanceModel(_Strict):
    """How often the simulated world differs from what the robot expects.

    Each field is a probability per opportunity (per grasp, per detection, per
    door at the start of a task, per object...). All zero: a perfect world.
    """

    grasp_slip: Probability = 0.0
    detection_miss: Probability = 0.0
    detection_confusion: Probability = 0.0
    door_closed: Probability = 0.0
    person_in_way: Probability = 0.0
    object_moved: Probability = 0.0
    object_moved_during_task: Probability = 0.0
    object_missing: Probability = 0.0


class WorldModel(_Strict):
    """A whole world file."""

    name: Name
    description: str = ""
    grid_resolution: float = Field(default=0.05, gt=0.005, le=0.5)
    wall_thickness: float = Field(default=0.1, gt=0.0, le=0.5)
    rooms: list[RoomModel] = Field(min_length=1)
    doors: list[DoorModel] = Field(default_factory=list)
    placements: list[PlacementModel] = Field(default_factory=list)
    categories: list[ObjectCategoryModel] = Field(default_factory=list)
    objects: list[ObjectModel] = Field(default_factory=list)
    people: list[PersonModel] = Field(default_factory=list)
    operator: Name | None = None
    robot: RobotModel
    disturbances: DisturbanceModel = Field(default_factory=DisturbanceModel)
    #: self-maintenance components and constraints, read by ``homebot golog maintain``
    maintenance: dict[str, Any] | None = None
