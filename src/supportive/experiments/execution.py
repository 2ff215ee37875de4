"""Where trials run: in this process, on a dask LocalCluster of worker processes, or on an existing dask
cluster.

dask is imported only when it is needed (it is the ``distributed`` extra). Whatever runs them, results come
back in trial order, so a run's results never depend on the number of workers.
"""

from __future__ import annotations

import logging
import queue
import re
import signal
import socket
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from types import ModuleType
from typing import Any, Protocol

from supportive.errors import ExperimentError, MissingExtraError
from supportive.experiments.registry import TrialResult
from supportive.experiments.trials import Trial
from supportive.io.atomic import uninterrupted

__all__ = [
    "CONNECT_TIMEOUT",
    "Executor",
    "InProcess",
    "OnDask",
    "check_backend",
    "check_listening",
    "import_distributed",
    "open_executor",
]

CONNECT_TIMEOUT = 30.0
"""Seconds to wait for an existing dask scheduler to answer, and then for it to have a worker."""

_ADDRESS = re.compile(r"^(tcp|tls|ws|wss|ucx|inproc)://\S+$")


class Executor(Protocol):
    """Runs a trial function over trials and returns the results in trial order."""

    description: str

    def map(
        self, function: Callable[[Trial], TrialResult], trials: Sequence[Trial], done: Callable[[], None]
    ) -> list[TrialResult]:
        """Run ``function`` on every trial, calling ``done()`` after each one finishes.

        Returns:
            The results, in the order of ``trials``.
        """
        ...


@dataclass
class InProcess:
    """Runs the trials one after another in this process."""

    description: str = "in process"

    def map(
        self, function: Callable[[Trial], TrialResult], trials: Sequence[Trial], done: Callable[[], None]
    ) -> list[TrialResult]:
        """Run ``function`` on every trial, in order (see :class:`Executor`)."""
        results = []
        for trial in trials:
            results.append(function(trial))
            done()
        return results


@dataclass
class OnDask:
    """Runs the trials as tasks of a ``dask.distributed`` client, whichever cluster it is connected to."""

    client: Any
    description: str

    def map(
        self, function: Callable[[Trial], TrialResult], trials: Sequence[Trial], done: Callable[[], None]
    ) -> list[TrialResult]:
        """Submit every trial, collect the results as they finish and return them in trial order.

        The results are waited for on a queue the futures' callbacks fill, not inside dask: a Ctrl-C while
        waiting stops the run without cutting one of dask's own calls in half (which makes it log errors);
        fetching a finished result and cancelling the rest on the way out hold Ctrl-C back for the moment
        they take."""
        futures = self.client.map(function, list(trials), pure=False)
        position = {future.key: index for index, future in enumerate(futures)}
        finished: queue.SimpleQueue[Any] = queue.SimpleQueue()
        for future in futures:
            future.add_done_callback(finished.put)
        found: dict[int, TrialResult] = {}
        try:
            while len(found) < len(futures):
                future = finished.get()
                with uninterrupted():
                    result = future.result()
                found[position[future.key]] = result
                done()
        finally:
            with uninterrupted():
                self.client.cancel(futures)
        return [found[index] for index in range(len(futures))]


def import_distributed() -> ModuleType:
    """``dask.distributed``, imported now.

    Raises:
        MissingExtraError: when dask.distributed is not installed (``pip install 'supportive[distributed]'``).
    """
    try:
        import dask.distributed as distributed
    except ImportError:
        raise MissingExtraError(
            "running trials on more than one worker", "dask.distributed", "distributed"
        ) from None
    return distributed


def check_backend(workers: int, scheduler: str | None) -> None:
    """Check the choice of workers and scheduler before anything starts.

    Raises:
        ExperimentError: for fewer than one worker, both ``workers`` (other than 1) and ``scheduler``, or a
            scheduler address that is not ``PROTOCOL://HOST:PORT``.
        MissingExtraError: for more than one worker without dask.distributed (asked for, even where a run
            with a single trial then needs none).
    """
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ExperimentError(f"workers must be an int >= 1, got {workers!r}")
    if scheduler is not None:
        if workers != 1:
            raise ExperimentError(
                "give either a number of workers (a local cluster) or a scheduler address (an existing "
                "cluster), not both"
            )
        if not _ADDRESS.match(scheduler):
            raise ExperimentError(f"scheduler address {scheduler!r}: expected tcp://HOST:PORT")
    if workers > 1:
        import_distributed()


def check_listening(scheduler: str, timeout: float = 5.0) -> None:
    """Fail at once when nothing listens at a ``tcp://``/``tls://`` scheduler address: dask's client retries a
    refused connection until its timeout (31.5 s), which only slows the error a mistyped port deserves. A
    host that does not answer is left to dask's own timeout; another scheme is not checked.

    Raises:
        ExperimentError: when the connection is refused, or the host name does not resolve.
    """
    found = re.fullmatch(r"(?:tcp|tls)://\[?([^\]]+?)\]?:(\d+)/?", scheduler)
    if found is None:
        return
    host, port = found.group(1), int(found.group(2))
    try:
        with socket.create_connection((host, port), timeout=timeout):
            return
    except ConnectionRefusedError:
        raise ExperimentError(
            f"cannot connect to the dask scheduler at {scheduler}: connection refused (is a scheduler running "
            "there, on that port?)"
        ) from None
    except socket.gaierror as exc:
        raise ExperimentError(f"cannot connect to the dask scheduler at {scheduler}: {exc.strerror}") from None
    except OSError:  # a timeout or an unreachable network: dask's client says more, in its own time
        return


