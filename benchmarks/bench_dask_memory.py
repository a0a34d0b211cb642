"""Benchmark: chunked snow and spectral noise written to zarr by memory-limited dask workers.

Run from the repository root::

    python3 benchmarks/bench_dask_memory.py                     # 512 MiB snow, 2 workers of 600 MiB (appends to bench_dask.md)
    python3 benchmarks/bench_dask_memory.py --mib 64 --limit 300 --no-write
    python3 benchmarks/bench_dask_memory.py --chunks 128x256x256 --timeout 300   # user's chunks, a case <= 5 min

A ``LocalCluster`` of worker processes (one thread each, ``memory_limit`` per
worker; the nanny kills a worker past 95 % of it and starts a new one) writes
``snow(shape, chunks=..., spill=...)`` through ``noiselab.io.write_zarr``, as
``noiselab snow -o out.zarr`` does, then ``spectral_noise`` of the same size.
A scheduler plugin counts the workers that joined after the start (each is a
restart) and left; each worker's peak RSS growth during the write is read
from ``/proc/self/status`` (``VmHWM``, reset through ``/proc/self/clear_refs``
before the write) and given against the largest output chunk.

Each case runs on a fresh cluster and is given ``--timeout`` seconds: a
write that has not finished by then (a worker paused by ``distributed`` at
80 % of its memory makes no progress) is reported as hung, with the restarts
counted up to then, and the next case runs; the cluster is closed under it.
"""
from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from noiselab.lab.measure import header_lines, load_average, run_info  # noqa: E402
from noiselab.scale.run import _worker_events, _worker_events_plugin  # noqa: E402


def _status_kib(field):
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


def _reset_peak():
    """On a worker: reset VmHWM to the current RSS; returns the RSS (KiB)."""
    import gc

    gc.collect()
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")
    return _status_kib("VmRSS")


def _peak():
    return _status_kib("VmHWM")


def run_case(client, name, lazy, path, out_mib, timeout):
    """Write ``lazy`` to ``path`` on the cluster; restarts, per-worker peak growth, wall time, hung or failed."""
    from noiselab.io import write_zarr

    joined0, left0 = client.run_on_scheduler(_worker_events)
    base = client.run(_reset_peak)
    t0 = time.perf_counter()
    outcome = {}

    def write():
        try:
            write_zarr(path, lazy, dims=tuple("tyx"[-lazy.ndim:]), rng=0)
        except Exception as exc:  # a task whose workers all died (KilledWorker), or the cluster closed under a hang
            outcome["failed"] = type(exc).__name__

    th = threading.Thread(target=write, daemon=True)
    th.start()
    th.join(timeout)
    wall = time.perf_counter() - t0
    hung = th.is_alive()
    failed = f"hung: no result after {timeout:g} s" if hung else outcome.get("failed")
    joined, left = client.run_on_scheduler(_worker_events)
    peaks = client.run(_peak) if not hung else {}
    # a restarted worker's peak is its own since it started: growth over the first worker's baseline
    growth = {w: (peaks[w] - base.get(w, min(base.values(), default=peaks[w]))) / 1024 for w in peaks}
    chunk_mib = float(np.prod([max(c) for c in lazy.chunks])) * lazy.dtype.itemsize / 2**20
    row = {"name": name, "failed": failed, "hung": hung, "shape": lazy.shape,
           "chunk": tuple(max(c) for c in lazy.chunks),
           "chunk_mib": chunk_mib, "restarts": joined - joined0, "left": left - left0, "wall_s": wall,
           "growth_mib": sorted(growth.values(), reverse=True),
           "before_mib": sorted((v / 1024 for v in base.values()), reverse=True), "out_mib": out_mib}
    print(row, flush=True)
    return row


