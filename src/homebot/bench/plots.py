"""Pictures of benchmark results (``--plot FILE.png``), drawn with matplotlib (the ``plots`` extra).

Each ``*_figure`` function is pure: it takes what its benchmark measured (its figures,
and the series behind them that the figures sum up) and returns a matplotlib ``Figure``,
never re-running anything; ``save`` writes one as a PNG. Figures are drawn on the Agg
canvas without ``pyplot``: no window, no global figure state.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from homebot.errors import BenchmarkError

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["INSTALL", "htn_figure", "localisation_figure", "navigation_figure", "require",
           "robustness_figure", "save", "speech_figure", "sweep_figure"]

INSTALL = "pip install 'homebot[plots]'"
_DPI = 110


def require() -> None:
    """Raise ``BenchmarkError`` saying how to install matplotlib, when it is missing."""
    if importlib.util.find_spec("matplotlib") is None:
        raise BenchmarkError(f"--plot needs matplotlib, the 'plots' extra: {INSTALL}")


def _figure(columns: int, width: float = 6.0, height: float = 4.5) -> tuple[Figure, list[Axes]]:
    require()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(width * columns, height), dpi=_DPI, layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.subplots(1, columns, squeeze=False)[0]
    return figure, list(axes)


def save(figure: Figure, path: Path) -> None:
    """Write ``figure`` to ``path`` as a PNG (a ``BenchmarkError`` when it cannot be)."""
    try:
        figure.savefig(path, format="png")
    except OSError as error:
        raise BenchmarkError(f"--plot {path}: cannot be written ({error.strerror or error}); "
                             "check the folder") from None


def navigation_figure(obstacles: np.ndarray, extent: tuple[float, float, float, float],
                      goals: Sequence[tuple[float, float]],
                      paths: Mapping[str, Sequence[Sequence[tuple[float, float]]]],
                      angular: Mapping[str, Sequence[float]], first: int = 0) -> Figure:
    """The true paths each local controller drove over the map, and how smoothly: for
    each angular acceleration, the share of control periods at or above it.

    Args:
        obstacles: the occupancy grid's occupied cells (row 0 at the lowest y).
        extent: (min x, min y, max x, max y) the grid covers, metres.
        goals: the goals driven to, in order.
        paths: per controller, the true (x, y) at each control period of each goal.
        angular: per controller, |angular acceleration| at each control period, rad/s².
        first: the number of the first goal (``--from``).
    """
    figure, (where, smooth) = _figure(2, width=6.5, height=5.5)
    min_x, min_y, max_x, max_y = extent
    where.imshow(obstacles, origin="lower", extent=(min_x, max_x, min_y, max_y),
                 cmap="Greys", vmin=0, vmax=1.6, interpolation="nearest")
    for (name, drives), colour in zip(paths.items(), ("tab:blue", "tab:orange", "tab:green"),
                                      strict=False):
        moved = [path for path in drives if len(path) > 1]
        for index, path in enumerate(moved):
            xs, ys = zip(*path, strict=True)
            where.plot(xs, ys, color=colour, linewidth=1.0, alpha=0.8,
                       label=name if index == 0 else None)
    if goals:
        xs, ys = zip(*goals, strict=True)
        where.scatter(xs, ys, marker="x", color="crimson", s=30, zorder=3,
                      label="goals (numbered as the figures list them)")
        for index, goal in enumerate(goals, start=first):
            where.annotate(str(index), goal, textcoords="offset points", xytext=(4, 4),
                           fontsize="x-small", color="crimson")
    where.set(title="True paths driven to the goals", xlabel="x (m)", ylabel="y (m)",
              aspect="equal")
    where.legend(loc="upper right", fontsize="small")
    for (name, values), colour in zip(angular.items(), ("tab:blue", "tab:orange", "tab:green"),
                                      strict=False):
        ordered = np.sort(np.asarray(values, dtype=float))
        if ordered.size:
            above = 1.0 - np.arange(ordered.size) / ordered.size  # share at or above each
            smooth.step(ordered, 100 * above, where="post", color=colour,
                        label=f"{name}: mean {ordered.mean():.2f} rad/s²")
    smooth.set(title="Smoothness: lower is smoother",
               xlabel="|angular acceleration| of the base (rad/s²)",
               ylabel="control periods at or above it (%)", yscale="log")
    smooth.grid(True, which="both", alpha=0.3)
    smooth.legend(fontsize="small")
    return figure


def localisation_figure(errors: Mapping[str, Sequence[Sequence[float]]],
                        tick_period: float) -> Figure:
    """Monte Carlo localisation's position error over the tracking drives: the median and
    the 5-95 % band across runs at each moment, one curve per experiment.

    Args:
        errors: per experiment, each run's error (m) at every tick.
        tick_period: simulated seconds per tick.
    """
    figure, (axes,) = _figure(1, width=8.0)
    for (name, runs), colour in zip(errors.items(), ("tab:blue", "tab:orange", "tab:green"),
                                    strict=False):
        runs = [run for run in runs if len(run)]
        if not runs:
            continue
        length = min(len(run) for run in runs)
        stack = 100 * np.asarray([run[:length] for run in runs], dtype=float)
        seconds = tick_period * np.arange(1, length + 1)
        axes.plot(seconds, np.median(stack, axis=0), color=colour,
                  label=f"{name}: median of {len(runs)} run(s)")
        if len(runs) > 1:
            axes.fill_between(seconds, np.percentile(stack, 5, axis=0),
                              np.percentile(stack, 95, axis=0), color=colour, alpha=0.2,
                              label=f"{name}: 5-95 % of runs")
    axes.axhline(20, color="grey", linestyle="--", linewidth=1,
                 label="20 cm: the bound the figures count runs over")
    axes.set(title="Localisation error while driving (by the truth)",
             xlabel="simulated time (s)", ylabel="position error (cm)")
    axes.set_ylim(bottom=0)
    axes.legend(fontsize="small")
    return figure


def _grouped_bars(axes: Axes, groups: Sequence[str], series: Mapping[str, Sequence[float]],
                  counts: Mapping[str, Sequence[int]] | None = None) -> None:
    """Bars of ``series`` (share 0-1, drawn in %) side by side in each group, each with
    its count above it."""
    width = 0.8 / max(len(series), 1)
    positions = np.arange(len(groups))
    for offset, (name, values) in enumerate(series.items()):
        bars = axes.bar(positions + (offset - (len(series) - 1) / 2) * width,
                        [100 * value for value in values], width, label=name)
        if counts is not None:
            axes.bar_label(bars, labels=[f"n={n}" for n in counts[name]], fontsize="x-small")
    axes.set_xticks(positions, groups, rotation=20, ha="right")
    axes.set_ylim(0, 128)  # room above 100 % for the legend
    axes.set_yticks(range(0, 101, 20))
    axes.legend(loc="upper center", ncols=len(series), fontsize="small")


def robustness_figure(results: Sequence[Mapping[str, Any]], level: float) -> Figure:
    """Each execution mode's verified deliveries by the disturbances the simulator logged
    in the task's run (a run with two counts under both), beside the runs with none.

    Args:
        results: the benchmark's per-mode figures, each with ``by_disturbance``.
        level: the disturbance level the tasks ran at.
    """
    figure, (axes,) = _figure(1, width=9.0)
    kinds = sorted({kind for result in results for kind in result["by_disturbance"]},
                   key=lambda kind: (kind == "none", kind))
    shares = {result["mode"]: [_rate(result["by_disturbance"].get(kind)) for kind in kinds]
              for result in results}
    counts = {result["mode"]: [result["by_disturbance"].get(kind, {}).get("tasks", 0)
                               for kind in kinds] for result in results}
    _grouped_bars(axes, [kind.replace("_", " ") for kind in kinds], shares, counts)
    axes.set(title=f"Verified deliveries by disturbance in the run (level {level:g})",
             xlabel="disturbance in the run (the simulator's log)",
             ylabel="verified deliveries (%)")
    return figure


def _rate(counts: Mapping[str, int] | None) -> float:
    if not counts or not counts["tasks"]:
        return 0.0
    return counts["verified"] / counts["tasks"]


def speech_figure(worlds: Mapping[str, Mapping[str, Any]], conditions: Sequence[str]) -> Figure:
    """Command accuracy for each voice, in each listening condition (all worlds together).

    Args:
        worlds: the benchmark's per-world figures, each condition with ``by_voice``.
        conditions: the conditions heard ("clean", "noisy", "babble").
    """
    figure, (axes,) = _figure(1, width=9.0)
    voices: list[str] = []
    totals: dict[str, dict[str, list[int]]] = {condition: {} for condition in conditions}
    for figures in worlds.values():
        for condition in conditions:
            for voice, tally in figures[condition]["by_voice"].items():
                if voice not in voices:
                    voices.append(voice)
                clips, correct = totals[condition].setdefault(voice, [0, 0])
                totals[condition][voice] = [clips + tally["clips"], correct + tally["correct"]]
    shares = {condition: [totals[condition].get(voice, [0, 0])[1] /
                          max(totals[condition].get(voice, [0, 0])[0], 1) for voice in voices]
              for condition in conditions}
    counts = {condition: [totals[condition].get(voice, [0, 0])[0] for voice in voices]
              for condition in conditions}
    _grouped_bars(axes, voices, shares, counts)
    axes.set(title="Spoken commands understood, by voice and listening condition",
             xlabel="voice (espeak-ng name @ words per minute)",
             ylabel="commands understood (%)")
    return figure


def htn_figure(tidy: Sequence[Mapping[str, Any]]) -> Figure:
    """Tidy-up planning time against the number of misplaced objects: our planner, and
    GTPyhop where it ran in the same process (log-log: the slope is the growth's power).

    Args:
        tidy: the benchmark's tidy-up rows (``misplaced``, ``ms``, ``gtpyhop_ms``).
    """
    figure, (axes,) = _figure(1, width=7.0)
    sizes = [row["misplaced"] for row in tidy]
    axes.plot(sizes, [row["ms"] for row in tidy], marker="o", label="homebot HTN planner")
    compared = [(row["misplaced"], row["gtpyhop_ms"]) for row in tidy if "gtpyhop_ms" in row]
    if compared:
        axes.plot(*zip(*compared, strict=True), marker="s", label="GTPyhop (same run)")
    axes.set(title="Tidy-up planning time by size", xlabel="misplaced objects",
             ylabel="planning time, median (ms)", xscale="log", yscale="log")
    axes.set_xticks(sizes, [str(size) for size in sizes])
    axes.minorticks_off()
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    return figure


def sweep_figure(cells: Sequence[Mapping[str, Any]]) -> Figure:
    """A sweep's verified share against the disturbance level: one panel per benchmark and
    fidelity, one line per world and mode, the mean over the seeds with their range.

    Args:
        cells: ``homebot.bench.sweep.cell_figures``: per cell and mode, ``level`` and
            ``verified_rate`` with the cell's names.
    """
    panels = list(dict.fromkeys((cell["benchmark"], cell["fidelity"]) for cell in cells))
    figure, axes_list = _figure(len(panels), width=6.5)
    for axes, (benchmark, fidelity) in zip(axes_list, panels, strict=True):
        rates: dict[tuple[str, str], dict[float, list[float]]] = {}
        for cell in cells:
            if (cell["benchmark"], cell["fidelity"]) == (benchmark, fidelity):
                line = rates.setdefault((cell["world"], cell["mode"]), {})
                line.setdefault(float(cell["level"]), []).append(100 * cell["verified_rate"])
        for (world, mode), by_level in rates.items():
            levels = sorted(by_level)
            means = np.array([np.mean(by_level[level]) for level in levels])
            low = means - np.array([min(by_level[level]) for level in levels])
            high = np.array([max(by_level[level]) for level in levels]) - means
            axes.errorbar(levels, means, yerr=[low, high], marker="o", capsize=3,
                          label=f"{world}, {mode}")
        axes.set(title=f"{benchmark} ({fidelity}): verified by the truth",
                 xlabel="disturbance level", ylabel="verified (%), mean and range over seeds")
        axes.set_ylim(0, 105)
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize="small")
    return figure
