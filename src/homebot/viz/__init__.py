"""Pictures of the home: a pure renderer of the world (and a path) to an image."""

from homebot.viz.embodied import EmbodiedRun, embodied_run
from homebot.viz.map_image import render_map

__all__ = ["EmbodiedRun", "embodied_run", "render_map"]
