"""The likelihood field: how far each point of the map lies from the nearest obstacle surface.

Computed once per map with a Euclidean distance transform (Probabilistic
Robotics §6.4). Two refinements over the textbook field matter at a 5 cm grid:

- distances are measured to the *surface* of the occupied region (its border
  cells, half a cell in), not to occupied cell centres, so a point deep inside a
  wall or outside the home is far from every surface, not "on an obstacle";
- the field is resampled bilinearly onto a grid ``upsample`` times finer, so one
  table look-up per beam (the cost that matters) gives a nearly continuous field.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from homebot.world import OccupancyGrid

__all__ = ["LikelihoodField"]


@dataclass(frozen=True)
class LikelihoodField:
    """Distances (metres) from each fine cell's centre to the nearest obstacle surface.

    ``distances`` has ``shape`` (rows along y, columns along x) of cells ``resolution``
    metres wide, starting at ``origin``; distances are capped at ``max_distance``.
    """

    origin: tuple[float, float]
    resolution: float
    shape: tuple[int, int]
    distances: np.ndarray
    solid: np.ndarray  #: fine cells inside walls or furniture

    @classmethod
    def from_grid(cls, grid: OccupancyGrid, *, upsample: int = 2,
                  max_distance: float = 2.0) -> LikelihoodField:
        """The field of ``grid.occupied`` (walls and furniture, not inflated)."""
        occupied = grid.occupied
        resolution = grid.resolution
        free_neighbour = ndimage.binary_dilation(~occupied, structure=np.ones((3, 3), bool))
        border = occupied & free_neighbour
        if not border.any():  # no obstacle at all: every point is far from everything
            coarse = np.full(grid.shape, max_distance)
        else:
            to_border = ndimage.distance_transform_edt(~border) * resolution
            # The surface lies half a cell from a border cell's centre: outwards in free
            # space, inwards inside the solid.
            coarse = np.where(occupied, to_border + resolution / 2,
                              np.maximum(to_border - resolution / 2, 0.0))
        rows, columns = grid.shape[0] * upsample, grid.shape[1] * upsample
        # Fine cell centres in coarse index coordinates (coarse centres at integers).
        fine_rows = (np.arange(rows) + 0.5) / upsample - 0.5
        fine_columns = (np.arange(columns) + 0.5) / upsample - 0.5
        coordinates = np.meshgrid(fine_rows, fine_columns, indexing="ij")
        fine = ndimage.map_coordinates(coarse, coordinates, order=1, mode="nearest")
        distances = np.minimum(fine, max_distance).astype(np.float32)
        solid = np.repeat(np.repeat(occupied, upsample, axis=0), upsample, axis=1)
        return cls(grid.origin, resolution / upsample, (rows, columns), distances, solid)

    def distance_at(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """The field at world points (arrays of equal shape); points off the map take the edge."""
        column = np.clip(((x - self.origin[0]) / self.resolution).astype(np.int64),
                         0, self.shape[1] - 1)
        row = np.clip(((y - self.origin[1]) / self.resolution).astype(np.int64),
                      0, self.shape[0] - 1)
        values: np.ndarray = self.distances[row, column]
        return values

    def raycast(self, x: float, y: float, angles: np.ndarray, range_max: float) -> np.ndarray:
        """Ranges from (x, y) along ``angles`` to the first solid cell (inf beyond ``range_max``).

        Every ray is sampled a fine cell apart up to its first solid cell (walls and
        furniture are several cells thick, so none is stepped over); points off the map
        are free.
        """
        from homebot.navigation import beams  # numba: only once the filter weighs a scan

        cells = np.arange(1, int(range_max / self.resolution) + 1, dtype=np.float32)
        steps = cells * self.resolution
        hits: np.ndarray = beams.raycast(
            self.solid, np.float32((x - self.origin[0]) / self.resolution),
            np.float32((y - self.origin[1]) / self.resolution),
            np.cos(angles).astype(np.float32), np.sin(angles).astype(np.float32), cells, steps)
        return hits
