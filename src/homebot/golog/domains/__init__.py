"""Basic action theories of the shipped programs: cups, maze, blocks, elevator, RIPS."""

from homebot.golog.domains.blocks import blocks_theory
from homebot.golog.domains.cups import CUPS, POSITIONS, cups_theory, minimum_moves
from homebot.golog.domains.elevator import elevator_theory
from homebot.golog.domains.maze import MAZE, Maze, maze_theory
from homebot.golog.domains.registry import domain_names, domain_theory
from homebot.golog.domains.rips import rips_theory

__all__ = [
    "CUPS",
    "MAZE",
    "POSITIONS",
    "Maze",
    "blocks_theory",
    "cups_theory",
    "domain_names",
    "domain_theory",
    "elevator_theory",
    "maze_theory",
    "minimum_moves",
    "rips_theory",
]

