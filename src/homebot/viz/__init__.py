"""Pictures of the home: a pure renderer of the world (and a run on it) to an image."""

from homebot.viz.embodied import EmbodiedRun, embodied_run
from homebot.viz.map_image import Canvas, FinalState, final_state, render_map

__all__ = ["Canvas", "EmbodiedRun", "FinalState", "embodied_run", "final_state", "render_map"]
