"""The home domain: its shipped file, planning states built from the robot's beliefs, and goals.

The initial state comes from ``Beliefs`` (what the robot perceived or was
told) and the world file as the robot's map, never from the simulator's truth.
World names become planning symbols with spaces written as underscores
(``kitchen table`` → ``kitchen_table``); ``Names`` turns them back.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from homebot.beliefs import Beliefs
from homebot.errors import KnowledgeError, PlanningError
from homebot.htn.domain import Domain
from homebot.htn.jshop import read_domain
from homebot.htn.state import Atom, State
from homebot.knowledge import KnowledgeBase
from homebot.task import Step
from homebot.text import closest_names, fold
from homebot.world import World

__all__ = ["HOME_TASKS", "ROBOT", "Goal", "Names", "goals_from_steps", "home_domain",
           "home_domain_path", "load_domain", "state_from_beliefs", "symbol"]

ROBOT = "robot"  #: the robot's symbol in plans (the paper's ``Jenny``)

#: The home domain's top-level tasks and the arguments a person gives (after the robot).
HOME_TASKS: Mapping[str, tuple[str, ...]] = {
    "bring_object": ("OBJECT", "PERSON"),
    "bring_objects": ("PERSON", "OBJECT..."),
    "guide_person": ("PERSON", "PLACE"),
    "put_away": ("OBJECT",),
    "place_object": ("OBJECT", "PLACEMENT"),
    "tidy": (),
    "tidy_room": ("ROOM",),
    "serve": ("OBJECT-OR-CATEGORY", "PERSON"),
}

# How near the robot must be to a person or a placement to plan as being "at" it, in metres.
_NEAR_PERSON = 1.2
_NEAR_PLACEMENT = 0.35


def symbol(name: str) -> str:
    """A world name as a planning symbol: spaces become underscores."""
    return name.replace(" ", "_")


@dataclass
class Names:
    """Planning symbols and the world names they stand for."""

    names: dict[str, str] = field(default_factory=dict)

    def of(self, name: str) -> str:
        """Register ``name`` and return its symbol."""
        sym = symbol(name)
        self.names.setdefault(sym, name)
        return sym

    def name(self, sym: Any) -> Any:
        """The world name a symbol stands for (anything else unchanged)."""
        return self.names.get(sym, sym) if isinstance(sym, str) else sym


def home_domain_path() -> Path:
    """The shipped home domain file (JSHOP2 syntax)."""
    return Path(str(resources.files("homebot.data") / "domains" / "home.jshop"))


def home_domain() -> Domain:
    """The home domain, read from its shipped file."""
    path = home_domain_path()
    return read_domain(path)


def load_domain(path: str | Path | None,
                functions: Mapping[str, Callable[..., Any]] | None = None) -> Domain:
    """The home domain (None), a JSHOP2 file, or a Python file defining ``domain() -> Domain``.

    ``functions`` adds to the functions a JSHOP2 file's ``call`` knows (see ``load_functions``).
    """
    if path is None:
        return home_domain()
    path = Path(path)
    if path.suffix == ".py":
        return _python_domain(path)
    return read_domain(path, functions)


def load_functions(path: str | Path) -> dict[str, Callable[..., Any]]:
    """The public functions of a Python file, by lower-case name, for JSHOP2's ``call``.

    JSHOP2 takes a domain's own functions as Java classes (``CheckNull``, a comparator
    for ``:sort-by``); homebot takes them as Python functions: ``def checknull(x, y)``,
    and for ``:sort-by`` a function ``(a, b) -> int``.
    """
    module = _python_module(Path(path), "functions")
    return {name.lower(): value for name, value in vars(module).items()
            if callable(value) and not name.startswith("_")
            and getattr(value, "__module__", None) == module.__name__}


def _python_module(path: Path, what: str) -> Any:
    import importlib.util

    spec = importlib.util.spec_from_file_location(f"homebot_{what}_{path.stem}", path)
    if spec is None or spec.loader is None or not path.exists():
        raise PlanningError(f"cannot load the Python {what} file '{path}'; check the path")
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except Exception as error:  # a person's file may fail in any way; report, do not crash
        raise PlanningError(f"{path}: the Python {what} file failed: "
                            f"{type(error).__name__}: {error}") from None
    return module


def _python_domain(path: Path) -> Domain:
    module = _python_module(path, "domain")
    try:
        made = module.domain() if hasattr(module, "domain") else None
    except PlanningError:
        raise
    except Exception as error:  # a person's file may fail in any way; report, do not crash
        raise PlanningError(f"{path}: the Python domain failed: {type(error).__name__}: "
                            f"{error}") from None
    if not isinstance(made, Domain):
        raise PlanningError(f"{path}: define a function domain() returning a "
                            "homebot.htn.Domain")
    made.check()
    return made


def _robot_at(world: World, beliefs: Beliefs, pose: tuple[float, float], names: Names) -> str:
    people = sorted((math.dist(position, pose), person)
                    for person, position in beliefs.person_at.items())
    if people and people[0][0] <= _NEAR_PERSON:
        return names.of(people[0][1])
    placements = sorted((math.dist(p.approach.xy(), pose), p.name)
                        for p in world.placements.values())
    if placements and placements[0][0] <= _NEAR_PLACEMENT:
        return names.of(placements[0][1])
    room = world.room_at(*pose)
    return names.of(room) if room else names.of(next(iter(world.rooms)))


def _kb_places(knowledge: KnowledgeBase, name: str, category: str) -> list[str]:
    """Where the KB says an object belongs (``loc``): its own value, else its category's."""
    for entity in (name, category):
        try:
            places = knowledge.values(entity, "loc")
        except KnowledgeError:
            continue
        if places:
            return [str(place) for place in places]
    return []


