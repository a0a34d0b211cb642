"""``workers=2`` on big lattice calls: the wall-clock speed-up here, and what the split gives two free cores.

Run::

    python benchmarks/bench_workers.py [--repeats 7] [--append]

noiselab's target is ``workers=2`` >= 1.7x ``workers=1`` on grids of 1024^2
and up. On a shared 2-core machine the second thread rarely gets a core of
its own, so the wall-clock ratio measures the load as much as the code. This
script therefore reports, beside it, what the split itself allows: every
block a thread computes is timed with that thread's CPU clock
(``time.thread_time``), so for one ``workers=2`` call

- ``caller`` = the calling thread's CPU time for the whole call (its set-up,
  its blocks, the hand-off and the wait),
- ``helper`` = the pooled thread's CPU time in its blocks,
- ``split`` = ``T1 / max(caller, helper)``, with ``T1`` the calling thread's
  CPU time for the ``workers=1`` call: the speed-up two cores that run
  nothing else would give, if the threads do not slow each other down
  (memory bandwidth, a shared cache: the control row, which only streams
  memory, shows that cost where it is visible);
- ``cpu sum`` = ``(caller + helper) / T1``: the work the split adds (1.0: none).

Each figure is the median over ``--repeats`` calls. A second table times the
set-up of a 512^2 fBm (everything but its kernel), which bounds small grids. CPU time does not count
the time a thread waits for a core, so ``split`` holds on a loaded machine
where the wall clock does not; it is a bound from the code's side, not a
wall-clock measurement.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import noiselab._core.workers as workers_mod  # noqa: E402
import noiselab.lattice.grid_path as grid_path  # noqa: E402
import noiselab.lattice.points_path as points_path  # noqa: E402
from noiselab import LatticeNoise, fractal_sum  # noqa: E402
from noiselab._core import run_split  # noqa: E402
from noiselab.lab.measure import header_lines, run_info  # noqa: E402
from noiselab.lattice import Grid  # noqa: E402

_BLOCKS = []  # (thread ident, CPU seconds) of every block of the call being measured


def _recording(map_blocks):
    """``map_blocks`` with each block's CPU time (its thread's clock) recorded in ``_BLOCKS``."""
    def timed_map(fn, blocks, n):
        def timed(block):
            c0 = time.thread_time()
            try:
                return fn(block)
            finally:
                _BLOCKS.append((threading.get_ident(), time.thread_time() - c0))
        return map_blocks(timed, blocks, n)
    return timed_map


# where a lattice call splits its work: run_split, the point kernels' own split, the grid bands
for _mod in (workers_mod, points_path, grid_path):
    _mod.map_blocks = _recording(_mod.map_blocks)


def _stream_points(pts, out):
    out[:] = pts.sum(axis=1)  # reads the points, writes one float32 each: memory traffic only


def measure(call, repeats):
    """``(wall speed-up, cores, split, cpu sum, blocks)`` of ``call(2)`` against ``call(1)``, medians."""
    call(1), call(2)  # compile, plan, touch the pages
    walls, cores, splits, sums, nblocks = [], [], [], [], []
    me = threading.get_ident()
    for r in range(repeats):
        order = (1, 2) if r % 2 == 0 else (2, 1)
        res = {}
        for w in order:
            _BLOCKS.clear()
            w0, c0, p0 = time.perf_counter(), time.thread_time(), time.process_time()
            call(w)
            res[w] = (time.perf_counter() - w0, time.thread_time() - c0, time.process_time() - p0, list(_BLOCKS))
        wall1, cpu1 = res[1][0], res[1][1]
        wall2, caller, proc2, blocks = res[2]
        helper = sum(c for ident, c in blocks if ident != me)
        walls.append(wall1 / wall2)
        cores.append(proc2 / wall2)
        splits.append(cpu1 / max(caller, helper))
        sums.append((caller + helper) / cpu1)
        nblocks.append(len(blocks))
    return tuple(float(np.median(v)) for v in (walls, cores, splits, sums)) + (int(np.median(nblocks)),)


def cases():
    rng = np.random.default_rng(1)
    pts32 = rng.uniform(0.0, 100.0, (4_000_000, 3)).astype(np.float32)
    out32 = np.empty(pts32.shape[0], np.float32)
    yield ("control: read 4e6 3-D float32 points, write one float32 each", "4e6 points",
           lambda w: run_split(_stream_points, pts32, out32, (), w))
    for dim, size, cells in ((2, 1024, 32), (2, 2048, 64), (3, 128, 4), (3, 256, 8)):
        grid = Grid((size,) * dim, [(0.0, float(cells))] * dim)
        for basis, hname in (("value", "table"), ("gradient", "integer")):
            noise = LatticeNoise(dim, rng=1, kernel="quintic", basis=basis,
                                 **({} if hname == "table" else {"hash": hname}))
            yield (f"{dim}-D 6-octave fBm, quintic {basis}, {hname} hash, float32", f"{size}^{dim}",
                   lambda w, noise=noise, grid=grid: fractal_sum(noise, grid, 6, dtype=np.float32, workers=w))
    for hname, x in (("table", pts32.astype(np.float64)), ("integer", pts32)):
        noise = LatticeNoise(3, rng=1, kernel="quintic", **({} if hname == "table" else {"hash": hname}))
        yield (f"3-D points, quintic value, {hname} hash, {x.dtype}", "4e6 points",
               lambda w, noise=noise, x=x: noise(x, workers=w))


def setup_rows(repeats, lines):
    """The set-up of a 512^2 6-octave fBm (all but its kernel), what it keeps from call to call kept or made, beside
    the kernel."""
    lines += ["", "### The set-up of a grid", "",
              "512^2 6-octave fBm (16 cells), float32, one thread: `set-up` = the call with the fused kernel "
              "replaced by a no-op (checks, octaves, axis taps, hash prefixes, the kernel's arguments), with the "
              "axis taps and the kernel's arguments kept from call to call (`kept`, the default), the axis taps "
              "kept and the arguments made by each call (`taps kept`, `grid_path.rows_plan` bypassed), or "
              "both made by each (`made`, `grid_path.AXIS_TAPS_KEPT = 0`); `kernel` = the fused kernel alone. "
              "CPU time of the calling thread, 10th percentile of 10 x `--repeats` calls (the set-up is a few "
              "hundred microseconds: the low percentile keeps the other jobs' interruptions out).", "",
              "| noise | hash | set-up, kept (ms) | set-up, taps kept (ms) | set-up, made (ms) | kernel (ms) |",
              "|---|---|---|---|---|---|"]
    grid = Grid((512, 512), [(0.0, 16.0)] * 2)
    real = grid_path.jit.grid_rows_kernel
    for basis, hname in (("value", "table"), ("gradient", "table"), ("value", "integer"), ("gradient", "integer")):
        noise = LatticeNoise(2, rng=1, kernel="quintic", basis=basis, **({} if hname == "table" else {"hash": hname}))
        kernel = real(2, 2, hname == "integer", basis == "gradient")
        kernel_times = []

        def timed_kernel(*args):
            c0 = time.thread_time()
            kernel(*args)
            kernel_times.append(time.thread_time() - c0)

        def p10(call, n=10 * repeats):
            call()
            times = []
            for _ in range(n):
                c0 = time.thread_time()
                call()
                times.append(time.thread_time() - c0)
            return 1e3 * float(np.percentile(times, 10))

        def call():
            return fractal_sum(noise, grid, 6, dtype=np.float32)
        kept = getattr(grid_path, "AXIS_TAPS_KEPT", None)  # None: a version that makes them every call
        plan = getattr(grid_path, "rows_plan", None)  # None: a version that makes the arguments every call
        try:
            grid_path.jit.grid_rows_kernel = lambda *key: (lambda *args: None)
            shared = p10(call)
            taps_kept = float("nan")
            if plan is not None:
                grid_path.rows_plan = lambda noise, axes: grid_path._make_rows_plan(noise, axes)[0]
                taps_kept = p10(call)
                grid_path.rows_plan = plan
            if kept is not None:
                grid_path.AXIS_TAPS_KEPT = 0
                grid_path._AXIS_TAPS.clear()
                made = p10(call)
                grid_path.AXIS_TAPS_KEPT = kept
            else:
                shared, made = float("nan"), shared
            grid_path.jit.grid_rows_kernel = lambda *key: timed_kernel
            p10(call)
        finally:
            grid_path.jit.grid_rows_kernel = real
            if plan is not None:
                grid_path.rows_plan = plan
            if kept is not None:
                grid_path.AXIS_TAPS_KEPT = kept
        ker = 1e3 * float(np.percentile(kernel_times, 10))
        lines.append(f"| 512^2 fBm, quintic {basis} | {hname} | {shared:.3f} | {taps_kept:.3f} | {made:.3f} | "
                     f"{ker:.3f} |")
        print(lines[-1], flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--append", action="store_true", help="append the table to benchmarks/bench_workers.md")
    args = ap.parse_args(argv)
    if args.repeats < 5:
        ap.error("--repeats must be >= 5 (medians)")
    info = run_info(f"python benchmarks/bench_workers.py --repeats {args.repeats}")
    rev = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                         text=True).stdout.strip() or "unknown"
    lines = ["", f"## {info['date']}: noiselab at {rev}", ""] + header_lines(
        info, timing="wall: perf_counter; CPU: each thread's own clock; medians of the calls") + [""]
    lines += ["| call | size | wall x (cores) | split x | cpu sum | blocks |", "|---|---|---|---|---|---|"]
    for name, size, call in cases():
        wall, cores, split, cpu_sum, nblocks = measure(call, args.repeats)
        lines.append(f"| {name} | {size} | {wall:.2f} ({cores:.1f}) | {split:.2f} | {cpu_sum:.2f} | {nblocks} |")
        print(lines[-1], flush=True)
    setup_rows(args.repeats, lines)
    lines += ["", f"Load average (1 min) at the end: {os.getloadavg()[0]:.1f}."]
    text = "\n".join(lines) + "\n"
    if args.append:
        path = Path(__file__).with_suffix(".md")
        head = "" if path.exists() else ("# `workers=2` on big lattice calls\n\nWhat the columns mean: "
                                         "`benchmarks/bench_workers.py`'s docstring.\n")
        with open(path, "a") as fh:
            fh.write(head + text)
    print(text)


if __name__ == "__main__":
    main()
