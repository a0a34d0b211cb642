"""``noiselab warmup``: compile noiselab's default kernels into numba's on-disk cache now.

numba compiles a kernel on its first call and keeps the machine code on disk
(``cache=True``), so only a first call waits. ``noiselab warmup`` makes those
first calls ahead, on small inputs, in parallel processes: the default
lattice paths (3-D points with either hash, a 2-D grid, a 6-octave fractal
sum on it) and, cheaply, spectral noise and falling snow. A later process
loads the compiled code from the cache instead of compiling it.
``install.sh`` runs it after installing (``NOISELAB_NO_WARMUP=1`` skips it).
The cache lives where ``noiselab cache`` lists it (``NUMBA_CACHE_DIR``, else
beside the package or in ``~/.cache``).
"""
from __future__ import annotations

NAME = "warmup"
HELP = "compile noiselab's default kernels into numba's cache now (seconds), so that first calls start warm"


def _points3():
    import numpy as np

    from ..lattice import LatticeNoise
    pts = np.random.default_rng(0).random((1 << 15, 3)) * 32   # enough points for the folded-table path
    LatticeNoise(3)(pts)
    LatticeNoise(3, basis="gradient")(pts)


def _int32():
    import numpy as np

    from ..lattice import LatticeNoise
    pts = (np.random.default_rng(0).random((1000, 3)) * 32).astype(np.float32)
    LatticeNoise(3, hash="integer")(pts)


def _grid2():
    from ..lattice import LatticeNoise
    LatticeNoise(2).grid((64, 64), [(0, 8), (0, 8)])


def _fbm2():
    from ..fractal import fractal_sum
    from ..lattice import Grid, LatticeNoise
    fractal_sum(LatticeNoise(2), Grid((64, 64), ((0, 8), (0, 8))), octaves=6)


def _spectral():
    from ..spectral import spectral_noise
    spectral_noise((32, 32), rng=0)


def _snow():
    from ..snowfall import snow
    snow((4, 32, 32), rng=0)


# name -> (what it compiles, the call); each runs in its own process
TASKS = {
    "points3": ("3-D points, table hash, value and gradient", _points3),
    "int32": ("3-D float32 points, integer hash", _int32),
    "grid2": ("a 2-D grid", _grid2),
    "fbm2": ("a 6-octave fractal sum on a 2-D grid", _fbm2),
    "spectral": ("2-D spectral noise", _spectral),
    "snow": ("falling snow", _snow),
}


def add_arguments(parser):
    parser.add_argument("--only", nargs="+", choices=list(TASKS), metavar="PATH",
                        help=f"compile these paths only (default: all of {', '.join(TASKS)})")
    parser.add_argument("--jobs", type=int, default=None,
                        help="processes compiling at once (default: the cores available, at most one per path)")


def _timed(name):
    import time

    t0 = time.perf_counter()
    c0 = time.process_time()
    TASKS[name][1]()
    return name, time.perf_counter() - t0, time.process_time() - c0


def warmup(names=None, jobs=None):
    """Run each path's first call in a pool of ``jobs`` processes; ``[(name, wall s, CPU s)]`` in ``names``' order.

    Parameters
    ----------
    names : sequence of str, optional
        Keys of :data:`TASKS` (default: all).
    jobs : int, optional
        Processes at once (default: the cores available, at most ``len(names)``).

    Returns
    -------
    list of tuple

    Examples
    --------
    >>> [name for name, wall, cpu in warmup(["grid2"], jobs=1)]
    ['grid2']
    """
    import concurrent.futures
    import multiprocessing
    import os

    from .._core.validate import check_int

    names = list(TASKS) if names is None else list(names)
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    jobs = min(len(names), cores) if jobs is None else check_int("jobs", jobs, lo=1)
    if jobs == 1 or len(names) == 1:
        return [_timed(name) for name in names]
    ctx = multiprocessing.get_context("fork")   # the children compile; this process has compiled nothing
    with concurrent.futures.ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
        return list(pool.map(_timed, names))


def run(args) -> int:
    import time

    from .._core.jitcache import cache_folders

    t0 = time.perf_counter()
    done = warmup(args.only, args.jobs)
    for name, wall, cpu in done:
        print(f"noiselab warmup: {name:<9} {TASKS[name][0]}: {wall:.1f} s ({cpu:.1f} s CPU)")
    print(f"noiselab warmup: {len(done)} path(s) compiled in {time.perf_counter() - t0:.1f} s; cache in "
          + ", ".join(str(f) for f in cache_folders()))
    return 0
