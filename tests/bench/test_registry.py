"""Every registered benchmark: its ``--help``, and a tiny run through the real command line.

A tiny run is the smallest arguments that still go through the benchmark's code: one task,
one seed, few samples; the parts that take minutes whatever their size (the face forests,
the load test) are left out with ``--only``. The figures are
checked for their shape, never for their values or their timing.
"""

from __future__ import annotations

import json
from typing import Any

import pytest

from homebot.bench import BENCHMARKS, EXTRA_MODULES, Benchmark, benchmark, missing_extras
from homebot.cli import main
from homebot.errors import BenchmarkError

#: name -> (the tiny run's arguments, the figures' top-level keys, keys under "figures")
TINY: dict[str, tuple[list[str], set[str], set[str]]] = {
    "parse": (["--count", "3", "--repeat", "1"], {"median_ms", "commands", "source"}, set()),
    "kb": (["--individuals", "10", "--chains", "5", "--repeat", "1"],
           {"chained_defaults", "generated"}, set()),
    "kb_original": (["--individuals", "10", "--queries", "1", "--time-limit", "1"], set(),
                    set()),
    "sitlog": (["--repeat", "1"], {"situations", "listing_a6_exact", "warm_median_ms"}, set()),
    "golog": (["--repeats", "1", "--maze-horizon", "2", "--cups-horizon", "1"], {"figures"},
              {"maze, memo on"}),
    "maintenance": (["--runs", "1", "--actions", "1", "--components", "2",
                     "--constraints", "1"], {"repairs", "speed"}, set()),
    "referring": (["--scenes", "1", "--repeats", "1"], {"scenes", "outcomes"}, set()),
    "htn": (["--repeats", "1", "--sizes", "1", "--runs", "1"], {"figures"},
            {"table1", "tidy", "execution"}),
    "inference": (["--worlds", "1", "--requests", "1"], {"worlds", "requests"}, set()),
    "gpsr": (["--commands", "1"], {"commands", "success_rate", "judged_by"}, set()),
    "robustness": (["--tasks", "1", "--workers", "1"], {"tasks", "modes"}, set()),
    "fetch": (["--tasks", "1"], {"tasks", "figures"}, {"warm_speedup_in_this_run"}),
    "startup": (["--runs", "1"], {"runs", "figures", "load_average_before_after"},
                {"homebot --help", "parse, cold (no names kept)"}),
    "long_run": (["--tasks", "1", "--warm-up", "0", "--keep", "1"],
                 {"tasks", "succeeded", "ms_per_task"}, set()),
    "navigation": (["--repeat", "1", "--goals", "0"], {"figures"},
                   {"apartment plan (all placement pairs)"}),
    "localisation": (["--runs", "1", "--only", "timing"], {"runs", "figures"},
                     {"update timing"}),
    "perception": (["--scenes", "1", "--only", "objects"], {"figures"}, {"objects"}),
    "guide": (["--runs", "1", "--world", "family_home"], {"success_rate", "ran", "episodes"},
              set()),
    "follow": (["--runs", "1", "--seed", "7", "--worlds", "apartment"],
               {"success_rate", "ran", "episodes"}, set()),
    "manipulation": (["--scenes", "1", "--hri-trials", "1"], {"figures"},
                     {"grasping", "physical HRI"}),
    "speech": (["--count", "1", "--rejection", "0", "--babble-talkers", "0",
                "--worlds", "apartment"], {"command_accuracy", "worlds", "speed"}, set()),
    "console": (["--trials", "1", "--clients", "0"], {"figures"}, {"estop_navigation"}),
    "console_fuzz": (["--requests", "20", "--big-mb", "1"], {"figures"},
                     {"fuzz", "unauthenticated_post"}),
    "transport": (["--seconds", "1", "--only", "throughput"], {"laser_scan"}, set()),
    "serve_fuzz": (["--requests", "20", "--warm-up", "5", "--only", "sim"], {"servers", "seed"},
                   set()),
}


def test_every_registered_benchmark_has_a_tiny_run_here() -> None:
    assert sorted(TINY) == sorted(entry.name for entry in BENCHMARKS)


def test_the_registry_names_modules_that_exist_and_extras_that_pyproject_has() -> None:
    import importlib.util

    for entry in BENCHMARKS:
        assert importlib.util.find_spec(entry.module) is not None, entry.module
        assert entry.help and entry.help == entry.help.strip()
        assert set(entry.extras) <= set(EXTRA_MODULES)
    assert len({entry.name for entry in BENCHMARKS}) == len(BENCHMARKS)


def test_an_unknown_benchmark_is_refused_with_the_choices() -> None:
    with pytest.raises(BenchmarkError, match="no benchmark 'gpsr_truth': choose one of parse"):
        benchmark("gpsr_truth")


def test_a_helper_module_is_no_benchmark(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["bench", "arguments"])
    assert exit_info.value.code == 2
    assert "invalid choice: 'arguments'" in capsys.readouterr().err


def test_a_missing_extra_is_named_and_all_carries_on(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    import homebot.bench
    import homebot.cli.bench

    lonely = Benchmark("lonely", "homebot.bench.nosuch", "needs what is not here", ("web",))
    monkeypatch.setitem(homebot.bench.EXTRA_MODULES, "web", ("homebot_no_such_library",))
    assert missing_extras(lonely) == ["web"]
    monkeypatch.setattr(homebot.cli.bench, "BENCHMARKS", (lonely, benchmark("sitlog")))
    assert main(["bench", "all", "--json"]) == 0
    skipped, sitlog = json.loads(capsys.readouterr().out)
    assert skipped == {"benchmark": "lonely", "skipped": "bench lonely needs the 'web' extra: "
                                                         "pip install 'homebot[web]'"}
    assert sitlog["benchmark"] == "sitlog"


def _runnable(entry: Benchmark) -> Any:
    missing = missing_extras(entry)
    marks = [pytest.mark.skip(reason=f"the {', '.join(missing)} extra is not installed")
             ] if missing else []
    return pytest.param(entry.name, id=entry.name, marks=marks)


@pytest.mark.parametrize("name", [_runnable(entry) for entry in BENCHMARKS])
def test_help_and_a_tiny_run(name: str, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["bench", name, "--help"])
    assert exit_info.value.code == 0
    assert f"usage: homebot bench {name}" in capsys.readouterr().out
    arguments, keys, figure_keys = TINY[name]
    assert main(["bench", name, *arguments, "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)
    assert figures["benchmark"] == name
    if "skipped" in figures:  # kb_original without SWI-Prolog and a SitLog checkout
        assert figures["skipped"].startswith("skipped: ")
        return
    assert keys <= set(figures)
    assert figure_keys <= set(figures.get("figures", {}))
