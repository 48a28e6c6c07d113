"""A maze with stochastic moves (CAESAR Fig. 5): the MDP behind ``navigate``.

Each move goes the intended way with probability 0.8 and slips to either side
with 0.1; a move into a wall leaves the robot where it was. Stepping onto the
stairs (``X``) is a fall: nothing is possible afterwards. Reward: 100 at the
goal, -100 fallen, -1 anywhere else.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

from homebot.golog.build import eq, f, not_
from homebot.golog.library import shipped_procedures
from homebot.golog.theory import GroundAction, State, Theory

__all__ = ["DIRECTIONS", "MAZE", "Maze", "maze_theory"]

#: the default maze: S start, G goal, # wall, X stairs, . floor (row 0 is the top)
MAZE = (
    "#....#",
    "S.#X.G",
    "..#...",
    ".....#",
    "#.#...",
    "......",
)
#: name, (dx, dy); up is towards row 0
DIRECTIONS = {"go_right": (1, 0), "go_left": (-1, 0), "go_up": (0, -1), "go_down": (0, 1)}
INTENDED, SLIP = 0.8, 0.1
GOAL_REWARD, FALL_REWARD, STEP_REWARD = 100.0, -100.0, -1.0

Cell = tuple[int, int]


@dataclass(frozen=True)
class Maze:
    """A grid maze read from rows of characters."""

    rows: tuple[str, ...] = MAZE

    def cells(self, mark: str) -> list[Cell]:
        return [(x, y) for y, row in enumerate(self.rows) for x, char in enumerate(row)
                if char == mark]

    @cached_property
    def start(self) -> Cell:
        return self.cells("S")[0]

    @cached_property
    def goal(self) -> Cell:
        return self.cells("G")[0]

    @cached_property
    def stairs(self) -> frozenset[Cell]:
        return frozenset(self.cells("X"))

    def free(self, cell: Cell) -> bool:
        x, y = cell
        return 0 <= y < len(self.rows) and 0 <= x < len(self.rows[y]) and \
            self.rows[y][x] != "#"

    def floor_cells(self) -> list[Cell]:
        return [(x, y) for y, row in enumerate(self.rows) for x in range(len(row))
                if self.free((x, y))]

    def step(self, cell: Cell, delta: tuple[int, int]) -> Cell:
        target = (cell[0] + delta[0], cell[1] + delta[1])
        return target if self.free(target) else cell

    def outcomes(self, cell: Cell, direction: str) -> list[tuple[Cell, float]]:
        """Where a move may end, with probabilities, merged per cell (intended first)."""
        dx, dy = DIRECTIONS[direction]
        found: dict[Cell, float] = {}
        for delta, chance in (((dx, dy), INTENDED), ((dy, dx), SLIP), ((-dy, -dx), SLIP)):
            target = self.step(cell, delta)
            found[target] = found.get(target, 0.0) + chance
        return list(found.items())

    def reward(self, cell: Cell) -> float:
        if cell == self.goal:
            return GOAL_REWARD
        return FALL_REWARD if cell in self.stairs else STEP_REWARD


def maze_theory(maze: Maze | None = None, start: Cell | None = None) -> Theory:
    """Fluents ``loc`` (a cell) and ``fallen``; stochastic ``go_*``; nature's ``arrive(x, y)``."""
    maze = maze or Maze()
    theory = Theory("maze")
    theory.fluent("loc", 0, maze.start)
    theory.fluent("fallen", 0, relational=True)
    theory.function("goal", maze.goal)
    theory.function("reward", lambda state: maze.reward(state.get(("loc",), maze.start)))

    def outcomes_of(direction: str) -> Callable[[State], list[tuple[GroundAction, float]]]:
        def outcomes(state: State) -> list[tuple[GroundAction, float]]:
            cell = state.get(("loc",), maze.start)
            return [(("arrive", x, y), chance) for (x, y), chance in
                    maze.outcomes(cell, direction)]
        return outcomes

    for direction in DIRECTIONS:
        theory.stochastic(direction, outcomes=outcomes_of(direction),
                          precondition=not_(f("fallen")))
    theory.action("arrive", ("x", "y"),
                  effects=lambda state, x, y: {("loc",): (x, y),
                                               ("fallen",): (x, y) in maze.stairs},
                  sense=eq(f("loc"), f("cell", "x", "y")))
    theory.function("cell", lambda state, x, y: (x, y))
    theory.define(*shipped_procedures("maze"))
    if start is not None:
        theory.initially({("loc",): start})
    return theory

