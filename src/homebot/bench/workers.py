"""Seeded tasks run on many worker processes: a local pool, or a running Dask cluster.

A benchmark or a sweep hands ``run_tasks`` a module-level function and a list of picklable
task units (one seeded task each); it gets back one ``TaskOutcome`` per unit, in the units'
order, whatever order the workers finished them in. A task's result depends only on its unit
(its seed is the benchmark's seed and the task's index), so the outcomes are the same for 1,
2 or N workers, apart from timings and which worker ran what.

The scheduling is Dask distributed's (the ``cluster`` extra): a ``LocalCluster`` of
``workers`` single-threaded processes on loopback, or the scheduler at ``--cluster
ADDRESS``. Dask was chosen over Ray for its light footprint on a small machine (pure Python
over tornado, a scheduler in this process, no object store or raylet) and for its plain
``dask scheduler`` / ``dask worker`` commands for a cluster. Without the extra, ``--workers``
falls back to the standard library's ``ProcessPoolExecutor`` and says so.

Short tasks go to a Dask worker in batches of about ``BATCH_SECONDS`` of work (``batch_size``);
a long task goes alone.

Faults: the tasks whose worker dies (killed, out of memory: its task, or its batch of short
ones) run once more, one by one, on another worker; a task whose worker dies again is an error
(``attempts`` 2), never a gap. A task that raises is an error at once (it would raise again).
The process pool breaks whole when a process dies, so it cannot tell which task in flight
killed it: it runs each of them again, alone.
"""

from __future__ import annotations

import argparse
import importlib.util
import logging
import os
import socket
import statistics
import sys
import time
import uuid
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager
from dataclasses import dataclass
from multiprocessing import get_context
from typing import Any, Generic, TypeVar

from homebot.bench.arguments import count
from homebot.errors import BenchmarkError
from homebot.progress import task

__all__ = ["ATTEMPTS", "BATCH_SECONDS", "CONNECT_SECONDS", "MAX_BATCH", "WORKERS_SECONDS",
           "TaskOutcome", "WorkerOptions", "add_worker_options", "batch_size", "cores",
           "each_outcome", "engine_installed", "run_tasks", "worker_options"]

_Unit = TypeVar("_Unit")
_Value = TypeVar("_Value")

#: A task is run at most this often: once, and once more when its worker died.
ATTEMPTS = 2
#: Seconds of work sent to a Dask worker at a time, and at most this many tasks together.
BATCH_SECONDS = 0.5
MAX_BATCH = 100
#: Seconds ``--cluster`` waits for its scheduler to answer, and then for a worker.
CONNECT_SECONDS = 10.0
WORKERS_SECONDS = 60.0