@contextmanager
def open_executor(workers: int = 1, scheduler: str | None = None) -> Iterator[Executor]:
    """An executor for ``workers`` processes or the dask scheduler at ``scheduler``; closed on exit.

    * ``workers == 1`` and no scheduler: :class:`InProcess` (dask is not imported).
    * ``workers > 1``: a ``dask.distributed.LocalCluster`` of ``workers`` processes with one thread each,
      listening on 127.0.0.1 only, without a dashboard; shut down on exit.
    * ``scheduler="tcp://HOST:PORT"``: a client of that existing cluster (its workers need ``supportive``
      installed); only the client is closed on exit.

    Raises:
        ExperimentError: for a bad choice (see :func:`check_backend`) or a scheduler that cannot be reached or
            has no worker.
        MissingExtraError: when dask.distributed is needed and not installed.
    """
    check_backend(workers, scheduler)
    if scheduler is None and workers == 1:
        yield InProcess()
        return
    distributed = import_distributed()
    if scheduler is not None:
        check_listening(scheduler)
        try:
            client = distributed.Client(scheduler, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError) as exc:
            reason = " ".join(str(exc).split()) or type(exc).__name__
            raise ExperimentError(f"cannot connect to the dask scheduler at {scheduler}: {reason}") from None
        try:
            try:
                client.wait_for_workers(1, timeout=CONNECT_TIMEOUT)
            except (OSError, TimeoutError):
                raise ExperimentError(
                    f"the dask scheduler at {scheduler} has no worker after {CONNECT_TIMEOUT:g} s"
                ) from None
            yield OnDask(client, f"dask scheduler {scheduler}")
        finally:
            client.close()
        return
    with _quiet_workers(distributed):
        with uninterrupted(), _held_back_from_new_processes():  # a Ctrl-C while the cluster starts takes
            cluster = _new_cluster(distributed, workers)  # effect once it has: none is half made
        try:
            client = distributed.Client(cluster, set_as_default=False)
            try:
                yield OnDask(client, f"dask LocalCluster, {workers} worker processes")
            finally:
                with uninterrupted():
                    client.close()
        finally:
            with uninterrupted():
                cluster.close()


@contextmanager
def _quiet_workers(distributed: ModuleType) -> Iterator[None]:
    """While the block runs, local worker processes ignore Ctrl-C from birth.

    A terminal's Ctrl-C reaches every process of its foreground group, the workers too: each would die with a
    traceback while the run shuts the cluster down in order. So the workers are forked by Python's fork
    server (dask's ``forkserver`` method), whose first preload, :mod:`supportive.quiet_fork` (a module of
    the standard library alone, imported in some milliseconds), makes it ignore SIGINT and hand that on to
    every worker it forks; this process's own handling of Ctrl-C is never touched.
    """
    import dask

    with dask.config.set({"distributed.worker.multiprocessing-method": "forkserver"}):
        context = distributed.utils.get_mp_context()  # dask sets its preloads once, on the first call
        context.set_forkserver_preload(["supportive.quiet_fork", "distributed"])
        yield


@contextmanager
def _held_back_from_new_processes() -> Iterator[None]:
    """While the block runs, this thread blocks Ctrl-C (SIGINT); the threads it starts, and the programs they
    start, inherit the block. The fork server is a new interpreter: a terminal's Ctrl-C that reached it while
    Python itself was starting, before :mod:`supportive.quiet_fork` could make it ignore the signal, printed
    "Fatal Python error" beside the run's one line; born with SIGINT blocked, it never sees one. A Ctrl-C
    this thread held back is delivered when the block ends.

    Python's resource tracker is started first, outside the block: starting it guards its own birth the same
    way (bpo-33613) but then unblocks SIGINT in the thread that started it, which would be the cluster's
    event loop, the thread that goes on to start the fork server."""
    from multiprocessing import resource_tracker

    resource_tracker.ensure_running()
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _new_cluster(distributed: ModuleType, workers: int) -> Any:
    """A ``LocalCluster`` of ``workers`` processes (see :func:`open_executor`)."""
    return distributed.LocalCluster(
        n_workers=workers,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
        # No dashboard; the scheduler's small HTTP endpoint (health, metrics) takes any free port on 127.0.0.1
        # instead of 8787, so that runs never collide with another cluster on this machine.
        scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        # dask's own errors while a cluster closes (a heartbeat missed under load) are noise to the person who
        # stopped the run; a trial's error reaches the run as the trial's result.
        silence_logs=logging.CRITICAL,
    )
