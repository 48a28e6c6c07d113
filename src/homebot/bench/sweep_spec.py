"""The sweep spec: a YAML file naming a grid of benchmark runs for ``homebot bench sweep``.

    benchmarks: [robustness]      # the benchmarks swept (their tasks must be units)
    worlds: [apartment, family_home]
    levels: [0, 1, 2]             # disturbance levels, 0 to 6
    seeds: [1, 2, 3]
    fidelities: [symbolic]        # symbolic and/or embodied
    tasks: 20                     # seeded tasks per cell (robustness: errands, in both modes)
    errands: everyday             # robustness's mix: everyday or fetch

A cell is one point of the grid (benchmark, world, level, seed, fidelity); its ``tasks``
seeded tasks are the sweep's units of work. A bad spec is refused with one line naming the
file, the line and the field.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

from homebot.app import Fidelity
from homebot.errors import BenchmarkError, WorldError
from homebot.seeds import MAX_SEED
from homebot.world import shipped_world_names
from homebot.world.loading import validate_document
from homebot.yamlfile import load_yaml_document

__all__ = ["MAX_SWEEP_TASKS", "Cell", "SweepSpec", "load_sweep_spec", "resolved_world"]

#: At most this many tasks in one sweep: a spec with a typo in a list stays a mistake.
MAX_SWEEP_TASKS = 1_000_000

_Level = Annotated[float, Field(ge=0.0, le=6.0)]
_Seed = Annotated[int, Field(ge=0, le=MAX_SEED)]


class SweepSpec(BaseModel):
    """A sweep's grid, as written in its YAML file."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    # the benchmarks whose tasks are picklable units (homebot.bench.robustness.ErrandTask)
    benchmarks: list[Literal["robustness"]] = Field(
        default=["robustness"], min_length=1, description="the benchmarks swept: robustness")
    worlds: list[str] = Field(min_length=1, description="shipped world names or YAML files")
    levels: list[_Level] = Field(default=[1.0], min_length=1,
                                 description="disturbance levels from 0 to 6")
    seeds: list[_Seed] = Field(min_length=1, description="the benchmark seeds of the cells")
    fidelities: list[Fidelity] = Field(default=[Fidelity.SYMBOLIC], min_length=1,
                                       description="symbolic and/or embodied")
    tasks: int = Field(ge=1, le=20_000, description="the seeded tasks of each cell")
    errands: Literal["everyday", "fetch"] = Field(
        default="everyday", description="robustness's errand mix: everyday or fetch")

    @field_validator("worlds", "levels", "seeds", "fidelities", "benchmarks")
    @classmethod
    def _distinct(cls, values: list[object]) -> list[object]:
        repeated = sorted({str(value) for value in values if values.count(value) > 1})
        if repeated:
            raise ValueError(f"{', '.join(repeated)} is listed twice; list each once")
        return values

    def cells(self) -> list[Cell]:
        """Every cell of the grid, in the spec's order (benchmark, world, level, seed,
        fidelity: the last varies fastest)."""
        return [Cell(*point) for point in itertools.product(
            self.benchmarks, self.worlds, self.levels, self.seeds, self.fidelities)]


@dataclass(frozen=True)
class Cell:
    """One point of a sweep's grid."""

    benchmark: str
    world: str
    level: float
    seed: int
    fidelity: Fidelity


def load_sweep_spec(path: Path) -> SweepSpec:
    """Read and check a sweep spec; a bad one raises ``BenchmarkError`` (one line)."""
    document = load_yaml_document(path, BenchmarkError)
    try:
        spec = validate_document(document, SweepSpec)
    except WorldError as error:  # the world's validator locates the field; say the first
        problems = str(error).splitlines()
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        raise BenchmarkError(f"sweep spec {problems[0]}{more}") from None
    for index, world in enumerate(spec.worlds):
        _check_world(path, document.line_of(["worlds", index]), world)
    total = len(spec.cells()) * spec.tasks
    if total > MAX_SWEEP_TASKS:
        raise BenchmarkError(f"sweep spec {path}: {total} tasks; a sweep holds at most "
                             f"{MAX_SWEEP_TASKS}: split it or list fewer values")
    return spec


def resolved_world(spec_path: Path, world: str) -> str:
    """How a worker finds a world of the spec: a file (beside the spec, when its path is
    relative) by its absolute path, else a shipped world by name."""
    candidate = _path_beside(spec_path, world)
    return str(candidate.resolve()) if candidate.is_file() else world


def _path_beside(spec_path: Path, name: str) -> Path:
    """``name`` as a path, relative ones taken from the spec's folder."""
    return Path(name) if Path(name).is_absolute() else spec_path.parent / name


def _check_world(path: Path, line: int | None, world: str) -> None:
    if _path_beside(path, world).is_file() or world in shipped_world_names():
        return
    raise BenchmarkError(f"sweep spec {path}: line {line}: worlds: no world '{world}' (neither "
                         f"shipped nor a file beside the spec); give a YAML file or one of: "
                         f"{', '.join(shipped_world_names())}")
