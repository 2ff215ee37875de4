"""Speed of the task board service (``make bench``): writes benchmarks/results/service.json.

A ``supportive serve`` process on 127.0.0.1 with a SQLite database (WAL) serves the IKEA chair's board; 20
clients (one HTTP/1.1 keep-alive connection each, all in one asyncio loop of another process — threads would
add the load generator's own GIL waits to the latencies) claim and release their own action, over and over,
for ``--seconds``; every operation is a write transaction and an event pushed to subscribers. Reported:
operations per second and latency percentiles over all operations (targets: ≥ 500 ops/s, p99 < 50 ms on 2
cores). The clients share the machine's two cores with the server, so the figures are a lower bound.

Run: ``.venv/bin/python benchmarks/bench_service.py``
"""

from __future__ import annotations

import argparse
import asyncio
import json
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import httpx
import numpy as np

from supportive.service.launch import free_port

THROUGHPUT_TARGET = 500.0
P99_TARGET_SECONDS = 0.050
CLIENTS = 20


def start(database: str, port: int) -> subprocess.Popen[bytes]:
    agents = [x for i in range(CLIENTS) for x in ("--agent", f"a{i}:robot:lead:t{i}")]
    process = subprocess.Popen(
        [sys.executable, "-m", "supportive.cli", "serve", "--db", database, "--port", str(port), *agents],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    for _ in range(300):
        try:
            if (
                httpx.get(
                    f"http://127.0.0.1:{port}/api/me", headers={"Authorization": "Bearer t0"}
                ).status_code
                == 200
            ):
                return process
        except httpx.HTTPError:
            time.sleep(0.1)
    process.kill()
    raise RuntimeError("the server did not start")


async def client(port: int, index: int, node: str, stop: asyncio.Event, latencies: list[float]) -> int:
    """One client: claim and release ``node`` over one keep-alive connection until ``stop``; refusals."""
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    refused = 0
    try:
        while not stop.is_set():
            for op in ("claim", "release"):
                began = time.perf_counter()
                writer.write(
                    f"POST /api/nodes/{node}/{op} HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                    f"Authorization: Bearer t{index}\r\nContent-Length: 0\r\n\r\n".encode()
                )
                status_line = await reader.readline()
                length = 0
                while (line := await reader.readline()) not in (b"\r\n", b""):
                    name, _, value = line.decode().partition(":")
                    if name.lower() == "content-length":
                        length = int(value)
                await reader.readexactly(length)
                latencies.append(time.perf_counter() - began)
                refused += b" 200 " not in status_line
    finally:
        writer.close()
    return refused


async def load(port: int, leaves: list[str], seconds: float) -> tuple[list[float], int, float]:
    """``CLIENTS`` concurrent clients for ``seconds``: every latency, the refusals, the time taken."""
    stop = asyncio.Event()
    latencies: list[float] = []
    tasks = [
        asyncio.create_task(client(port, i, leaves[i % len(leaves)], stop, latencies)) for i in range(CLIENTS)
    ]
    began = time.perf_counter()
    await asyncio.sleep(seconds)
    stop.set()
    refused = sum(await asyncio.gather(*tasks))
    return latencies, refused, time.perf_counter() - began


def run(seconds: float) -> dict[str, Any]:
    with tempfile.TemporaryDirectory() as directory:
        port = free_port()
        server = start(f"sqlite:///{Path(directory) / 'board.db'}", port)
        try:
            url = f"http://127.0.0.1:{port}"
            leaves = [
                n["id"]
                for n in httpx.get(f"{url}/api/board", headers={"Authorization": "Bearer t0"}).json()["nodes"]
                if n["kind"] == "action"
            ]
            latencies, errors, elapsed = asyncio.run(load(port, leaves, seconds))
        finally:
            server.terminate()
            server.wait(10)
    values = np.array(latencies)
    return {
        "operations": int(values.size),
        "seconds": round(elapsed, 3),
        "ops_per_second": round(values.size / elapsed, 1),
        "p50_ms": round(float(np.percentile(values, 50)) * 1000, 2),
        "p90_ms": round(float(np.percentile(values, 90)) * 1000, 2),
        "p99_ms": round(float(np.percentile(values, 99)) * 1000, 2),
        "max_ms": round(float(values.max()) * 1000, 2),
        "refused": int(errors),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "service.json")
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    measured = run(args.seconds)
    result: dict[str, Any] = {
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "setup": {"clients": CLIENTS, "database": "SQLite (WAL, synchronous=NORMAL)", "task": "ikea-chair"},
        "claim_release": measured,
        "targets": {"ops_per_second": THROUGHPUT_TARGET, "p99_ms": P99_TARGET_SECONDS * 1000},
        "meets_target": measured["ops_per_second"] >= THROUGHPUT_TARGET
        and measured["p99_ms"] < P99_TARGET_SECONDS * 1000,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