def shape_for(mib):
    """A (T, 1024, 1024) snow video (or (T, 512, 512) under 16 MiB) of about ``mib`` MiB of float32."""
    hw = 1024 if mib >= 16 else 512
    return (max(2, int(round(mib * 2**20 / (4 * hw * hw)))), hw, hw)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mib", type=float, default=512, help="size of the snow video (float32 MiB)")
    ap.add_argument("--limit", type=float, default=600, help="memory limit per worker, MiB")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--chunks", default="auto", help="TxHxW or auto (as noiselab snow --chunks)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds a case may run before it is reported hung")
    ap.add_argument("--cases", default="snow-spill,noise-spill,snow,noise",
                    help="comma-separated, of snow-spill, noise-spill, snow, noise (no spill=: the route chooses)")
    ap.add_argument("--no-write", action="store_true", help="print the report, do not append it to bench_dask.md")
    args = ap.parse_args(argv)
    import distributed

    from noiselab.snowfall import snow
    from noiselab.spectral import spectral_noise

    chunks = "auto" if args.chunks == "auto" else tuple(int(x) for x in args.chunks.split("x"))
    shape = shape_for(args.mib)
    out_mib = float(np.prod(shape)) * 4 / 2**20
    load0 = load_average()
    tmp = Path(tempfile.mkdtemp(prefix="bench-dask-memory-"))
    rows = []
    cases = {
        "snow-spill": ("snow, spill= (as `noiselab snow -o x.zarr`)",
                       lambda: snow(shape, rng=3, chunks=chunks, spill=tmp / "s1")),
        "noise-spill": ("spectral_noise (3-D), spill=",
                        lambda: spectral_noise(shape, rng=3, chunks=chunks, spill=tmp / "s2")),
        "snow": ("snow, no spill=", lambda: snow(shape, rng=3, chunks=chunks)),
        "noise": ("spectral_noise (3-D), no spill=", lambda: spectral_noise(shape, rng=3, chunks=chunks)),
    }
    try:
        for i, key in enumerate(args.cases.split(",")):
            name, make = cases[key]
            # a fresh cluster per case: a hung case is closed under its write, and no case inherits another's restarts
            with distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                          dashboard_address=None, memory_limit=f"{args.limit}MiB") as cluster, \
                    distributed.Client(cluster) as client:
                client.register_plugin(_worker_events_plugin())
                client.run(lambda: __import__("noiselab.scale.spectral") and None)  # imports, before the baseline
                client.submit(lambda: snow((4, 32, 32), rng=0).sum(), pure=False).result()
                lazy = make()  # built under the client: the route reads the workers' memory
                rows.append(run_case(client, name, lazy, tmp / f"{i}.zarr", out_mib, args.timeout))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    cmd = "python3 benchmarks/bench_dask_memory.py" + "".join(
        f" --{k} {v}" for k, v in (("mib", args.mib), ("limit", args.limit), ("workers", args.workers),
                                   ("chunks", args.chunks), ("timeout", args.timeout),
                                   ("cases", args.cases)) if v != ap.get_default(k))
    lines = ["", "# Chunked snow and spectral noise within the workers' memory", "",
             *header_lines(run_info(cmd, ["dask", "distributed", "zarr", "noiselab"], load=load0)),
             f"- cluster: `LocalCluster` of {args.workers} worker processes, 1 thread each, memory_limit "
             f"{args.limit:g} MiB each (the nanny restarts a worker past 95 %); load average (1 min) at the end "
             f"{load_average():.1f}",
             f"- field: {shape} float32 ({out_mib:.0f} MiB), chunks={args.chunks!r}, written to zarr by "
             "`noiselab.io.write_zarr`", "",
             "| path | output chunk | chunk MiB | worker restarts (left) | worker peak growth MiB (each) | "
             "growth / chunk (largest) | worker RSS before MiB | wall s |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        lines.append(f"| {r['name']} | {'x'.join(map(str, r['chunk']))} | {r['chunk_mib']:.0f} | **{r['restarts']}** ({r['left']})"
                     + (f" ({r['failed']})" if r["failed"] else "") + " | "
                     + (", ".join(f"{g:.0f}" for g in r["growth_mib"]) or "-")
                     + (f" | {r['growth_mib'][0] / r['chunk_mib']:.1f}x | " if r["growth_mib"] else " | - | ")
                     + ", ".join(f"{b:.0f}" for b in r["before_mib"]) + f" | {r['wall_s']:.1f} |")
    lines.append("")
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        with open(ROOT / "benchmarks" / "bench_dask.md", "a") as fh:
            fh.write(text)
    return rows


if __name__ == "__main__":
    main()