def state_from_beliefs(world: World, beliefs: Beliefs, robot_pose: tuple[float, float],
                       names: Names | None = None, extra: Iterable[Atom] = (),
                       knowledge: KnowledgeBase | None = None) -> tuple[State, Names]:
    """The planning state: what the robot believes, on its map (``world``).

    ``robot_pose`` is where the robot believes it is (its localisation);
    ``extra`` adds atoms kept by the actor between plans (what it has told whom);
    ``knowledge`` says where objects belong (``loc=>PLACE``, defaults with exceptions).
    """
    names = names or Names()
    of = names.of
    atoms: list[Atom] = [("robot", ROBOT), ("at", ROBOT, _robot_at(world, beliefs, robot_pose,
                                                                    names))]
    for hand, held in beliefs.holding.items():
        atoms.append(("free-hand", ROBOT, hand) if held is None else
                     ("holding", ROBOT, of(held), hand))
    doors_of: dict[str, list[str]] = {room: [] for room in world.rooms}
    for door in world.doors.values():
        for room in door.rooms:
            doors_of[room].append(door.name)
    for room, doors in doors_of.items():
        atoms += [("room", of(room)), ("room-of", of(room), of(room))]
        if len(doors) == 1:
            atoms.append(("only-door", of(doors[0]), of(room)))
    atoms += [("door-closed", of(door)) for door in sorted(beliefs.closed_doors)]
    for placement in world.placements.values():
        atoms += [("placement", of(placement.name)),
                  ("room-of", of(placement.name), of(placement.room))]
        atoms += [("holds", of(placement.name), of(category)) for category in placement.holds]
    for name, obj in world.objects.items():
        atoms += [("category", of(name), of(obj.category)), ("told-at", of(name),
                                                             of(obj.placement))]
        where = beliefs.object_at.get(name)
        if where in world.placements:
            atoms.append(("object-at", of(name), of(where)))
        elif isinstance(where, str) and where.startswith("person:"):
            atoms.append(("has", of(where[len("person:"):]), of(name)))
        atoms += [("ruled-out", of(name), of(p)) for p in sorted(beliefs.not_at.get(name, ()))]
        if knowledge is not None:
            atoms += [("kb-belongs", of(name), of(place))
                      for place in _kb_places(knowledge, name, obj.category)
                      if place in world.placements]
    for person, position in beliefs.person_at.items():
        person_room = world.room_at(*position)
        atoms.append(("person", of(person)))
        if person_room is not None:
            atoms += [("person-in", of(person), of(person_room)),
                      ("room-of", of(person), of(person_room))]
    if world.model.operator:
        atoms.append(("operator", of(world.model.operator)))
    atoms += list(extra)
    return State(atoms), names