def cores() -> int:
    """The cores this process may run on (the default number of workers)."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (
        os.cpu_count() or 1)


def engine_installed() -> bool:
    """Whether Dask distributed (the ``cluster`` extra) is installed, found without importing."""
    return importlib.util.find_spec("distributed") is not None


@dataclass(frozen=True)
class WorkerOptions:
    """Where tasks run: ``workers`` local processes, or the Dask scheduler at ``cluster``."""

    workers: int = 1
    cluster: str | None = None


def add_worker_options(parser: argparse.ArgumentParser) -> None:
    """``--workers N`` and ``--cluster ADDRESS``."""
    parser.add_argument("--workers", type=count("--workers", 1, 1024), default=None,
                        metavar="N",
                        help=f"worker processes on this machine (default: its cores, {cores()} "
                             "here); 1 runs the tasks in this process, one after another")
    parser.add_argument("--cluster", default=None, metavar="ADDRESS",
                        help="run the tasks on the Dask scheduler at ADDRESS (e.g. "
                             "tcp://127.0.0.1:8786) instead of local workers (cluster extra)")


def worker_options(args: argparse.Namespace) -> WorkerOptions:
    """The options ``add_worker_options`` parsed (``--workers`` defaults to the cores)."""
    workers = args.workers if args.workers is not None else cores()
    return WorkerOptions(workers=workers, cluster=args.cluster)


@dataclass(frozen=True)
class TaskOutcome(Generic[_Value]):
    """What became of one task: its value, or why there is none."""

    index: int  #: the unit's place in the list given to ``run_tasks``
    value: _Value | None  #: what the task returned (None on an error)
    error: str | None = None  #: "Type: message" of an exception, or the workers it killed
    attempts: int = 1  #: 2 when its first worker died and it ran again
    worker: str = ""  #: host:pid of the process that ran it last (differs from run to run)

    @property
    def retried(self) -> bool:
        return self.attempts > 1


@dataclass(frozen=True)
class _Attempt(Generic[_Value]):
    value: _Value | None
    error: str | None
    worker: str
    seconds: float = 0.0  #: wall time, for sizing batches (never in the results)


def _attempt(function: Callable[[_Unit], _Value], unit: _Unit) -> _Attempt[_Value]:
    """Run one task where it was sent; its exception becomes an error, not a lost worker."""
    worker = f"{socket.gethostname()}:{os.getpid()}"
    started = time.perf_counter()
    try:
        value = function(unit)
    except Exception as error:  # a task's own failure is its outcome; the others go on
        return _Attempt(None, f"{type(error).__name__}: {error}", worker,
                        time.perf_counter() - started)
    return _Attempt(value, None, worker, time.perf_counter() - started)


def _outcome(index: int, attempt: _Attempt[_Value], attempts: int) -> TaskOutcome[_Value]:
    return TaskOutcome(index, attempt.value, attempt.error, attempts, attempt.worker)


def _lost(index: int, attempts: int, why: str) -> TaskOutcome[Any]:
    return TaskOutcome(index, None, f"worker lost: {why} (tried {attempts} times)", attempts)


def each_outcome(function: Callable[[_Unit], _Value], units: Sequence[_Unit],
                 options: WorkerOptions, description: str = "tasks"
                 ) -> Iterator[TaskOutcome[_Value]]:
    """Every unit's outcome of ``function`` (a module-level function, so workers can import
    it), as each task finishes."""
    if not units:
        return
    with task(description, len(units)) as under_way:
        for outcome in _engine(options, len(units))(function, units):
            yield outcome
            under_way.advance()


def run_tasks(function: Callable[[_Unit], _Value], units: Sequence[_Unit],
              options: WorkerOptions, description: str = "tasks") -> list[TaskOutcome[_Value]]:
    """Every unit's outcome of ``function``, in the units' order."""
    outcomes = {outcome.index: outcome
                for outcome in each_outcome(function, units, options, description)}
    return [outcomes[index] for index in range(len(units))]


_Engine = Callable[[Callable[[Any], Any], Sequence[Any]], Iterator[TaskOutcome[Any]]]


def _engine(options: WorkerOptions, tasks: int) -> _Engine:
    if options.cluster is not None:
        if not engine_installed():
            raise BenchmarkError("--cluster needs the 'cluster' extra (Dask distributed): "
                                 "pip install 'homebot[cluster]'")
        address = options.cluster
        return lambda function, units: _on_dask(function, units, address=address)
    workers = min(options.workers, tasks)
    if workers <= 1:
        return _in_this_process
    if not engine_installed():
        print(f"the 'cluster' extra (Dask distributed) is not installed: running on "
              f"{workers} processes of the standard library's process pool instead "
              "(pip install 'homebot[cluster]' for clusters)", file=sys.stderr)
        return lambda function, units: _on_process_pool(function, units, workers)
    return lambda function, units: _on_dask(function, units, workers=workers)


def _in_this_process(function: Callable[[_Unit], _Value], units: Sequence[_Unit]
                     ) -> Iterator[TaskOutcome[_Value]]:
    for index, unit in enumerate(units):
        yield _outcome(index, _attempt(function, unit), 1)


def _on_process_pool(function: Callable[[_Unit], _Value], units: Sequence[_Unit],
                     workers: int) -> Iterator[TaskOutcome[_Value]]:
    """At most ``workers`` tasks in flight. A process that dies breaks the pool whole and
    every task in flight with it; those run again one at a time in a new pool, so a second
    death is its own task's."""
    waiting = list(reversed(range(len(units))))
    suspects: list[int] = []
    attempts = dict.fromkeys(range(len(units)), 0)
    # spawn: the parent may hold threads (a progress display), which fork would copy locked
    pool = ProcessPoolExecutor(workers, mp_context=get_context("spawn"))
    in_flight: dict[Future[_Attempt[_Value]], int] = {}

    def send(index: int) -> None:
        attempts[index] += 1
        in_flight[pool.submit(_attempt, function, units[index])] = index

    try:
        while waiting or suspects or in_flight:
            if suspects:
                if not in_flight:
                    send(suspects.pop())
            else:
                while waiting and len(in_flight) < workers:
                    send(waiting.pop())
            done, _ = wait(in_flight, return_when=FIRST_COMPLETED)
            broken = False
            for future in done:
                error = future.exception()
                if isinstance(error, BrokenProcessPool):
                    broken = True
                    continue
                index = in_flight.pop(future)
                if error is None:
                    yield _outcome(index, future.result(), attempts[index])
                else:  # the unit or its value could not be pickled
                    yield TaskOutcome(index, None, f"{type(error).__name__}: {error}",
                                      attempts[index])
            if broken:
                for index in in_flight.values():
                    if attempts[index] >= ATTEMPTS:
                        yield _lost(index, attempts[index], "its process died")
                    else:
                        suspects.append(index)
                in_flight.clear()
                _close(pool)
                print("a worker process died: the tasks it had in flight run once more, one "
                      "at a time", file=sys.stderr)
                pool = ProcessPoolExecutor(workers, mp_context=get_context("spawn"))
    finally:
        _close(pool)


def _close(pool: ProcessPoolExecutor) -> None:
    """Shut ``pool`` down, its worker processes ended first. Python 3.11's pool, once
    broken by a dead worker, joins the workers still alive, which wait for work that never
    comes: the shutdown hung for ever now and then. Every task has returned by now, so an
    idle worker loses nothing."""
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        process.terminate()
    pool.shutdown(wait=True, cancel_futures=True)


