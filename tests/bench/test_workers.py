"""Tasks on worker processes: outcomes in order, a raising task, a worker killed mid-task,
and the standard library's pool when Dask (the cluster extra) is missing.

The killing tasks kill their own process with SIGKILL, as ``kill -9`` or the kernel's
out-of-memory killer would, at a point fixed by the unit (deterministic).
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

import pytest

import homebot.bench.workers as workers
from homebot.bench.workers import WorkerOptions, run_tasks
from homebot.errors import BenchmarkError

needs_dask = pytest.mark.skipif(not workers.engine_installed(),
                                reason="the cluster extra (Dask distributed) is not installed")


def square(number: int) -> int:  # a task for the refusals, which never run it
    return number * number


def refuse_three(number: int) -> int:
    if number == 3:
        raise ValueError("three is refused")
    return number


def die_at(unit: tuple[str, int]) -> int:
    """Unit (folder, n): n == 2 kills its worker the first time only (a marker in the
    folder remembers), n == 5 every time; the others return n."""
    folder, number = unit
    marker = Path(folder) / f"died-{number}"
    if number == 5 or (number == 2 and not marker.exists()):
        marker.touch()
        os.kill(os.getpid(), signal.SIGKILL)
    return number


def test_one_worker_runs_in_this_process_and_a_raising_task_is_an_error() -> None:
    outcomes = run_tasks(refuse_three, list(range(5)), WorkerOptions(1))
    assert [outcome.value for outcome in outcomes] == [0, 1, 2, None, 4]
    assert outcomes[3].error == "ValueError: three is refused"
    assert [outcome.attempts for outcome in outcomes] == [1] * 5  # a raise is not retried
    assert {outcome.worker.rsplit(":", 1)[1] for outcome in outcomes} == {str(os.getpid())}


def _check_killed_workers(outcomes: list[workers.TaskOutcome[int]]) -> None:
    assert [outcome.value for outcome in outcomes] == [0, 1, 2, 3, 4, None, 6, 7]
    retried_once = outcomes[2]
    assert retried_once.attempts == 2 and retried_once.error is None
    lost = outcomes[5]
    assert lost.attempts == 2 and lost.error is not None and "worker lost" in lost.error


@needs_dask
def test_a_killed_dask_worker_loses_only_its_task_retried_once(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(workers, "MAX_BATCH", 1)  # as long tasks go: one at a time
    outcomes = run_tasks(die_at, [(str(tmp_path), n) for n in range(8)], WorkerOptions(2))
    _check_killed_workers(outcomes)
    assert [outcome.index for outcome in outcomes] == list(range(8))
    assert str(os.getpid()) not in {outcome.worker.rsplit(":", 1)[-1] for outcome in outcomes}
    # one task per worker at a time: the deaths involved no other task
    assert [outcome.attempts for index, outcome in enumerate(outcomes)
            if index not in (2, 5)] == [1] * 6


def test_without_dask_the_process_pool_runs_them_and_says_so(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
        tmp_path: Path) -> None:
    monkeypatch.setattr(workers, "engine_installed", lambda: False)
    outcomes = run_tasks(die_at, [(str(tmp_path), n) for n in range(8)], WorkerOptions(2))
    assert "the 'cluster' extra (Dask distributed) is not installed: running on 2 processes " \
           "of the standard library's process pool" in capsys.readouterr().err
    # the pool breaks whole: the tasks in flight beside a death ran again, no more
    _check_killed_workers(outcomes)
    assert sum(outcome.attempts > 1 for outcome in outcomes) <= 2 * 2


@needs_dask
def test_a_lost_batch_runs_again_task_by_task(tmp_path: Path) -> None:
    """Short tasks go in batches: a death loses its batch, whose tasks run again alone."""
    units = [(str(tmp_path), n) for n in range(40) if n not in (2, 5)] + [(str(tmp_path), 2)]
    outcomes = run_tasks(die_at, units, WorkerOptions(2))
    assert [outcome.value for outcome in outcomes] == [unit[1] for unit in units]
    retried = [outcome for outcome in outcomes if outcome.retried]
    assert outcomes[-1] in retried and all(outcome.error is None for outcome in retried)


def test_short_tasks_go_in_batches_and_long_ones_alone() -> None:
    assert workers.batch_size([]) == 1  # nothing known yet
    assert workers.batch_size([3.0, 0.05, 0.05]) == int(workers.BATCH_SECONDS / 0.05)
    assert workers.batch_size([15.0, 14.0]) == 1
    assert workers.batch_size([1e-9]) == workers.MAX_BATCH


@needs_dask
def test_batches_come_back_whole_and_in_order() -> None:
    outcomes = run_tasks(refuse_three, list(range(200)), WorkerOptions(2))
    assert [outcome.value for outcome in outcomes] == [None if n == 3 else n
                                                       for n in range(200)]
    assert outcomes[3].error == "ValueError: three is refused"
    assert len({outcome.worker for outcome in outcomes}) == 2


def test_a_cluster_without_dask_is_refused_with_the_install_line(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(workers, "engine_installed", lambda: False)
    with pytest.raises(BenchmarkError, match=r"--cluster needs the 'cluster' extra \(Dask "
                                             r"distributed\): pip install 'homebot\[cluster\]'"):
        run_tasks(square, [1, 2], WorkerOptions(cluster="tcp://127.0.0.1:8786"))


@needs_dask
def test_a_cluster_address_where_no_scheduler_answers_is_one_clear_error(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(workers, "CONNECT_SECONDS", 1.0)
    with pytest.raises(BenchmarkError, match=r"--cluster tcp://127\.0\.0\.1:9: no Dask "
                                             r"scheduler answers there"):
        run_tasks(square, [1, 2], WorkerOptions(cluster="tcp://127.0.0.1:9"))


@needs_dask
def test_a_running_cluster_runs_them_and_says_when_its_scheduler_retries_itself(
        capsys: pytest.CaptureFixture[str]) -> None:
    from distributed import LocalCluster

    # in-process workers (threads): the cluster's address is what is tested, not its processes
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False, protocol="tcp",
                      host="127.0.0.1",
                      dashboard_address="127.0.0.1:0") as cluster:
        outcomes = run_tasks(refuse_three, list(range(6)),
                             WorkerOptions(cluster=cluster.scheduler_address))
    assert [outcome.value for outcome in outcomes] == [0, 1, 2, None, 4, 5]
    assert "its scheduler reruns a task whose worker died up to 3 times itself" in \
        capsys.readouterr().err