@dataclass(frozen=True)
class Goal:
    """A top-level task for the home domain, with atoms it adds to the state (``wanted``)."""

    task: tuple[Any, ...]
    atoms: tuple[Atom, ...] = ()

    @classmethod
    def of(cls, task: str, args: Sequence[str], world: World, names: Names | None = None,
           domain: Domain | None = None) -> Goal:
        """A goal from a task name and the arguments a person gives (world names or symbols).

        ``operator`` and ``me`` stand for the world's operator. Unknown names raise
        ``PlanningError`` naming the closest known one.
        """
        names = names or Names()
        if domain is not None and not domain.is_task(task):
            domain.check_task((task,), "task")
        if task == "bring_objects":
            if len(args) < 2:
                raise PlanningError("bring_objects needs a PERSON and one or more OBJECTs")
            person = _known(args[0], world, names)
            objects = [_known(arg, world, names) for arg in args[1:]]
            return cls(("bring_objects", ROBOT, person),
                       tuple(("wanted", obj, person) for obj in objects))
        expected = HOME_TASKS.get(task)
        if expected is not None and len(args) != len(expected):
            raise PlanningError(f"{task} takes {len(expected)} argument"
                                f"{'s' * (len(expected) != 1)} ({' '.join(expected) or 'none'})"
                                f", got {len(args)}")
        return cls((task, ROBOT, *(_known(arg, world, names) for arg in args)))


def _known(text: str, world: World, names: Names) -> str:
    if text.lower() in {"operator", "me", "guest"} and world.model.operator:
        return names.of(world.model.operator)
    everything = {*world.objects, *world.people, *world.placements, *world.rooms,
                  *world.categories, *world.doors}
    lookup = {fold(symbol(name)): name for name in everything}
    found = lookup.get(fold(symbol(text)))  # "patricia" and "Patrícia" alike
    if found is not None:
        return names.of(found)
    guess = closest_names(text.replace("_", " "), sorted(everything))
    hint = f"did you mean '{guess[0]}'?" if guess else "check the world's names"
    raise PlanningError(f"'{text}' is not an object, person, place or category of world "
                        f"'{world.name}'; {hint}")


def goals_from_steps(steps: Sequence[Step], world: World,
                     names: Names | None = None) -> list[Goal] | None:
    """HTN goals for what a GPSR parse means, or None when a step has no home task.

    A pick later given to a person is ``serve`` (an object or a category); a pick
    later placed is ``place_object``; a person found and then guided is
    ``guide_person``. Steps that only lead up to these (navigate, find) are left
    to the planner.
    """
    names = names or Names()
    goals: list[Goal] = []
    wanted: str | None = None
    person: str | None = None
    for step in steps:
        args = step.args
        if step.skill == "pick":
            wanted = str(args["object"])
        elif step.skill == "give" and wanted is not None:
            who = str(args.get("person") or person or "operator")
            goals.append(Goal.of("serve", [wanted, who], world, names))
            wanted = None
        elif step.skill == "place" and wanted is not None:
            goals.append(Goal.of("place_object", [wanted, str(args["placement"])], world, names))
            wanted = None
        elif step.skill == "find_person":
            description = args.get("person") or {}
            person = description.get("name") if isinstance(description, Mapping) else None
        elif step.skill == "guide" and (args.get("person") or person):
            goals.append(Goal.of("guide_person", [str(args.get("person") or person),
                                                  str(args["to"])], world, names))
        elif step.skill not in {"navigate", "find_object", "say"}:
            return None
    return goals if goals and wanted is None else None
