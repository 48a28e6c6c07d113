"""Argument types for benchmarks: sizes, seeds, files, disturbance levels, the fidelity and
``--plot``.

They raise ``BenchmarkError`` (a ``HomebotError``), which the command line prints as one
line with exit status 2, so ``--count 0`` never reaches ``statistics.median([])`` and
``--count 10**12`` never starts an endless run.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from pathlib import Path

from homebot.errors import BenchmarkError
from homebot.seeds import MAX_SEED, seed  # the one ``--seed`` type every command shares

__all__ = ["MAX_SEED", "add_fidelity_option", "add_plot_option", "count", "disturbance_level",
           "plot_file", "readable_file", "seed"]



def count(option: str, low: int = 1, high: int = 100_000) -> Callable[[str], int]:
    """An argument type for ``option``: a whole number from ``low`` to ``high``."""
    def whole(text: str) -> int:
        stripped = text.strip()
        number = int(stripped) if stripped.lstrip("-").isdigit() else None
        if number is None or not low <= number <= high:
            raise BenchmarkError(f"{option} {text!r}: give a whole number from {low} to "
                                 f"{high:,}".replace(",", " "))
        return number
    whole.__name__ = option.lstrip("-")  # argparse names the type in its own messages
    return whole


def readable_file(option: str) -> Callable[[str], Path]:
    """An argument type for ``option``: a file that exists and can be read."""
    def path(text: str) -> Path:
        candidate = Path(text)
        try:
            with candidate.open("rb") as handle:
                handle.read(1)
        except IsADirectoryError:
            raise BenchmarkError(f"{option} {text}: is a folder; give a file") from None
        except OSError as error:
            raise BenchmarkError(f"{option} {text}: cannot be read "
                                 f"({error.strerror or error}); check the path") from None
        return candidate
    path.__name__ = option.lstrip("-")
    return path


def disturbance_level(text: str) -> float:
    """An argument type for ``--level``: a level for ``homebot.app.disturbed``, 0 (none) to 6
    (90 % of grasps slip); argparse refuses anything else as a usage error."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0.0 <= value <= 6.0:  # also false for nan
        raise argparse.ArgumentTypeError(f"a disturbance level is a number from 0 to 6, "
                                         f"not '{text}'")
    return value


def add_fidelity_option(parser: argparse.ArgumentParser) -> None:
    """``--fidelity symbolic|embodied``: the robot a benchmark's runs are built with."""
    from homebot.app import Fidelity  # only the benchmarks that build runs load the app

    parser.add_argument("--fidelity", type=Fidelity, choices=list(Fidelity),
                        default=Fidelity.SYMBOLIC,
                        help="symbolic (fast, the default) or embodied (the robot localises "
                             "from its laser and drives with the reactive planner)")


def plot_file(text: str) -> Path:
    """An argument type for ``--plot``: a new or old ``.png`` file in a folder that exists,
    refused before the benchmark runs when matplotlib (the ``plots`` extra) is missing."""
    path = Path(text)
    if path.suffix.lower() != ".png":
        raise BenchmarkError(f"--plot {text}: give a file name ending in .png")
    if not path.parent.is_dir():
        raise BenchmarkError(f"--plot {text}: the folder {path.parent} does not exist; "
                             "create it or choose another")
    if path.is_dir():
        raise BenchmarkError(f"--plot {text}: is a folder; give a file")
    from homebot.bench.plots import require

    require()
    return path


def add_plot_option(parser: argparse.ArgumentParser, what: str) -> None:
    """``--plot FILE.png``: draw ``what`` into a picture (matplotlib, the ``plots`` extra)."""
    parser.add_argument("--plot", type=plot_file, default=None, metavar="FILE.png",
                        help=f"also draw {what} into FILE.png (needs the plots extra: "
                             "pip install 'homebot[plots]')")
