"""Worker counts and the one thread pool of the package.

``workers`` means what it means in :mod:`scipy.fft` on every noiselab
function that takes it: ``None`` is scipy's current default (1, or what a
``scipy.fft.set_workers`` block around the call says), ``1`` one thread,
``-1`` every core, ``-k`` every core but ``k - 1``. Results never depend on
the count (each thread fills a fixed block of the output), so any count
gives the same bits.

The threads come from one process-wide pool per count, created on first use:
starting a thread per call costs about 0.1 ms each, more than a small block
of work. The compiled kernels release the GIL, so the threads run in parallel.
"""
from __future__ import annotations

import os
import sys
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np

__all__ = ["resolve_workers", "thread_pool", "map_blocks", "run_split"]

_POOLS = {}   # worker count -> a thread pool kept for the process
_POOLS_LOCK = threading.Lock()


def resolve_workers(workers) -> int:
    """``workers`` with scipy.fft's meaning, as a thread count >= 1.

    Examples
    --------
    >>> resolve_workers(1)
    1
    >>> resolve_workers(-1) == (os.cpu_count() or 1)
    True
    """
    if workers is None:
        # scipy.fft's current default; with scipy.fft not yet imported no set_workers block can be open, and
        # the default is 1 (importing scipy.fft only to read it took 0.15 s of a first lattice call)
        fft = sys.modules.get("scipy.fft")
        return 1 if fft is None else int(fft.get_workers())
    if isinstance(workers, (bool, np.bool_)) or not isinstance(workers, (int, np.integer)):
        raise TypeError(f"workers must be an int (scipy.fft's meaning: -1 for every core) or None, got {workers!r}")
    if workers > 0:
        return int(workers)
    cores = os.cpu_count() or 1   # ~14 us a call: only for the relative counts
    n = cores + 1 + int(workers)
    if workers == 0 or n < 1:
        raise ValueError(f"workers must be a positive count or -1 .. -{cores} (every core, every core but one, ...), "
                         f"got {workers!r}")
    return n


def thread_pool(n: int) -> ThreadPoolExecutor:
    """The process-wide pool of ``n`` threads (created on first use)."""
    with _POOLS_LOCK:
        pool = _POOLS.get(n)
        if pool is None:
            pool = _POOLS[n] = ThreadPoolExecutor(max_workers=n, thread_name_prefix="noiselab")
    return pool


def map_blocks(fn, blocks, n: int) -> list:
    """``[fn(b) for b in blocks]`` on ``n`` threads: the calling thread and ``n - 1`` pooled ones.

    The threads take the blocks in turn from one queue, so the caller works
    instead of waiting, and a call with two blocks hands one block to the
    pool, not two (a hand-off costs about 0.1 ms, the time of a 512² grid's
    octave). Which thread computes a block never changes its result. Once a
    block raises, no thread starts another; the exception is raised when
    every thread has stopped.
    """
    blocks = list(blocks)
    k = min(n, len(blocks))
    if k <= 1:
        return [fn(b) for b in blocks]
    results = [None] * len(blocks)
    queue = iter(range(len(blocks)))
    lock = threading.Lock()
    failed = []  # once a block fails, no thread starts another

    def work():
        while True:
            with lock:
                i = None if failed else next(queue, None)
            if i is None:
                return
            try:
                results[i] = fn(blocks[i])
            except BaseException:
                failed.append(i)
                raise

    helpers = [thread_pool(k - 1).submit(work) for _ in range(k - 1)]
    try:
        work()
    finally:
        errors = [f.exception() for f in helpers]  # waits for every helper
    for err in errors:
        if err is not None:
            raise err
    return results


def run_split(kernel, points, out, rest, n: int, *, min_block: int = 4096):
    """``kernel(points, out, *rest)`` over ``n`` contiguous blocks of rows, on pooled threads.

    A block has at least ``min_block`` rows (threads cost more than a few
    thousand points). Returns the sum of what the kernel returns (kernels that
    count non-finite inputs return a count; others return None, counted 0).
    """
    rows = points.shape[0]
    n = min(n, max(1, rows // min_block))
    if n <= 1:
        return kernel(points, out, *rest) or 0
    bounds = np.linspace(0, rows, n + 1).astype(np.int64)
    blocks = list(zip(bounds[:-1].tolist(), bounds[1:].tolist()))
    return sum(r or 0 for r in map_blocks(lambda ab: kernel(points[ab[0]:ab[1]], out[ab[0]:ab[1]], *rest), blocks, n))