@contextmanager
def _dask_client(workers: int | None, address: str | None) -> Iterator[Any]:
    """A Dask client of a new local cluster (``workers``), or of the one at ``address``."""
    import dask
    from distributed import Client, LocalCluster

    # A task whose worker dies fails at once (our retry runs it on another worker), and a
    # worker holds only the task it runs, so a death involves no queued task beside it. The
    # workers' statistical profiler (a stack sample every 10 ms) cost a quarter of their CPU.
    settings = {"distributed.scheduler.allowed-failures": 0,
                "distributed.scheduler.worker-saturation": 1.0,
                "distributed.worker.profile.enabled": False}
    with dask.config.set(settings):
        if address is None:
            with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                              host="127.0.0.1", dashboard_address="127.0.0.1:0",
                              silence_logs=logging.CRITICAL) as cluster, \
                    Client(cluster) as client:
                yield client
            return
        try:
            client = Client(address, timeout=CONNECT_SECONDS)
        except (OSError, TimeoutError, ValueError) as error:
            raise BenchmarkError(f"--cluster {address}: no Dask scheduler answers there "
                                 f"({error}); start one with 'dask scheduler' and its "
                                 "workers with 'dask worker ADDRESS'") from None
        with client:
            _check_scheduler(client, address)
            yield client


def _allowed_failures(dask_scheduler: Any) -> int:
    allowed: int = dask_scheduler.allowed_failures
    return allowed


def _check_scheduler(client: Any, address: str) -> None:
    """Say when a running scheduler retries lost tasks itself (then ``attempts`` counts only
    homebot's own retry), and wait until it has a worker."""
    allowed = client.run_on_scheduler(_allowed_failures)
    if allowed:
        print(f"--cluster {address}: its scheduler reruns a task whose worker died up to "
              f"{allowed} times itself before homebot's one retry; start it with "
              "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES=0 for exact attempts",
              file=sys.stderr)
    try:
        client.wait_for_workers(1, timeout=WORKERS_SECONDS)
    except TimeoutError:
        raise BenchmarkError(f"--cluster {address}: the scheduler has had no worker for "
                             f"{WORKERS_SECONDS:g} s; start some with 'dask worker "
                             f"{address}'") from None


def batch_size(seconds: Sequence[float]) -> int:
    """How many tasks to send a Dask worker together, from the seconds the tasks so far took:
    about ``BATCH_SECONDS`` of work (at most ``MAX_BATCH`` tasks), one until any is known.
    A batch spares a short task the scheduler's milliseconds (a symbolic errand takes about
    4 ms); a task as long as a batch goes alone, so a worker that dies loses only its task."""
    if not seconds:
        return 1
    typical = statistics.median(seconds)
    return max(1, min(MAX_BATCH, int(BATCH_SECONDS / max(typical, 1e-6))))


def _attempt_batch(function: Callable[[_Unit], _Value], units: Sequence[_Unit]
                   ) -> list[_Attempt[_Value]]:
    return [_attempt(function, unit) for unit in units]


def _on_dask(function: Callable[[_Unit], _Value], units: Sequence[_Unit], *,
             workers: int | None = None, address: str | None = None
             ) -> Iterator[TaskOutcome[_Value]]:
    """One batch per worker thread at a time, the next sent as one comes back (``batch_size``
    from the tasks' times so far), so a worker that dies takes no other batch down with it.
    The tasks of a lost batch run again one by one, each once."""
    from distributed import as_completed
    from distributed.scheduler import KilledWorker

    with _dask_client(workers, address) as client:
        threads = max(sum(client.nthreads().values()), 1)
        name = f"homebot-tasks-{uuid.uuid4().hex}"  # unique on a cluster shared with others
        attempts = dict.fromkeys(range(len(units)), 1)
        unsent = list(reversed(range(len(units))))
        again: list[int] = []
        seconds: list[float] = []
        batch_of: dict[Any, tuple[int, ...]] = {}
        completed = as_completed()

        def send() -> None:
            while (again or unsent) and len(batch_of) < threads:
                if again:
                    batch: tuple[int, ...] = (again.pop(0),)
                    key = (f"{name}-again", batch[0])
                else:
                    size = min(batch_size(seconds[-64:]), len(unsent))
                    batch = tuple(unsent.pop() for _ in range(size))
                    key = (name, batch[0])
                sent = client.submit(_attempt_batch, function, [units[i] for i in batch],
                                     pure=False, key=key)
                batch_of[sent.key] = batch
                completed.add(sent)

        send()
        for future in completed:
            batch = batch_of.pop(future.key)
            try:
                found = future.result()
            except KilledWorker as error:
                for index in batch:
                    if attempts[index] >= ATTEMPTS:
                        yield _lost(index, attempts[index], f"its worker died ({error.task})")
                    else:
                        attempts[index] += 1
                        again.append(index)
                print(f"tasks {batch[0]}-{batch[-1]} lost their worker; they run once more "
                      "on another", file=sys.stderr)
            else:
                for index, attempt in zip(batch, found, strict=True):
                    seconds.append(attempt.seconds)
                    yield _outcome(index, attempt, attempts[index])
            future.release()
            send()
