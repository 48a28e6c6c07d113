"""Fetch & Carry's action theory (CAESAR Alg. 1): positions, the robot, one object in hand.

Fluents: ``pos(obj)`` (a point, the items database Φ: unknown objects have none),
``robot`` (where the robot stands) and ``holding`` (``nothing`` or an object).
Functions: ``places`` (every known position), ``phi(obj)`` (the object is in the
database), ``standpoints(p)`` (free floor points around p, nearest first),
``spot(dest)`` (the middle of a placement), and the qualitative ``dist``,
``orient``, ``is`` and ``degree`` (``homebot.golog.qualitative``).

Actions:

- ``goto(q)``: effect ``robot = q``;
- ``pickup(obj)``: precondition ``holding = nothing``, effect ``holding = obj``;
- ``putdown(obj, dest)``: precondition ``holding = obj``; effects ``pos(obj) =
  spot(dest)``, ``holding = nothing``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from homebot.golog.build import eq, f
from homebot.golog.library import shipped_procedures
from homebot.golog.qualitative import FrameOf, add_qualitative
from homebot.golog.theory import State, Theory

__all__ = ["fetch_carry_theory"]

Point = tuple[float, float]


def fetch_carry_theory(positions: Mapping[str, Point], robot: Point,
                       spots: Mapping[str, Point],
                       standpoints: Callable[[Point], tuple[Point, ...]],
                       frame: FrameOf) -> Theory:
    """The theory with the items database ``positions``, the robot at ``robot``, the
    placements' middles ``spots``, the free floor ``standpoints`` round a point and
    the ``frame`` (scale, front) two points are read in."""
    theory = Theory("fetch_carry")
    theory.fluent("pos", 1)
    theory.fluent("robot", 0)
    theory.fluent("holding", 0, "nothing")

    def places(state: State) -> tuple[Point, ...]:
        return tuple(dict.fromkeys(value for key, value in sorted(state.values.items(),
                                                                    key=lambda kv: str(kv[0]))
                                   if key[0] == "pos" and value is not None))

    theory.function("places", places)
    theory.function("phi", lambda state, obj: state.get(("pos", obj)) is not None)
    theory.function("standpoints", lambda state, point: standpoints(tuple(point)))
    theory.function("spot", lambda state, dest: spots[str(dest)])
    add_qualitative(theory, frame)
    theory.action("goto", ("q",), effects=lambda state, q: {("robot",): tuple(q)},
                  description="drive to a point")
    theory.action("pickup", ("obj",), precondition=eq(f("holding"), "nothing"),
                  effects=lambda state, obj: {("holding",): obj},
                  description="take the object in hand")
    theory.action("putdown", ("obj", "dest"), precondition=eq(f("holding"), "obj"),
                  effects=lambda state, obj, dest: {("pos", obj): spots[str(dest)],
                                                    ("holding",): "nothing"},
                  description="put the object down on the placement")
    theory.define(*shipped_procedures("fetch_carry"))
    theory.initially({("robot",): robot, **{("pos", name): point
                                            for name, point in positions.items()}})
    return theory
