"""Where trials run. The dask tests start real LocalClusters on 127.0.0.1 (a few seconds each)."""

from __future__ import annotations

import logging
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import dask.distributed as distributed
import pytest

from supportive.errors import ExperimentError, MissingExtraError
from supportive.experiments import execution, run_experiment
from supportive.experiments.execution import check_backend, import_distributed, open_executor

TRIALS = 4
QUIET_HTTP = {"dashboard_address": "127.0.0.1:0"}  # the scheduler's HTTP endpoint on any free local port


@pytest.fixture(scope="module")
def external_cluster() -> Iterator[Any]:
    """A separate LocalCluster, standing in for a real cluster that ``--scheduler`` connects to."""
    cluster = distributed.LocalCluster(
        n_workers=1,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
        scheduler_kwargs=QUIET_HTTP,
        silence_logs=logging.ERROR,
    )
    try:
        yield cluster
    finally:
        cluster.close()


@pytest.fixture(scope="module")
def in_process(tmp_path_factory: pytest.TempPathFactory) -> Path:
    output = tmp_path_factory.mktemp("w1")
    run_experiment("edge-reduction", trials=TRIALS, seed=5, workers=1, output=output, progress=False)
    return output


def test_local_cluster_gives_identical_metrics(in_process: Path, tmp_path: Path) -> None:
    result = run_experiment(
        "edge-reduction", trials=TRIALS, seed=5, workers=2, output=tmp_path, progress=False
    )
    assert result.backend == "dask LocalCluster, 2 worker processes"
    assert [r["index"] for r in result.results] == list(range(TRIALS))
    assert (tmp_path / "metrics.json").read_bytes() == (in_process / "metrics.json").read_bytes()
    assert (tmp_path / "report.md").read_text() == (in_process / "report.md").read_text()
    assert "LocalCluster" in (tmp_path / "run.json").read_text()


@pytest.mark.parametrize(("trials", "backend"), [(1, "in process"), (2, "dask LocalCluster, 2 worker processes")])
def test_no_more_workers_start_than_there_are_trials(trials: int, backend: str, tmp_path: Path) -> None:
    """``workers=4`` with one trial runs it in process and with two starts two workers: the others would only
    wait. The metrics are the same wherever the trials ran."""
    alone = run_experiment("edge-reduction", trials=trials, seed=5, workers=1, progress=False)
    result = run_experiment("edge-reduction", trials=trials, seed=5, workers=4, output=tmp_path, progress=False)
    assert result.backend == backend and result.trials == trials
    assert result.metrics == alone.metrics


def test_existing_scheduler_gives_identical_metrics(
    in_process: Path, tmp_path: Path, external_cluster: Any
) -> None:
    address = external_cluster.scheduler_address
    assert address.startswith("tcp://127.0.0.1:")
    result = run_experiment(
        "edge-reduction", trials=TRIALS, seed=5, scheduler=address, output=tmp_path, progress=False
    )
    assert result.backend == f"dask scheduler {address}"
    assert (tmp_path / "metrics.json").read_bytes() == (in_process / "metrics.json").read_bytes()


def test_unreachable_scheduler(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(execution, "CONNECT_TIMEOUT", 0.5)
    with (
        pytest.raises(ExperimentError, match=r"cannot connect to the dask scheduler at tcp://127\.0\.0\.1:9"),
        open_executor(scheduler="tcp://127.0.0.1:9"),
    ):
        pass  # pragma: no cover


def test_a_refused_scheduler_address_fails_at_once() -> None:
    """Issue 26: a refused address waited 31.5 s (dask's retries) before failing."""
    import socket
    import time

    with socket.socket() as probe:  # a port nothing listens on: bound, then closed
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    began = time.monotonic()
    with (
        pytest.raises(ExperimentError, match=rf"tcp://127\.0\.0\.1:{port}: connection refused"),
        open_executor(scheduler=f"tcp://127.0.0.1:{port}"),
    ):
        pass  # pragma: no cover
    assert time.monotonic() - began < 5.0


def test_scheduler_without_workers(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(execution, "CONNECT_TIMEOUT", 0.5)
    with distributed.LocalCluster(
        n_workers=0,
        host="127.0.0.1",
        dashboard_address=None,
        scheduler_kwargs=QUIET_HTTP,
        silence_logs=logging.ERROR,
    ) as cluster:
        address = cluster.scheduler_address
        with pytest.raises(ExperimentError, match="has no worker"), open_executor(scheduler=address):
            pass  # pragma: no cover


@pytest.mark.parametrize(
    ("workers", "scheduler", "message"),
    [
        (0, None, "workers must be an int >= 1"),
        (2, "tcp://127.0.0.1:8786", "not both"),
        (1, "127.0.0.1:8786", "expected tcp://HOST:PORT"),
        (1, "tcp://", "expected tcp://HOST:PORT"),
    ],
)
def test_bad_backends(workers: int, scheduler: str | None, message: str) -> None:
    with pytest.raises(ExperimentError, match=message):
        check_backend(workers, scheduler)
    with pytest.raises(ExperimentError, match=message):
        run_experiment("edge-reduction", trials=1, workers=workers, scheduler=scheduler, progress=False)


def test_one_worker_needs_no_dask(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "dask.distributed", None)  # import fails as if not installed
    with open_executor(1) as executor:
        assert executor.description == "in process"
    with pytest.raises(MissingExtraError, match=r"pip install 'supportive\[distributed\]'"):
        import_distributed()
    with pytest.raises(MissingExtraError, match=r"supportive\[distributed\]"):
        run_experiment("edge-reduction", trials=1, workers=2, progress=False)


SIGNAL_MASKS = """
import psutil
from supportive.experiments.execution import open_executor
with open_executor(workers=2):
    server = next(p for p in psutil.Process().children() if "forkserver" in " ".join(p.cmdline()))
    status = dict(line.split(":", 1) for line in open(f"/proc/{server.pid}/status").read().splitlines())
    print(status["SigBlk"].strip(), status["SigIgn"].strip())
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads the fork server's /proc/PID/status")
def test_the_fork_server_holds_ctrl_c_back_from_its_start() -> None:
    # The local cluster's fork server starts as a new interpreter; a terminal's Ctrl-C that reached it while
    # Python itself started (before it could ignore the signal) printed "Fatal Python error: init_import_site"
    # beside the run's one line. It is born with SIGINT blocked (inherited from the thread that started it),
    # and ignores it once started; the workers it forks inherit both.
    done = subprocess.run([sys.executable, "-c", SIGNAL_MASKS], capture_output=True, text=True, timeout=120, check=True)
    blocked, ignored = (int(mask, 16) for mask in done.stdout.split()[-2:])
    sigint = 1 << (signal.SIGINT - 1)
    assert blocked & sigint, done.stdout
    assert ignored & sigint, done.stdout
